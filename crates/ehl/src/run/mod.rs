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

pub mod cancel;
pub mod stress;
pub mod thermal;
pub mod transient;

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

/// Receives the steps of a transient run as they are solved: the output writer of the CLI
/// streams `timeline.csv`, the frames' `.vtr` files and the data of `frames.npz` to disk through
/// it, so that a long run holds no frame in memory. [`solve`] uses [`KeepFrames`].
pub trait StepSink: Send {
    /// Called once before the first step, with the grid of the frames and whether the run is
    /// thermal (the extra timeline columns).
    fn begin(&mut self, _grid: &Grid, _thermal: bool) -> Result<()> {
        Ok(())
    }
    /// Called after each step (step 0 is the steady start) with its timeline row and, for a
    /// kept step (every `output.frames_every`-th and the last), its frame. Returns whether the
    /// run keeps the frame in [`crate::solution::TransientRecord::frames`] as well. An error
    /// stops the run and is returned by [`solve_with`].
    fn step(
        &mut self,
        row: &crate::solution::StepRecord,
        frame: Option<&crate::solution::Frame>,
    ) -> Result<bool>;
    /// Whether the frames this sink takes need memory (the default `output.frames_every` fits
    /// them into the memory left free; a sink that writes them to disk returns false and the
    /// run keeps every step's frame unless the case says otherwise).
    fn frames_in_memory(&self) -> bool {
        true
    }
}

/// The [`StepSink`] of [`solve`]: every kept frame stays in the solution, nothing is written.
pub struct KeepFrames;

impl StepSink for KeepFrames {
    fn step(
        &mut self,
        _row: &crate::solution::StepRecord,
        _frame: Option<&crate::solution::Frame>,
    ) -> Result<bool> {
        Ok(true)
    }
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

/// Largest `solver.mirror_levels` accepted. Each level adds images of the pressure beyond each
/// free end, one roller length further out, so their effect on the contact decays with the
/// level. Measured on `examples/dry_roller_mirror1.toml` (psi = 1, the slowest case), the
/// maximum pressure is 7.3987, 7.2887, 7.2544, 7.2473, 7.2447, 7.2428 GPa at levels 2, 4, 8,
/// 12, 16, 24: one more level changes it by less than 1e-4 relative from level 12 on
/// (9e-5 per level between 12 and 16, 3e-5 between 16 and 24). 16 is the cap: more levels cost
/// one kernel table each (time, no memory) and change nothing that matters.
pub const MAX_MIRROR_LEVELS: usize = 16;

/// Bytes used when /proc/meminfo has no MemAvailable line (not Linux): 16 GiB.
pub const DEFAULT_MEMORY_LIMIT: f64 = 16.0 * (1u64 << 30) as f64;

/// The environment variable that overrides the memory limit (bytes, e.g. `8e9`).
pub const MEMORY_LIMIT_ENV: &str = "EHL_MEMORY_LIMIT";

/// The peak memory a solve of `case` needs, estimated before solving, and the case key that
/// drives it. A model of the large arrays, correct to within about a factor 2 (checked against
/// the peak resident size of dry and EHL runs from 64 x 64 to 512 x 512, see the test
/// `memory_estimate_tracks_measured_peaks` in the notes of docs/case-file.md).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MemoryEstimate {
    /// estimated peak bytes
    pub bytes: f64,
    /// `grid.nx` (or `grid.ny` when ny > nx): the grid drives the estimate
    pub key: &'static str,
}

/// Bytes of one elastic operator on an `nx x ny` grid, while it is built and after: the kernel
/// spectra (one, two with reflected images) of (px/2+1) x py complex numbers, the scratch of an
/// application (row spectra, two transposed spectra, real rows) and, during the build, the
/// padded real table, its row spectra and two (2nx-1)(2ny-1) kernel tables.
fn operator_bytes(nx: usize, ny: usize, reflected: bool) -> f64 {
    let px = crate::elastic::operator::fast_len(2 * nx - 1).max(2) as f64;
    let py = if ny == 1 {
        1.0
    } else {
        crate::elastic::operator::fast_len(2 * ny - 1) as f64
    };
    let hx = (px / 2.0).floor() + 1.0;
    let (nxf, nyf) = (nx as f64, ny as f64);
    let spectra = (if reflected { 2.0 } else { 1.0 }) * hx * py * 16.0;
    let scratch = nyf * hx * 16.0 + 2.0 * hx * py * 16.0 + nyf * px * 8.0;
    let build = py * px * 8.0
        + py * hx * 16.0
        + hx * py * 16.0
        + 2.0 * (2.0 * nxf - 1.0) * (2.0 * nyf - 1.0).max(1.0) * 8.0;
    spectra + scratch + build
}

