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

#[test]
fn explore() {
    for &(m, l) in &[(20.0, 10.0), (100.0, 10.0), (1000.0, 10.0)] {
        let c = line_case(m, l, ViscosityModel::Barus, DensityModel::Constant);
        let mut par = EhlParams::default();
        if let Ok(v) = std::env::var("MINC") { par.multigrid.min_cells = v.parse().unwrap(); }
        if let Ok(v) = std::env::var("CS") { par.multigrid.coarse_sweeps = v.parse().unwrap(); }
        if let Ok(v) = std::env::var("WJ") { par.multigrid.omega_jd = v.parse().unwrap(); }
        if let Ok(v) = std::env::var("WG") { par.multigrid.omega_gs = v.parse().unwrap(); }
        if let Ok(v) = std::env::var("HF") { par.multigrid.h0_factor = v.parse().unwrap(); }
        let nx = std::env::var("NX").map(|v| v.parse().unwrap()).unwrap_or(256);
        let (res, grid) = solve_line_p(&c, nx, -4.5, 1.5, &par);
        let hmin = res.film.iter().cloned().fold(f64::INFINITY, f64::min);
        let i0 = (0..grid.nx).min_by(|&a, &b| grid.x(a).abs().total_cmp(&grid.x(b).abs())).unwrap();
        let hc = res.film[i0];
        let u = c.lub.viscosity * c.ue / (c.e * c.r);
        let hm = moes_line_central(m, l) * c.r * u.sqrt();
        println!("M {m} L {l}: conv {} {} it {} work {:.1} res {:.2e} lerr {:.2e} hc {:.4e} moes {:.4e} ratio {:.3} hmin {:.3e} pmax {:.3}",
            res.converged, res.termination, res.iterations, res.work_units, res.residual, res.load_error, hc, hm, hc / hm, hmin,
            res.pressure.iter().cloned().fold(0.0, f64::max) / c.ph);
    }
}

#[test]
fn debug_relax() {
    use ehl::reynolds::multigrid::*;
    let c = line_case(100.0, 10.0, ViscosityModel::Barus, DensityModel::Constant);
    let nx = 32;
    let grid = Grid::new(nx, 1, -4.5 * c.b, 1.5 * c.b, -0.5, 0.5);
    let r = c.r;
    let gap = move |x: f64, _y: f64| x * x / (2.0 * r);
    let mut lv = Level::new(grid, Box::new(ToeplitzLine::new(grid, c.e)), &gap, c.b, c.r, c.ph);
    let lambda = 12.0 * c.ue * c.lub.viscosity * r * r / (c.b.powi(3) * c.ph);
    let phys = Physics { lubricant: c.lub.clone(), ph: c.ph, lambda };
    for i in 0..nx { let x = grid.x(i) / c.b; lv.p[i] = (1.0 - x * x).max(0.0).sqrt(); }
    lv.update_film(0.0, &phys);
    let h0 = 0.3 - lv.h[lv.argmax()];
    println!("h0 {h0} H {:?} gap {:?} def {:?}", &lv.h[..4], &lv.gap[..4], &lv.def[..4]);
    lv.load = lv.carried();
    let mp = MgParams::default();
    println!("lambda {lambda}");
    for s in 0..20 {
        lv.relax(h0, &phys, &mp);
        lv.update_film(h0, &phys);
        let rn = lv.residual_norm();
        println!("sweep {s} res {rn:.3e} pmax {:.3}", lv.p[lv.argmax()]);
    }
    for i in 0..nx { println!("{:.3} P {:.4} H {:.4} eps/dx2 {:.3e}", grid.x(i)/c.b, lv.p[i], lv.h[i], lv.eps[i]/lv.rg.dx.powi(2)); }
}
