//! From a validated case to a solution: builds the grid, the gap and the operators, dispatches to
//! the dry or EHL solver and fills the summary. No file I/O here.

use crate::case::{Case, Kind, Shape};
use crate::dry::{DryParams, DryProblem};
use crate::ehl::{EhlParams, EhlProblem};
use crate::elastic::{guilbault_psi, BodyCompliance, Deflection, EndImages, FftDeflection};
use crate::geometry::Geometry;
use crate::grid::Grid;
use crate::solution::{Fields, Solution, Summary};
use crate::{Error, Result};
use std::time::Instant;

/// Receives progress reports from long solves: a fraction in [0, 1] (or NaN if unknown) and a
/// short message. The CLI turns these into a progress bar; the library never prints.
pub trait Progress: Sync {
    fn report(&self, fraction: f64, message: &str);
}

/// A [`Progress`] that ignores every report.
pub struct Silent;

impl Progress for Silent {
    fn report(&self, _fraction: f64, _message: &str) {}
}

/// The elastic operator factory for a case: the plane-strain strip kernel for an infinite line
/// contact, else the half-space with, for each finite roller, the mirror images about its free
/// ends (`solver.mirror_levels`) carrying Guilbault's psi of that body's Poisson ratio when
/// `solver.free_end_correction` is set. A skewed body 2 gets no images (its ends are not
/// planes y = const).
///
/// Operators are remembered by grid: the dry start and the EHL solve ask for the same grids,
/// and building one (its kernel table and spectra) costs ~50 applications (108 ms on the
/// 256 x 512 roller with images); a repeat request gets a clone sharing the spectra.
pub fn operator_factory(
    case: &Case,
    geometry: &Geometry,
) -> impl Fn(Grid) -> Box<dyn Deflection> + Sync {
    let e_red = case.reduced_modulus();
    let line = case.is_infinite_line();
    let mut bodies = Vec::new();
    for (k, body) in [(1usize, &case.body1), (2, &case.body2)] {
        let mut b = BodyCompliance::new(body.youngs_modulus, body.poisson_ratio);
        // A skewed body's free ends are slanted lines across the contact, which reflections
        // about planes y = const cannot represent (they would wipe out real contact near the
        // ends): body 2 of a skewed pair gets no images; body 1 keeps its own.
        let skewed = k == 2 && case.alignment.skew != 0.0;
        if body.shape == Shape::Roller && case.solver.mirror_levels > 0 && !skewed {
            if let Some(ends) = geometry.body_ends(k) {
                b.images = Some(EndImages {
                    ends,
                    levels: case.solver.mirror_levels,
                    psi: if case.solver.free_end_correction {
                        guilbault_psi(body.poisson_ratio)
                    } else {
                        1.0
                    },
                });
            }
        }
        bodies.push(b);
    }
    let built: std::sync::Mutex<Vec<FftDeflection>> = std::sync::Mutex::new(Vec::new());
    move |grid: Grid| -> Box<dyn Deflection> {
        let mut built = built.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(op) = built.iter().find(|op| *op.grid() == grid) {
            return Box::new(op.clone());
        }
        let op = if line {
            FftDeflection::line(grid, e_red)
        } else {
            FftDeflection::with_images(grid, &bodies)
        };
        built.push(op.clone());
        Box::new(op)
    }
}

/// Index and value of the largest entry.
fn argmax(v: &[f64]) -> (usize, f64) {
    v.iter().enumerate().fold(
        (0, f64::NEG_INFINITY),
        |(k, m), (i, &x)| if x > m { (i, x) } else { (k, m) },
    )
}