/// Estimates the peak memory of [`solve`] for `case` (see [`MemoryEstimate`]). Per cell
/// (n = nx ny, 8-byte floats):
///
/// * elastic operators: `operator_bytes` (about 200 bytes per cell) on the fine grid and, as the
///   dry and EHL solvers ask for coarser grids, about 1/3 more;
/// * dry solver: about 16 work vectors (128 bytes) and the output fields (5 x 8);
/// * EHL: the flexible GMRES basis, 2 (restart + 1) vectors (restart 80: 1296 bytes), four
///   Newton states of 9 vectors, the 7 vectors of the linearisation, the line preconditioner's
///   banded blocks (2 kl + ku + 1 = 3 band + 6 diagonals, band up to 64 on grids with
///   dy >> dx), twice (the spare of the next Newton step), with 1/3 more for its multigrid
///   levels.
pub fn memory_estimate(case: &Case) -> MemoryEstimate {
    let g = case.grid;
    let (nx, ny) = (g.nx.max(1), g.ny.max(1));
    let n = nx as f64 * ny as f64;
    let images = case.solver.mirror_levels > 0
        && !case.is_infinite_line()
        && [&case.body1, &case.body2]
            .iter()
            .any(|b| b.shape == Shape::Roller && b.length.is_finite());
    let elastic = operator_bytes(nx, ny, images) * 4.0 / 3.0;
    let dry = 16.0 * 8.0 * n;
    let fields = 5.0 * 8.0 * n;
    let ehl = if case.kind == Kind::Ehl {
        let restart = EhlParams::default().gmres_restart as f64;
        let gmres = 2.0 * (restart + 1.0) * 8.0 * n;
        let states = 4.0 * 9.0 * 8.0 * n + 7.0 * 8.0 * n;
        // the band: the Hertz contact is -1..1 in grid units b along x and along y
        let (dx, dy) = (
            (g.x_max - g.x_min) / nx as f64,
            (g.y_max - g.y_min) / ny as f64,
        );
        let band = if ny > 1 {
            ((dy / (2.0 * dx)).ceil().min(64.0)).max(4.0)
        } else {
            4.0
        }
        .min(nx as f64);
        let precond = 2.0 * (3.0 * band + 6.0 + 2.0) * 8.0 * n * 4.0 / 3.0;
        // a transient infinite line keeps a dense LU of its (n + 1)^2 Jacobian as the
        // preconditioner: assembled and factored in f64, kept in f32 (`linalg::dense`)
        let dense =
            if ny == 1 && nx <= crate::ehl::DENSE_MAX && transient::kinematics(case).is_some() {
                (n + 1.0) * (n + 1.0) * (8.0 + 4.0)
            } else {
                0.0
            };
        gmres + states + precond + dense
    } else {
        0.0
    };
    // a transient run's frames, when output.frames_every fixes how many (otherwise
    // `transient::frames_every` fits them into what the solve leaves free)
    let frames = case
        .output
        .frames_every
        .map_or(0.0, |k| transient::frames_memory(case, k));
    // [stress]: per body the six components, von Mises and the maximum shear (f32), plus one
    // criterion copy for [fatigue]; per thread the layer's tables and FFT buffers (~20 cells x 16 B)
    let stress = case.stress.as_ref().map_or(0.0, |s| {
        let per_body = crate::stress::field::field_bytes(nx * ny, s.layers, 3);
        let threads = rayon::current_num_threads() as f64;
        per_body * s.bodies.len() as f64 + threads * (nx * ny) as f64 * 20.0 * 16.0
    }) + stress::shared_kernel_bytes(case)
        + stress::worst_frame_bytes(case);
    // a transient run's passage maps: accumulators on the body-frame grid x the window layers
    let passage = stress::passage_memory(case);
    let total = elastic + dry + fields + ehl + frames + stress + passage;
    MemoryEstimate {
        bytes: total,
        key: if frames > 0.5 * total {
            "output.frames_every"
        } else if passage > 0.5 * total {
            "stress.window"
        } else if stress > 0.5 * total {
            "stress.layers"
        } else if ny > nx {
            "grid.ny"
        } else {
            "grid.nx"
        },
    }
}

/// The memory a solve may use (bytes): `EHL_MEMORY_LIMIT` when set to a positive number, else
/// MemAvailable of /proc/meminfo, else [`DEFAULT_MEMORY_LIMIT`]. The second value says where the
/// figure comes from, for messages.
pub fn memory_limit() -> (f64, String) {
    // a value that is no positive number is ignored, and the source says so (the CLI refuses
    // it outright; a library or Python caller learns it from the refusal's text)
    let mut ignored = String::new();
    if let Ok(v) = std::env::var(MEMORY_LIMIT_ENV) {
        match v.trim().parse::<f64>() {
            Ok(b) if b > 0.0 && b.is_finite() => return (b, MEMORY_LIMIT_ENV.to_string()),
            _ if v.trim().is_empty() => {}
            _ => {
                ignored = format!(
                    "; {MEMORY_LIMIT_ENV} = {v:?} is not a positive number of bytes and was ignored"
                )
            }
        }
    }
    if let Ok(text) = std::fs::read_to_string("/proc/meminfo") {
        for line in text.lines() {
            if let Some(rest) = line.strip_prefix("MemAvailable:") {
                let mut it = rest.split_whitespace();
                if let Some(Ok(kb)) = it.next().map(|t| t.parse::<f64>()) {
                    return (
                        kb * 1024.0,
                        format!("the available memory (MemAvailable{ignored})"),
                    );
                }
            }
        }
    }
    (
        DEFAULT_MEMORY_LIMIT,
        format!("the default limit (no /proc/meminfo{ignored})"),
    )
}

/// `Err((key, message))` when the estimated memory of `case` exceeds `limit` bytes
/// (`source` says where the limit comes from).
pub fn check_memory(
    case: &Case,
    limit: f64,
    source: &str,
) -> std::result::Result<(), (String, String)> {
    let est = memory_estimate(case);
    if est.bytes <= limit {
        return Ok(());
    }
    let kind = if case.kind == Kind::Ehl {
        "an EHL"
    } else {
        "a dry"
    };
    let (nx, ny) = (case.grid.nx, case.grid.ny);
    let layers = case.stress.as_ref().map_or(0, |s| s.layers);
    // what needs the memory, and what to change
    let (what, cure) = match est.key {
        "output.frames_every" => (
            format!("the frames kept of a transient run on {nx} x {ny} cells need about {} in all (estimate)", bytes_text(est.bytes)),
            "keep fewer frames (a larger output.frames_every, or leave it out to let ehl choose), take fewer motion.travel.steps",
        ),
        "stress.window" => (
            format!("the passage maps of a transient run with [stress] (accumulators on the body-frame grid, the contact grid of {nx} x {ny} cells extended by the travel, times the window's layers) need about {} in all (estimate)", bytes_text(est.bytes)),
            "take a shallower stress.window (fewer layers), one body (stress.body = 1 or 2), leave out fatigue.dang_van (13 of the 19 f32 per point, and the kept surface loads), shorten motion.travel",
        ),
        "stress.layers" => (
            format!("the stress field of {layers} layers below {nx} x {ny} cells needs about {} (estimate)", bytes_text(est.bytes)),
            "take fewer stress.layers (the memory grows with nx * ny * layers), one body (stress.body = 1 or 2), fewer cells",
        ),
        _ => (
            format!("{kind} solve on nx x ny = {nx} x {ny} cells needs about {} (estimate, good to a factor 2)", bytes_text(est.bytes)),
            "use fewer cells (the memory grows with nx * ny)",
        ),
    };
    Err((
        est.key.to_string(),
        format!(
            "{what}, more than the {} of {source}; {cure}, or set {MEMORY_LIMIT_ENV} (bytes) to allow more",
            bytes_text(limit)
        ),
    ))
}

