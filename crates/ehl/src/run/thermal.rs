//! A thermal steady run (`[thermal]`): the temperature model built from the case, the thermal
//! fixed point from the isothermal solution, and the summary figures (temperatures, heat
//! balance, flash temperature, friction from the thermal shear). The physics is in
//! [`crate::thermal`], the fixed point in [`crate::ehl::thermal`].

use crate::case::Case;
use crate::ehl::thermal::{
    solve_thermal, ThermalParams, ThermalResult, ThermalTimes, CONVERGED_THERMAL_LOADING,
};
use crate::ehl::{EhlParams, EhlProblem, EhlResult};
use crate::lubricant::temperature::ThermalLaws;
use crate::solution::{Summary, TemperatureFields, ThermalTimeSplit};
use crate::thermal::ThermalContact;
use crate::{Error, Result};

/// The energy balance (heat generated against heat into the bodies and convected out) that
/// issue 13 asks every converged solution to close within: past it, the summary warns. On
/// coarse grids it is the discretisation that leaves it open (the glass-disc ball at 3 m/s and
/// SRR 2: 2 % on 32^2, 0.8 % on 64^2, 0.36 % on 129^2).
pub const ENERGY_BALANCE_WARNING: f64 = 0.01;

/// The summary warning for an energy balance `err` (relative) past [`ENERGY_BALANCE_WARNING`],
/// `what` saying where it was taken.
pub fn energy_balance_warning(err: f64, what: &str) -> Option<String> {
    (err.abs() > ENERGY_BALANCE_WARNING).then(|| {
        format!(
            "the energy balance {what} closes to {:.2} % only (heat generated against heat into the bodies and convected out; {} % asked): refine the grid (grid.nx, grid.ny) or thermal.points_across_film",
            100.0 * err.abs(),
            100.0 * ENERGY_BALANCE_WARNING
        )
    })
}

/// What a thermal run adds to the isothermal one.
pub struct ThermalRun {
    pub result: ThermalResult,
    pub fields: TemperatureFields,
    /// x-force of the film on body 2 (N; a line contact per metre), the friction convention of
    /// [`crate::friction`]
    pub friction_force: f64,
    pub contact: ThermalContact,
}

pub use crate::ehl::thermal::START_TOLERANCE;

/// Solves the thermal problem of `case` from the isothermal solution `iso` of `problem`.
pub fn solve(
    case: &Case,
    problem: &EhlProblem,
    params: &EhlParams,
    iso: &EhlResult,
    observer: &mut (dyn FnMut(usize, f64) + Send),
) -> Result<ThermalRun> {
    let contact = contact_for(case, problem.grid)?;
    solve_in(case, problem, params, iso, contact, observer)
}

/// [`solve`] with the case's contact `contact` already built ([`contact_for`] on
/// `problem.grid`).
pub fn solve_in(
    case: &Case,
    problem: &EhlProblem,
    params: &EhlParams,
    iso: &EhlResult,
    mut contact: ThermalContact,
    observer: &mut (dyn FnMut(usize, f64) + Send),
) -> Result<ThermalRun> {
    let mut result = solve_thermal(
        problem,
        params,
        &params_for(case),
        iso,
        &mut contact,
        observer,
    );
    for hint in [loading_hint, rheology_hint] {
        if let Some(hint) = hint(case, result.ehl.converged, &result.ehl.termination) {
            result.ehl.termination.push_str(&hint);
        }
    }
    let fields = contact.fields(&result.ehl.fields.film);
    let friction_force = contact.friction_force();
    Ok(ThermalRun {
        result,
        fields,
        friction_force,
        contact,
    })
}

/// The thermal fixed point's controls for `case`: the defaults with `[thermal]`'s
/// `tolerance`, `film_tolerance` (also the factors' residual), `max_iterations` and
/// `coupled_newton`.
pub fn params_for(case: &Case) -> ThermalParams {
    let mut p = ThermalParams::default();
    if let Some(t) = &case.thermal {
        p.tolerance_k = t.tolerance_k;
        p.film_tolerance = t.film_tolerance;
        p.factor_tolerance = t.film_tolerance;
        p.max_outer = t.max_iterations;
        p.coupled_newton = t.coupled_newton;
    }
    p
}