/// Solves `case`. A solver that does not converge still returns a solution with
/// `summary.converged == false`; errors are reserved for cases that cannot be solved at all.
pub fn solve(case: &Case, progress: &dyn Progress) -> Result<Solution> {
    let start = Instant::now();
    let geometry = Geometry::new(case);
    let grid = geometry.grid();
    let hertz = geometry.hertz();
    let factory = operator_factory(case, &geometry);
    let gap = |x: f64, y: f64| geometry.gap(x, y);
    let load = if case.is_infinite_line() {
        case.load.force_per_length
    } else {
        case.load.force
    };
    progress.report(0.0, "dry contact");
    let dry = crate::dry::solve(
        &DryProblem {
            grid,
            gap: &gap,
            operator: &factory,
            load,
        },
        &DryParams {
            tolerance: if case.kind == Kind::Dry {
                case.solver.tolerance
            } else {
                case.solver.tolerance.max(1e-8)
            },
            max_iterations: case.solver.max_iterations,
            ..DryParams::default()
        },
    );
    let mut summary = Summary {
        hertz_pressure_pa: hertz.ph,
        hertz_half_width_m: hertz.b,
        ..Summary::default()
    };
    let solution = match case.kind {
        Kind::Dry => {
            summary.converged = dry.converged;
            summary.termination = dry.termination.clone();
            summary.iterations = dry.total_iterations;
            summary.residual = dry.residual;
            summary.load_n = dry.load;
            summary.load_error = (dry.load - load).abs() / load;
            summary.approach_m = dry.approach.is_finite().then_some(dry.approach);
            summary.contact_area_m2 = Some(dry.contact_area);
            let (k, pmax) = argmax(&dry.pressure);
            summary.max_pressure_pa = pmax;
            summary.max_pressure_at_m = [grid.x(k % grid.nx), grid.y(k / grid.nx)];
            Solution {
                grid,
                fields: Fields {
                    pressure: dry.pressure,
                    deformation: dry.deflection,
                    // a failed solve has no loaded gap: leave it out rather than write NaN
                    film: dry.gap.iter().all(|v| !v.is_nan()).then_some(dry.gap),
                    viscosity: None,
                    density: None,
                },
                summary,
            }
        }
        Kind::Ehl => solve_ehl(
            case, &geometry, &factory, &gap, load, dry, summary, progress,
        )?,
    };
    let mut solution = solution;
    solution.summary.wall_time_s = start.elapsed().as_secs_f64();
    progress.report(1.0, "done");
    Ok(solution)
}

/// Film value at (x, y) by bilinear interpolation between cell centres (clamped at the edges);
/// `None` where a neighbouring cell has no material.
fn film_at(grid: &Grid, h: &[f64], x: f64, y: f64) -> Option<f64> {
    let fx = ((x - grid.x_min) / grid.dx - 0.5).clamp(0.0, (grid.nx - 1) as f64);
    let fy = if grid.ny == 1 {
        0.0
    } else {
        ((y - grid.y_min) / grid.dy - 0.5).clamp(0.0, (grid.ny - 1) as f64)
    };
    let (i0, j0) = (fx.floor() as usize, fy.floor() as usize);
    let (i1, j1) = ((i0 + 1).min(grid.nx - 1), (j0 + 1).min(grid.ny - 1));
    let (tx, ty) = (fx - i0 as f64, fy - j0 as f64);
    let v = |i: usize, j: usize| h[grid.idx(i, j)];
    let val = (1.0 - ty) * ((1.0 - tx) * v(i0, j0) + tx * v(i1, j0))
        + ty * ((1.0 - tx) * v(i0, j1) + tx * v(i1, j1));
    val.is_finite().then_some(val)
}