/// A byte count for a message: GB with two decimals from 0.1 GB, MB below (a limit of 1 MB
/// read "0.00 GB").
fn bytes_text(b: f64) -> String {
    if b >= 1e8 {
        format!("{:.2} GB", b / 1e9)
    } else {
        format!("{:.1} MB", b / 1e6)
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
    solve_with(case, progress, &mut KeepFrames)
}

/// [`solve`], with the steps of a transient run passed to `sink` as they are solved (a steady
/// run never calls it). The frames `sink` declines stay out of the solution's
/// [`crate::solution::TransientRecord::frames`], except in a run with `[stress]`, whose
/// worst-frame analysis needs them all.
pub fn solve_with(
    case: &Case,
    progress: &dyn Progress,
    sink: &mut dyn StepSink,
) -> Result<Solution> {
    let start = Instant::now();
    let geometry = Geometry::new(case);
    let grid = geometry.grid();
    let hertz = geometry.hertz();
    let factory = operator_factory(case, &geometry);
    let smooth = |x: f64, y: f64| geometry.gap(x, y);
    // each body's features, at their t = 0 positions (a steady run: see case validation)
    let surfaces: Vec<crate::surface::Surface> = [1u8, 2]
        .iter()
        .map(|&k| {
            crate::surface::Surface::new(
                case.features
                    .iter()
                    .filter(|f| f.body == k)
                    .map(|f| f.feature.clone())
                    .collect(),
            )
        })
        .collect();
    // a transient run places the surfaces at their t = 0 shift (the path form of the travel)
    let kin = transient::kinematics(case);
    let shift0 = kin.map_or(0.0, |k| k.shift0);
    let gap = crate::geometry::GapWithFeatures {
        smooth: &smooth,
        surfaces: surfaces
            .iter()
            .filter(|s| !s.features.is_empty())
            .map(|s| (s, shift0))
            .collect(),
    };
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
            summary.residual = dry.residual.is_finite().then_some(dry.residual);
            summary.load_n = dry.load;
            summary.load_error = (dry.load - load).abs() / load;
            summary.approach_m = dry.approach.is_finite().then_some(dry.approach);
            summary.contact_area_m2 = Some(dry.contact_area);
            let (k, pmax) = argmax(&dry.pressure);
            summary.max_pressure_pa = pmax;
            summary.max_pressure_at_m = [grid.x(k % grid.nx), grid.y(k / grid.nx)];
            Solution {
                stress: None,
                temperature: None,
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
                transient: None,
            }
        }
        Kind::Ehl => match kin {
            Some(kin) => {
                let budget = memory_limit().0 - memory_estimate(case).bytes;
                // frames that go to disk need no memory (unless the run keeps them all the
                // same: `[stress]`, see `frames_every_streamed`)
                let frames_every = if sink.frames_in_memory() {
                    transient::frames_every(case, budget)
                } else {
                    transient::frames_every_streamed(case, budget)
                };
                transient::solve(
                    &transient::Context {
                        case,
                        grid,
                        factory: &factory,
                        smooth: &smooth,
                        surfaces: &surfaces,
                        load,
                        initial_pressure: dry.converged.then_some(dry.pressure.as_slice()),
                        hertz: (hertz.b, hertz.ph),
                        kin,
                        frames_every,
                    },
                    summary,
                    progress,
                    sink,
                )?
            }
            None => solve_ehl(
                case, &geometry, &factory, &gap, load, dry, summary, progress,
            )?,
        },
    };
    let mut solution = solution;
    check_fields(case, &solution)?;
    solution.summary.friction_requested = friction_requested(case);
    clamp_negative_film(&mut solution);
    edge_pressure_warnings(case, &geometry, &mut solution);
    friction_warning(case, &mut solution.summary);
    inlet_warning(case, &mut solution);
    elastic_range_warning(case, &mut solution.summary);
    add_stress(case, &mut solution, progress)?;
    solution.summary.wall_time_s = start.elapsed().as_secs_f64();
    progress.report(1.0, "done");
    Ok(solution)
}

/// `[stress]` and `[fatigue]`: the stress below the surface, its figures, and with features the
/// life against the same case with smooth surfaces (solved here, steadily, with the same grid).
fn add_stress(case: &Case, solution: &mut Solution, progress: &dyn Progress) -> Result<()> {
    if case.stress.is_none() {
        return Ok(());
    }
    progress.report(f64::NAN, "stress below the surface");
    let mut warnings = Vec::new();
    if !solution.summary.converged {
        warnings.push(
            "the stress below the surface is computed from a solution that did not converge: its figures (max von Mises, the fatigue integral, the life ratio) inherit the unconverged pressure"
                .to_string(),
        );
    }
    if let Some(a) = stress::analyse(case, solution, &mut warnings)? {
        stress::summarise(case, &a, &mut solution.summary);
        solution.stress = Some(a);
    }
    solution.summary.warnings.extend(warnings);
    if let (Some(params), false) = (case.fatigue, case.features.is_empty()) {
        progress.report(f64::NAN, "smooth reference for the life ratio");
        let smooth = solve(&stress::smooth_reference(case), &Silent)?;
        if !smooth.summary.converged {
            solution.summary.warnings.push(
                "life_ratio: the smooth reference solve did not converge; the ratio is left out"
                    .into(),
            );
        } else if let (Some(i_ref), Some(i)) = (
            smooth.summary.fatigue_integral,
            solution.summary.fatigue_integral,
        ) {
            solution.summary.smooth_fatigue_integral = Some(i_ref);
            let ratio = crate::stress::fatigue::life_ratio(i_ref, i, params.weibull_slope);
            if ratio.is_finite() {
                solution.summary.life_ratio = Some(ratio);
            } else {
                // I = 0 < I_ref: the surface with features stays below the fatigue limit
                // everywhere while the smooth one does not; JSON has no infinity
                solution.summary.warnings.push(format!(
                    "life_ratio left out: with the features the stress stays below fatigue.fatigue_limit everywhere (integral 0) while the smooth surfaces exceed it (integral {i_ref:e}): an unbounded ratio"
                ));
            }
        }
    }
    Ok(())
}

