//! EHL coupling and the steady driver: film h = h0 + g + deflection (thesis eq. 2.3), the load
//! balance through h0 (thesis fig. 2.3), Newtonian compressible Reynolds (eq. 2.1) with
//! Dowson-Higginson (2.10) or constant density and Roelands (2.11) or Barus viscosity.
//!
//! The problem is solved in the dimensionless form of Venner & Lubrecht (2000):
//! X = x/b, P = p/p_h, H = h R/b^2, lambda = 12 u_e eta0 R^2/(b^3 p_h), by the FAS multigrid of
//! [`crate::reynolds::multigrid`]; results are returned in SI.

use crate::case::Lubricant;
use crate::elastic::Deflection;
use crate::grid::Grid;
use crate::reynolds::multigrid::{Hierarchy, Level, MgParams, Physics};
use crate::reynolds::residual::{self, Fields};

/// A steady isothermal EHL problem (SI units).
pub struct EhlProblem<'a> {
    pub grid: Grid,
    /// undeformed gap g(x, y) (m), f64::INFINITY where there is no material
    pub gap: &'a (dyn Fn(f64, f64) -> f64 + Sync),
    /// elastic operator factory (any grid): deflection (m) from cell pressures (Pa)
    pub operator: &'a (dyn Fn(Grid) -> Box<dyn Deflection> + Sync),
    /// N, or N/m when grid.ny == 1 (infinite line)
    pub load: f64,
    pub lubricant: &'a Lubricant,
    /// u_e = (u1 + u2)/2 (m/s)
    pub entrainment_speed: f64,
    /// R in the rolling direction (m)
    pub reduced_radius: f64,
    /// E' (Pa)
    pub reduced_modulus: f64,
    /// b (m): the length scale
    pub hertz_half_width: f64,
    /// p_h (Pa): the pressure scale
    pub hertz_pressure: f64,
    /// initial pressure (Pa) on `grid`, e.g. the dry solution; None: a Hertz profile
    pub initial_pressure: Option<&'a [f64]>,
}

/// Solver controls.
#[derive(Debug, Clone, Copy)]
pub struct EhlParams {
    /// on the relative residual (see [`EhlResult::residual`]) and the relative load error
    pub tolerance: f64,
    /// maximum number of V-cycles on the finest grid
    pub max_iterations: usize,
    /// relaxation and cycle parameters
    pub multigrid: MgParams,
}

impl Default for EhlParams {
    fn default() -> Self {
        EhlParams {
            tolerance: 1e-6,
            max_iterations: 100,
            multigrid: MgParams::default(),
        }
    }
}

/// The steady solution (SI) and how it was reached.
#[derive(Debug, Clone)]
pub struct EhlResult {
    /// Pa
    pub pressure: Vec<f64>,
    /// m
    pub film: Vec<f64>,
    /// m (both bodies, positive opening the gap)
    pub deflection: Vec<f64>,
    /// Pa s
    pub viscosity: Vec<f64>,
    /// kg/m^3
    pub density: Vec<f64>,
    /// m
    pub h0: f64,
    /// V-cycles on the finest grid
    pub iterations: usize,
    /// relaxation work in fine-grid sweeps (a sweep on a grid 2^d times coarser counts 1/2^d)
    pub work_units: f64,
    /// sum |r| over pressurised cells / sum |d(rho H)/dX| (relative mass imbalance)
    pub residual: f64,
    /// (sum p dA - load) / load
    pub load_error: f64,
    pub converged: bool,
    pub termination: String,
    /// mass flows (kg/s; per metre of length for a line contact): through the inlet; through
    /// the outlet and into the cavitated zone; out through the free y-edges
    pub inflow: f64,
    pub outflow: f64,
    pub side_leakage: f64,
}

/// Classical central-film estimate (h/R) to place H0 at the start: Dowson-Toyoda for lines,
/// Hamrock-Dowson for points. Only a starting value; the load balance fixes H0.
fn film_guess(p: &EhlProblem, point: bool) -> f64 {
    let (e, r) = (p.reduced_modulus, p.reduced_radius);
    let u = p.lubricant.viscosity * p.entrainment_speed / (e * r);
    let g = p.lubricant.pressure_viscosity_coefficient * e;
    if point {
        let w = p.load / (e * r * r);
        2.69 * u.powf(0.67) * g.powf(0.53) * w.powf(-0.067)
    } else {
        let wl = if p.grid.ny == 1 {
            p.load
        } else {
            p.load / (p.grid.y_max() - p.grid.y_min)
        };
        let w = wl / (e * r);
        3.06 * g.powf(0.56) * u.powf(0.69) * w.powf(-0.1)
    }
}

