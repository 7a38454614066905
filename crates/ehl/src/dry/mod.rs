//! Dry contact of finite rollers and balls (thesis ch. 1, eq. 1.1-1.4).
//!
//! Find the cell pressures `p` (Pa) and the rigid-body approach `delta` (m) such that, with the
//! loaded gap `h = g + K p - delta` (thesis eq. 1.1-1.2 written for the gap; `K` the elastic
//! operator, `g` the undeformed separation):
//!
//! * `h = 0` where `p > 0` (eq. 1.1), `h >= 0` where `p = 0` (eq. 1.2),
//! * `p >= 0` (eq. 1.4),
//! * `sum(p) dx dy = F` (eq. 1.3; for `ny == 1` line contact `F` is per unit length, N/m).
//!
//! Method: the constrained conjugate gradient of Polonsky & Keer (1999, Wear 231, 206-219), with
//! the load constraint imposed by subtracting the mean gap over the contact set (which makes the
//! approach a by-product: `delta` = mean of `g + K p` over the contact cells) and rescaling the
//! pressure to the load after each step. Two changes make it fast:
//!
//! 1. **One operator application per iteration.** The deflection `u = K p` is kept up to date
//!    incrementally, `u <- s (u - tau K t)` (`t` the search direction, `s` the load rescaling),
//!    so only `K t` is computed. The projection onto `p >= 0` and the Polonsky-Keer re-activation
//!    of overlapping cells change `p` by a small correction `c` that this update misses; its
//!    effect on `u` is tracked by accumulating `sum |c|`, and `u` is recomputed from scratch as
//!    soon as that exceeds a fraction (default 0) of the steps taken (and every
//!    [`DryParams::refresh_interval`] iterations, and always before convergence is declared), so
//!    the reported result is always checked against a fresh `K p`.
//! 2. **Nested-grid start.** The problem is first solved on grids coarsened by two (down to
//!    [`DryParams::min_coarse_cells`] cells per direction; `ny == 1` stays 1), each level's
//!    operator rebuilt through the factory and its gap sampled at its own cell centres; the
//!    pressure is interpolated (bilinear, at cell centres) up as the next level's initial guess.
//!
//! Convergence (the *relative residual*, [`DryResult::residual`]):
//!
//! ```text
//! residual = max( sqrt( (sum_{p>0} h^2 + sum_{p=0} min(h,0)^2) / n_contact ) / h_ref,
//!                 |A sum(p) - F| / F )
//! h_ref    = max( max(K p) - min(K p) over the cells with finite gap,  K_00 F / (A n_contact) )
//! ```
//!
//! i.e. the RMS violation of the contact conditions (gap left open inside the contact, overlap
//! outside it) relative to the variation of the elastic deflection over the domain (a scale of
//! the order of the approach that is also defined for the 2D line contact, whose approach is not;
//! floored by the self-deflection of a cell at the mean contact pressure, `K_00` the operator's
//! diagonal and `A` the cell area, for a flat punch whose deflection is uniform), together
//! with the load error. The load is re-imposed exactly at every iteration, so at
//! convergence the load balance holds to rounding (~1e-14).
//!
//! Cells whose gap is `f64::INFINITY` (no material) carry no pressure and take no part in the
//! residual.

use crate::elastic::Deflection;
use crate::geometry::GapSampler;
use crate::grid::Grid;

/// Solver settings.
#[derive(Debug, Clone)]
pub struct DryParams {
    /// Relative residual to reach (see the module documentation), e.g. 1e-10.
    pub tolerance: f64,
    /// Maximum conjugate-gradient iterations on the finest grid (each coarse level gets as many).
    pub max_iterations: usize,
    /// Start from the solution on successively coarsened grids (nested iteration).
    pub coarse_start: bool,
    /// Coarsening stops before a direction would have fewer cells than this (`ny == 1` exempt).
    pub min_coarse_cells: usize,
    /// Relative residual to which the coarse levels are solved (they only provide a start).
    pub coarse_tolerance: f64,
    /// Recompute `u = K p` from scratch at least every this many iterations (rounding drift).
    pub refresh_interval: usize,
    /// Recompute `u = K p` when the projection corrections missed by the incremental update,
    /// summed since the last refresh, exceed this fraction of the summed step sizes. The default
    /// 0 recomputes after every iteration whose projection changed `p` (measured: a larger value
    /// lets `u` drift from `K p` and stalls the iteration near 1e-7; with 0 only ~10-20 % of
    /// the iterations need the second application, mostly early on each level).
    pub correction_fraction: f64,
    /// Precondition the conjugate gradient with the approximate inverse of the half-space
    /// operator ([`crate::elastic::InverseHalfSpace`], Vollebregt 2014): one more convolution per
    /// iteration, far fewer iterations on fine grids.
    pub precondition: bool,
}

