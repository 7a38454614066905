//! A transient case (`motion.travel` given): the surfaces moving with their bodies, the time
//! loop of [`crate::ehl::transient`], and per step the figures of a `timeline.csv` row
//! (friction included), the frames kept and the snapshots asked for. No file I/O here.
//!
//! Kinematics (docs/case-file.md, "Transient runs"): body k's surface moves along +x at
//! u1 = u_e (1 + SRR/2) or u2 = u_e (1 - SRR/2), carrying its features. x_p is the centre of
//! `features[0]` along x: x_p(t) = x_p(0) + u_body t. The path form `{ from, to, steps }` shifts
//! every body's surface at t = 0 by `from - features[0].x` (the features keep their relative
//! places) and takes dt = (to - from) / steps / u_body; the duration form keeps the case's
//! positions and takes dt = duration / steps. Without a feature, x_p reports the distance the
//! mean flow has travelled, u_e t.

use super::{film_at, Progress};
use crate::case::{Case, Travel};
use crate::ehl::thermal::ThermalTimes;
use crate::ehl::{
    solve_transient_observed, EhlParams, EhlProblem, MovingSurface, StartObserver, StepResult,
    TimeScheme, TransientEnd, TransientParams, TransientProblem,
};
use crate::elastic::Deflection;
use crate::geometry::GapSampler;
use crate::grid::Grid;
use crate::solution::{
    Fields, Frame, Solution, StepRecord, StepThermalRecord, Summary, TransientRecord,
};
use crate::surface::Surface;
use crate::{Error, Result};
use std::ops::ControlFlow;

/// Where the surfaces start and how x_p moves, from `motion.travel`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// shift of every body's surface along x at t = 0 (m)
    pub shift0: f64,
    /// time step (s)
    pub dt: f64,
    pub steps: usize,
    /// x_p at t = 0 (m)
    pub xp0: f64,
    /// dx_p/dt (m/s): the speed of `features[0]`'s body, or u_e without a feature
    pub xp_speed: f64,
}

impl Kinematics {
    /// x_p (m) at time `t` (s).
    pub fn x_p(&self, t: f64) -> f64 {
        self.xp0 + self.xp_speed * t
    }

    /// The step whose x_p is nearest to `x` (clamped to 0 ..= steps).
    pub fn nearest_step(&self, x: f64) -> usize {
        let per_step = self.xp_speed * self.dt;
        if !(per_step > 0.0) {
            return 0;
        }
        ((x - self.xp0) / per_step)
            .round()
            .clamp(0.0, self.steps as f64) as usize
    }
}

/// The kinematics of a transient case; `None` for a steady case (no `motion.travel`).
pub fn kinematics(case: &Case) -> Option<Kinematics> {
    let m = case.motion.as_ref()?;
    let travel = m.travel?;
    let speed = |body: u8| if body == 2 { m.u2() } else { m.u1() };
    let first = case.features.first();
    Some(match travel {
        Travel::Path { from, to, steps } => {
            // the case reader guarantees a feature on a moving body (docs/case-file.md)
            let (x0, u) = first.map_or((0.0, m.entrainment_speed), |f| {
                (f.feature.centre.0, speed(f.body))
            });
            Kinematics {
                shift0: from - x0,
                dt: (to - from) / steps as f64 / u,
                steps,
                xp0: from,
                xp_speed: u,
            }
        }
        Travel::Duration { duration, steps } => {
            let (x0, u) = first.map_or((0.0, m.entrainment_speed), |f| {
                (f.feature.centre.0, speed(f.body))
            });
            Kinematics {
                shift0: 0.0,
                dt: duration / steps as f64,
                steps,
                xp0: x0,
                xp_speed: u,
            }
        }
    })
}

/// Bytes of one kept frame (pressure and film) on `nx x ny` cells.
pub fn frame_bytes(nx: usize, ny: usize) -> f64 {
    2.0 * 8.0 * nx as f64 * ny as f64
}

