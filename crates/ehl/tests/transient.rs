//! Transient EHL (thesis ch. 3): identities, mass conservation, and the amplitude reduction of
//! waviness against Venner et al. (1997).
mod common;
use common::*;
use ehl::case::{DensityModel, ViscosityModel};
use ehl::ehl::{
    solve_transient, EhlParams, EhlProblem, MovingSurface, StepResult, TimeScheme, TransientEnd,
    TransientParams, TransientProblem,
};
use ehl::elastic::{Deflection, FftDeflection};
use ehl::grid::Grid;
use ehl::surface::{Feature, FeatureShape, Surface};
use std::ops::ControlFlow;

fn line(m: f64, l: f64) -> LineCase {
    line_case(
        m,
        l,
        ViscosityModel::Roelands,
        DensityModel::DowsonHigginson,
    )
}

/// Runs a transient line contact on `nx` cells over [xin, xout] b with body 1's and body 2's
/// features (`s1`, `s2`, moving at u_e (1 +- srr/2)), `steps` steps of `dt` s; every step.
#[allow(clippy::too_many_arguments)]
fn run_line(
    c: &LineCase,
    nx: usize,
    (xin, xout): (f64, f64),
    srr: f64,
    s1: &Surface,
    s2: &Surface,
    dt: f64,
    steps: usize,
    scheme: TimeScheme,
) -> (Grid, Vec<StepResult>, TransientEnd) {
    let grid = Grid::new(nx, 1, xin * c.b, xout * c.b, -0.5, 0.5);
    let r = c.r;
    let smooth = move |x: f64, _y: f64| x * x / (2.0 * r);
    let e = c.e;
    let op = move |g: Grid| -> Box<dyn Deflection> { Box::new(FftDeflection::line(g, e)) };
    let problem = TransientProblem {
        base: EhlProblem {
            grid,
            gap: &smooth,
            operator: &op,
            load: c.w,
            lubricant: &c.lub,
            entrainment_speed: c.ue,
            reduced_radius: c.r,
            reduced_modulus: c.e,
            hertz_half_width: c.b,
            hertz_pressure: c.ph,
            initial_pressure: None,
        },
        smooth: &smooth,
        surfaces: vec![
            MovingSurface {
                surface: s1,
                shift0: 0.0,
                speed: c.ue * (1.0 + 0.5 * srr),
            },
            MovingSurface {
                surface: s2,
                shift0: 0.0,
                speed: c.ue * (1.0 - 0.5 * srr),
            },
        ],
        dt,
        steps,
    };
    let params = TransientParams {
        newton: EhlParams {
            tolerance: 1e-8,
            ..EhlParams::default()
        },
        scheme,
    };
    let mut out = Vec::new();
    let end = solve_transient(&problem, &params, &mut |s| {
        out.push(s.clone());
        ControlFlow::Continue(())
    });
    (grid, out, end)
}

fn none() -> Surface {
    Surface::new(vec![])
}

fn groove(width: f64, depth: f64, x: f64) -> Surface {
    Surface::new(vec![Feature::new(
        FeatureShape::Pit {
            width,
            length: f64::INFINITY,
            depth,
        },
        (x, 0.0),
    )])
}

