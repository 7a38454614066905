//! Infinite line contact (ny == 1): film against the classical fits, grid convergence.
mod common;
use common::*;
use ehl::case::{DensityModel, ViscosityModel};
use ehl::ehl::{solve_steady, EhlParams, EhlProblem, EhlResult};
use ehl::elastic::Deflection;
use ehl::grid::Grid;
use ehl::units;

pub struct LineCase {
    pub e: f64,
    pub r: f64,
    pub w: f64,
    pub ue: f64,
    pub b: f64,
    pub ph: f64,
    pub lub: ehl::case::Lubricant,
}

/// A line contact with Moes groups (M, L): E' = 2.2e11 Pa, R = 0.02 m, eta0 = 0.04 Pa s,
/// alpha from G = alpha E' = 4400 (alpha = 20 GPa^-1); U from L, W from M.
pub fn line_case(m: f64, l: f64, visc: ViscosityModel, dens: DensityModel) -> LineCase {
    let (e, r, eta0, alpha) = (2.2e11, 0.02, 0.04, 2.0e-8);
    let g = alpha * e;
    let u = (l / g).powi(4);
    let wd = m * u.sqrt();
    let w = wd * e * r;
    let ue = u * e * r / eta0;
    LineCase {
        e,
        r,
        w,
        ue,
        b: units::hertz_line_half_width(w, r, e),
        ph: units::hertz_line_pressure(w, r, e),
        lub: lubricant(eta0, alpha, visc, dens),
    }
}

pub fn solve_line(c: &LineCase, nx: usize, xin: f64, xout: f64) -> (EhlResult, Grid) {
    solve_line_p(c, nx, xin, xout, &EhlParams::default())
}

pub fn solve_line_p(c: &LineCase, nx: usize, xin: f64, xout: f64, par: &EhlParams) -> (EhlResult, Grid) {
    let grid = Grid::new(nx, 1, xin * c.b, xout * c.b, -0.5, 0.5);
    let r = c.r;
    let gap = move |x: f64, _y: f64| x * x / (2.0 * r);
    let e = c.e;
    let op = move |g: Grid| -> Box<dyn Deflection> { Box::new(ToeplitzLine::new(g, e)) };
    let prob = EhlProblem {
        grid,
        gap: &gap,
        operator: &op,
        load: c.w,
        lubricant: &c.lub,
        entrainment_speed: c.ue,
        reduced_radius: c.r,
        reduced_modulus: c.e,
        hertz_half_width: c.b,
        hertz_pressure: c.ph,
        initial_pressure: None,
    };
    (solve_steady(&prob, par), grid)
}

/// Every field finite and an honest report, whatever the outcome: the solver is stopped after a
/// few V-cycles on a hard case (M = 1000, L = 10: a thin film on a coarse grid), so it cannot have
/// converged to 1e-6; it must say so and return finite fields.
#[test]
fn reports_honestly_and_never_nan() {
    let c = line_case(1000.0, 10.0, ViscosityModel::Roelands, DensityModel::DowsonHigginson);
    let mut par = EhlParams::default();
    par.max_iterations = 3;
    let (res, _) = solve_line_p(&c, 128, -4.5, 1.5, &par);
    for (name, f) in [("p", &res.pressure), ("h", &res.film), ("eta", &res.viscosity), ("rho", &res.density)] {
        assert!(f.iter().all(|v| v.is_finite()), "{name} not finite: {} {:?}", res.termination, &f[..4]);
    }
    assert!(res.residual.is_finite() && res.load_error.is_finite() && res.h0.is_finite());
    assert!(!res.termination.is_empty());
    if res.converged {
        assert!(res.residual <= par.tolerance && res.load_error.abs() <= par.tolerance);
    } else {
        assert_ne!(res.termination, "converged");
    }
}

/// Central film against Moes (Barus, constant density: the assumptions of the fit).
/// IGNORED: the solver does not yet converge to tolerance; at 256 cells on [-4.5, 1.5] b it
/// stalls at a relative residual of ~1e-3 with h_c / Moes = 1.5-1.8 for M = 20, 100 (L = 10)
/// and a negative film at M = 1000. Kept as the acceptance test for the next step.
#[test]
#[ignore]
fn central_film_against_moes() {
    for &(m, l) in &[(20.0, 10.0), (100.0, 10.0), (1000.0, 10.0), (100.0, 3.0), (100.0, 20.0)] {
        let c = line_case(m, l, ViscosityModel::Barus, DensityModel::Constant);
        let (res, grid) = solve_line(&c, 512, -4.5, 1.5);
        let i0 = (0..grid.nx).min_by(|&a, &b| grid.x(a).abs().total_cmp(&grid.x(b).abs())).unwrap();
        let u = c.lub.viscosity * c.ue / (c.e * c.r);
        let hm = moes_line_central(m, l) * c.r * u.sqrt();
        assert!(res.converged, "M {m} L {l}: {}", res.termination);
        // 10 %: the stated accuracy of the Moes fit over this range
        assert!((res.film[i0] / hm - 1.0).abs() < 0.10, "M {m} L {l}: {} vs {}", res.film[i0], hm);
    }
}