/// Bytes of the frames a transient case keeps with `output.frames_every = k`, plus the
/// snapshots (5 fields each); 0 for a steady case.
pub fn frames_memory(case: &Case, k: usize) -> f64 {
    let Some(kin) = kinematics(case) else {
        return 0.0;
    };
    let (nx, ny) = (case.grid.nx, case.grid.ny);
    (kin.steps / k.max(1) + 2) as f64 * frame_bytes(nx, ny)
        + case.output.snapshots.len() as f64 * 2.5 * frame_bytes(nx, ny)
}

/// The `output.frames_every` a transient case uses: the case's value, or the least k that
/// keeps the frames and the snapshots ([`frames_memory`]) within `budget` bytes (every step's
/// frame dropped but the first and last when even that does not fit).
pub fn frames_every(case: &Case, budget: f64) -> usize {
    if let Some(k) = case.output.frames_every {
        return k.max(1);
    }
    let Some(kin) = kinematics(case) else {
        return 1;
    };
    // frames_memory(k) = (steps / k + 2) frame + snapshots: the least k with that <= budget
    let frame = frame_bytes(case.grid.nx, case.grid.ny);
    let fixed = frames_memory(case, kin.steps.max(1)) - (1 + 2) as f64 * frame;
    let room = budget - fixed - 2.0 * frame;
    if !(room > frame) {
        return kin.steps.max(1);
    }
    // floor(steps / k) <= m frames beyond the two fixed: k = floor(steps / (m + 1)) + 1
    let m = (room / frame).floor() as usize;
    if m >= kin.steps {
        return 1;
    }
    (kin.steps / (m + 1) + 1).clamp(1, kin.steps.max(1))
}

/// The `output.frames_every` of `ehl run`, which streams the frames to disk
/// ([`crate::output::stream`]): the case's value, else every step; a run with `[stress]` holds
/// its frames for the worst-frame analysis, so there the memory bound of [`frames_every`]
/// (within `budget` bytes) applies as in the library.
pub fn frames_every_streamed(case: &Case, budget: f64) -> usize {
    match case.output.frames_every {
        Some(k) => k.max(1),
        None if case.stress.is_some() => frames_every(case, budget),
        None => 1,
    }
}

/// Everything the transient run needs from `solve`.
pub(super) struct Context<'a> {
    pub case: &'a Case,
    pub grid: Grid,
    pub factory: &'a (dyn Fn(Grid) -> Box<dyn Deflection> + Sync),
    pub smooth: &'a dyn GapSampler,
    pub surfaces: &'a [Surface],
    pub load: f64,
    pub initial_pressure: Option<&'a [f64]>,
    pub hertz: (f64, f64),
    pub kin: Kinematics,
    pub frames_every: usize,
}