/// The friction figures into `summary`, or, when the integral fails, `friction_failed` and a
/// warning (the solved pressure and film are kept).
fn add_friction(summary: &mut Summary, input: &crate::friction::FrictionInput) {
    match crate::friction::friction(input) {
        Ok(f) if f.force.is_finite() && f.coefficient.is_finite() => {
            summary.friction_force_n = Some(f.force);
            summary.friction_coefficient = Some(f.coefficient);
        }
        Ok(f) => {
            summary.friction_failed = true;
            summary.warnings.push(format!(
                "friction not computed: the friction integral gave a non-finite force ({}); pressure and film are solved, friction_force_n and friction_coefficient are left out",
                f.force
            ));
        }
        Err(e) => {
            summary.friction_failed = true;
            let m = e.to_string();
            let m = m.strip_prefix("solver: ").unwrap_or(&m);
            summary.warnings.push(format!(
                "friction not computed ({m}); pressure and film are solved, friction_force_n and friction_coefficient are left out (check lubricant.rheology, motion.slide_to_roll)"
            ));
        }
    }
}

/// Whether `case` asks for friction: an EHL case with sliding (`motion.slide_to_roll != 0`) or
/// a non-Newtonian `lubricant.rheology` (whose only use is the friction figure). Pure rolling of
/// a Newtonian film still gets a friction figure (the Poiseuille part) when it can be computed,
/// but its failure is then only a warning.
pub fn friction_requested(case: &Case) -> bool {
    case.kind == Kind::Ehl
        && (case.motion.as_ref().is_some_and(|m| m.slide_to_roll != 0.0)
            || case
                .lubricant
                .as_ref()
                .is_some_and(|l| l.rheology != crate::case::Rheology::Newtonian))
}

/// The case keys that most likely drive a non-finite value in the solved fields, for the error
/// that replaces it.
fn likely_keys(case: &Case, field: &str) -> String {
    let mut keys = vec!["body1.youngs_modulus", "body2.youngs_modulus", "load"];
    if case.kind == Kind::Ehl {
        keys.extend(["motion.entrainment_speed", "lubricant.viscosity"]);
        if matches!(field, "viscosity" | "film" | "pressure") {
            keys.push("lubricant.pressure_viscosity_coefficient");
        }
    }
    keys.push("grid");
    keys.join(", ")
}

/// Safety net after the solvers: a NaN in a field, or an infinity where none may be (any field
/// but the film, which is +inf where a body has no material), is an error naming the keys that
/// likely drive it instead of a summary or an output file with non-finite numbers.
fn check_fields(case: &Case, s: &Solution) -> Result<()> {
    let f = &s.fields;
    let mut named: Vec<(&str, &[f64], bool)> = vec![
        ("pressure", &f.pressure, false),
        ("deformation", &f.deformation, false),
    ];
    if let Some(h) = &f.film {
        named.push(("film", h, true));
    }
    if let Some(v) = &f.viscosity {
        named.push(("viscosity", v, false));
    }
    if let Some(v) = &f.density {
        named.push(("density", v, false));
    }
    for (name, v, inf_ok) in named {
        if let Some(x) = v
            .iter()
            .find(|x| x.is_nan() || (x.is_infinite() && !(inf_ok && **x > 0.0)))
        {
            return Err(Error::Solver(format!(
                "the solved {name} holds {x}: the case is outside the range where the solver's arithmetic holds; check {}",
                likely_keys(case, name)
            )));
        }
    }
    if let Err(k) = crate::output::summary::check_finite(&s.summary) {
        return Err(Error::Solver(format!(
            "the summary figure {k} is not finite: the case is outside the range where the solver's arithmetic holds; check {}",
            likely_keys(case, &k)
        )));
    }
    let sm = &s.summary;
    for (name, v) in [
        ("max_pressure_pa", sm.max_pressure_pa),
        ("load_n", sm.load_n),
        ("hertz_pressure_pa", sm.hertz_pressure_pa),
        ("hertz_half_width_m", sm.hertz_half_width_m),
    ] {
        if !v.is_finite() {
            return Err(Error::Solver(format!(
                "the summary figure {name} is {v}: the case is outside the range where the solver's arithmetic holds; check {}",
                likely_keys(case, name)
            )));
        }
    }
    Ok(())
}

/// A film is never negative. The EHL film h = h0 + gap + deflection can end a little below zero
/// where the film has collapsed to contact (at round-off of the film scale on a converged
/// solution, more on one that did not converge); such values are written as 0 and reported.
fn clamp_negative_film(s: &mut Solution) {
    let Some(h) = s.fields.film.as_mut() else {
        return;
    };
    let (mut count, mut worst) = (0usize, 0.0f64);
    for v in h.iter_mut() {
        if *v < 0.0 {
            count += 1;
            worst = worst.min(*v);
            *v = 0.0;
        }
    }
    let sm = &mut s.summary;
    for v in [
        &mut sm.central_film_m,
        &mut sm.min_film_m,
        &mut sm.centerline_min_film_m,
    ]
    .into_iter()
    .flatten()
    {
        if *v < 0.0 {
            *v = 0.0;
        }
    }
    // dry: the loaded gap is zero in contact, its negative values are the round-off of the
    // contact condition; EHL: a film that collapsed is a finding worth a warning
    if count > 0 && s.fields.viscosity.is_some() {
        sm.warnings.push(format!(
            "the film collapsed to contact: the solver's film was negative in {count} cell(s) (down to {worst:.3e} m) and is written as 0 there"
        ));
    }
}

/// Fraction of the maximum pressure above which a pressure on a domain edge means that the
/// contact reaches the edge: under Hertz, p/p0 = sqrt(1 - (r/a)^2) > 0.1 only for r > 0.995 a,
/// so a boundary cell above 10 % lies within 0.5 % of the contact edge or the contact is cut
/// off by the domain. A domain that contains the contact has (numerically) zero pressure there.
pub const EDGE_PRESSURE_FRACTION: f64 = 0.1;