/// What to add to the reason `termination` of a thermal run of `case`, steady or transient,
/// that failed (`converged` false) at a thermal loading above [`CONVERGED_THERMAL_LOADING`]
/// (None when it converged, was cancelled, has no `[thermal]`, or L is below).
pub fn loading_hint(case: &Case, converged: bool, termination: &str) -> Option<String> {
    let l = crate::reference::check::case_thermal_loading(case)?;
    (!converged && termination != "cancelled" && l > CONVERGED_THERMAL_LOADING).then(|| {
        format!(
            "; the thermal loading L = eta0 beta u_e^2/k_f is {l:.2}, above {CONVERGED_THERMAL_LOADING}, below which the thermal solver converged in every case measured (above it some runs with sliding did not settle: docs/thermal.md, \"Left open\")"
        )
    })
}

/// What to add to the reason `termination` of a thermal run of `case` with the Eyring law that
/// failed (None when it converged, was cancelled, has no `[thermal]` or another law): what the
/// robustness scan of docs/thermal.md found of Eyring films at tau_0 = 5 MPa from 0.77 GPa on
/// ([`crate::reference::check::EYRING_THERMAL_LIMIT`]): on the fixed point alone a ball at
/// 0.77 GPa and 5 m/s did not settle (traced: its outer map expands, local contraction
/// estimates 1.3-5, which no damping of the lagged factors settles; its neighbour at 1 m/s did
/// not before 2026-12-02, stalled by Reynolds solves that left its pressure unmoved; on the
/// lines, which did not either before 2026-12-01, a spike column's flux match had more than one
/// root: docs/thermal.md, "The Eyring lines settle", "The pressure answers every step of the
/// factors"); the steady lines at 1-2 GPa and the ball settle with Newton's method on the
/// coupled problem, and the Carreau law with a limiting shear stress settled in the same
/// contacts.
pub fn rheology_hint(case: &Case, converged: bool, termination: &str) -> Option<String> {
    case.thermal.as_ref()?;
    let eyring = matches!(
        case.lubricant.as_ref()?.rheology,
        crate::lubricant::Rheology::Eyring { .. }
    );
    (eyring && !converged && termination != "cancelled")
        .then(|| format!("; {}", crate::reference::check::EYRING_THERMAL_LIMIT))
}

/// The thermal figures of `run` into `summary`; `mu` the friction coefficient when known (for
/// Blok's estimate, line contacts only).
pub fn summarise(case: &Case, run: &ThermalRun, mu: Option<f64>, summary: &mut Summary) {
    summarise_contact(
        case,
        &run.contact,
        &run.fields,
        run.result.outer_iterations,
        mu,
        summary,
    );
    if case.thermal.as_ref().is_some_and(|t| t.coupled_newton) {
        summary.thermal_newton_steps = Some(run.result.coupled_newton_steps);
    }
    // a converged solution whose balance stays open: said (a failed one says why it failed)
    if summary.converged {
        let err = run.contact.heat().balance_error();
        summary
            .warnings
            .extend(energy_balance_warning(err, "of the solution"));
    }
}

/// The summary's `thermal_time` of a thermal run: `start_s` the isothermal start's wall time
/// (s), `t` the fixed point's phases (a transient run: summed over its steps). `other_s` is
/// what the phases leave of `t.total_s`, not clamped: a phase counted twice shows as a
/// negative rest.
pub(crate) fn time_split(start_s: f64, t: &ThermalTimes) -> ThermalTimeSplit {
    let phases = t.film_energy_s
        + t.body_temperature_s
        + t.reynolds_factors_s
        + t.reynolds_s
        + t.coupled_newton_s;
    ThermalTimeSplit {
        isothermal_start_s: start_s,
        film_energy_s: t.film_energy_s,
        body_temperature_s: t.body_temperature_s,
        reynolds_factors_s: t.reynolds_factors_s,
        reynolds_s: t.reynolds_s,
        coupled_newton_s: t.coupled_newton_s,
        other_s: t.total_s - phases,
    }
}