/// Runs the transient case and returns its solution: the last step's fields and summary
/// figures, the extremes over the travel, the timeline, the frames and the snapshots.
pub(super) fn solve(
    ctx: &Context,
    mut summary: Summary,
    progress: &dyn Progress,
    sink: &mut dyn super::StepSink,
) -> Result<Solution> {
    let case = ctx.case;
    let (lubricant, motion) = match (&case.lubricant, &case.motion) {
        (Some(l), Some(m)) => (l, m),
        _ => {
            return Err(Error::Solver(
                "an ehl case needs [lubricant] and [motion]".into(),
            ))
        }
    };
    let grid = ctx.grid;
    let (b, ph) = ctx.hertz;
    let kin = ctx.kin;
    let speeds = [motion.u1(), motion.u2()];
    let problem = TransientProblem {
        base: EhlProblem {
            grid,
            gap: ctx.smooth,
            operator: ctx.factory,
            load: ctx.load,
            lubricant,
            entrainment_speed: motion.entrainment_speed,
            reduced_radius: case.reduced_radius(),
            reduced_modulus: case.reduced_modulus(),
            hertz_half_width: b,
            hertz_pressure: ph,
            initial_pressure: ctx.initial_pressure,
        },
        smooth: ctx.smooth,
        surfaces: ctx
            .surfaces
            .iter()
            .zip(speeds)
            .map(|(s, speed)| MovingSurface {
                surface: s,
                shift0: kin.shift0,
                speed,
            })
            .collect(),
        dt: kin.dt,
        steps: kin.steps,
    };
    let params = TransientParams {
        newton: EhlParams {
            tolerance: case.solver.tolerance,
            max_iterations: case.solver.max_iterations,
            wedge_upwind_order: case.solver.wedge_upwind_order,
            ..EhlParams::default()
        },
        scheme: TimeScheme::Bdf2,
        feature_transport: true,
    };
    // the step each snapshot is taken at
    let snapshot_steps: Vec<(f64, usize)> = case
        .output
        .snapshots
        .iter()
        .map(|&x| (x, kin.nearest_step(x)))
        .collect();
    let mut record = TransientRecord {
        dt_s: kin.dt,
        frames_every: ctx.frames_every,
        ..TransientRecord::default()
    };
    // [stress]: the stress history in each chosen body's material frame
    let mut passage = super::stress::PassageRun::new(case, &grid, kin.steps, kin.dt);
    let mut last: Option<StepResult> = None;
    let mut friction_failures = 0usize;
    let mut first_failure: Option<(usize, String)> = None;
    let steps = kin.steps;
    let area = grid.cell_area();
    // [thermal]: the temperature model, stepped with the pressure
    let mut contact = match &case.thermal {
        Some(_) => Some(super::thermal::contact_for(case, grid)?),
        None => None,
    };
    // the run's own need for every frame: the worst-frame stress analysis after the run
    let keep_anyway = case.stress.is_some();
    sink.begin(&grid, contact.is_some())?;
    let mut sink_error: Option<Error> = None;
    // [thermal]: where the steps' time went, the isothermal start's and the phases' sums
    let mut thermal_times: Option<(f64, ThermalTimes)> = None;
    let mut observer = |s: &StepResult| {
        if let Some(th) = &s.thermal {
            let sum = thermal_times.get_or_insert((0.0, ThermalTimes::default()));
            sum.0 += th.isothermal_start_s;
            sum.1.add(&th.times);
        }
        let x_p = kin.x_p(s.time);
        let friction = if let (true, Some(th)) = (s.converged, &s.thermal) {
            // the thermal shear of the film's own velocity profile (as a steady thermal run)
            let mu = th.friction_force / ctx.load;
            if mu.is_finite() {
                Some(mu)
            } else {
                friction_failures += 1;
                None
            }
        } else if s.converged {
            match crate::friction::friction(&crate::friction::FrictionInput {
                grid: &grid,
                pressure: &s.fields.pressure,
                film: &s.fields.film,
                viscosity: &s.fields.viscosity,
                u1: motion.u1(),
                u2: motion.u2(),
                rheology: &lubricant.rheology,
                load: ctx.load,
            }) {
                Ok(f) if f.coefficient.is_finite() => Some(f.coefficient),
                _ => {
                    friction_failures += 1;
                    None
                }
            }
        } else {
            if first_failure.is_none() {
                first_failure = Some((s.step, s.reason.to_string()));
            }
            None
        };
        let min_film = s
            .fields
            .film
            .iter()
            .cloned()
            .filter(|h| h.is_finite())
            .fold(f64::INFINITY, f64::min);
        let max_p = s.fields.pressure.iter().cloned().fold(0.0f64, f64::max);
        let row = StepRecord {
            step: s.step,
            time_s: s.time,
            x_p_m: x_p,
            max_pressure_pa: max_p,
            min_film_m: if min_film.is_finite() {
                min_film.max(0.0)
            } else {
                0.0
            },
            central_film_m: film_at(&grid, &s.fields.film, 0.0, 0.0).map_or(0.0, |h| h.max(0.0)),
            friction_coefficient: friction,
            centerline_min_film_m: {
                let jc = if grid.ny == 1 {
                    0
                } else {
                    ((-grid.y_min / grid.dy - 0.5).round().max(0.0) as usize).min(grid.ny - 1)
                };
                let m = s.fields.film[jc * grid.nx..(jc + 1) * grid.nx]
                    .iter()
                    .cloned()
                    .filter(|h| h.is_finite())
                    .fold(f64::INFINITY, f64::min);
                if m.is_finite() {
                    m.max(0.0)
                } else {
                    0.0
                }
            },
            load_error: s.fields.pressure.iter().sum::<f64>() * area / ctx.load - 1.0,
            converged: s.converged,
            h0_m: s.fields.h0,
            newton_iterations: s.newton_iterations,
            linear_iterations: s.linear_iterations,
            operator_applications: s.operator_applications,
            mass_balance: s.mass.relative_error(),
            mass_inflow_kg_s: s.mass.inflow,
            mass_outflow_kg_s: s.mass.outflow,
            side_leakage_kg_s: s.mass.side_leakage,
            mass_storage_kg_s: s.mass.storage,
            wall_time_s: s.wall_time,
            thermal: s.thermal.map(|th| StepThermalRecord {
                max_film_temperature_k: th.max_film_temperature_k,
                max_surface_temperature_1_k: th.max_surface_temperature_k[0],
                max_surface_temperature_2_k: th.max_surface_temperature_k[1],
                heat_generated_w: th.heat.generated,
                heat_stored_w: th.heat.stored,
                energy_balance_error: th.heat.balance_error(),
                thermal_passes: th.passes,
            }),
        };
        let frame = (s.step.is_multiple_of(ctx.frames_every) || s.step == steps).then(|| Frame {
            step: s.step,
            time_s: s.time,
            x_p_m: x_p,
            pressure: s.fields.pressure.clone(),
            film: s.fields.film.iter().map(|&h| h.max(0.0)).collect(),
        });
        match sink.step(&row, frame.as_ref()) {
            Ok(keep) => {
                if let (true, Some(f)) = (keep || keep_anyway, frame) {
                    record.frames.push(f);
                }
            }
            Err(e) => {
                sink_error = Some(e);
                return ControlFlow::Break(());
            }
        }
        record.timeline.push(row);
        if let Some(pr) = passage.as_mut() {
            pr.step(
                case,
                &grid,
                s.step,
                steps,
                s.time,
                s.converged,
                &s.fields.pressure,
                &s.fields.film,
                &s.fields.viscosity,
            );
        }
        for &(x, k) in &snapshot_steps {
            if k == s.step {
                record.snapshots.push((x, k, fields_of(s)));
            }
        }
        progress.report(
            s.step as f64 / steps.max(1) as f64,
            &format!(
                "step {}/{steps}, x_p = {:.4} mm{}",
                s.step,
                x_p * 1e3,
                if s.converged { "" } else { " (not converged)" }
            ),
        );
        last = Some(s.clone());
        ControlFlow::Continue(())
    };
    // the steady start (which can take most of a short run) shows on the progress bar too
    let mut start_newton = |it: &crate::ehl::NewtonIterate| {
        progress.report(
            0.0,
            &format!(
                "steady start: Newton step {}, residual {:.1e} (tolerance {:.0e}), {} cells",
                it.newton_steps, it.residual, it.tolerance, it.cells
            ),
        )
    };
    let mut start_thermal = |outer: usize, change: f64| {
        progress.report(
            0.0,
            &format!(
                "steady start: thermal outer iteration {outer}{}",
                super::thermal::change_text(change)
            ),
        )
    };
    let start = StartObserver {
        newton: Some(&mut start_newton),
        thermal: Some(&mut start_thermal),
    };
    let thermal_params = super::thermal::params_for(case);
    let end = solve_transient_observed(
        &problem,
        &params,
        contact.as_mut().map(|c| (&thermal_params, c)),
        start,
        &mut observer,
    );
    if let Some(e) = sink_error {
        return Err(e);
    }
    let Some(last) = last else {
        return Err(Error::Solver("the transient run produced no step".into()));
    };
    let failed_steps: Vec<usize> = record
        .timeline
        .iter()
        .filter(|r| !r.converged)
        .map(|r| r.step)
        .collect();
    // the last step's figures
    super::ehl_figures(
        &mut summary,
        &grid,
        &last.fields.pressure,
        &last.fields.film,
        ctx.load,
    );
    summary.residual =
        (last.residual.is_finite() && last.residual < f64::MAX).then_some(last.residual);
    summary.mass_inflow_kg_s = Some(last.mass.inflow);
    summary.mass_outflow_kg_s = Some(last.mass.outflow);
    summary.side_leakage_kg_s = Some(last.mass.side_leakage);
    summary.iterations = record.timeline.iter().map(|r| r.newton_iterations).sum();
    summary.converged = failed_steps.is_empty() && matches!(end, TransientEnd::Completed { .. });
    summary.termination = if failed_steps.is_empty() {
        format!(
            "{steps} time steps, every step converged (tolerance {:.1e})",
            case.solver.tolerance
        )
    } else {
        let (k, why) = first_failure.unwrap_or((failed_steps[0], String::new()));
        format!(
            "{} of {} steps (step 0, the steady start, included) did not converge; first: step {k}: {why}",
            failed_steps.len(),
            steps + 1
        )
    };
    for hint in [super::thermal::loading_hint, super::thermal::rheology_hint] {
        if let Some(hint) = hint(case, summary.converged, &summary.termination) {
            summary.termination.push_str(&hint);
        }
    }
    if let Some(last_row) = record.timeline.last() {
        if let Some(f) = last_row.friction_coefficient {
            summary.friction_coefficient = Some(f);
            summary.friction_force_n = Some(f * ctx.load);
        }
    }
    if friction_failures > 0 {
        summary.warnings.push(format!(
            "the friction integral failed at {friction_failures} converged step(s); their friction_coefficient cells in timeline.csv are empty"
        ));
    }
    // a feature that never comes onto the grid leaves the run smooth (a scan: a pit travelling
    // from -5 to -4 mm towards a contact within +-0.5 mm, run and reported without a word)
    let duration = kin.dt * kin.steps as f64;
    let (xlo, xhi) = (grid.x_min, grid.x_min + grid.nx as f64 * grid.dx);
    for (i, f) in case.features.iter().enumerate() {
        let Some((a, b)) = f.feature.x_span() else {
            continue;
        };
        let u = case
            .motion
            .as_ref()
            .map_or(0.0, |m| if f.body == 1 { m.u1() } else { m.u2() });
        // every surface starts shifted by shift0 (the path form puts features[0] at `from`)
        let s = u * duration;
        let (lo, hi) = (a + kin.shift0 + s.min(0.0), b + kin.shift0 + s.max(0.0));
        if hi <= xlo || lo >= xhi {
            summary.warnings.push(format!(
                "features[{i}] never comes onto the grid: over the travel it covers x = {lo:.4e} .. {hi:.4e} m, the grid x = {xlo:.4e} .. {xhi:.4e} m, so the run is that of smooth surfaces; move features[{i}].x or lengthen motion.travel"
            ));
        }
    }
    let cells = kin.xp_speed.abs() * kin.dt / grid.dx;
    if let Some(steps) =
        crate::reference::check::steps_for_one_cell(!case.features.is_empty(), kin.steps, cells)
    {
        summary.warnings.push(format!(
            "features[0] moved {cells:.1} cells a step: at more than about one a steep-walled feature's wall pressures depend on the step (docs/pits.md, \"Sharp edges and the time step\"); motion.travel.steps = {steps} gives one"
        ));
    }
    // the extremes over the travel come from the converged steps (a step that did not converge
    // holds its best state, whose spikes are not the physics); from every step when none did
    let any_converged = record.timeline.iter().any(|r| r.converged);
    let counted: Vec<&StepRecord> = record
        .timeline
        .iter()
        .filter(|r| r.converged || !any_converged)
        .collect();
    let top = counted
        .iter()
        .copied()
        .max_by(|a, b| a.max_pressure_pa.total_cmp(&b.max_pressure_pa))
        .expect("step 0 is always in the timeline");
    summary.max_pressure_over_travel_pa = Some(top.max_pressure_pa);
    summary.max_pressure_over_travel_at_xp_m = Some(top.x_p_m);
    let thin = counted
        .iter()
        .copied()
        .min_by(|a, b| a.min_film_m.total_cmp(&b.min_film_m))
        .expect("step 0 is always in the timeline");
    summary.min_film_over_travel_m = Some(thin.min_film_m);
    summary.min_film_over_travel_at_xp_m = Some(thin.x_p_m);
    let fr: Vec<f64> = record
        .timeline
        .iter()
        .filter_map(|r| r.friction_coefficient)
        .collect();
    if !fr.is_empty() {
        summary.friction_coefficient_mean_over_travel =
            Some(fr.iter().sum::<f64>() / fr.len() as f64);
        summary.friction_coefficient_over_travel = Some([
            fr.iter().cloned().fold(f64::INFINITY, f64::min),
            fr.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
        ]);
    }
    summary.steps = Some(steps);
    summary.max_mass_balance_error = Some(
        record
            .timeline
            .iter()
            .map(|r| r.mass_balance.abs())
            .fold(0.0, f64::max),
    );
    summary.failed_steps = Some(failed_steps);
    if let Some(pr) = passage.as_mut() {
        progress.report(f64::NAN, "passage maps: Dang Van second pass");
        pr.finish(&grid);
        super::stress::summarise_passage(pr, &mut summary);
    }
    record.passage = passage;
    // [thermal]: where the time went
    summary.thermal_time = thermal_times.map(|(start, t)| super::thermal::time_split(start, &t));
    // [thermal]: the last step's temperatures and heat, and the extremes over the travel
    let mut temperature = None;
    if let Some(c) = contact.as_ref().filter(|c| c.solved()) {
        let fields = c.fields(&last.fields.film);
        let outer = record
            .timeline
            .first()
            .and_then(|r| r.thermal)
            .map_or(0, |t| t.thermal_passes);
        super::thermal::summarise_contact(
            case,
            c,
            &fields,
            outer,
            summary.friction_coefficient,
            &mut summary,
        );
        let rows: Vec<(f64, StepThermalRecord)> = record
            .timeline
            .iter()
            .filter(|r| r.converged || !any_converged)
            .filter_map(|r| r.thermal.map(|t| (r.x_p_m, t)))
            .collect();
        if let Some((x, t)) = rows.iter().max_by(|a, b| {
            a.1.max_film_temperature_k
                .total_cmp(&b.1.max_film_temperature_k)
        }) {
            summary.max_film_temperature_over_travel_k = Some(t.max_film_temperature_k);
            summary.max_film_temperature_over_travel_at_xp_m = Some(*x);
        }
        if !rows.is_empty() {
            let top = |f: fn(&StepThermalRecord) -> f64| {
                rows.iter()
                    .map(|(_, t)| f(t))
                    .fold(f64::NEG_INFINITY, f64::max)
            };
            summary.max_surface_temperature_over_travel_k = Some([
                top(|t| t.max_surface_temperature_1_k),
                top(|t| t.max_surface_temperature_2_k),
            ]);
            let worst = top(|t| t.energy_balance_error.abs());
            summary.max_energy_balance_error = Some(worst);
            summary
                .warnings
                .extend(crate::run::thermal::energy_balance_warning(
                    worst,
                    "of the worst time step",
                ));
        }
        temperature = Some(fields);
    }
    Ok(Solution {
        stress: None,
        temperature,
        grid,
        fields: fields_of(&last),
        summary,
        transient: Some(record),
    })
}