/// Moes' load parameter M below which a steady film is set in a long inlet (the rigid and
/// elastic-isoviscous regimes, M of order 1-10): there an inlet of 4 b (the default
/// `grid.x_min`) can starve the film (measured: a line at M = 0.96 gave 0.58 of Moes' central
/// film with x_min = -4 b, 0.75 with -20 b).
pub const LONG_INLET_M: f64 = 20.0;

/// A warning when a steady, isothermal EHL infinite line or circular contact at low M
/// ([`LONG_INLET_M`]) has a central film below 0.65 of the full-regime fit (Moes 1992 for the
/// line, Nijenbanning, Venner & Moes 1994 for the circle; both within a few % of numerical
/// solutions over all regimes, with Barus viscosity and an incompressible oil: Roelands and
/// Dowson-Higginson give 10-25 % less, e.g. 0.82 of it for the thesis Table 3.7 line at
/// M = 10.8) while its inlet starts within 10 b: the short inlet, not the physics, is then the
/// likely cause (a line at M = 0.96 gave 0.58 with x_min = -4 b, 0.75 with -20 b).
fn inlet_warning(case: &Case, solution: &mut Solution) {
    // (features: the film at the centre is the feature's, not the smooth contact's the fits give)
    if case.kind != Kind::Ehl
        || solution.transient.is_some()
        || case.thermal.is_some()
        || !solution.summary.converged
        || !case.features.is_empty()
    {
        return;
    }
    let report = crate::reference::check_report(case);
    let (Some((m, l)), Some(hc)) = (report.moes, solution.summary.central_film_m) else {
        return;
    };
    let h = &report.hertz;
    let light = m < LONG_INLET_M;
    let (Some(u), true) = (report.u, !light || case.grid.x_min > -10.0) else {
        return;
    };
    let estimate = if !h.point && h.contact_length.is_infinite() {
        crate::reference::film::moes_line_central(m, l) * h.r * (2.0 * u).sqrt()
    } else if h.point && (h.ellipticity - 1.0).abs() < 1e-6 {
        crate::reference::film::nijenbanning_circular_central(m, l) * h.r * (2.0 * u).sqrt()
    } else {
        return;
    };
    let ratio = hc / estimate;
    if ratio < 0.65 && light {
        solution.summary.warnings.push(format!(
            "the central film is {ratio:.2} of the full-regime fit's {:.3e} m (Barus, incompressible) at Moes M = {m:.3}: at so light a load the film is built in a long inlet, and grid.x_min = {} b likely starves it; widen the inlet (grid.x_min = -16 or less) and compare",
            estimate, case.grid.x_min
        ));
    } else if ratio < 0.65
        && matches!(
            case.lubricant.as_ref().map(|l| &l.rheology),
            Some(crate::lubricant::Rheology::Newtonian)
        )
    {
        // (a Newtonian film only: shear thinning in the inlet thins a film by itself)
        // a heavier load builds the film in a short inlet: an inlet cut to ~1 b, or a grid too
        // coarse for the thin film's steep Hertz-zone gradients (a scan: the EHL-FBNS ball with
        // x_min = -1 b on 32^2 cells gave 53 nm against 207 nm; a line at M = 100 on 256 cells
        // 0.80 of Moes' film), is then the likely cause
        let cells = 2.0 * case.grid.nx as f64 / (case.grid.x_max - case.grid.x_min);
        solution.summary.warnings.push(format!(
            "the central film is {ratio:.2} of the full-regime fit's {:.3e} m (Barus, incompressible) at Moes M = {m:.3}: grid.x_min = {} b may cut the inlet short, or {cells:.0} cells across the Hertz width (grid.nx) may not resolve the film; widen the inlet (grid.x_min = -4 or less), refine the grid and compare",
            estimate, case.grid.x_min
        ));
    }
}

/// What to add to the reason `termination` of a steady EHL solve of a point contact that
/// failed (`converged` false, not cancelled) where `ehl check` notes the contact heavily
/// loaded on a coarse grid ([`crate::reference::check::CheckReport::heavy_and_coarse`]; None
/// otherwise). Called for an isothermal run, or a thermal one whose isothermal start failed.
pub fn heavy_load_hint(case: &Case, converged: bool, termination: &str) -> Option<String> {
    if converged || termination == "cancelled" || case.kind != Kind::Ehl {
        return None;
    }
    crate::reference::check_report(case)
        .heavy_and_coarse()
        .map(|text| format!("; {text}"))
}

/// A warning when the solved pressure (the last step's, or the largest over the travel) leaves
/// the range the contact models hold for, p / E' above
/// [`crate::case::MAX_PRESSURE_OVER_MODULUS`]: the case's Hertz pressure is checked against it
/// before solving, but a sharp feature concentrates the load further (a scan: a bump of slope ~4
/// on a dry ball solved to 139 GPa, p / E' = 0.6, without a word).
fn elastic_range_warning(case: &Case, s: &mut Summary) {
    let e_red = case.reduced_modulus();
    let peak = s
        .max_pressure_pa
        .max(s.max_pressure_over_travel_pa.unwrap_or(0.0));
    let ratio = peak / e_red;
    if ratio > crate::case::MAX_PRESSURE_OVER_MODULUS {
        s.warnings.push(format!(
            "the pressure peaks at {:.3e} Pa, {ratio:.2} times the reduced modulus E' = {e_red:.3e} Pa: beyond p / E' = {} the half-space and linear elasticity no longer hold (steel yields near 0.02); a feature sharper than the grid or steeper than the small-slope gap assumes, or the sharp end of a straight roller (edge loading: profile the roller, docs/ehl.md section 6), is the likely cause",
            peak,
            crate::case::MAX_PRESSURE_OVER_MODULUS
        ));
    }
}

/// Largest friction coefficient of a lubricated contact `ehl` reports without a warning:
/// measured EHL traction stays below about 0.1 (traction fluids about 0.12; Johnson & Tevaarwerk
/// 1977, Evans & Johnson 1986); beyond that the model has left its ground.
pub const FRICTION_WARNING: f64 = 0.2;