/// Solve the steady isothermal EHL problem (thesis ch. 2) by FAS multigrid.
///
/// Never panics on a physical input and never returns NaN: when the iteration fails or does
/// not reach the tolerance within `max_iterations` V-cycles, the best state seen is returned
/// with `converged == false` and the reason in `termination`.
pub fn solve_steady(problem: &EhlProblem, params: &EhlParams) -> EhlResult {
    let b = problem.hertz_half_width;
    let r = problem.reduced_radius;
    let ph = problem.hertz_pressure;
    let lub = problem.lubricant;
    let lambda = 12.0 * problem.entrainment_speed * lub.viscosity * r * r / (b * b * b * ph);
    let phys = Physics {
        lubricant: lub.clone(),
        ph,
        lambda,
    };
    let mp = params.multigrid;
    let grids = Hierarchy::grids(problem.grid, mp.min_cells);
    let mut levels: Vec<Level> = grids
        .iter()
        .map(|&g| Level::new(g, (problem.operator)(g), problem.gap, b, r, ph))
        .collect();
    levels[0].rg.second_order = mp.second_order;
    let fine_grid = problem.grid;
    let n = fine_grid.len();
    // is it a point contact? the gap grows along y over the domain (ball), a roller does not
    let point = fine_grid.ny > 1 && {
        let ymid = 0.5 * (fine_grid.y_min + fine_grid.y_max());
        let yedge = fine_grid.y(0);
        let g0 = (problem.gap)(0.0, ymid);
        let ge = (problem.gap)(0.0, yedge);
        ge.is_finite() && g0.is_finite() && (ge - g0) * r / (b * b) > 0.5
    };
    // dimensionless load target
    let load = problem.load / (ph * b * b);
    {
        let f = &mut levels[0];
        f.load = load;
        match problem.initial_pressure {
            Some(p0) if p0.len() == n => {
                for k in 0..n {
                    f.p[k] = if f.active[k] && p0[k].is_finite() { (p0[k] / ph).max(0.0) } else { 0.0 };
                }
            }
            _ => {
                let ymid = 0.5 * (fine_grid.y_min + fine_grid.y_max());
                for j in 0..fine_grid.ny {
                    for i in 0..fine_grid.nx {
                        let k = fine_grid.idx(i, j);
                        let x = fine_grid.x(i) / b;
                        let y = if point { (fine_grid.y(j) - ymid) / b } else { 0.0 };
                        let s = 1.0 - x * x - y * y;
                        f.p[k] = if f.active[k] && s > 0.0 { s.sqrt() } else { 0.0 };
                    }
                }
            }
        }
        let c = f.carried();
        if c > 0.0 {
            let s = load / c;
            f.p.iter_mut().for_each(|p| *p *= s);
        }
    }
    // H0 from the classical film estimate at the pressure maximum
    let hc_guess = film_guess(problem, point) * r * r / (b * b);
    levels[0].update_film(0.0, &phys);
    let kmax = levels[0].argmax();
    let h0 = hc_guess - (levels[0].h[kmax]);
    let mut hier = Hierarchy {
        levels,
        h0,
        phys,
        mp,
        work: 0.0,
    };
    // the starting state is the fallback if everything after it fails
    let mut best: Option<(f64, Vec<f64>, f64)> = Some((f64::MAX, hier.levels[0].p.clone(), hier.h0));
    let coarse_start = 10 * mp.coarse_sweeps;
    hier.fmg(coarse_start);

    let mut iterations = 0;
    let mut converged = false;
    let mut termination = String::from("maximum number of iterations reached");
    let mut res;
    let mut lerr;
    loop {
        let h0 = hier.h0;
        let f = &mut hier.levels[0];
        f.update_film(h0, &hier.phys);
        res = f.residual_norm();
        lerr = (f.carried() - f.load) / f.load;
        let finite = res.is_finite()
            && lerr.is_finite()
            && h0.is_finite()
            && f.p.iter().chain(&f.h).all(|v| v.is_finite())
            // a pressure 1000 times Hertz is divergence, whatever its floating-point value
            && f.p.iter().all(|&v| v < 1e3);
        if !finite {
            termination = String::from("diverged: non-finite pressure or film");
            break;
        }
        let score = res.max(lerr.abs());
        if best.as_ref().is_none_or(|b| score < b.0) {
            best = Some((score, f.p.clone(), h0));
        }
        if res <= params.tolerance && lerr.abs() <= params.tolerance {
            converged = true;
            termination = String::from("converged");
            break;
        }
        if iterations >= params.max_iterations {
            break;
        }
        hier.vcycle(0);
        iterations += 1;
    }
    if !converged {
        if let Some((_, p, h0)) = best {
            hier.levels[0].p = p;
            hier.h0 = h0;
        }
        let h0 = hier.h0;
        let f = &mut hier.levels[0];
        f.update_film(h0, &hier.phys);
        res = f.residual_norm();
        lerr = (f.carried() - f.load) / f.load;
    }
    finish(problem, &hier, iterations, res, lerr, converged, termination)
}

fn finish(
    problem: &EhlProblem,
    hier: &Hierarchy,
    iterations: usize,
    res: f64,
    lerr: f64,
    converged: bool,
    termination: String,
) -> EhlResult {
    let f = &hier.levels[0];
    let b = problem.hertz_half_width;
    let r = problem.reduced_radius;
    let ph = problem.hertz_pressure;
    let lub = problem.lubricant;
    let hs = b * b / r;
    let n = f.p.len();
    let mut out = EhlResult {
        pressure: f.p.iter().map(|p| p * ph).collect(),
        film: (0..n).map(|k| if f.active[k] { f.h[k] * hs } else { f64::INFINITY }).collect(),
        deflection: f.def.iter().map(|d| d * hs).collect(),
        viscosity: f.p.iter().map(|&p| lub.viscosity * hier.phys.eta(p)).collect(),
        density: f.p.iter().map(|&p| lub.density * hier.phys.rho(p)).collect(),
        h0: hier.h0 * hs,
        iterations,
        work_units: hier.work,
        residual: if res.is_finite() { res } else { f64::MAX },
        load_error: if lerr.is_finite() { lerr } else { f64::MAX },
        converged,
        termination,
        inflow: 0.0,
        outflow: 0.0,
        side_leakage: 0.0,
    };
    let m = residual::mass_flow(
        &f.rg,
        &Fields {
            p: &f.p,
            rho: &f.rho,
            h: &f.h,
            eps: &f.eps,
            active: &f.active,
        },
    );
    // dimensionless flow (rho/rho0) H dY per unit u_e -> kg/s: rho0 u_e (b^2/R) b
    let q = lub.density * problem.entrainment_speed * hs * b;
    out.inflow = m.inflow * q;
    out.outflow = m.outflow * q;
    out.side_leakage = m.side_leakage * q;
    out
}
