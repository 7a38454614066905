//! Infinite line contact (ny == 1): film against the classical fits, grid convergence.
mod common;
use common::*;
use ehl::case::{DensityModel, ViscosityModel};
use ehl::ehl::{EhlParams, EhlResult};
use ehl::elastic::{Deflection, FftDeflection};
use ehl::grid::Grid;

pub fn solve_line(c: &LineCase, nx: usize, xin: f64, xout: f64) -> (EhlResult, Grid) {
    solve_line_p(c, nx, xin, xout, &EhlParams::default())
}

pub fn solve_line_p(
    c: &LineCase,
    nx: usize,
    xin: f64,
    xout: f64,
    par: &EhlParams,
) -> (EhlResult, Grid) {
    solve_line_observed(c, nx, xin, xout, par, &mut |_| {})
}

/// [`solve_line_p`] telling `observer` of every Newton iterate.
pub fn solve_line_observed(
    c: &LineCase,
    nx: usize,
    xin: f64,
    xout: f64,
    par: &EhlParams,
    observer: &mut (dyn FnMut(&ehl::ehl::NewtonIterate) + Send),
) -> (EhlResult, Grid) {
    let grid = Grid::new(nx, 1, xin * c.b, xout * c.b, -0.5, 0.5);
    let r = c.r;
    let gap = move |x: f64, _y: f64| x * x / (2.0 * r);
    let e = c.e;
    let op = move |g: Grid| -> Box<dyn Deflection> { Box::new(FftDeflection::line(g, e)) };
    let prob = c.problem(grid, &gap, &op);
    (ehl::ehl::solve_steady_observed(&prob, par, observer), grid)
}

fn centre_index(grid: &Grid) -> usize {
    (0..grid.nx)
        .min_by(|&a, &b| grid.x(a).abs().total_cmp(&grid.x(b).abs()))
        .unwrap()
}

/// Mean-speed groups (W, U, G) of a case.
fn groups(c: &LineCase) -> (f64, f64, f64) {
    (
        c.w / (c.e * c.r),
        c.lub.viscosity * c.ue / (c.e * c.r),
        c.lub.pressure_viscosity_coefficient * c.e,
    )
}

/// The (M, L) table of the film tests: M 10..100, L 3..20, restricted to realistic Hertz pressures
/// (alpha p_h = L sqrt(M / 2 pi) <= ~40, i.e. p_h <= 2 GPa at alpha = 20 GPa^-1; see the report for
/// M >= 300).
const TABLE: [(f64, f64); 8] = [
    (10.0, 3.0),
    (20.0, 6.0),
    (20.0, 10.0),
    (50.0, 10.0),
    (100.0, 3.0),
    (100.0, 5.0),
    (100.0, 10.0),
    (30.0, 20.0),
];

/// Every field finite and an honest report, whatever the outcome: the solver is stopped after
/// two Newton steps without continuation on a case that needs more (M = 100, L = 10 takes ~10),
/// so it must say it did not converge and still return finite fields.
#[test]
fn reports_honestly_and_never_nan() {
    let c = line_case(
        100.0,
        10.0,
        ViscosityModel::Roelands,
        DensityModel::DowsonHigginson,
    );
    let par = EhlParams {
        max_iterations: 2,
        continuation: false,
        ..EhlParams::default()
    };
    let (res, _) = solve_line_p(&c, 256, -4.5, 1.5, &par);
    for (name, f) in [
        ("p", &res.fields.pressure),
        ("h", &res.fields.film),
        ("eta", &res.fields.viscosity),
        ("rho", &res.fields.density),
    ] {
        assert!(
            f.iter().all(|v| v.is_finite()),
            "{name} not finite: {} {:?}",
            res.termination,
            &f[..4]
        );
    }
    assert!(res.residual.is_finite() && res.load_error.is_finite() && res.fields.h0.is_finite());
    assert!(
        !res.converged && res.termination != "converged",
        "{}",
        res.termination
    );
    assert!(res.residual > par.tolerance);
}

/// Central film against Moes (Barus viscosity and an incompressible lubricant: the assumptions of
/// the fit), 512 cells on [-4.5 b, 1.5 b]. 10 %: the accuracy claimed for the fit (Venner &
/// Lubrecht 2000 ch. 4) plus the discretisation error (< 1 %, see the grid test); measured
/// 0.1 to 7.0 % (the largest at M = 100, L = 3).
/// Also: converged to the default tolerance, the returned pressure carrying the load to 1e-6
/// (the solve's tolerance, on the same balance), inflow = outflow (mass balance of the flux
/// form to 1e-4 of the inflow).
#[test]
fn central_film_against_moes() {
    let mut worst: f64 = 0.0;
    for &(m, l) in &TABLE {
        let c = line_case(m, l, ViscosityModel::Barus, DensityModel::Constant);
        let (res, grid) = solve_line(&c, 512, -4.5, 1.5);
        assert!(res.converged, "M {m} L {l}: {}", res.termination);
        // the load the returned pressure carries, integrated here over its cells (the
        // uniform-pressure elements' rectangle rule the solver balances: a check that the
        // returned field is the balanced one, at the solve's tolerance)
        let carried = res.fields.pressure.iter().sum::<f64>() * grid.dx;
        assert!(
            (carried / c.w - 1.0).abs() < 1e-6,
            "M {m} L {l}: carried {carried} N/m of {}",
            c.w
        );
        assert!(
            (res.inflow - res.outflow).abs() < 1e-4 * res.inflow,
            "M {m} L {l}: {} vs {}",
            res.inflow,
            res.outflow
        );
        let (w, u, g) = groups(&c);
        let hm = ehl::reference::film::moes_line_central_film(w, u, g) * c.r;
        let e = res.fields.film[centre_index(&grid)] / hm - 1.0;
        println!(
            "M {m:5} L {l:4}: h_c / Moes = {:.4}  (Newton {}, GMRES {})",
            1.0 + e,
            res.iterations,
            res.linear_iterations
        );
        worst = worst.max(e.abs());
        assert!(
            e.abs() < 0.10,
            "M {m} L {l}: {} vs {}",
            res.fields.film[centre_index(&grid)],
            hm
        );
    }
    println!("worst deviation from Moes: {:.1} %", 100.0 * worst);
}