/// A warning when the friction coefficient (the last step's, or any over the travel) exceeds
/// [`FRICTION_WARNING`]: an isothermal Newtonian film, or one without a limiting shear stress,
/// turns the viscosity of ~1 GPa into shear stresses no oil carries (the thesis' own rheology
/// is Carreau with the limit of eq. 2.14-2.15).
fn friction_warning(case: &Case, s: &mut Summary) {
    // the figure of largest magnitude, with its sign (negative: the traction on body 2 points
    // against the rolling direction, e.g. body 2 the faster one)
    let worst = s
        .friction_coefficient_over_travel
        .map_or(vec![], |[lo, hi]| vec![lo, hi])
        .into_iter()
        .chain(s.friction_coefficient)
        .fold(0.0f64, |m, f| if f.abs() > m.abs() { f } else { m });
    if !(worst.abs() > FRICTION_WARNING) {
        return;
    }
    let (newtonian, limited) = match case.lubricant.as_ref().map(|l| &l.rheology) {
        Some(crate::lubricant::Rheology::Newtonian) | None => (true, false),
        Some(r) => (
            false,
            crate::lubricant::rheology::limiting_shear_stress(r, 1.0).is_some(),
        ),
    };
    let why = if newtonian {
        "the lubricant is Newtonian: at the contact's pressure its viscosity gives shear stresses no oil carries; give lubricant.rheology a non-Newtonian model with a limiting shear stress (Carreau or Eyring with limiting_shear_coefficient)"
    } else if !limited {
        "the rheology has no limiting shear stress: give lubricant.rheology a limiting_shear_coefficient (0.04-0.08 for mineral oils; thesis eq. 2.14)"
    } else {
        "check the rheology's parameters and the slide-to-roll ratio"
    };
    // sliding heats the film and lowers the traction: a cure only where the run is isothermal
    let thermal = if case.thermal.is_none() {
        ", or add [thermal] (sliding heats the film and lowers the traction)"
    } else {
        ""
    };
    s.warnings.push(format!(
        "friction coefficient {worst:.3} exceeds {FRICTION_WARNING} in magnitude, more than lubricated contacts show (EHL traction stays below about 0.1): {why}{thermal}"
    ));
}

