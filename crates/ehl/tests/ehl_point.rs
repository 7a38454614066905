//! Ball on flat (circular point contact): film against EHL-FBNS and Hamrock-Dowson.
mod common;
use common::*;
use ehl::case::{DensityModel, ViscosityModel};
use ehl::ehl::{solve_steady, EhlParams, EhlProblem, EhlResult};
use ehl::elastic::{Deflection, FftDeflection};
use ehl::grid::Grid;
use ehl::units;

/// Ball R on a flat: E' (Pa), load (N), u_e (m/s), eta0, alpha, on n x n cells over [-3a, 3a]^2.
#[allow(clippy::too_many_arguments)]
fn solve_ball(
    r: f64,
    e: f64,
    f: f64,
    ue: f64,
    eta0: f64,
    alpha: f64,
    n: usize,
) -> (EhlResult, Grid, f64, f64) {
    let hz = units::hertz_point(f, r, e);
    let lub = lubricant(
        eta0,
        alpha,
        ViscosityModel::Roelands,
        DensityModel::DowsonHigginson,
    );
    let a = hz.a;
    let grid = Grid::new(n, n, -3.0 * a, 3.0 * a, -3.0 * a, 3.0 * a);
    let gap = move |x: f64, y: f64| (x * x + y * y) / (2.0 * r);
    let op = move |g: Grid| -> Box<dyn Deflection> { Box::new(FftDeflection::half_space(g, e)) };
    let prob = EhlProblem {
        grid,
        gap: &gap,
        operator: &op,
        load: f,
        lubricant: &lub,
        entrainment_speed: ue,
        reduced_radius: r,
        reduced_modulus: e,
        hertz_half_width: a,
        hertz_pressure: hz.p0,
        initial_pressure: None,
    };
    (solve_steady(&prob, &EhlParams::default()), grid, a, hz.p0)
}

/// Issue 3 reference: EHL-FBNS (Habchi's full-system finite-element code; Roelands + Dowson-Higginson)
/// for a ball R = 12.5 mm on glass, E' = 110 GPa, F = 15 N, u_m = 0.09 m/s, eta0 = 0.25 Pa s,
/// alpha = 22 GPa^-1, 129^2 cells on [-3a, 3a]^2 (a = 136.5 um): h_c = 225.8 nm,
/// h_min = 125.5 nm, p_max = 0.388 GPa. Tolerances 3 % (h_c) and 6 % (h_min): two different
/// discretisations (FE vs finite volumes) at this resolution; the minimum film sits in the
/// narrow side lobes and is the less resolved quantity.
///
/// IGNORED (open): the solver converges (14 Newton steps, 566 GMRES iterations) but gives
/// h_c = 207.1 nm (-8.3 %), h_min = 116.7 nm (-7.0 %), p_max = 0.3855 GPa (-0.6 %) at 129^2 and
/// h_c = 211.1 nm, h_min = 119.0 nm at 256^2: the films grow with refinement but stay ~5 % thin.
/// Run: `cargo test -p ehl --test ehl_point -- --ignored --nocapture`.
#[test]
#[ignore]
fn ball_on_glass_against_ehl_fbns() {
    let t = std::time::Instant::now();
    let (res, grid, a, _p0) = solve_ball(0.0125, 110e9, 15.0, 0.09, 0.25, 22e-9, 129);
    println!(
        "a = {:.1} um; {} Newton {} GMRES {} ops {} stages {} res {:.2e} in {:.2} s",
        a * 1e6,
        res.termination,
        res.iterations,
        res.linear_iterations,
        res.operator_applications,
        res.continuation_stages,
        res.residual,
        t.elapsed().as_secs_f64()
    );
    assert!(res.converged, "{}", res.termination);
    let kc = grid.idx(grid.nx / 2, grid.ny / 2);
    let hc = res.film[kc];
    let hmin = res.film.iter().cloned().fold(f64::INFINITY, f64::min);
    let pmax = res.pressure.iter().cloned().fold(0.0, f64::max);
    println!(
        "h_c {:.1} nm (225.8), h_min {:.1} nm (125.5), p_max {:.4} GPa (0.388)",
        hc * 1e9,
        hmin * 1e9,
        pmax / 1e9
    );
    assert!((hc / 225.8e-9 - 1.0).abs() < 0.03);
    assert!((hmin / 125.5e-9 - 1.0).abs() < 0.06);
}

/// The same ball against Hamrock & Dowson (1977) (Roelands + Dowson-Higginson, the laws of the
/// fit), 129^2 cells: central and minimum film within 15 % (the fit's scatter against its own
/// data is 5-8 %, plus the discretisation error of the coarse grid, which thins the film by
/// ~3 % between 256^2 and 129^2). Load balance 1e-6, symmetric about y = 0 to 1e-6 relative.
#[test]
fn ball_against_hamrock_dowson() {
    let (r, e, f, ue, eta0, alpha) = (0.0125, 110e9, 15.0, 0.09, 0.25, 22e-9);
    let (res, grid, _a, _p0) = solve_ball(r, e, f, ue, eta0, alpha, 129);
    assert!(res.converged, "{}", res.termination);
    assert!(res.load_error.abs() < 1e-6);
    let (w, u, g) = (f / (e * r * r), eta0 * ue / (e * r), alpha * e);
    let hc_ref = ehl::reference::film::hamrock_dowson_central(w, u, g, 1.0) * r;
    let hm_ref = ehl::reference::film::hamrock_dowson_min(w, u, g, 1.0) * r;
    let hc = res.film[grid.idx(grid.nx / 2, grid.ny / 2)];
    let hmin = res.film.iter().cloned().fold(f64::INFINITY, f64::min);
    println!(
        "h_c {:.1} nm vs HD {:.1}; h_min {:.1} nm vs HD {:.1}",
        hc * 1e9,
        hc_ref * 1e9,
        hmin * 1e9,
        hm_ref * 1e9
    );
    assert!((hc / hc_ref - 1.0).abs() < 0.15);
    assert!((hmin / hm_ref - 1.0).abs() < 0.15);
    let pmax = res.pressure.iter().cloned().fold(0.0, f64::max);
    for j in 0..grid.ny / 2 {
        for i in 0..grid.nx {
            let (a, b) = (
                res.pressure[grid.idx(i, j)],
                res.pressure[grid.idx(i, grid.ny - 1 - j)],
            );
            assert!(
                (a - b).abs() < 1e-6 * pmax,
                "asymmetric at ({i}, {j}): {a} vs {b}"
            );
        }
    }
}