/// Minimum and central film against Pan & Hamrock (Roelands + Dowson-Higginson, the laws of that
/// fit). 15 % on the minimum film: the fit's stated scatter (~5-10 %) plus the discretisation
/// error of the outlet constriction at 512 cells (~1.5 %, grid test), with a margin: measured
/// -3.9 to +11.8 %, the largest at M = 30, L = 20 (p_h 2.2 GPa, the edge of the fit's data).
/// The central film is printed only: Pan-Hamrock's central fit is 20 % off at L = 20 (Moes,
/// above, is the central reference).
#[test]
fn films_against_pan_hamrock() {
    for &(m, l) in &TABLE {
        let c = line_case(
            m,
            l,
            ViscosityModel::Roelands,
            DensityModel::DowsonHigginson,
        );
        let (res, grid) = solve_line(&c, 512, -4.5, 1.5);
        assert!(res.converged, "M {m} L {l}: {}", res.termination);
        let (w, u, g) = groups(&c);
        let hmin = thinnest(&res.fields.film);
        let rmin = hmin / (ehl::reference::film::pan_hamrock_min(w, u, g) * c.r);
        let rc = res.fields.film[centre_index(&grid)]
            / (ehl::reference::film::pan_hamrock_central(w, u, g) * c.r);
        println!(
            "M {m:5} L {l:4}: h_min / PH = {rmin:.4}, h_c / PH = {rc:.4}, p_h = {:.2} GPa",
            c.ph / 1e9
        );
        assert!((rmin - 1.0).abs() < 0.15, "M {m} L {l}: h_min ratio {rmin}");
    }
}

/// Grid convergence (M = 50, L = 10, Roelands + DH): central and minimum film change by less
/// than 1 % between the two finest of 512, 1024, 2048 cells, and the change at least halves with
/// each halving of the cells (measured: 1.1 % -> 0.27 % on h_c, 1.4 % -> 0.34 % on h_min).
#[test]
fn grid_convergence() {
    let c = line_case(
        50.0,
        10.0,
        ViscosityModel::Roelands,
        DensityModel::DowsonHigginson,
    );
    let mut hs = vec![];
    for &nx in &[512usize, 1024, 2048] {
        let par = EhlParams::default();
        let t = std::time::Instant::now();
        let (res, grid) = solve_line_p(&c, nx, -4.5, 1.5, &par);
        println!(
            "nx {nx}: {} Newton {} GMRES {} in {:.2} s",
            res.termination,
            res.iterations,
            res.linear_iterations,
            t.elapsed().as_secs_f64()
        );
        assert!(res.converged, "nx {nx}: {}", res.termination);
        let hmin = thinnest(&res.fields.film);
        // the centre value by linear interpolation between the two cells around x = 0
        let i = (0..grid.nx).find(|&i| grid.x(i) >= 0.0).unwrap();
        let t = -grid.x(i - 1) / grid.dx;
        let hc = res.fields.film[i - 1] * (1.0 - t) + res.fields.film[i] * t;
        println!("nx {nx}: h_c {hc:.5e} h_min {hmin:.5e}");
        hs.push((hc, hmin));
    }
    let d = |a: f64, b: f64| (a / b - 1.0).abs();
    let (dc1, dm1) = (d(hs[1].0, hs[0].0), d(hs[1].1, hs[0].1));
    let (dc2, dm2) = (d(hs[2].0, hs[1].0), d(hs[2].1, hs[1].1));
    println!("changes: h_c {dc1:.4} -> {dc2:.4}, h_min {dm1:.4} -> {dm2:.4}");
    assert!(dc2 < 0.01 && dm2 < 0.01);
    // the change shrinks with refinement: at least halved per halving of the cells (first
    // order; measured 4x, second order)
    assert!(dc2 < 0.5 * dc1 && dm2 < 0.5 * dm1);
}

/// The observer of a steady solve sees every Newton iterate: the last one is the converged
/// state (residual and load error within the tolerance, its step count the result's), the
/// counts never decrease, and the typed termination agrees with the words of the summary.
#[test]
fn observer_sees_the_newton_history_and_the_typed_termination() {
    let c = line_case(
        20.0,
        10.0,
        ViscosityModel::Roelands,
        DensityModel::DowsonHigginson,
    );
    let par = EhlParams::default();
    let mut seen: Vec<ehl::ehl::NewtonIterate> = Vec::new();
    let (res, _) = solve_line_observed(&c, 256, -4.5, 1.5, &par, &mut |it| seen.push(*it));
    assert!(res.converged, "{}", res.termination);
    assert_eq!(res.reason, ehl::ehl::Termination::Converged);
    assert_eq!(res.termination, res.reason.to_string());
    assert!(
        seen.len() > res.iterations,
        "{} iterates, {} Newton steps",
        seen.len(),
        res.iterations
    );
    let last = seen.last().unwrap();
    assert!(last.residual <= par.tolerance && last.load_error.abs() <= par.tolerance);
    assert_eq!(last.newton_steps, res.iterations);
    assert_eq!(last.cells, 256);
    assert!(seen
        .windows(2)
        .all(|w| w[1].newton_steps >= w[0].newton_steps
            && w[1].linear_iterations >= w[0].linear_iterations));
}