impl Default for DryParams {
    fn default() -> Self {
        DryParams {
            tolerance: 1e-10,
            max_iterations: 1000,
            coarse_start: true,
            min_coarse_cells: 32,
            coarse_tolerance: 1e-6,
            refresh_interval: 50,
            correction_fraction: 0.0,
            precondition: true,
        }
    }
}

/// A dry contact problem.
pub struct DryProblem<'a> {
    /// The finest grid, on which the result is returned.
    pub grid: Grid,
    /// Undeformed separation g (m) on the cells of any grid; `f64::INFINITY` where there is no
    /// material (a closure g(x, y) is sampled at the cell centres).
    pub gap: &'a dyn GapSampler,
    /// Builds the elastic operator on any grid (called once per level).
    pub operator: &'a (dyn Fn(Grid) -> Box<dyn Deflection> + Sync),
    /// Applied load F (N); for `ny == 1` line contact the load per unit length (N/m).
    pub load: f64,
}

/// Work done on one grid level.
#[derive(Debug, Clone, PartialEq)]
pub struct LevelStats {
    pub nx: usize,
    pub ny: usize,
    pub iterations: usize,
    /// operator applications on this level (one per iteration plus the refreshes)
    pub applications: usize,
    pub residual: f64,
}

/// The result of a dry solve (fields on the finest grid, row-major `j * nx + i`).
#[derive(Debug, Clone)]
pub struct DryResult {
    /// cell pressures (Pa)
    pub pressure: Vec<f64>,
    /// combined elastic deflection of both bodies (m), `K p`
    pub deflection: Vec<f64>,
    /// loaded gap h = g + deflection - approach (m); infinite where g is
    pub gap: Vec<f64>,
    /// rigid-body approach (m): mean of g + deflection over the contact cells. For the `ny == 1`
    /// line contact it depends on the (arbitrary) constant of the plane-strain kernel.
    pub approach: f64,
    /// conjugate-gradient iterations on the finest grid
    pub iterations: usize,
    /// iterations on all levels
    pub total_iterations: usize,
    /// operator applications on all levels (each coarse one costs about 1/4 of the next finer)
    pub applications: usize,
    /// per level, coarsest first
    pub levels: Vec<LevelStats>,
    /// final relative residual (module documentation)
    pub residual: f64,
    pub converged: bool,
    /// why the solver stopped, in words
    pub termination: String,
    /// area of the cells with p > 0 (m^2; line contact: m^2 per 1 m of length)
    pub contact_area: f64,
    /// integrated load sum(p) dx dy (N; line contact N/m)
    pub load: f64,
}

impl DryResult {
    /// The maximum pressure (Pa), 0 for an empty result.
    pub fn max_pressure(&self) -> f64 {
        self.pressure.iter().cloned().fold(0.0, f64::max)
    }

    fn failed(grid: &Grid, reason: String) -> DryResult {
        let n = grid.len();
        DryResult {
            pressure: vec![0.0; n],
            deflection: vec![0.0; n],
            gap: vec![f64::NAN; n],
            approach: f64::NAN,
            iterations: 0,
            total_iterations: 0,
            applications: 0,
            levels: Vec::new(),
            residual: f64::INFINITY,
            converged: false,
            termination: reason,
            contact_area: 0.0,
            load: 0.0,
        }
    }
}