/// Steady EHL from the dry solution: the Reynolds solver, then the summary figures and, for a
/// converged solution only, the friction integral.
#[allow(clippy::too_many_arguments)]
fn solve_ehl(
    case: &Case,
    geometry: &Geometry,
    factory: &(dyn Fn(Grid) -> Box<dyn Deflection> + Sync),
    gap: &dyn crate::geometry::GapSampler,
    load: f64,
    dry: crate::dry::DryResult,
    mut summary: Summary,
    progress: &dyn Progress,
) -> Result<Solution> {
    let (lubricant, motion) = match (&case.lubricant, &case.motion) {
        (Some(l), Some(m)) => (l, m),
        _ => {
            return Err(Error::Solver(
                "an ehl case needs [lubricant] and [motion]".into(),
            ))
        }
    };
    let grid = geometry.grid();
    let hertz = geometry.hertz();
    progress.report(0.1, "EHL");
    let params = EhlParams {
        tolerance: case.solver.tolerance,
        max_iterations: case.solver.max_iterations,
        wedge_upwind_order: case.solver.wedge_upwind_order,
        ..EhlParams::default()
    };
    let dry_start = dry.converged.then_some(dry.pressure.as_slice());
    let r = crate::ehl::solve_steady_with_fallback(
        &EhlProblem {
            grid,
            gap,
            operator: factory,
            load,
            lubricant,
            entrainment_speed: motion.entrainment_speed,
            reduced_radius: case.reduced_radius(),
            reduced_modulus: case.reduced_modulus(),
            hertz_half_width: hertz.b,
            hertz_pressure: hertz.ph,
            initial_pressure: dry_start,
        },
        &params,
        &|| progress.report(0.5, "EHL, second start"),
    );
    let area = grid.cell_area();
    summary.converged = r.converged;
    summary.termination = r.termination.clone();
    summary.iterations = r.iterations;
    summary.residual = r.residual;
    summary.load_n = r.pressure.iter().sum::<f64>() * area;
    summary.load_error = (summary.load_n - load).abs() / load;
    let (k, pmax) = argmax(&r.pressure);
    summary.max_pressure_pa = pmax;
    summary.max_pressure_at_m = [grid.x(k % grid.nx), grid.y(k / grid.nx)];
    summary.central_film_m = film_at(&grid, &r.film, 0.0, 0.0);
    let jc = if grid.ny == 1 {
        0
    } else {
        (((0.0 - grid.y_min) / grid.dy - 0.5).round().max(0.0) as usize).min(grid.ny - 1)
    };
    summary.centerline_min_film_m = (0..grid.nx)
        .map(|i| r.film[grid.idx(i, jc)])
        .filter(|h| h.is_finite())
        .reduce(f64::min);
    summary.mass_inflow_kg_s = Some(r.inflow);
    summary.mass_outflow_kg_s = Some(r.outflow);
    summary.side_leakage_kg_s = Some(r.side_leakage);
    let (kmin, hmin) = r
        .film
        .iter()
        .enumerate()
        .filter(|(_, h)| h.is_finite())
        .fold(
            (0, f64::INFINITY),
            |(k, m), (i, &h)| if h < m { (i, h) } else { (k, m) },
        );
    if hmin.is_finite() {
        summary.min_film_m = Some(hmin);
        summary.min_film_at_m = Some([grid.x(kmin % grid.nx), grid.y(kmin / grid.nx)]);
    }
    // Friction only from a converged solution: a figure from a half-solved film would be noise.
    if r.converged {
        let f = crate::friction::friction(&crate::friction::FrictionInput {
            grid: &grid,
            pressure: &r.pressure,
            film: &r.film,
            viscosity: &r.viscosity,
            u1: motion.u1(),
            u2: motion.u2(),
            rheology: &lubricant.rheology,
            load,
        })?;
        summary.friction_force_n = Some(f.force);
        summary.friction_coefficient = Some(f.coefficient);
    }
    Ok(Solution {
        grid,
        fields: Fields {
            pressure: r.pressure,
            deformation: r.deflection,
            film: Some(r.film),
            viscosity: Some(r.viscosity),
            density: Some(r.density),
        },
        summary,
    })
}

/// The text `ehl check` prints: derived quantities, dimensionless groups, classical film
/// estimates, grid resolution.
pub fn check_text(case: &Case) -> String {
    crate::reference::check_report(case).to_string()
}