/// Warns, per domain edge, when the pressure stays high at the edge (see
/// [`EDGE_PRESSURE_FRACTION`]). A y edge that lies at a roller's free end (within one cell) is
/// not checked: the pressure legitimately peaks there, and the grid's default y range is the
/// rollers' axial extent.
fn edge_pressure_warnings(case: &Case, geometry: &Geometry, s: &mut Solution) {
    let g = s.grid;
    let p = &s.fields.pressure;
    let pmax = p.iter().cloned().fold(0.0f64, f64::max);
    if !(pmax > 0.0) {
        return;
    }
    let mut ends = Vec::new();
    for k in [1, 2] {
        if let Some((lo, hi)) = geometry.body_ends(k) {
            ends.extend([lo, hi]);
        }
    }
    let at_end = |y: f64| ends.iter().any(|e| (e - y).abs() <= g.dy * (1.0 + 1e-9));
    let mut edges: Vec<(&str, f64)> = Vec::new();
    let col = |i: usize| (0..g.ny).map(|j| p[g.idx(i, j)]).fold(0.0f64, f64::max);
    let row = |j: usize| (0..g.nx).map(|i| p[g.idx(i, j)]).fold(0.0f64, f64::max);
    edges.push(("grid.x_min", col(0)));
    edges.push(("grid.x_max", col(g.nx - 1)));
    if g.ny > 1 && !case.is_infinite_line() {
        if !at_end(g.y_min) {
            edges.push(("grid.y_min", row(0)));
        }
        if !at_end(g.y_max()) {
            edges.push(("grid.y_max", row(g.ny - 1)));
        }
    }
    for (key, pe) in edges {
        if pe > EDGE_PRESSURE_FRACTION * pmax {
            s.summary.warnings.push(format!(
                "the pressure at the {key} edge of the domain is {:.0} % of the maximum pressure: the contact reaches the edge and may be cut off, so the pressure and load figures are doubtful; widen {key}",
                100.0 * pe / pmax
            ));
        }
    }
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

/// The summary figures of an EHL pressure and film (SI): integrated load and its error, the
/// maximum pressure and its place, the central film (x = 0, y = 0), the minimum film on the
/// axial centre row and overall, with its place.
fn ehl_figures(summary: &mut Summary, grid: &Grid, pressure: &[f64], film: &[f64], load: f64) {
    let grid = *grid;
    summary.load_n = pressure.iter().sum::<f64>() * grid.cell_area();
    summary.load_error = (summary.load_n - load).abs() / load;
    let (k, pmax) = argmax(pressure);
    summary.max_pressure_pa = pmax;
    summary.max_pressure_at_m = [grid.x(k % grid.nx), grid.y(k / grid.nx)];
    summary.central_film_m = film_at(&grid, film, 0.0, 0.0);
    let jc = if grid.ny == 1 {
        0
    } else {
        (((0.0 - grid.y_min) / grid.dy - 0.5).round().max(0.0) as usize).min(grid.ny - 1)
    };
    summary.centerline_min_film_m = (0..grid.nx)
        .map(|i| film[grid.idx(i, jc)])
        .filter(|h| h.is_finite())
        .reduce(f64::min);
    let (kmin, hmin) = film.iter().enumerate().filter(|(_, h)| h.is_finite()).fold(
        (0, f64::INFINITY),
        |(k, m), (i, &h)| if h < m { (i, h) } else { (k, m) },
    );
    if hmin.is_finite() {
        summary.min_film_m = Some(hmin);
        summary.min_film_at_m = Some([grid.x(kmin % grid.nx), grid.y(kmin / grid.nx)]);
    }
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
    // the progress bar follows the Newton residual on a log scale from the first iterate of
    // each start down to the tolerance
    // (never backwards: a finer grid of the sequence starts at a higher residual)
    let mut first: Option<f64> = None;
    let mut shown = 0.0f64;
    // the share of the bar the isothermal solve fills: with [thermal] the outer iterations
    // come after it (reported at a fixed 0.9 after up to 0.95, the bar went backwards; a scan)
    let span = if case.thermal.is_some() { 0.3 } else { 0.85 };
    let mut observer = |it: &crate::ehl::NewtonIterate| {
        let r0 = *first.get_or_insert(it.residual.max(it.tolerance * 10.0));
        let done = if it.residual > 0.0 && r0 > it.tolerance {
            ((r0 / it.residual).ln() / (r0 / it.tolerance).ln()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        shown = shown.max(done);
        progress.report(
            0.1 + span * shown,
            &format!(
                "EHL: Newton step {}, residual {:.1e} (tolerance {:.0e}), {} cells",
                it.newton_steps, it.residual, it.tolerance, it.cells
            ),
        );
    };
    let problem = EhlProblem {
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
    };
    // a thermal run's isothermal solution is only the seed of its first outer iteration, whose
    // own Reynolds solve goes to at most 1e-3 (thermal::START_TOLERANCE)
    let start_params = match &case.thermal {
        Some(_) => EhlParams {
            tolerance: params.tolerance.max(thermal::START_TOLERANCE),
            ..params.clone()
        },
        None => params.clone(),
    };
    // a thermal run's contact (its bodies' moving-heat-source tables: 0.12 s of the thesis
    // roller's 256 x 512) is built beside the isothermal start, whose coarse grids leave a
    // core idle; its error, if any, is reported only where the start converged, as when it
    // was built after (a cancel during the start waits for the build: ~0.3 s at most on the
    // thesis roller at 256 x 512)
    let mut start = || {
        crate::ehl::solve_steady_with_fallback_observed(
            &problem,
            &start_params,
            // (the fraction unknown: the first start may have shown more than any fixed figure)
            &|| progress.report(f64::NAN, "EHL, second start"),
            &mut observer,
        )
    };
    // (an isothermal run solves on the calling thread as before: moved into the pool by the
    // join, its criterion solves ran 7-11 % slower, `thermal_roller/isothermal_128x64` and
    // `thermal_line/isothermal_512`; a thermal run's did not, `thermal_line/thermal_256` 6.7 %
    // faster with the join than without it, `thermal_roller/thermal_128x64` the same)
    let start_clock = Instant::now();
    let (mut r, contact) = if case.thermal.is_some() {
        let (r, contact) = rayon::join(start, || thermal::contact_for(case, grid));
        (r, Some(contact))
    } else {
        (start(), None)
    };
    let start_s = start_clock.elapsed().as_secs_f64();
    // [thermal]: the temperature fixed point from the isothermal solution
    let mut thermal_run = None;
    if let (Some(contact), true) = (contact, r.converged) {
        let mut told = |outer: usize, change: f64| {
            // the outer iterations' count is not known ahead: a fraction that grows with them
            // towards 0.95, never back
            let k = outer as f64;
            progress.report(
                0.1 + span + (0.85 - span) * k / (k + 5.0),
                &format!(
                    "thermal: outer iteration {outer}{}",
                    thermal::change_text(change)
                ),
            )
        };
        let run = thermal::solve_in(case, &problem, &params, &r, contact?, &mut told)?;
        r = run.result.ehl.clone();
        thermal_run = Some(run);
    }
    summary.converged = r.converged;
    summary.termination = r.termination.clone();
    if thermal_run.is_none() {
        if let Some(hint) = heavy_load_hint(case, r.converged, &r.termination) {
            summary.termination.push_str(&hint);
        }
    }
    summary.iterations = r.iterations;
    // the EHL solver writes f64::MAX for a residual it could not evaluate: leave it out
    summary.residual = (r.residual.is_finite() && r.residual < f64::MAX).then_some(r.residual);
    ehl_figures(
        &mut summary,
        &grid,
        &r.fields.pressure,
        &r.fields.film,
        load,
    );
    summary.mass_inflow_kg_s = Some(r.inflow);
    summary.mass_outflow_kg_s = Some(r.outflow);
    summary.side_leakage_kg_s = Some(r.side_leakage);
    // Friction only from a converged solution: a figure from a half-solved film would be noise.
    // A failed friction integral does not throw away the solved pressure and film: the friction
    // keys are left out, `friction_failed` is set and a warning says why.
    if let Some(run) = &thermal_run {
        // the thermal shear of the film's own velocity profile (the viscosity across z at its
        // temperature, the rheology's effective viscosity), not the isothermal estimate
        let mu = run.friction_force / load;
        if r.converged && mu.is_finite() {
            summary.friction_force_n = Some(run.friction_force);
            summary.friction_coefficient = Some(mu);
        }
        summary.thermal_time = Some(thermal::time_split(start_s, &run.result.times));
        if run.contact.solved() {
            thermal::summarise(case, run, summary.friction_coefficient, &mut summary);
            if !r.converged {
                // a scan found an unsettled thermal roller reporting absurd temperatures with
                // only `converged = false` to flag them
                summary.warnings.push(
                    "the temperatures and heat flows are those of the last outer iteration of a thermal solve that did not settle: not a solution; see termination".into(),
                );
            }
        }
    } else if r.converged {
        add_friction(
            &mut summary,
            &crate::friction::FrictionInput {
                grid: &grid,
                pressure: &r.fields.pressure,
                film: &r.fields.film,
                viscosity: &r.fields.viscosity,
                u1: motion.u1(),
                u2: motion.u2(),
                rheology: &lubricant.rheology,
                load,
            },
        );
    }
    Ok(Solution {
        stress: None,
        temperature: thermal_run.filter(|t| t.contact.solved()).map(|t| t.fields),
        grid,
        fields: Fields {
            pressure: r.fields.pressure,
            deformation: r.fields.deflection,
            film: Some(r.fields.film),
            viscosity: Some(r.fields.viscosity),
            density: Some(r.fields.density),
        },
        summary,
        transient: None,
    })
}

/// The text `ehl check` prints: derived quantities, dimensionless groups, classical film
/// estimates, grid resolution.
pub fn check_text(case: &Case) -> String {
    crate::reference::check_report(case).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_friction_integral_is_a_warning_not_an_error() {
        // a Newtonian film without limiting shear stress, collapsed (h = 0) in a pressurised
        // cell under sliding: the shear stress is unbounded and the integral fails
        let grid = Grid::new(2, 1, -1e-4, 1e-4, -0.5, 0.5);
        let mut s = Summary::default();
        add_friction(
            &mut s,
            &crate::friction::FrictionInput {
                grid: &grid,
                pressure: &[1e9, 1e9],
                film: &[0.0, 1e-7],
                viscosity: &[1.0, 1.0],
                u1: 2.1,
                u2: 1.9,
                rheology: &crate::case::Rheology::Newtonian,
                load: 2e5,
            },
        );
        assert!(s.friction_failed && s.friction_coefficient.is_none());
        assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
        assert!(
            s.warnings[0].contains("friction not computed"),
            "{:?}",
            s.warnings
        );
        s.friction_requested = true;
        assert!(s.requested_friction_failed());
        s.friction_requested = false;
        assert!(!s.requested_friction_failed());
        let json = serde_json::to_value(&s).unwrap();
        assert_eq!(json["friction_failed"], true);
        assert!(json.get("friction_coefficient").is_none());
    }

    /// The hint of a failed heavily loaded point contact: given at M >= 1000 on fewer than 64
    /// cells across the contact along x or y, not on a grid fine in both, a light load, a line
    /// or a solve that converged; `ehl check` notes the same case beforehand.
    #[test]
    fn a_failed_heavily_loaded_ball_is_told_to_refine_its_grid() {
        let ball = "title = \"heavy ball\"\nkind = \"ehl\"\n\
            [body1]\nshape = \"ball\"\nradius = 0.0127\nyoungs_modulus = 206e9\npoisson_ratio = 0.3\n\
            [body2]\nshape = \"flat\"\nyoungs_modulus = 206e9\npoisson_ratio = 0.3\n\
            [load]\nforce = 1000.0\n[motion]\nentrainment_speed = 1.0\n\
            [lubricant]\nviscosity = 0.05\npressure_viscosity_coefficient = 2.0e-8\ndensity = 870.0\n\
            [grid]\nnx = 97\nny = 97\nx_min = -3.5\nx_max = 1.5\ny_min = -2.5\ny_max = 2.5\n";
        let case = |sets: &[&str]| {
            let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
            crate::case::parse_str(ball, "b.toml", &sets).unwrap()
        };
        let failed = "Newton: line search failed";
        let heavy = case(&[]);
        let m = crate::reference::check_report(&heavy).moes.unwrap().0;
        assert!((1900.0..1930.0).contains(&m), "{m}");
        let hint = heavy_load_hint(&heavy, false, failed).expect("a hint");
        assert!(
            hint.contains(&format!("M = {m:.0}")) && hint.contains("39 x 39 cells"),
            "{hint}"
        );
        // `ehl check` says the same beforehand
        let noted = |c: &Case| {
            crate::reference::check_report(c)
                .to_string()
                .contains("note: a heavily loaded contact")
        };
        assert!(noted(&heavy));
        assert!(heavy_load_hint(&case(&[]), true, "converged").is_none());
        assert!(heavy_load_hint(&case(&[]), false, "cancelled").is_none());
        let fine = ["grid.nx=193", "grid.ny=193", "grid.x_min=-2.5"];
        assert!(heavy_load_hint(&case(&fine), false, failed).is_none());
        assert!(!noted(&case(&fine)));
        // fine along x only: still too coarse along y (39 cells across 2 a)
        let fine_x = ["grid.nx=193", "grid.x_min=-2.5"];
        assert!(heavy_load_hint(&case(&fine_x), false, failed).is_some());
        assert!(heavy_load_hint(&case(&["load.force=30"]), false, failed).is_none());
        let line = crate::case::parse_str(
            &ball
                .replace(
                    "shape = \"ball\"\nradius = 0.0127",
                    "shape = \"roller\"\nradius = 0.02\nlength = inf",
                )
                .replace(
                    "shape = \"flat\"",
                    "shape = \"roller\"\nradius = 0.02\nlength = inf",
                )
                .replace("force = 1000.0", "max_hertz_pressure = 3e9")
                .replace("ny = 97", "ny = 1")
                .replace("y_min = -2.5\ny_max = 2.5\n", ""),
            "l.toml",
            &[],
        )
        .unwrap();
        assert!(heavy_load_hint(&line, false, failed).is_none());
    }

    #[test]
    fn memory_estimate_scales_with_the_grid_and_the_limit_names_the_key() {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../examples/ehl_ball_on_glass.toml"
        ))
        .unwrap();
        let small = crate::case::parse_str(&text, "c.toml", &[]).unwrap();
        let mut big = small.clone();
        big.grid.nx = 8192;
        big.grid.ny = 8192;
        let (es, eb) = (memory_estimate(&small), memory_estimate(&big));
        let cells = |c: &Case| (c.grid.nx * c.grid.ny) as f64;
        // per cell: a few kB for EHL (GMRES basis, operator spectra, preconditioner)
        let per_cell = eb.bytes / cells(&big);
        assert!((1500.0..6000.0).contains(&per_cell), "{per_cell}");
        assert!(es.bytes < eb.bytes);
        let (k, m) = check_memory(&big, 8e9, "a test limit").unwrap_err();
        assert_eq!(k, "grid.nx");
        assert!(m.contains("GB") && m.contains("EHL_MEMORY_LIMIT"), "{m}");
        assert!(check_memory(&small, 8e9, "a test limit").is_ok());
        // a deep stress field names stress.layers and says so (a scan found its message
        // telling to use fewer cells); a small limit reads in MB, not "0.00 GB"
        let mut deep =
            crate::case::parse_str(&text, "c.toml", &["stress={ layers = 8 }".into()]).unwrap();
        deep.grid.nx = 1024;
        deep.grid.ny = 1024;
        deep.stress.as_mut().unwrap().layers = 1024;
        let (k, m) = check_memory(&deep, 8e9, "a test limit").unwrap_err();
        assert_eq!(k, "stress.layers");
        assert!(m.contains("fewer stress.layers"), "{m}");
        let (_, m) = check_memory(&small, 1e6, "a test limit").unwrap_err();
        assert!(m.contains("1.0 MB"), "{m}");
        // a dry solve needs far less per cell
        let mut dry = big.clone();
        dry.kind = Kind::Dry;
        assert!(memory_estimate(&dry).bytes < 0.5 * eb.bytes);
    }
}