/// Solve the dry contact problem (module documentation). Never panics on odd input: a zero,
/// negative or non-finite load, a gap that is NaN or infinite everywhere, or an operator on the
/// wrong grid give `converged == false` with the reason in `termination`.
pub fn solve(problem: &DryProblem, params: &DryParams) -> DryResult {
    let grid = problem.grid;
    if grid.nx == 0 || grid.ny == 0 {
        return DryResult::failed(&grid, "empty grid".into());
    }
    if !(grid.dx > 0.0 && grid.dy > 0.0 && grid.dx.is_finite() && grid.dy.is_finite()) {
        return DryResult::failed(&grid, "grid cell size must be positive and finite".into());
    }
    if !problem.load.is_finite() || problem.load <= 0.0 {
        return DryResult::failed(
            &grid,
            format!("load must be positive and finite (got {})", problem.load),
        );
    }
    if !(params.tolerance > 0.0) {
        return DryResult::failed(&grid, "tolerance must be positive".into());
    }

    // Levels, finest first.
    let mut grids = vec![grid];
    if params.coarse_start {
        let min = params.min_coarse_cells.max(2);
        loop {
            let g = *grids.last().unwrap();
            let nxc = g.nx.div_ceil(2);
            let nyc = if g.ny == 1 { 1 } else { g.ny.div_ceil(2) };
            if nxc < min || (g.ny > 1 && nyc < min) {
                break;
            }
            grids.push(Grid::new(nxc, nyc, g.x_min, g.x_max(), g.y_min, g.y_max()));
        }
    }
    grids.reverse();

    let mut levels = Vec::new();
    let mut pressure: Option<(Grid, Vec<f64>)> = None;
    let mut total_iterations = 0;
    let mut applications = 0;
    let nlev = grids.len();
    for (l, g) in grids.iter().enumerate() {
        let fine = l + 1 == nlev;
        let gap = problem.gap.sampled(g);
        if let Some(k) = gap.iter().position(|v| v.is_nan()) {
            return DryResult::failed(
                &grid,
                format!(
                    "gap is NaN at x = {:e} m, y = {:e} m",
                    g.x(k % g.nx),
                    g.y(k / g.nx)
                ),
            );
        }
        if !gap.iter().any(|v| v.is_finite()) {
            return DryResult::failed(
                &grid,
                "no cell can carry load: the gap is infinite everywhere".into(),
            );
        }
        let mut op = (problem.operator)(*g);
        if op.grid().nx != g.nx || op.grid().ny != g.ny {
            return DryResult::failed(
                &grid,
                format!(
                    "operator factory returned a {}x{} operator for a {}x{} grid",
                    op.grid().nx,
                    op.grid().ny,
                    g.nx,
                    g.ny
                ),
            );
        }
        let start = pressure.as_ref().map(|(cg, cp)| interpolate(cg, cp, g));
        let tol = if fine {
            params.tolerance
        } else {
            params.coarse_tolerance.max(params.tolerance)
        };
        let r = solve_level(g, &gap, op.as_mut(), problem.load, start, tol, params);
        total_iterations += r.iterations;
        applications += r.applications;
        levels.push(LevelStats {
            nx: g.nx,
            ny: g.ny,
            iterations: r.iterations,
            applications: r.applications,
            residual: r.residual,
        });
        if fine {
            let h: Vec<f64> = gap
                .iter()
                .zip(&r.u)
                .map(|(gi, ui)| {
                    if gi.is_finite() {
                        gi + ui - r.approach
                    } else {
                        f64::INFINITY
                    }
                })
                .collect();
            let area = g.cell_area();
            let contact = r.p.iter().filter(|&&v| v > 0.0).count() as f64 * area;
            let load = r.p.iter().sum::<f64>() * area;
            return DryResult {
                pressure: r.p,
                deflection: r.u,
                gap: h,
                approach: r.approach,
                iterations: r.iterations,
                total_iterations,
                applications,
                levels,
                residual: r.residual,
                converged: r.converged,
                termination: r.termination,
                contact_area: contact,
                load,
            };
        }
        pressure = Some((*g, r.p));
    }
    unreachable!("the finest level returns")
}

/// Bilinear interpolation of a cell-centred field from `cg` to the cell centres of `fg` (both
/// covering the same domain); values beyond the outer centres are held constant.
fn interpolate(cg: &Grid, cp: &[f64], fg: &Grid) -> Vec<f64> {
    let pos = |x: f64, x0: f64, d: f64, n: usize| -> (usize, usize, f64) {
        let s = (x - x0) / d - 0.5;
        if n == 1 || s <= 0.0 {
            return (0, 0, 0.0);
        }
        let i = s.floor() as usize;
        if i + 1 >= n {
            return (n - 1, n - 1, 0.0);
        }
        (i, i + 1, s - i as f64)
    };
    let mut out = vec![0.0; fg.len()];
    let xs: Vec<_> = (0..fg.nx)
        .map(|i| pos(fg.x(i), cg.x_min, cg.dx, cg.nx))
        .collect();
    for j in 0..fg.ny {
        let (j0, j1, wy) = pos(fg.y(j), cg.y_min, cg.dy, cg.ny);
        for (i, &(i0, i1, wx)) in xs.iter().enumerate() {
            let a = cp[j0 * cg.nx + i0] * (1.0 - wx) + cp[j0 * cg.nx + i1] * wx;
            let b = cp[j1 * cg.nx + i0] * (1.0 - wx) + cp[j1 * cg.nx + i1] * wx;
            out[j * fg.nx + i] = a * (1.0 - wy) + b * wy;
        }
    }
    out
}