/// The output fields of a step.
fn fields_of(s: &StepResult) -> Fields {
    Fields {
        pressure: s.fields.pressure.clone(),
        deformation: s.fields.deflection.clone(),
        film: Some(s.fields.film.clone()),
        viscosity: Some(s.fields.viscosity.clone()),
        density: Some(s.fields.density.clone()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn groove(set: &[&str]) -> Case {
        let path = std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../examples/ehl_transient_line_groove.toml"
        ));
        let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        crate::case::load_file(path, &set).expect("example case")
    }

    /// Without `output.frames_every` the least k whose frames and snapshots fit the budget is
    /// taken: k fits, k - 1 does not (snapshots included, which do not shrink with k).
    #[test]
    fn frames_every_is_the_least_that_fits() {
        let case = groove(&[
            "motion.travel.steps=100",
            "output.snapshots=[0.0, 0.1e-3, 0.2e-3]",
        ]);
        let frame = frame_bytes(case.grid.nx, case.grid.ny);
        for budget_frames in [200.0, 60.0, 30.0, 12.0] {
            let budget = budget_frames * frame;
            let k = frames_every(&case, budget);
            assert!(frames_memory(&case, k) <= budget, "{budget_frames}: k {k}");
            assert!(
                k == 1 || frames_memory(&case, k - 1) > budget,
                "{budget_frames}: k {k}"
            );
        }
        // nothing fits: keep the first and the last only
        assert_eq!(frames_every(&case, 2.0 * frame), 100);
        // the case's own value wins
        let fixed = groove(&["motion.travel.steps=100", "output.frames_every=7"]);
        assert_eq!(frames_every(&fixed, 1.0), 7);
    }

    /// A transient infinite line counts its dense preconditioner (n^2 entries, f64 while
    /// factoring, f32 kept): ~200 MB at 4096 cells, absent from a steady run of the same line.
    #[test]
    fn memory_estimate_counts_the_dense_preconditioner() {
        let transient = groove(&["grid.nx=4096"]);
        let mut steady = transient.clone();
        steady.motion.as_mut().unwrap().travel = None;
        let (t, s) = (
            crate::run::memory_estimate(&transient).bytes,
            crate::run::memory_estimate(&steady).bytes,
        );
        assert!(t - s >= 4096.0 * 4096.0 * 12.0, "{t} vs {s}");
    }

    /// A transient run with `[stress]` and `[fatigue]` searches the frames for the worst one
    /// with each Poisson ratio's kernel spectra kept: the estimate counts them (and the second
    /// analysis), which it did not (issue 12), and the same run without `[fatigue]` does not.
    #[test]
    fn memory_estimate_counts_the_worst_frame_search() {
        let sliding = crate::case::load_file(
            std::path::Path::new(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../examples/stress_line_sliding.toml"
            )),
            &[],
        )
        .expect("example case");
        let mut with = groove(&["grid.nx=1024"]);
        with.stress = sliding.stress.clone();
        with.fatigue = sliding.fatigue;
        assert!(with.stress.is_some() && with.fatigue.is_some());
        let mut without = with.clone();
        without.fatigue = None;
        let spec = with.stress.as_ref().unwrap();
        let dx = (with.grid.x_max - with.grid.x_min) / 1024.0;
        let layers = spec.depths(dx, f64::INFINITY).len();
        let spectra = crate::run::stress::kernel_cache_bytes(1024, 1, layers, 1) as f64;
        let (w, wo) = (
            crate::run::memory_estimate(&with).bytes,
            crate::run::memory_estimate(&without).bytes,
        );
        assert!(
            spectra > 0.0 && w - wo >= spectra,
            "{w} vs {wo}: spectra {spectra}"
        );
    }

    /// x_p and the snapshot steps of the path form: from at step 0, to at the last step.
    #[test]
    fn path_kinematics_reach_the_ends() {
        let case = groove(&["motion.travel.steps=40"]);
        let kin = kinematics(&case).expect("a travel");
        assert_eq!(kin.steps, 40);
        assert!((kin.x_p(0.0) + 1.2e-3).abs() < 1e-15);
        assert!((kin.x_p(40.0 * kin.dt) - 1.0e-3).abs() < 1e-12);
        assert_eq!(kin.nearest_step(-1.2e-3), 0);
        assert_eq!(kin.nearest_step(1.0e-3), 40);
        assert_eq!(kin.nearest_step(5.0), 40);
        assert_eq!(kin.nearest_step(-1.2e-3 + 2.2e-3 * 0.5), 20);
    }
}