/// The contact for a thermal case's `[thermal]` table and motion on `grid`.
pub fn contact_for(case: &Case, grid: crate::grid::Grid) -> Result<ThermalContact> {
    let (Some(spec), Some(lub), Some(m)) = (&case.thermal, &case.lubricant, &case.motion) else {
        return Err(Error::Solver(
            "a thermal run needs [thermal], [lubricant] and [motion]".into(),
        ));
    };
    let laws = ThermalLaws::new(lub, &spec.lubricant);
    let mut contact = ThermalContact::new(grid, laws, spec.bodies, m.u1(), m.u2())?;
    contact.options.side_flow = spec.side_flow;
    Ok(contact)
}

/// The thermal figures of `contact` (its last update) and its output `fields` into `summary`;
/// `outer` the fixed point's outer iterations, `mu` as in [`summarise`].
pub fn summarise_contact(
    case: &Case,
    contact: &ThermalContact,
    t: &TemperatureFields,
    outer: usize,
    mu: Option<f64>,
    summary: &mut Summary,
) {
    if let Some(spec) = &case.thermal {
        let asked = spec.lubricant.points_across_film;
        if contact.nz() != asked {
            let why = contact
                .retry_reason()
                .map_or(String::new(), |w| format!(" ({w})"));
            summary.warnings.push(format!(
                "the temperature solve failed with thermal.points_across_film = {asked}{why}; the run was solved again with {} points across the film: set them in the case to start there",
                contact.nz()
            ));
        }
    }
    let g = contact.grid();
    let argmax = |v: &[f64]| {
        (0..v.len()).fold(0, |m, k| {
            if v[k].is_finite() && (!v[m].is_finite() || v[k] > v[m]) {
                k
            } else {
                m
            }
        })
    };
    let k = argmax(&t.max_film);
    summary.max_film_temperature_k = Some(t.max_film[k]);
    summary.max_film_temperature_at_m = Some([g.x(k % g.nx), g.y(k / g.nx)]);
    let smax = |v: &[f64]| {
        v.iter()
            .cloned()
            .filter(|x| x.is_finite())
            .fold(t.inlet, f64::max)
    };
    let s = [smax(&t.surface_1), smax(&t.surface_2)];
    summary.max_surface_temperature_k = Some(s);
    summary.flash_temperature_k = Some(s[0].max(s[1]) - t.inlet);
    let heat = contact.heat();
    summary.mean_film_temperature_k = Some(heat.mean_film_temperature);
    summary.heat_generated_w = Some(heat.generated);
    summary.heat_to_body_w = Some(heat.to_body);
    summary.heat_convected_w = Some(heat.convected);
    summary.energy_balance_error = Some(heat.balance_error());
    summary.thermal_iterations = Some(outer);
    let line = !case.is_point();
    if let (Some(mu), Some(spec), Some(m), true) = (mu, &case.thermal, &case.motion, line) {
        // Blok for a line contact: w' the load per length, body 1's properties for both
        let w = case.load.force_per_length;
        let b = summary.hertz_half_width_m;
        let bt = spec.bodies[0];
        summary.flash_temperature_blok_k = Some(crate::reference::thermal::blok_flash(
            mu,
            w,
            m.u1(),
            m.u2(),
            b,
            bt.conductivity,
            bt.density,
            bt.heat_capacity,
        ));
    }
}

/// ", film temperature change X K" for a progress message; nothing before the first change is
/// known (the outer iteration's change is infinite until two temperature fields exist).
pub(crate) fn change_text(change_k: f64) -> String {
    if change_k.is_finite() {
        format!(", film temperature change {change_k:.2e} K")
    } else {
        String::new()
    }
}