struct LevelResult {
    p: Vec<f64>,
    u: Vec<f64>,
    approach: f64,
    iterations: usize,
    applications: usize,
    residual: f64,
    converged: bool,
    termination: String,
}

/// Polonsky-Keer constrained conjugate gradient on one grid (module documentation).
fn solve_level(
    grid: &Grid,
    g: &[f64],
    op: &mut dyn Deflection,
    load: f64,
    start: Option<Vec<f64>>,
    tol: f64,
    params: &DryParams,
) -> LevelResult {
    let n = grid.len();
    let area = grid.cell_area();
    let finite: Vec<bool> = g.iter().map(|v| v.is_finite()).collect();
    let n_finite = finite.iter().filter(|&&f| f).count();

    // Initial pressure: the interpolated start, else uniform over the cells with material.
    let mut p = match start {
        Some(p) => p,
        None => vec![1.0; n],
    };
    for k in 0..n {
        if !finite[k] || !(p[k] > 0.0) {
            p[k] = 0.0;
        }
    }
    let mut sum: f64 = p.iter().sum();
    if !(sum > 0.0) {
        p.iter_mut()
            .zip(&finite)
            .for_each(|(v, &f)| *v = if f { 1.0 } else { 0.0 });
        sum = n_finite as f64;
    }
    let s = load / (sum * area);
    p.iter_mut().for_each(|v| *v *= s);

    let c00 = op.coefficient(0, 0).abs();
    // E' from the operator's own diagonal (its kernel is 2/(pi E') times the geometric one)
    let geometric = if grid.ny == 1 {
        crate::elastic::kernel::strip(0.0, 0.5 * grid.dx)
    } else {
        crate::elastic::kernel::rectangle(0.0, 0.0, 0.5 * grid.dx, 0.5 * grid.dy)
    };
    let e_est = 2.0 * geometric / (std::f64::consts::PI * c00);
    let mut pre = (params.precondition && e_est.is_finite() && e_est > 0.0)
        .then(|| crate::elastic::InverseHalfSpace::new(*grid, e_est));
    let mut z = vec![0.0; n];
    let mut zin = vec![0.0; n];
    let mut u = vec![0.0; n];
    let mut r = vec![0.0; n];
    let mut t = vec![0.0; n];
    let mut h = vec![0.0; n];
    op.apply(&p, &mut u);
    let mut applications = 1;
    let mut fresh = true; // u == K p up to rounding
    let mut since_refresh = 0usize;
    let mut dropped = 0.0f64; // sum |corrections| missed by the incremental update
    let mut stepped = 0.0f64; // sum tau |t| since the refresh
    let mut g_old = 1.0f64;
    let mut conjugate = false;
    let mut approach;
    let mut residual = f64::INFINITY;
    let mut iterations = 0usize;

    loop {
        // Gap on the current contact set and the approach (mean of g + u over it).
        let (mut sgu, mut nc) = (0.0, 0usize);
        for k in 0..n {
            if p[k] > 0.0 {
                sgu += g[k] + u[k];
                nc += 1;
            }
        }
        if nc == 0 {
            return LevelResult {
                p,
                u,
                approach: f64::NAN,
                iterations,
                applications,
                residual,
                converged: false,
                termination: "contact set became empty".into(),
            };
        }
        approach = sgu / nc as f64;
        let (mut gg, mut neg) = (0.0, 0.0);
        let (mut umin, mut umax) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..n {
            if finite[k] {
                let hk = g[k] + u[k] - approach;
                h[k] = hk;
                if p[k] > 0.0 {
                    gg += hk * hk;
                } else if hk < 0.0 {
                    neg += hk * hk;
                }
                umin = umin.min(u[k]);
                umax = umax.max(u[k]);
            } else {
                h[k] = f64::INFINITY;
            }
        }
        // the floor c00 * mean contact pressure keeps the scale positive for a flat punch,
        // whose deflection is uniform over a domain wholly in contact
        let h_ref = (umax - umin).max(c00 * load / (area * nc as f64));
        let load_err = (p.iter().sum::<f64>() * area - load).abs() / load;
        residual = (((gg + neg) / nc as f64).sqrt() / h_ref).max(load_err);
        if !residual.is_finite() {
            return LevelResult {
                p,
                u,
                approach,
                iterations,
                applications,
                residual,
                converged: false,
                termination: "residual is not finite (degenerate operator or gap)".into(),
            };
        }
        if crate::run::cancel::requested() {
            return LevelResult {
                p,
                u,
                approach,
                iterations,
                applications,
                residual,
                converged: false,
                termination: "cancelled".into(),
            };
        }
        if residual < tol {
            if fresh {
                return LevelResult {
                    p,
                    u,
                    approach,
                    iterations,
                    applications,
                    residual,
                    converged: true,
                    termination: format!("residual {residual:.3e} < tolerance {tol:.1e}"),
                };
            }
            // Confirm against a fresh K p before declaring convergence.
            op.apply(&p, &mut u);
            applications += 1;
            fresh = true;
            since_refresh = 0;
            dropped = 0.0;
            stepped = 0.0;
            continue;
        }
        if iterations >= params.max_iterations {
            return LevelResult {
                p,
                u,
                approach,
                iterations,
                applications,
                residual,
                converged: false,
                termination: format!(
                    "no convergence in {iterations} iterations (residual {residual:.3e}, tolerance {tol:.1e})"
                ),
            };
        }
        iterations += 1;

        // Search direction on the contact set, preconditioned: z = Q M^-1 h with M^-1 the
        // approximate inverse operator and Q the projection onto mean-free fields on the contact
        // set (h is mean-free there already, so Q M^-1 Q stays symmetric).
        let gz = if let Some(pre) = pre.as_mut() {
            for k in 0..n {
                zin[k] = if p[k] > 0.0 { h[k] } else { 0.0 };
            }
            pre.apply(&zin, &mut z);
            applications += 1;
            let mean = (0..n).filter(|&k| p[k] > 0.0).map(|k| z[k]).sum::<f64>() / nc as f64;
            let mut gz = 0.0;
            for k in 0..n {
                if p[k] > 0.0 {
                    z[k] -= mean;
                    gz += h[k] * z[k];
                } else {
                    z[k] = 0.0;
                }
            }
            gz
        } else {
            z.copy_from_slice(&h);
            gg
        };
        let beta = if conjugate { gz / g_old } else { 0.0 };
        g_old = gz;
        for k in 0..n {
            t[k] = if p[k] > 0.0 { z[k] + beta * t[k] } else { 0.0 };
        }
        op.apply(&t, &mut r);
        applications += 1;
        let (mut sr, mut srt, mut st, mut sht) = (0.0, 0.0, 0.0, 0.0);
        for k in 0..n {
            if p[k] > 0.0 {
                sr += r[k];
                srt += r[k] * t[k];
                st += t[k];
                sht += h[k] * t[k];
            }
        }
        let rbar = sr / nc as f64;
        let denom = srt - rbar * st;
        if !(denom > 0.0) {
            return LevelResult {
                p,
                u,
                approach,
                iterations,
                applications,
                residual,
                converged: false,
                termination: "search direction lost positivity (operator not positive definite?)"
                    .into(),
            };
        }
        let tau = sht / denom;

        // Step, projection onto p >= 0, re-activation of overlapping cells (Polonsky-Keer).
        let mut overlap = false;
        let (mut corr, mut step, mut psum) = (0.0, 0.0, 0.0);
        for k in 0..n {
            if p[k] > 0.0 {
                let pk = p[k] - tau * t[k];
                step += (tau * t[k]).abs();
                if pk > 0.0 {
                    p[k] = pk;
                } else {
                    corr += -pk;
                    p[k] = 0.0;
                    if h[k] < 0.0 {
                        // clipped cell still overlapping
                        overlap = true;
                        let add = -tau * h[k];
                        p[k] = add;
                        corr += add;
                    }
                }
            } else if finite[k] && h[k] < 0.0 {
                overlap = true;
                let add = -tau * h[k];
                p[k] = add;
                corr += add;
            }
            psum += p[k];
        }
        conjugate = !overlap;
        let scale = load / (psum * area);
        for k in 0..n {
            p[k] *= scale;
            u[k] = scale * (u[k] - tau * r[k]);
        }
        dropped += corr;
        stepped += step;
        since_refresh += 1;
        fresh = false;
        if (corr > 0.0 && dropped >= params.correction_fraction * stepped)
            || since_refresh >= params.refresh_interval
        {
            op.apply(&p, &mut u);
            applications += 1;
            fresh = true;
            since_refresh = 0;
            dropped = 0.0;
            stepped = 0.0;
        }
    }
}