fn waviness(amplitude: f64, wavelength: f64) -> Surface {
    Surface::new(vec![Feature::new(
        FeatureShape::Waviness {
            amplitude,
            wavelength,
        },
        (0.0, 0.0),
    )])
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Smooth surfaces in a transient run stay on the steady solution: the squeeze term of an
/// unchanging film is zero, so every step must reproduce step 0 to the Newton tolerance
/// (1e-8 relative residual; we allow 1e-6 p_h and 1e-6 of the film, two orders above it).
#[test]
fn smooth_transient_stays_on_the_steady_solution() {
    let c = line(20.0, 10.0);
    let dt = 0.01 * c.b / c.ue;
    let (_, steps, end) = run_line(
        &c,
        256,
        (-4.5, 1.5),
        0.5,
        &none(),
        &none(),
        dt,
        10,
        TimeScheme::Bdf2,
    );
    assert_eq!(
        end,
        TransientEnd::Completed {
            failed_steps: vec![]
        }
    );
    assert_eq!(steps.len(), 11);
    let s0 = &steps[0];
    let hc = s0.film[128];
    for s in &steps[1..] {
        assert!(s.converged, "step {}: {}", s.step, s.termination);
        let dp = max_abs_diff(&s.pressure, &s0.pressure) / c.ph;
        let dh = max_abs_diff(&s.film, &s0.film) / hc;
        assert!(
            dp < 1e-6 && dh < 1e-6,
            "step {}: dp {dp:e} dh {dh:e}",
            s.step
        );
    }
}

/// Film at x = 0 by linear interpolation between the two nearest cell centres.
fn film_at_centre(grid: &Grid, h: &[f64]) -> f64 {
    let s = (0.0 - grid.x_min) / grid.dx - 0.5;
    let i = s.floor() as usize;
    let t = s - i as f64;
    h[i] * (1.0 - t) + h[i + 1] * t
}

/// The deformed amplitude A_d of a waviness (wavelength `lambda_b` b, amplitude 5 % of the
/// central film) on body 1 in pure rolling: half the peak-to-peak of the film at X = 0 over the
/// last wavelength's passage, after the start's disturbance has left the contact.
fn amplitude_ratio(m: f64, l: f64, lambda_b: f64, nx: usize) -> (f64, f64) {
    let c = line(m, l);
    let (xin, xout) = (-4.5, 1.5);
    let (grid, s0, _) = run_line(
        &c,
        nx,
        (xin, xout),
        0.0,
        &none(),
        &none(),
        1.0,
        0,
        TimeScheme::Bdf2,
    );
    let hc = film_at_centre(&grid, &s0[0].film);
    let ai = 0.05 * hc;
    let lambda = lambda_b * c.b;
    // one cell per step; the start's disturbance travels at u_e from the inlet to the centre
    // (4.5 b), then one period is sampled
    let dt = grid.dx / c.ue;
    let flush = ((-xin) * c.b / grid.dx).ceil() as usize + 20;
    let period = (lambda / grid.dx).ceil() as usize;
    let (_, steps, end) = run_line(
        &c,
        nx,
        (xin, xout),
        0.0,
        &waviness(ai, lambda),
        &none(),
        dt,
        flush + period,
        TimeScheme::Bdf2,
    );
    assert_eq!(
        end,
        TransientEnd::Completed {
            failed_steps: vec![]
        }
    );
    let h: Vec<f64> = steps[flush..]
        .iter()
        .map(|s| film_at_centre(&grid, &s.film))
        .collect();
    let (lo, hi) = h
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let nabla = ehl::reference::waviness::line_nabla(lambda_b, m, l);
    (nabla, 0.5 * (hi - lo) / ai)
}

#[test]
fn waviness_amplitude_reduction_probe() {
    for &(m, l) in &[(20.0, 10.0)] {
        for &nabla in &[1.0, 3.0, 10.0] {
            let lambda_b = nabla * (l as f64).sqrt() / (m as f64).powf(0.75);
            let t = std::time::Instant::now();
            let (nb, ratio) = amplitude_ratio(m, l, lambda_b, 1024);
            println!(
                "M {m} L {l} nabla {nb:.2} lambda/b {lambda_b:.3}: Ad/Ai {ratio:.4} Venner {:.4} ({:.1} s)",
                ehl::reference::waviness::line_amplitude_ratio(nb),
                t.elapsed().as_secs_f64()
            );
        }
    }
}

#[test]
#[ignore]
fn cost_probe() {
    let c = line(20.0, 10.0);
    let nx = 1024;
    let grid = Grid::new(nx, 1, -4.5 * c.b, 1.5 * c.b, -0.5, 0.5);
    for tol in [1e-8, 1e-6] {
        let t = std::time::Instant::now();
        let (_, steps, _) = {
            let _ = tol;
            run_line(
                &c,
                nx,
                (-4.5, 1.5),
                0.0,
                &waviness(2e-8, c.b),
                &none(),
                grid.dx / c.ue,
                100,
                TimeScheme::Bdf2,
            )
        };
        let n: usize = steps[1..].iter().map(|s| s.newton_iterations).sum();
        let g: usize = steps[1..].iter().map(|s| s.linear_iterations).sum();
        let a: usize = steps[1..].iter().map(|s| s.operator_applications).sum();
        let w: f64 = steps[1..].iter().map(|s| s.wall_time).sum();
        println!("tol {tol}: {:.1} s total, steps {:.2} ms each, newton {n} gmres {g} applies {a} per 100 steps; first step wall {:.3}", t.elapsed().as_secs_f64(), w*10.0, steps[0].wall_time);
    }
}
