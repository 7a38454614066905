//! Transient EHL (thesis ch. 3): identities, mass conservation, and the amplitude reduction of
//! waviness against Venner et al. (1997).
mod common;
use common::*;
use ehl::case::{DensityModel, ViscosityModel};
use ehl::ehl::{
    solve_transient, EhlParams, MovingSurface, StepResult, TimeScheme, TransientEnd,
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
/// features (`s1`, `s2`, moving at u_e (1 +- srr/2)), `steps` steps of `dt` s; every step;
/// `transport`: the features' own transport (else the plain upwind wedge term).
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
    transport: bool,
) -> (Grid, Vec<StepResult>, TransientEnd) {
    let grid = Grid::new(nx, 1, xin * c.b, xout * c.b, -0.5, 0.5);
    let r = c.r;
    let smooth = move |x: f64, _y: f64| x * x / (2.0 * r);
    let e = c.e;
    let op = move |g: Grid| -> Box<dyn Deflection> { Box::new(FftDeflection::line(g, e)) };
    let problem = TransientProblem {
        base: c.problem(grid, &smooth, &op),
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
        feature_transport: transport,
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

/// The steady solution of the smooth line contact of [`run_line`] (no feature, no time step).
fn smooth_steady(c: &LineCase, nx: usize, x_range: (f64, f64), srr: f64) -> (Grid, StepResult) {
    let (grid, mut steps, _) = run_line(
        c,
        nx,
        x_range,
        srr,
        &none(),
        &none(),
        1.0,
        0,
        TimeScheme::Bdf2,
        true,
    );
    (grid, steps.remove(0))
}

/// Asserts that every step converged and stayed on `reference`: pressure within 1e-6 `ph`, film
/// within 1e-6 `hc`.
#[track_caller]
fn assert_every_step_on(steps: &[StepResult], reference: &StepResult, ph: f64, hc: f64) {
    for s in steps {
        assert!(s.converged, "step {}: {}", s.step, s.reason);
        let dp = max_abs_diff(&s.fields.pressure, &reference.fields.pressure) / ph;
        let dh = max_abs_diff(&s.fields.film, &reference.fields.film) / hc;
        assert!(
            dp < 1e-6 && dh < 1e-6,
            "step {}: dp {dp:e} dh {dh:e}",
            s.step
        );
    }
}

/// Smooth surfaces in a transient run stay on the steady solution: the squeeze term of an
/// unchanging film is zero, so every step must reproduce step 0 to the Newton tolerance
/// (1e-8 relative residual; we allow 1e-6 p_h and 1e-6 of the film, two orders above it).
#[test]
fn smooth_transient_stays_on_the_steady_solution() {
    let c = line(20.0, 10.0);
    let dt = 0.01 * c.b / c.ue;
    let (grid, steps, end) = run_line(
        &c,
        256,
        (-4.5, 1.5),
        0.5,
        &none(),
        &none(),
        dt,
        10,
        TimeScheme::Bdf2,
        true,
    );
    assert_eq!(
        end,
        TransientEnd::Completed {
            failed_steps: vec![]
        }
    );
    assert_eq!(steps.len(), 11);
    let s0 = &steps[0];
    assert_every_step_on(
        &steps[1..],
        s0,
        c.ph,
        film_at_centre(&grid, &s0.fields.film),
    );
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
fn amplitude_ratio(m: f64, l: f64, lambda_b: f64, nx: usize, transport: bool) -> (f64, f64) {
    let c = line(m, l);
    let (xin, xout) = (-4.5, 1.5);
    let (grid, s0) = smooth_steady(&c, nx, (xin, xout), 0.0);
    let hc = film_at_centre(&grid, &s0.fields.film);
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
        transport,
    );
    assert_eq!(
        end,
        TransientEnd::Completed {
            failed_steps: vec![]
        }
    );
    let h: Vec<f64> = steps[flush..]
        .iter()
        .map(|s| film_at_centre(&grid, &s.fields.film))
        .collect();
    let (lo, hi) = h
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let nabla = ehl::reference::waviness::line_nabla(lambda_b, m, l);
    (nabla, 0.5 * (hi - lo) / ai)
}

/// Amplitude reduction of waviness in pure rolling (Venner et al. 1997): short waves pass the
/// contact nearly undeformed, long ones are flattened, and at high load A_d / A_i is one function
/// of nabla = (lambda/b) M^(3/4) / L^(1/2), fitted as 1 / (1 + 0.17 nabla + 0.03 nabla^2).
/// Checked at M = 100, L = 10 (a heavily loaded, strongly piezoviscous contact) on 1024 cells,
/// one cell per step:
///
/// * nabla = 4 and 10: within 3 % of the fit. Measured 0.4705 / 0.1726 against 0.463 / 0.175
///   (1.6 / 1.6 %); grid-converged (4096 cells) 0.4627 / 0.1700, 0.1 / 3.1 % from the fit.
/// * nabla = 2 (lambda = 0.2 b, 34 cells a wavelength): the grid-converged ratio lies 9 % above
///   the fit (0.7515 / 0.7491 on 2048 / 4096 cells against 0.685; docs/pits.md), so the check
///   is the grid: 1024 cells within 3 % of 2048. Measured 0.7654 against 0.7515 (1.8 %). The
///   plain upwind transport of the features (`feature_transport = false`) gives 0.683 / 0.741 /
///   0.748 on 1024 / 2048 / 4096 cells: it met the fit on 1024 cells through its own damping of
///   short waves, and it fails this check by 8 %.
///
/// A missing or wrong squeeze term fails this by far: a film that follows each frozen gap
/// flattens every wavelength alike. At lower load (M = 10-20) or L = 5 the ratios lie further
/// above the fit (docs/pits.md, "Amplitude reduction"; the ignored
/// `waviness_amplitude_reduction_probe`).
#[test]
fn waviness_amplitude_reduction_follows_venner_at_high_load() {
    let (m, l) = (100.0f64, 10.0f64);
    let lambda_b = |nabla: f64| nabla * l.sqrt() / m.powf(0.75);
    for nabla in [4.0, 10.0] {
        let (nb, ratio) = amplitude_ratio(m, l, lambda_b(nabla), 1024, true);
        let fit = ehl::reference::waviness::line_amplitude_ratio(nb);
        println!("nabla {nb:.2}: A_d/A_i {ratio:.4}, fit {fit:.4}");
        assert!(
            (ratio / fit - 1.0).abs() < 0.03,
            "nabla {nb}: A_d/A_i {ratio} against the fit's {fit}"
        );
    }
    let (nb, coarse) = amplitude_ratio(m, l, lambda_b(2.0), 1024, true);
    let (_, fine) = amplitude_ratio(m, l, lambda_b(2.0), 2048, true);
    let fit = ehl::reference::waviness::line_amplitude_ratio(nb);
    println!("nabla {nb:.2}: A_d/A_i {coarse:.4} (1024 cells), {fine:.4} (2048), fit {fit:.4}");
    assert!(
        (coarse / fine - 1.0).abs() < 0.03,
        "nabla {nb}: A_d/A_i {coarse} on 1024 cells against {fine} on 2048"
    );
}

#[test]
#[ignore]
fn waviness_amplitude_reduction_probe() {
    let nx: usize = std::env::var("NX")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(512);
    // ML = "M,L;M,L" (default the two pairs of docs/pits.md), NABLA = "1,2,4,10"
    let pairs: Vec<(f64, f64)> = match std::env::var("ML") {
        Ok(v) => v
            .split(';')
            .map(|p| {
                let (m, l) = p.split_once(',').expect("ML = \"M,L;M,L\"");
                (m.trim().parse().unwrap(), l.trim().parse().unwrap())
            })
            .collect(),
        Err(_) => vec![(20.0, 10.0), (10.0, 5.0)],
    };
    let nablas: Vec<f64> = match std::env::var("NABLA") {
        Ok(v) => v.split(',').map(|s| s.trim().parse().unwrap()).collect(),
        Err(_) => vec![1.0, 2.0, 4.0, 10.0],
    };
    // PLAIN_TRANSPORT=1: the features carried by the plain upwind wedge term (the figures before
    // the features' own transport, docs/pits.md)
    let transport = std::env::var("PLAIN_TRANSPORT").is_err();
    for &(m, l) in &pairs {
        for &nabla in &nablas {
            let lambda_b = nabla * (l as f64).sqrt() / (m as f64).powf(0.75);
            let t = std::time::Instant::now();
            let (nb, ratio) = amplitude_ratio(m, l, lambda_b, nx, transport);
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
    // EHL_PROBE_NX (default 1024 and 2048), EHL_PROBE_STEPS (default 100)
    let c = line(20.0, 10.0);
    let nxs: Vec<usize> = match std::env::var("EHL_PROBE_NX") {
        Ok(v) => v.split(',').map(|s| s.trim().parse().unwrap()).collect(),
        Err(_) => vec![1024, 2048],
    };
    let nsteps: usize = std::env::var("EHL_PROBE_STEPS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(100);
    for nx in nxs {
        let grid = Grid::new(nx, 1, -4.5 * c.b, 1.5 * c.b, -0.5, 0.5);
        let t = std::time::Instant::now();
        let (_, steps, end) = run_line(
            &c,
            nx,
            (-4.5, 1.5),
            0.0,
            &waviness(2e-8, c.b),
            &none(),
            grid.dx / c.ue,
            nsteps,
            TimeScheme::Bdf2,
            true,
        );
        let k = nsteps as f64;
        let n: usize = steps[1..].iter().map(|s| s.newton_iterations).sum();
        let g: usize = steps[1..].iter().map(|s| s.linear_iterations).sum();
        let a: usize = steps[1..].iter().map(|s| s.operator_applications).sum();
        let w: f64 = steps[1..].iter().map(|s| s.wall_time).sum();
        let worst = steps[1..]
            .iter()
            .map(|s| s.residual.max(s.load_error.abs()))
            .fold(0.0, f64::max);
        println!(
            "nx {nx}: {nsteps} steps {:.2} s total ({:.3} s steady start); per step {:.2} ms, newton {:.2} gmres {:.1} applies {:.1}; worst residual {worst:.1e}; {end:?}",
            t.elapsed().as_secs_f64(),
            steps[0].wall_time,
            w / k * 1e3,
            n as f64 / k,
            g as f64 / k,
            a as f64 / k,
        );
    }
}

/// A groove of zero depth is no feature: every step reproduces the smooth steady solution
/// (the squeeze term of an unchanged film is zero). Same bound as the smooth run above.
#[test]
fn zero_depth_groove_reproduces_the_smooth_solution() {
    let c = line(20.0, 10.0);
    let nx = 256;
    let dx = 6.0 * c.b / nx as f64;
    let (_, steps, end) = run_line(
        &c,
        nx,
        (-4.5, 1.5),
        0.5,
        &groove(0.5 * c.b, 0.0, -1.0 * c.b),
        &none(),
        dx / (1.25 * c.ue),
        20,
        TimeScheme::Bdf2,
        true,
    );
    assert!(matches!(end, TransientEnd::Completed { ref failed_steps } if failed_steps.is_empty()));
    let (grid, smooth) = smooth_steady(&c, nx, (-4.5, 1.5), 0.5);
    assert_every_step_on(
        &steps,
        &smooth,
        c.ph,
        film_at_centre(&grid, &smooth.fields.film),
    );
}

/// A groove on a body that stands still (SRR = 2: u2 = 0, the groove on body 2) is a steady
/// problem: the run starts on the steady solution with the groove in place and must stay there
/// (nothing moves, so the squeeze term is zero at the solution), while the other body slides.
#[test]
fn feature_on_a_standing_body_stays_on_its_steady_solution() {
    let c = line(20.0, 10.0);
    let nx = 256;
    let dx = 6.0 * c.b / nx as f64;
    let g = groove(0.4 * c.b, 0.3e-6, -0.2 * c.b);
    let (grid, steps, end) = run_line(
        &c,
        nx,
        (-4.5, 1.5),
        2.0,
        &none(),
        &g,
        dx / c.ue,
        20,
        TimeScheme::Bdf2,
        true,
    );
    assert!(matches!(end, TransientEnd::Completed { ref failed_steps } if failed_steps.is_empty()));
    let s0 = &steps[0];
    let hc = film_at_centre(&grid, &s0.fields.film);
    // the groove changes the steady film: the identity is not the smooth solution (by more
    // than 0.1 h_c; measured 0.24 h_c, the groove 0.3 um deep)
    let (_, smooth) = smooth_steady(&c, nx, (-4.5, 1.5), 2.0);
    let changed = max_abs_diff(&s0.fields.film, &smooth.fields.film) / hc;
    assert!(
        changed > 0.1,
        "the groove changed the film by {changed} h_c only"
    );
    assert_every_step_on(&steps[1..], s0, c.ph, hc);
}

/// Mass: at every step of a groove's passage (the groove on the faster body, SRR = 0.5), the
/// discrete balance of the pressurised zone, inflow - outflow - side leakage = d(mass)/dt, holds.
#[test]
fn mass_is_conserved_at_every_step_of_a_groove_passage() {
    let c = line(20.0, 10.0);
    let nx = 256;
    let dx = 6.0 * c.b / nx as f64;
    let u1 = 1.25 * c.ue;
    let steps_n = (4.0 * c.b / dx) as usize;
    let (_, steps, end) = run_line(
        &c,
        nx,
        (-4.5, 1.5),
        0.5,
        &groove(0.5 * c.b, 0.3e-6, -2.5 * c.b),
        &none(),
        dx / u1,
        steps_n,
        TimeScheme::Bdf2,
        true,
    );
    assert!(matches!(end, TransientEnd::Completed { ref failed_steps } if failed_steps.is_empty()));
    // The imbalance is the sum of the converged cell residuals over the wet cells: with the
    // Newton tolerance 1e-8 per (scaled) row on ~150 wet cells it is ~1e-6 of the flows
    // (measured: 2.8e-6 of the inflow, while the storage reaches 27 times the inflow as the
    // groove's volume enters). A storage term inconsistent with the residual's squeeze term
    // (a wrong c0 or history) would leave an O(1) imbalance. Bound: 1e-5 of the largest flow.
    let mut storage_seen = 0.0f64;
    for s in &steps {
        let m = s.mass;
        let scale = m.inflow.abs().max(m.outflow.abs()).max(m.storage.abs());
        let r = (m.inflow - m.outflow - m.side_leakage - m.storage).abs() / scale;
        assert!(
            r < 1e-5,
            "step {}: imbalance {r:e} of the largest flow ({m:?})",
            s.step
        );
        storage_seen = storage_seen.max(m.storage.abs() / m.inflow);
    }
    // the groove's passage does move mass in and out of the zone (the test is not vacuous)
    assert!(storage_seen > 1.0, "storage / inflow {storage_seen}");
}

/// Dominant wavelength (in b) of `v` sampled at `x` (in b) within `lo..hi`: the Λ in 0.1 .. 1.5 b
/// that maximises the windowed Fourier amplitude (scan, then a parabola through the best three).
fn dominant_wavelength(x: &[f64], v: &[f64], (lo, hi): (f64, f64)) -> f64 {
    let pts: Vec<(f64, f64)> = x
        .iter()
        .zip(v)
        .filter(|(x, _)| **x >= lo && **x <= hi)
        .map(|(a, b)| (*a, *b))
        .collect();
    let mean = pts.iter().map(|p| p.1).sum::<f64>() / pts.len() as f64;
    let amp = |lam: f64| {
        let (mut c, mut s) = (0.0, 0.0);
        for &(xi, vi) in &pts {
            // Hann window over lo..hi
            let w = 0.5 - 0.5 * (2.0 * std::f64::consts::PI * (xi - lo) / (hi - lo)).cos();
            let ph = 2.0 * std::f64::consts::PI * xi / lam;
            c += w * (vi - mean) * ph.cos();
            s += w * (vi - mean) * ph.sin();
        }
        (c * c + s * s).sqrt()
    };
    let grid: Vec<f64> = (0..=1400).map(|k| 0.1 + k as f64 * 0.001).collect();
    let a: Vec<f64> = grid.iter().map(|&l| amp(l)).collect();
    let k = (1..a.len() - 1)
        .max_by(|&i, &j| a[i].total_cmp(&a[j]))
        .unwrap();
    let (y0, y1, y2) = (a[k - 1], a[k], a[k + 1]);
    grid[k] + 0.5 * 0.001 * (y0 - y2) / (y0 - 2.0 * y1 + y2)
}

/// Shift (in cells, continuous) that best maps `a` onto `b` within the index range `r`:
/// the least-squares shift of linear interpolation, scanned in 0.01-cell steps.
fn best_shift(a: &[f64], b: &[f64], r: std::ops::Range<usize>, max: f64) -> f64 {
    let at = |v: &[f64], s: f64| {
        let i = s.floor() as usize;
        let t = s - i as f64;
        v[i] * (1.0 - t) + v[i + 1] * t
    };
    let mut best = (f64::INFINITY, 0.0);
    let mut s = 0.0;
    while s <= max {
        let e: f64 = r
            .clone()
            .map(|i| (b[i] - at(a, i as f64 - s)).powi(2))
            .sum();
        if e < best.0 {
            best = (e, s);
        }
        s += 0.01;
    }
    best.1
}

/// Rolling with sliding (Greenwood & Morales-Espejel 1994; Hooke 2006; Venner & Lubrecht 2000
/// ch. 13): a waviness of wavelength lambda on a body moving at u_body leaves in the film a
/// ripple that travels with the mean speed u_e, so its wavelength in the contact is
/// lambda u_e / u_body. Measured from the frames: the dominant wavelength of the film change
/// over -0.8 .. 0.8 b, and the shift of that change between two frames `lag` steps apart.
/// Returns (ripple wavelength / expected, disturbance speed / u_e).
fn ripple(srr: f64, lambda_b: f64) -> (f64, f64) {
    let c = line(20.0, 10.0);
    let nx = 384;
    let (xin, xout) = (-4.5, 1.5);
    let dx = (xout - xin) / nx as f64; // in b
    let u1 = c.ue * (1.0 + 0.5 * srr);
    let (grid, s0) = smooth_steady(&c, nx, (xin, xout), srr);
    let hc = film_at_centre(&grid, &s0.fields.film);
    // the surface moves one cell per step; the start's disturbance leaves the contact centre
    // after about 3 b / u_e
    let dt = dx * c.b / u1;
    let flush = (3.0 * u1 / c.ue / dx) as usize;
    // the ripple repeats every lambda u_e / u_body: a lag of 0.4 of that keeps the shift
    // unambiguous (ripple shift per step: u_e dt = u_e / u1 cells)
    let ripple_cells = lambda_b * c.ue / u1 / dx;
    let lag = (0.4 * ripple_cells * u1 / c.ue).round() as usize;
    let (_, steps, end) = run_line(
        &c,
        nx,
        (xin, xout),
        srr,
        &waviness(0.05 * hc, lambda_b * c.b),
        &none(),
        dt,
        flush + lag,
        TimeScheme::Bdf2,
        true,
    );
    assert!(matches!(end, TransientEnd::Completed { ref failed_steps } if failed_steps.is_empty()));
    let xs: Vec<f64> = (0..nx).map(|i| grid.x(i) / c.b).collect();
    let dh = |s: &StepResult| -> Vec<f64> {
        s.fields
            .film
            .iter()
            .zip(&s0.fields.film)
            .map(|(a, b)| a - b)
            .collect()
    };
    let (ha, hb) = (dh(&steps[flush]), dh(&steps[flush + lag]));
    let lam = dominant_wavelength(&xs, &hb, (-0.8, 0.8));
    let r = ((-0.6 - xin) / dx) as usize..((0.6 - xin) / dx) as usize;
    let shift = best_shift(&ha, &hb, r, 0.5 * ripple_cells);
    let speed = shift * dx * c.b / (lag as f64 * dt);
    (lam / (lambda_b * c.ue / u1), speed / c.ue)
}

/// Tolerance 5 %: the 1.6 b window holds 3-5 ripple wavelengths, so the Fourier peak is located
/// to a few per cent (measured: +2.3 % at SRR = 1); the shift over 30 steps is resolved to
/// 0.01 cell of ~20 cells, but the part of the film change that follows the surface (at u_body)
/// biases it (measured +1.4 %). The alternatives the test rules out are 33-100 % away: a ripple
/// with the surface's own wavelength, or a disturbance moving with the surface.
#[test]
fn film_ripple_travels_at_the_mean_speed_with_wavelength_lambda_ue_over_u_body() {
    for (srr, lambda_b) in [(1.0, 0.5), (-0.8, 0.3)] {
        let (wave, speed) = ripple(srr, lambda_b);
        println!(
            "SRR {srr}: ripple wavelength {wave:.4} of lambda u_e / u_body, speed {speed:.4} u_e"
        );
        assert!(
            (wave - 1.0).abs() < 0.05 && (speed - 1.0).abs() < 0.05,
            "SRR {srr}: ripple wavelength {wave} of lambda u_e / u_body, speed {speed} u_e"
        );
    }
}

/// A groove on body 2 at SRR 1.9 (body 2 at 0.05 u_e, the slowest body whose features are carried
/// by their own transport, `ehl::transient::TRANSPORT_MIN_SPEED`): the peak pressure over the
/// passage is the same on twice the cells (and steps), within 1 %, and every step converges.
/// Measured 1.1167 / 1.1189 GPa (0.2 %); the plain rule (the constant at 0.5, as first chosen)
/// gives 1.1564 / 1.1390 GPa (1.5 %) and fails.
#[test]
fn a_groove_on_a_slow_body_is_carried_consistently() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/ehl_transient_line_groove.toml");
    let peak = |nx: usize| {
        let set: Vec<String> = [
            "features[0].body=2".to_string(),
            "motion.slide_to_roll=1.9".into(),
            format!("grid.nx={nx}"),
            format!("motion.travel.steps={}", nx * 200 / 512),
            "output.snapshots=[]".into(),
        ]
        .to_vec();
        let case = ehl::case::load_file(&path, &set).expect("example case");
        let s = ehl::run::solve(&case, &ehl::run::Silent).unwrap().summary;
        assert!(s.converged, "{}", s.termination);
        s.max_pressure_over_travel_pa.unwrap()
    };
    let (coarse, fine) = (peak(512), peak(1024));
    assert!(
        (coarse / fine - 1.0).abs() < 0.01,
        "{coarse} Pa on 512 cells against {fine} Pa on 1024"
    );
}

// ------------------------------------------------------------------ 2D: finite roller and ball

/// An example case solved through `run::solve` with `--set` style overrides.
fn solve_example(name: &str, sets: &[&str]) -> ehl::solution::Solution {
    solve_example_edited(name, &|t| t.to_string(), sets)
}

/// The example's text as `edit` leaves it (to take a table or a key out), then solved.
fn solve_example_edited(
    name: &str,
    edit: &dyn Fn(&str) -> String,
    sets: &[&str],
) -> ehl::solution::Solution {
    let path = format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = edit(&std::fs::read_to_string(&path).expect("example"));
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let case = ehl::case::parse_str(&text, &path, &sets).expect("valid case");
    ehl::run::solve(&case, &ehl::run::Silent).expect("solved")
}

/// A case text without its `travel = ...` line: the steady case.
fn without_travel(t: &str) -> String {
    t.lines()
        .filter(|l| !l.trim_start().starts_with("travel"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// A case text without its `[[features]]` tables (up to the next table).
fn without_features(t: &str) -> String {
    let mut out = Vec::new();
    let mut skip = false;
    for l in t.lines() {
        let head = l.trim_start();
        if head.starts_with('[') {
            skip = head.starts_with("[[features]]");
        }
        if !skip {
            out.push(l);
        }
    }
    out.join("\n")
}

/// Every kept frame of a 2D transient run against `reference` (pressure, film): the largest
/// difference relative to the largest pressure and to the thinnest film.
fn frames_off(sol: &ehl::solution::Solution, reference: (&[f64], &[f64])) -> (f64, f64) {
    let t = sol.transient.as_ref().expect("a transient run");
    let ph = reference.0.iter().cloned().fold(0.0, f64::max);
    // the thinnest film: the strictest scale for the film's differences
    let hmin = reference
        .1
        .iter()
        .cloned()
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold(f64::INFINITY, f64::min);
    let (mut dp, mut dh) = (0.0_f64, 0.0_f64);
    for f in &t.frames {
        for k in 0..f.pressure.len() {
            dp = dp.max((f.pressure[k] - reference.0[k]).abs() / ph);
            if reference.1[k].is_finite() {
                dh = dh.max((f.film[k] - reference.1[k]).abs() / hmin);
            }
        }
    }
    (dp, dh)
}

/// The identities on a finite roller (mirror images, psi) and a ball, through the whole run
/// (`run::solve`): a pit of zero depth passing through the thesis roller reproduces the smooth
/// steady solution at every step, and a dent on a ball's flat that stands still (SRR = 2, the
/// dent on body 2, `travel = { duration, steps }`) stays on the steady solution with the dent in
/// place, which a steady run of the same case gives. Asked: 1e-6 of the peak pressure and of
/// the thinnest film, two orders above the Newton tolerance (1e-8 here) as on the line above.
#[test]
fn identities_hold_on_a_finite_roller_and_a_ball() {
    let roller = [
        "grid.nx=64",
        "grid.ny=64",
        "solver.tolerance=1e-8",
        "features[0].depth=0.0",
        "motion.travel={from=-0.6e-3,to=0.2e-3,steps=8}",
        "output.snapshots=[]",
    ];
    let sol = solve_example("ehl_thesis_ch3_single_pit.toml", &roller);
    let t = sol.transient.as_ref().unwrap();
    assert!(t.timeline.iter().all(|s| s.converged) && t.frames.len() == 9);
    // the smooth steady case: the example without its travel and its feature
    let smooth: Vec<&str> = roller
        .iter()
        .copied()
        .filter(|s| !s.starts_with("motion.travel") && !s.starts_with("features"))
        .collect();
    let steady = solve_example_edited(
        "ehl_thesis_ch3_single_pit.toml",
        &|t| without_travel(&without_features(t)),
        &smooth,
    );
    let (dp, dh) = frames_off(
        &sol,
        (
            &steady.fields.pressure,
            steady.fields.film.as_ref().unwrap(),
        ),
    );
    eprintln!("roller, zero-depth pit: dp {dp:.1e} dh {dh:.1e}");
    assert!(dp < 1e-6 && dh < 1e-6, "roller: dp {dp:e} dh {dh:e}");
    // the check can fail: the thesis' 25 nm pit moves the solution well past it
    let mut pitted = roller.to_vec();
    pitted[3] = "features[0].depth=2.5e-8";
    let (dp, dh) = frames_off(
        &solve_example("ehl_thesis_ch3_single_pit.toml", &pitted),
        (
            &steady.fields.pressure,
            steady.fields.film.as_ref().unwrap(),
        ),
    );
    assert!(dp > 1e-4 && dh > 1e-3, "25 nm pit: dp {dp:e} dh {dh:e}");

    let ball = [
        "grid.nx=48",
        "grid.ny=48",
        "solver.tolerance=1e-8",
        "features[0].body=2",
        "features[0].x=-0.05e-3",
        "motion.slide_to_roll=2.0",
        "output.snapshots=[]",
    ];
    let mut moving = ball.to_vec();
    moving.push("motion.travel={duration=2e-3,steps=6}");
    let sol = solve_example("ehl_transient_ball_dent.toml", &moving);
    let t = sol.transient.as_ref().unwrap();
    assert!(t.timeline.iter().all(|s| s.converged) && t.frames.len() == 7);
    let steady = solve_example_edited("ehl_transient_ball_dent.toml", &without_travel, &ball);
    assert!(steady.transient.is_none());
    let (dp, dh) = frames_off(
        &sol,
        (
            &steady.fields.pressure,
            steady.fields.film.as_ref().unwrap(),
        ),
    );
    eprintln!("ball, dent on the flat at rest: dp {dp:.1e} dh {dh:.1e}");
    assert!(dp < 1e-6 && dh < 1e-6, "ball: dp {dp:e} dh {dh:e}");
    // the identity is not the smooth solution: the dent changes the steady film
    let smooth = solve_example_edited(
        "ehl_transient_ball_dent.toml",
        &|t| without_travel(&without_features(t)),
        &ball[..3],
    );
    let (_, dh) = frames_off(
        &sol,
        (
            &smooth.fields.pressure,
            smooth.fields.film.as_ref().unwrap(),
        ),
    );
    assert!(
        dh > 0.05,
        "the dent leaves the film within {dh:e} of the smooth one"
    );
}

/// A time step predicted within sqrt(tol) of its solution ends in one Newton step: its first
/// linear solve goes as far as the tolerance needs (`ehl::transient`, `step_first_eta`), not to
/// the loosest forcing term, after which a second step followed. The thesis pit on the finite
/// rollers at 64^2, 12 steps: once the pit has passed the inlet (the 6th step on) every step
/// took 2 Newton steps with the first solved to 0.1 and takes 1 now (28 -> 21 in all). The
/// total is asserted, not each step: the bound, 24, fails with the first step to 0.1
/// throughout and leaves room for a step or two of drift elsewhere (the predictor, the
/// preconditioner).
#[test]
fn a_time_step_predicted_near_its_solution_takes_one_newton_step() {
    let sol = solve_example(
        "ehl_thesis_ch3_single_pit.toml",
        &[
            "grid.nx=64",
            "grid.ny=64",
            "motion.travel={from=-0.6e-3,to=0.3e-3,steps=12}",
            "output.snapshots=[]",
        ],
    );
    let t = sol.transient.as_ref().unwrap();
    let newton: Vec<usize> = t.timeline[1..]
        .iter()
        .map(|s| s.newton_iterations)
        .collect();
    eprintln!("Newton steps per time step: {newton:?}");
    assert!(t.timeline.iter().all(|s| s.converged));
    assert!(newton.iter().sum::<usize>() <= 24, "{newton:?}");
}

/// Mass on a finite roller: a 1 um pit passing through the thesis roller (mirror images, psi,
/// side leakage at the ends), the discrete balance inflow - outflow - side leakage = d(mass)/dt
/// at every step, relative to the inflow. The balance is the residual summed over the
/// pressurised zone, each row solved to the Newton tolerance 1e-6 here (the line's test asks
/// 1e-5 of a solve to 1e-8): asked 1e-4 for the sum over the wet cells, measured 4.1e-7.
#[test]
fn mass_is_conserved_at_every_step_on_a_finite_roller() {
    let sol = solve_example(
        "ehl_thesis_ch3_single_pit.toml",
        &[
            "grid.nx=64",
            "grid.ny=64",
            "features[0].depth=1e-6",
            "motion.travel={from=-0.6e-3,to=0.3e-3,steps=12}",
            "output.snapshots=[]",
        ],
    );
    let t = sol.transient.as_ref().unwrap();
    let worst = t
        .timeline
        .iter()
        .map(|s| s.mass_balance.abs())
        .fold(0.0, f64::max);
    let leak = t
        .timeline
        .iter()
        .map(|s| s.side_leakage_kg_s.abs())
        .fold(0.0, f64::max);
    let storage = t
        .timeline
        .iter()
        .map(|s| s.mass_storage_kg_s.abs() / s.mass_inflow_kg_s)
        .fold(0.0, f64::max);
    eprintln!("roller, 1 um pit: worst mass balance {worst:.1e}, side leakage up to {leak:.2e} kg/s, storage up to {storage:.2e} of the inflow");
    assert!(t.timeline.iter().all(|s| s.converged));
    // the balance is not trivially closed: both the ends and the pit's squeeze carry mass,
    // the squeeze far more than the balance's error (measured 1.2e-2 of the inflow)
    assert!(
        leak > 0.0 && storage > 1e-3,
        "leakage {leak}, storage {storage}"
    );
    assert!(worst < 1e-4, "{worst:e}");
}
