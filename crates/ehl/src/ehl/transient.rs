//! Transient isothermal EHL: surface features moving through the contact with their bodies
//! (thesis ch. 3), the time loop around the steady system.
//!
//! The Reynolds equation keeps its squeeze term whole (thesis eq. 3.1):
//!
//! ```text
//!   d/dX (eps dP/dX) + d/dY (eps dP/dY) - d(rho H)/dX - d(rho H)/dT = 0,   T = t u_e / b
//! ```
//!
//! with the film H(X, Y, T) = H0(T) + G(X, Y, T) + D(P), where the undeformed gap G holds each
//! body's features at the position its surface has reached, x_k(t) = x_k(0) + u_k t
//! (u1 = u_e (1 + SRR/2), u2 = u_e (1 - SRR/2)). The wedge term carries the film with the mean
//! speed u_e; the features move with their own body's speed; d(rho H)/dT takes the density's,
//! the deflection's, the rigid approach H0's and the features' changes together, which is what
//! conserves mass and lets the film's disturbances travel at u_e (Venner & Lubrecht 2000,
//! ch. 13; Greenwood & Morales-Espejel 1994).
//!
//! The features' own transport: on a body moving at least [`TRANSPORT_MIN_SPEED`] u_e, the
//! wedge term carries the features by a flux taken from their BDF storage
//! ([`residual::feature_transport`]), not by the upwind differences of their cell averages.
//! The two discretisations of one translation do not cancel at a step in the gap; a pit's wall
//! then left a source and a sink a cell apart, and pressure spikes that fell only with the cell
//! and the step (the 1 um thesis pit: 1.35 -> 1.17 GPa from 128 to 384 cells; a Venner
//! waviness at 34 cells a wavelength damped by 9 %). Measured in docs/pits.md.
//!
//! Time discretisation: BDF2 with a constant step (second order, A-stable), backward Euler
//! (BDF1) for the first step from the steady start (whose history is not known). Each step is
//! a steady-like Newton-Krylov solve of the same system with the squeeze term's c0 on its
//! diagonal (`super::system::Squeeze`); the load balance holds at every step (constant load,
//! H0 varies).
//!
//! Cost of a step (a waviness passing an infinite line, 1 cell per step, tolerance 1e-8):
//!
//! * predictor: each step starts from P and H0 extrapolated from the last three solutions
//!   (quadratic; linear after the first step), P clamped at >= 0, instead of the last
//!   solution: the first Newton residual fell from ~4e-2 to ~2e-5 and one Newton step is
//!   usually enough. If Newton fails from the prediction, the step is solved again from the
//!   last solution.
//! * infinite line (ny == 1, up to [`DENSE_MAX`] cells): the exact Jacobian as the
//!   preconditioner, kept over the steps (see `super::line_jacobian_solve`). Measured on 1024
//!   cells: 22.9 -> ~4 ms per step (Newton 3.0 -> 1.1, GMRES 226 -> ~6 per step) with dense LU
//!   factors, 2048 cells: 104 -> ~21 ms; then 1.2 and 3.6 ms with the factors in HODLR form
//!   (their solves O(n k log n) instead of O(n^2)).

use super::system::{Physics, Squeeze, State, System, ThermalFactors};
use super::thermal::{
    fields_si, polish_coupled, relax_factors, solve_thermal, timed, timed_update, ThermalParams,
    ThermalTimes, START_TOLERANCE,
};
use super::{
    better, line_band, solve_from, solve_from_with, solve_steady_with_fallback_observed, EhlParams,
    EhlProblem, SolvedFields, Stats, Termination,
};
use crate::geometry::{GapSampler, GapWithFeatures};
use crate::reynolds::residual;
use crate::surface::Surface;
use crate::thermal::{HeatBalance, ThermalContact};
use std::ops::ControlFlow;
use std::time::Instant;

/// A thermal step's first Newton solve, with the last step's Reynolds factors, only seeds the
/// step's first temperature update: it goes to this tolerance (or the case's, where looser),
/// the solves after it to the case's. The step's stop is barely weakened: its film test
/// compares the film of the last solve with that of the one before, so a seed left further off
/// mostly fails it (one more pass); it could let a step pass only by its own error, ~1e-5 of
/// the film against the test's 1e-4. A seed that stalls between 1e-5 and the case's tolerance
/// now counts as solved (no retry from the last solution); the solve after it, at the case's
/// tolerance, keeps its own fallbacks. Measured on the thesis pit with `[thermal]` at 256 x 256, its first
/// 30 steps (case tolerance 1e-6): Newton steps 182 -> 151, 2 passes a step; at 1e-4, 141
/// Newton steps but 2.4 passes a step (the seed's film then 1-2e-4 of the thinnest off, past
/// the film test), no faster.
pub const THERMAL_SEED_TOLERANCE: f64 = 1e-5;

/// and the step's first temperature update, whose temperatures only give the factors of the
/// next solve, stops its film and body iterations at this fraction of `thermal.tolerance_k`
/// (where its own stops are tighter): the step's stop compares the second update's
/// temperatures with the first's, so the first's looseness mostly fails it, and could let a
/// step pass only by ~0.01 K against the test's 0.05 K. The same 30
/// steps: 35.1-35.5 s -> 31.1 s with this alone, 27.4-28.1 s with both.
pub const THERMAL_SEED_TEMPERATURE: f64 = 0.2;

/// The step's later temperature updates stop their film and body iterations at this fraction
/// of `thermal.tolerance_k` (where their own stops are tighter): the step accepts temperatures
/// that moved by up to `tolerance_k` from one pass to the next, and the film's own iterations
/// stopped at a tenth of it (their last change, instead of 1e-4 K) leave the temperatures
/// near their fixed point by as much as that change times the iterations' contraction allows
/// (a heuristic: measured below, 5e-4 to 2.3e-3 K from the tight solves). The same 30 steps: 28.4 -> 23.5-24.0 s, the same
/// passes and Newton steps, friction within 1.1e-6, films 5e-8, the largest film temperature
/// 5e-4 K; the groove example at SRR 0.3 and 1.0 2.24 -> 1.65 s and 6.53 -> 4.57 s, friction
/// within 1.7e-5, films 4.4e-5 (at SRR 1.0; the step's film test is 1e-4), film temperatures
/// 2.3e-3 K, the same worst energy balance (0.14 % and 0.39 %).
pub const THERMAL_STEP_TEMPERATURE: f64 = 0.1;

/// The forcing term of the first Newton step of each of a time step's solves (the step's first,
/// from the state predicted from the last steps, and a thermal step's later ones, from the last
/// pass's solution with the factors' small change): where the start's residual
/// (`super::newton_score`, the score `NewtonRun::evaluate` tests) is at most the square root of
/// the solve's tolerance, [`super::ETA_MIN`], which the floor in `NewtonRun::evaluate` raises
/// to what the tolerance needs (max(ETA_MIN, 0.1 tol / score), a reduction of the merit
/// standing in for the residual's, as that floor does); elsewhere [`super::ETA_MAX`], as a
/// steady solve's first step. Newton's error after a step with an exact linear solve is about
/// the square of the error before it (in the solver's dimensionless variables, the constant of
/// order one), so from a start within sqrt(tol) one step solved to the tolerance can end the
/// solve, and the first step's error is the linear solve's, not the non-linearity's: solved to
/// ETA_MAX it took the residual down only 15-35 times and a second step followed (traced on the
/// thermal pit at 128^2: a step's seed solve 1.06e-3 -> 3.0e-5 -> 2.1e-6 against its 1e-5, a
/// later pass's 2.09e-4 -> 1.28e-5 -> 3.3e-7 against 1e-6), each Newton step costing a
/// preconditioner, a line search and the H0 column besides its GMRES iterations. Further out
/// the non-linearity limits the step and a tight linear solve is wasted: the ball dent's steps
/// mostly start at ~1.2e-2 against 1e-6 and take 3.8 Newton steps on average; with the first
/// solved tight regardless, 12 % fewer Newton steps but 5.5 % more GMRES iterations and 1-2 %
/// more time. A transient line's whole-Jacobian preconditioner solves every first step tight
/// anyway (`NewtonRun::new`), so its solves skip the test. The fallback from the last solution,
/// after a failed first solve, keeps ETA_MAX. Measured: BENCHMARKS.md, "A time step's first
/// Newton step solved as far as its tolerance needs".
fn step_first_eta(sys: &System, st: &State, tol: f64) -> f64 {
    if !sys.jacobian_reuse && super::newton_score(sys, st) <= tol.sqrt() {
        super::ETA_MIN
    } else {
        super::ETA_MAX
    }
}

/// A thermal time step that has not settled in `thermal.max_step_passes` passes is handed to
/// Newton's method on the coupled problem of the step (`super::thermal_newton`: the Reynolds
/// rows with their squeeze term, the film's energy rows with their time derivatives against
/// the step's previous level, both surfaces; with `thermal.coupled_newton`, once a step), and
/// this many more passes check its result by the step's own test (the first of them, with
/// every flux-driven column on the root nearest the pressure's gradient, as the steady fixed
/// point checks a polish). A 2D contact whose step polish fails is not polished again in the
/// run: each of its GMRES iterations is a film solve of every row (~0.1 s at 256 x 256), and a
/// failing polish runs to its limits. Steps that settle in their passes are untouched.
const STEP_POLISH_CHECKS: usize = 3;

/// Largest line (cells) whose time steps are preconditioned by a dense LU kept over the steps:
/// 4096 cells hold 128 MiB in f64 while factoring, and a factorisation takes ~2 s (2049
/// unknowns: 0.26 s) on the 2-core machine.
pub const DENSE_MAX: usize = 4096;

/// A body's surface with its features, where it starts and how fast it moves along x.
#[derive(Clone, Copy)]
pub struct MovingSurface<'a> {
    pub surface: &'a Surface,
    /// shift of the surface along x at t = 0 (m)
    pub shift0: f64,
    /// surface speed (m/s)
    pub speed: f64,
}

impl MovingSurface<'_> {
    /// Shift of the surface along x at time `t` (s): x(0) + u t.
    pub fn shift(&self, t: f64) -> f64 {
        self.shift0 + self.speed * t
    }
}

/// A transient problem: the steady problem's contact and lubricant (its `gap` is not used: the
/// gap is `smooth` plus the moving surfaces), `steps` steps of `dt` seconds.
pub struct TransientProblem<'a> {
    pub base: EhlProblem<'a>,
    pub smooth: &'a dyn GapSampler,
    pub surfaces: Vec<MovingSurface<'a>>,
    /// s
    pub dt: f64,
    pub steps: usize,
}

/// Time integration rule.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeScheme {
    /// backward Euler at every step (first order, strongly damping: for comparisons only)
    BackwardEuler,
    /// BDF2 after a backward-Euler first step (second order)
    Bdf2,
}

/// Controls of a transient run.
#[derive(Debug, Clone, Copy)]
pub struct TransientParams {
    /// the Newton-Krylov controls, used for the steady start and for every step (a thermal
    /// run's isothermal start, which only seeds its steady thermal solution, to
    /// max(tolerance, [`super::thermal::START_TOLERANCE`]))
    pub newton: EhlParams,
    pub scheme: TimeScheme,
    /// carry the moving features by their own discrete transport
    /// ([`residual::feature_transport`]) on every body moving at least
    /// [`TRANSPORT_MIN_SPEED`] u_e; false: the plain upwind wedge term on the whole film (for
    /// comparisons)
    pub feature_transport: bool,
}

impl Default for TransientParams {
    fn default() -> Self {
        TransientParams {
            newton: EhlParams::default(),
            scheme: TimeScheme::Bdf2,
            feature_transport: true,
        }
    }
}

/// The features of a body slower than this fraction of u_e keep the plain wedge term: their
/// transport flux is divided by the speed ([`residual::feature_transport`]), which must stay
/// well away from 0, and a standing body's features do not move at all. Measured down to
/// 0.05 (a groove on body 2 at SRR 1.9: peak 1.117 / 1.123 / 1.119 GPa on 512 cells and 200
/// steps, 400 steps, 1024 cells and 400 steps, where the plain rule gives 1.156; the peak grows
/// smoothly from SRR 0.9 to 1.9). At 0.5, the first choice, a sweep over SRR jumped by 3 % where
/// body 2 crossed it (SRR 1.0 -> 1.1).
pub const TRANSPORT_MIN_SPEED: f64 = 0.05;

/// The discrete mass balance of the pressurised zone (cells with P > 0) at one step, kg/s
/// (line contact: per metre): inflow - outflow - side leakage = storage (the rate of change of
/// the mass held), up to the solver tolerance. Outflow counts the flow into cavitated cells
/// (the cavitation loss) with that through the outlet.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MassBalance {
    pub inflow: f64,
    pub outflow: f64,
    pub side_leakage: f64,
    pub storage: f64,
}

impl MassBalance {
    /// (inflow - outflow - side leakage - storage) / inflow; without an inflow, relative to
    /// the largest of the flows (0 when there is no flow at all).
    pub fn relative_error(&self) -> f64 {
        let r = self.inflow - self.outflow - self.side_leakage - self.storage;
        let scale = if self.inflow != 0.0 {
            self.inflow
        } else {
            [self.outflow, self.side_leakage, self.storage]
                .iter()
                .fold(0.0f64, |m, v| m.max(v.abs()))
        };
        if scale != 0.0 {
            r / scale
        } else {
            0.0
        }
    }
}

/// One solved time step (SI). Step 0 is the steady start.
#[derive(Debug, Clone)]
pub struct StepResult {
    pub step: usize,
    /// s
    pub time: f64,
    /// pressure, film, deflection, viscosity, density, h0
    pub fields: SolvedFields,
    pub converged: bool,
    /// why the step's Newton solve stopped (its `Display` is the sentence of `summary.json`)
    pub reason: Termination,
    /// relative residual (see [`super::EhlResult::residual`])
    pub residual: f64,
    /// (sum p dA - load) / load
    pub load_error: f64,
    pub newton_iterations: usize,
    pub linear_iterations: usize,
    pub operator_applications: usize,
    pub mass: MassBalance,
    /// s
    pub wall_time: f64,
    /// a thermal run's temperatures and heat at this step
    pub thermal: Option<StepThermal>,
}

/// The thermal figures of one step of a thermal transient run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepThermal {
    /// Reynolds - temperature passes of this step (step 0: the steady fixed point's outer
    /// iterations)
    pub passes: usize,
    /// film-temperature change of the last pass (K)
    pub change_k: f64,
    /// largest film temperature (K)
    pub max_film_temperature_k: f64,
    /// largest surface temperature of body 1 and body 2 (K)
    pub max_surface_temperature_k: [f64; 2],
    /// heat balance (W; per metre on a line contact), `stored` the film's enthalpy change
    pub heat: HeatBalance,
    /// x-force of the film on body 2 from the thermal velocity profile (N; per metre on a line)
    pub friction_force: f64,
    /// where this step's wall time went (step 0: the steady fixed point's phases); `total_s`
    /// the step's wall time from its start to the end of its passes
    pub times: ThermalTimes,
    /// step 0: the wall time (s) of the isothermal steady solve the thermal start began from
    /// (0 for the time steps)
    pub isothermal_start_s: f64,
}

impl StepThermal {
    fn of(contact: &ThermalContact, passes: usize, change_k: f64, times: ThermalTimes) -> Self {
        let (film, surface) = contact.extremes();
        StepThermal {
            passes,
            change_k,
            max_film_temperature_k: film,
            max_surface_temperature_k: surface,
            heat: contact.heat(),
            friction_force: contact.friction_force(),
            times,
            isothermal_start_s: 0.0,
        }
    }
}

/// How a transient run ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TransientEnd {
    /// every step was solved (some may not have converged: see `failed_steps`)
    Completed { failed_steps: Vec<usize> },
    /// the observer asked to stop after this step
    Stopped { after_step: usize },
}

/// Runs the transient problem: the steady start, then `steps` time steps; `observer` receives
/// every step (step 0 first) and may stop the run. Never panics on a physical input; a step that
/// does not converge is reported (`converged == false`) and the run goes on from its best state.
pub fn solve_transient(
    problem: &TransientProblem,
    params: &TransientParams,
    observer: &mut (dyn FnMut(&StepResult) -> ControlFlow<()> + Send),
) -> TransientEnd {
    solve_transient_observed(problem, params, None, StartObserver::default(), observer)
}

/// Told of the steady start of a transient run (which can take most of a short run): every
/// Newton iterate, then for a thermal run each outer iteration of the temperature fixed point
/// (its number and the film temperature's change, K). For progress bars.
#[derive(Default)]
pub struct StartObserver<'a> {
    pub newton: Option<super::NewtonObserver<'a>>,
    pub thermal: Option<&'a mut (dyn FnMut(usize, f64) + Send)>,
}

/// [`solve_transient`] (`thermal` None) or [`solve_transient_thermal`], with `start` told of
/// the steady start.
pub fn solve_transient_observed(
    problem: &TransientProblem,
    params: &TransientParams,
    thermal: Option<(&ThermalParams, &mut ThermalContact)>,
    start: StartObserver,
    observer: &mut (dyn FnMut(&StepResult) -> ControlFlow<()> + Send),
) -> TransientEnd {
    rayon::scope(|_| run(problem, params, thermal, start, observer))
}

/// [`solve_transient`] with the temperature (issue 13): the steady start is the thermal fixed
/// point of [`super::thermal`]; each step then
///
/// 1. solves the Reynolds equation with the generalized Reynolds factors of the last
///    temperatures (the squeeze term's rho H carries the Couette density rho* of the factors, at
///    both time levels);
/// 2. solves the film's energy equation with its time derivatives against the previous step
///    (backward Euler, [`ThermalContact::begin_step`]; the bodies quasi-steady);
/// 3. repeats 1-2 with the factors relaxed as in the steady fixed point until, between two
///    passes, the film temperature changes by less than `thermal.tolerance_k` (where the film
///    is at most 5 times its thinnest) and the film by less than `thermal.film_tolerance` of
///    its thinnest (at least two passes, at most `thermal.max_step_passes`); a step that does
///    not settle is reported (`converged == false`, termination
///    [`super::Termination::ThermalNotSettled`]).
///
/// The first pass only seeds the second: its Newton solve goes to [`THERMAL_SEED_TOLERANCE`],
/// its temperature update to [`THERMAL_SEED_TEMPERATURE`] of `thermal.tolerance_k`; the later
/// updates go to [`THERMAL_STEP_TEMPERATURE`] of it.
///
/// The step's viscosity and density fields are the thermal ones (low-shear viscosity at the
/// mid-film temperature, density averaged across the film), as in a steady thermal run.
///
/// `contact` keeps the last step's temperatures. Every [`StepResult`] carries its
/// [`StepThermal`].
pub fn solve_transient_thermal(
    problem: &TransientProblem,
    params: &TransientParams,
    thermal: &ThermalParams,
    contact: &mut ThermalContact,
    observer: &mut (dyn FnMut(&StepResult) -> ControlFlow<()> + Send),
) -> TransientEnd {
    solve_transient_observed(
        problem,
        params,
        Some((thermal, contact)),
        StartObserver::default(),
        observer,
    )
}

fn gap_at<'a>(problem: &'a TransientProblem, t: f64) -> GapWithFeatures<'a> {
    GapWithFeatures {
        smooth: problem.smooth,
        surfaces: problem
            .surfaces
            .iter()
            .filter(|s| !s.surface.features.is_empty())
            .map(|s| (s.surface, s.shift(t)))
            .collect(),
    }
}

fn run(
    problem: &TransientProblem,
    params: &TransientParams,
    mut thermal: Option<(&ThermalParams, &mut ThermalContact)>,
    start: StartObserver,
    observer: &mut (dyn FnMut(&StepResult) -> ControlFlow<()> + Send),
) -> TransientEnd {
    let base = &problem.base;
    let grid = base.grid;
    let (b, r, ph) = (
        base.hertz_half_width,
        base.reduced_radius,
        base.hertz_pressure,
    );
    let hs = b * b / r;
    let clock = Instant::now();

    // the steady start with the features at their t = 0 positions
    let gap0 = gap_at(problem, 0.0);
    let steady_problem = EhlProblem {
        gap: &gap0,
        ..*base
    };
    let mut quiet_newton = |_: &super::NewtonIterate| {};
    let mut quiet_thermal = |_: usize, _: f64| {};
    let (newton_told, thermal_told): (super::NewtonObserver, &mut (dyn FnMut(usize, f64) + Send)) = (
        start.newton.unwrap_or(&mut quiet_newton),
        start.thermal.unwrap_or(&mut quiet_thermal),
    );
    // (a thermal run's isothermal start only seeds its steady thermal solution: see
    // super::thermal::START_TOLERANCE)
    let start_params = match thermal {
        Some(_) => EhlParams {
            tolerance: params.newton.tolerance.max(START_TOLERANCE),
            ..params.newton
        },
        None => params.newton,
    };
    let mut steady =
        solve_steady_with_fallback_observed(&steady_problem, &start_params, &|| {}, newton_told);
    let isothermal_start_s = clock.elapsed().as_secs_f64();
    // a thermal run starts from the steady thermal solution
    let mut start_thermal = None;
    if let Some((tp, contact)) = thermal.as_mut() {
        if steady.converged {
            let r = solve_thermal(
                &steady_problem,
                &params.newton,
                tp,
                &steady,
                contact,
                thermal_told,
            );
            start_thermal = Some(StepThermal {
                isothermal_start_s,
                ..StepThermal::of(contact, r.outer_iterations, r.last_change_k, r.times)
            });
            steady = r.ehl;
        }
    }
    let lub = base.lubricant;
    let phys = Physics::new(
        lub.clone(),
        ph,
        12.0 * base.entrainment_speed * lub.viscosity * r * r / (b * b * b * ph),
    );
    let mut sys = System::new(
        grid,
        (base.operator)(grid),
        &gap0,
        b,
        r,
        phys,
        base.load,
        line_band(grid, params.newton.band),
        params.newton.wedge_upwind_order != 1,
    );
    let n = grid.len();
    sys.jacobian_reuse = grid.ny == 1 && n <= DENSE_MAX;
    let mut st = State::new(n);
    for k in 0..n {
        st.p[k] = if sys.active[k] {
            steady.fields.pressure[k] / ph
        } else {
            0.0
        };
    }
    st.h0 = steady.fields.h0 / hs;
    sys.eval(&mut st);
    let mut start = StepResult {
        step: 0,
        time: 0.0,
        fields: steady.fields.clone(),
        converged: steady.converged,
        reason: steady.reason.clone(),
        residual: steady.residual,
        load_error: steady.load_error,
        newton_iterations: steady.iterations,
        linear_iterations: steady.linear_iterations,
        operator_applications: steady.operator_applications,
        mass: balance(problem, &sys, &st),
        wall_time: clock.elapsed().as_secs_f64(),
        thermal: start_thermal,
    };
    // the thermal start's Reynolds factors, from its temperatures
    let mut factors = ThermalFactors {
        flow: vec![1.0; n],
        couette: vec![1.0; n],
    };
    let (mut p_si, mut h_si) = (vec![0.0; n], vec![0.0; n]);
    let mut fresh = factors.clone();
    if let Some((_, contact)) = thermal.as_mut() {
        if contact.solved() {
            contact.reynolds_factors(
                &start.fields.pressure,
                &sys.active,
                &mut factors.flow,
                &mut factors.couette,
            );
        }
        sys.thermal = Some(factors.clone());
        sys.eval(&mut st);
        // the start's mass balance with the coefficients it was solved with (before, the
        // isothermal ones: 1.4 % off on the thesis pit at 128^2 with [thermal])
        start.mass = balance(problem, &sys, &st);
    }
    if observer(&start).is_break() {
        return TransientEnd::Stopped { after_step: 0 };
    }

    // time steps: q = rho H at the two previous levels
    let dtau = problem.dt * base.entrainment_speed / b;
    let q = |st: &State| -> Vec<f64> { st.rho.iter().zip(&st.h).map(|(r, h)| r * h).collect() };
    let mut q1 = q(&st);
    let mut q2: Option<Vec<f64>> = None;
    let mut failed = Vec::new();
    // a 2D contact whose step polish failed is not polished again (see STEP_POLISH_CHECKS)
    let mut step_polish_off = false;
    // the features' cell averages at the last time levels (their own transport)
    let mut transport = params
        .feature_transport
        .then(|| FeatureLevels::new(problem, &sys));
    // (P, H0) of the last three solutions, newest last: the predictor's history
    let mut past: Vec<(Vec<f64>, f64)> = vec![(st.p.clone(), st.h0)];
    for step in 1..=problem.steps {
        if crate::run::cancel::requested() {
            return TransientEnd::Stopped {
                after_step: step - 1,
            };
        }
        let t0 = Instant::now();
        let t = step as f64 * problem.dt;
        sys.set_gap(&gap_at(problem, t));
        let c0_before = sys.squeeze_c0();
        sys.squeeze = Some(match (&q2, params.scheme) {
            (Some(q2), TimeScheme::Bdf2) => Squeeze {
                c0: 1.5 / dtau,
                history: q1
                    .iter()
                    .zip(q2)
                    .map(|(a, b)| (4.0 * a - b) / (2.0 * dtau))
                    .collect(),
            },
            _ => Squeeze {
                c0: 1.0 / dtau,
                history: q1.iter().map(|a| a / dtau).collect(),
            },
        });
        // kept dense factors hold the old c0 on their diagonal: the switch from backward Euler
        // to BDF2 (c0 from 1/dT to 3/(2 dT)) makes them a poor preconditioner (review: 14-16
        // GMRES iterations a step until the budget forced a refactorisation)
        if sys.squeeze_c0() != c0_before {
            sys.jacobian_stale = true;
        }
        if let Some(levels) = transport.as_mut() {
            levels.advance(problem, &sys, t);
            let bdf2 = q2.is_some() && params.scheme == TimeScheme::Bdf2;
            sys.couette_shift = levels.shift(&sys, dtau, bdf2);
        }
        predict(&past, &mut st);
        sys.eval(&mut st);
        let mut stats = Stats::default();
        let applies0 = sys.applies;
        // a thermal step's first solve seeds its first temperature update
        let first_tol = if thermal.is_some() {
            params.newton.tolerance.max(THERMAL_SEED_TOLERANCE)
        } else {
            params.newton.tolerance
        };
        let first_eta = step_first_eta(&sys, &st, first_tol);
        // where a thermal step's time goes (its Newton solves, temperature updates, factors)
        let mut times = ThermalTimes::default();
        let mut end = timed(&mut times.reynolds_s, || {
            solve_from_with(
                &mut sys,
                &mut st,
                first_tol,
                first_eta,
                &params.newton,
                &mut stats,
            )
        });
        if !end.converged && past.len() > 1 {
            // the prediction may have led Newton astray: again from the last solution
            let mut again = State::new(n);
            let last = &past[past.len() - 1];
            again.p.copy_from_slice(&last.0);
            again.h0 = last.1;
            sys.eval(&mut again);
            let e = timed(&mut times.reynolds_s, || {
                solve_from(&mut sys, &mut again, first_tol, &params.newton, &mut stats)
            });
            // (a NaN residual loses to any other)
            if e.converged || better(e.residual, end.residual) {
                st = again;
                end = e;
            }
        }
        // the temperature of this step: passes of (temperature, factors, Newton) until the film
        // temperature settles
        let mut step_thermal = None;
        if let Some((tp, contact)) = thermal.as_mut() {
            let mut passes = 0;
            let mut change = f64::INFINITY;
            let mut prev = f64::INFINITY;
            let mut w = tp.relaxation;
            let mut failure = None;
            let mut h_prev = vec![f64::NAN; n];
            // a step that has not settled in its passes is handed once to Newton's method on
            // the coupled problem (see STEP_POLISH_CHECKS); its film start's hold is the
            // polish's alone
            let mut polished = false;
            let mut max_passes = tp.max_step_passes;
            let hysteresis = contact.options.inlet_hysteresis;
            let mut check_polish = false;
            while end.converged {
                passes += 1;
                fields_si(&sys, &st, ph, hs, &mut p_si, &mut h_si);
                let film_change = super::thermal::film_change(&h_si, &h_prev);
                h_prev.copy_from_slice(&h_si);
                let own = contact.options;
                if passes == 1 {
                    contact.begin_step(problem.dt);
                }
                // the first update seeds the next solve's factors; the later ones are held to
                // the step's own test
                let fraction = if passes == 1 {
                    THERMAL_SEED_TEMPERATURE
                } else {
                    THERMAL_STEP_TEMPERATURE
                };
                contact.options.line.tol = own.line.tol.max(fraction * tp.tolerance_k);
                contact.options.surface_tol = own.surface_tol.max(fraction * tp.tolerance_k);
                contact.options.line.nearest_root = std::mem::take(&mut check_polish);
                let updated =
                    timed_update(contact, &p_si, &h_si, &sys.active, &factors, &mut times);
                contact.options = own;
                match updated {
                    Ok(c) => change = c,
                    Err(e) => {
                        failure = Some(super::Termination::ThermalFailed(e.to_string()));
                        break;
                    }
                }
                // the first pass's change is the step's own (time), not the iteration's
                if passes >= 2
                    && change <= tp.tolerance_k
                    && contact.inner_residual() <= tp.tolerance_k
                    && film_change <= tp.film_tolerance
                {
                    break;
                }
                if passes >= max_passes && tp.coupled_newton && !polished && !step_polish_off {
                    polished = true;
                    let saved = (st.clone(), sys.thermal.clone());
                    let rp = timed(&mut times.coupled_newton_s, || {
                        polish_coupled(
                            &mut sys,
                            &mut st,
                            contact,
                            ph,
                            hs,
                            &params.newton,
                            tp,
                            &mut stats,
                        )
                    });
                    match rp {
                        Ok(pol) => {
                            // the next passes check it, as the steady fixed point does
                            factors = pol.factors;
                            end = pol.end;
                            check_polish = true;
                            max_passes = passes + STEP_POLISH_CHECKS;
                            continue;
                        }
                        Err(_) => {
                            st = saved.0;
                            sys.thermal = saved.1;
                            sys.eval(&mut st);
                            step_polish_off = grid.ny > 1;
                        }
                    }
                }
                if passes >= max_passes {
                    failure = Some(super::Termination::ThermalNotSettled {
                        outer: passes,
                        change_k: change,
                        film_change,
                        residual_k: contact.inner_residual(),
                        factor_residual: None,
                    });
                    break;
                }
                if passes >= 3 && change > prev {
                    w = (0.5 * w).max(tp.min_relaxation.min(tp.relaxation));
                }
                if passes >= 2 {
                    prev = change;
                }
                let wk = if passes == 1 { 1.0 } else { w };
                timed(&mut times.reynolds_factors_s, || {
                    relax_factors(contact, &p_si, &sys.active, &mut factors, &mut fresh, wk)
                });
                sys.thermal = Some(factors.clone());
                sys.eval(&mut st);
                let first_eta = step_first_eta(&sys, &st, params.newton.tolerance);
                end = timed(&mut times.reynolds_s, || {
                    solve_from_with(
                        &mut sys,
                        &mut st,
                        params.newton.tolerance,
                        first_eta,
                        &params.newton,
                        &mut stats,
                    )
                });
            }
            contact.options.inlet_hysteresis = hysteresis;
            if let Some(f) = failure {
                end.converged = false;
                end.reason = f;
            }
            // a step whose Newton solve failed before any temperature update has no
            // temperatures of its own: none rather than the last step's
            if passes > 0 && contact.solved() {
                times.total_s = t0.elapsed().as_secs_f64();
                step_thermal = Some(StepThermal::of(contact, passes, change, times));
            }
        }
        if !end.converged {
            failed.push(step);
        }
        let mut res = StepResult {
            step,
            time: t,
            fields: SolvedFields::of(&sys, &st, ph, hs, lub),
            converged: end.converged,
            reason: end.reason,
            residual: end.residual,
            load_error: end.load_error,
            newton_iterations: stats.newton,
            linear_iterations: stats.gmres,
            operator_applications: sys.applies - applies0,
            mass: balance(problem, &sys, &st),
            wall_time: t0.elapsed().as_secs_f64(),
            thermal: step_thermal,
        };
        if let Some((_, contact)) = thermal.as_ref().filter(|(_, c)| c.solved()) {
            contact.fill_laws(
                &res.fields.pressure,
                &sys.active,
                &mut res.fields.viscosity,
                &mut res.fields.density,
            );
        }
        if observer(&res).is_break() {
            return TransientEnd::Stopped { after_step: step };
        }
        if past.len() == 3 {
            past.remove(0);
        }
        past.push((st.p.clone(), st.h0));
        let qn = q(&st);
        q2 = Some(std::mem::replace(&mut q1, qn));
    }
    TransientEnd::Completed {
        failed_steps: failed,
    }
}

/// The start of a step's Newton iteration: P and H0 extrapolated from the last solutions in
/// `past` (newest last) at the constant step, quadratic from three, linear from two, the last
/// one alone; P clamped at >= 0. Extrapolation of the previous steps is the usual predictor
/// of implicit time integration (Hairer & Wanner, *Solving ODEs II*, sec. IV.8 and VIII.1):
/// its error is O(dt^3) against O(dt) for the last solution.
fn predict(past: &[(Vec<f64>, f64)], st: &mut State) {
    let m = past.len();
    let (w, terms): ([f64; 3], usize) = match m {
        0 => return,
        1 => ([1.0, 0.0, 0.0], 1),
        2 => ([2.0, -1.0, 0.0], 2),
        _ => ([3.0, -3.0, 1.0], 3),
    };
    let at = |j: usize| &past[m - 1 - j];
    for (k, p) in st.p.iter_mut().enumerate() {
        let v: f64 = (0..terms).map(|j| w[j] * at(j).0[k]).sum();
        *p = v.max(0.0);
    }
    st.h0 = (0..terms).map(|j| w[j] * at(j).1).sum();
}

/// The cell averages (in H, 0 where there is no material) of the features of each body that
/// moves at least [`TRANSPORT_MIN_SPEED`] u_e, at the newest time level and the two before it:
/// what the features' own transport ([`residual::feature_transport`]) of a step needs. Each
/// step samples one new level.
struct FeatureLevels {
    /// (index in `problem.surfaces`, speed / u_e, levels newest first)
    bodies: Vec<(usize, f64, [Vec<f64>; 3])>,
    storage: Vec<f64>,
}

impl FeatureLevels {
    /// The levels at t = 0 (the steady start's features), repeated.
    fn new(problem: &TransientProblem, sys: &System) -> FeatureLevels {
        let ue = problem.base.entrainment_speed;
        let n = problem.base.grid.len();
        let mut bodies = Vec::new();
        for (i, s) in problem.surfaces.iter().enumerate() {
            let speed = s.speed / ue;
            if !s.surface.features.is_empty() && speed >= TRANSPORT_MIN_SPEED {
                let mut f = vec![0.0; n];
                Self::sample(problem, sys, i, 0.0, &mut f);
                bodies.push((i, speed, [f.clone(), f.clone(), f]));
            }
        }
        FeatureLevels {
            bodies,
            storage: vec![0.0; n],
        }
    }

    fn sample(problem: &TransientProblem, sys: &System, i: usize, t: f64, out: &mut [f64]) {
        let s = &problem.surfaces[i];
        s.surface.cell_averages(&problem.base.grid, s.shift(t), out);
        let hs = sys.hscale();
        for (v, &a) in out.iter_mut().zip(&sys.active) {
            *v = if a { *v * hs } else { 0.0 };
        }
    }

    /// Moves to time `t` (s): the newest level becomes the one before.
    fn advance(&mut self, problem: &TransientProblem, sys: &System, t: f64) {
        for (i, _, levels) in &mut self.bodies {
            levels.rotate_right(1);
            Self::sample(problem, sys, *i, t, &mut levels[0]);
        }
    }

    /// The Couette shift of a step of `dtau` (dimensionless) with the BDF2 rule (else
    /// backward Euler), or None when no body's features are transported.
    fn shift(&mut self, sys: &System, dtau: f64, bdf2: bool) -> Option<Vec<f64>> {
        if self.bodies.is_empty() {
            return None;
        }
        let mut shift = vec![0.0; self.storage.len()];
        for (_, speed, [f0, f1, f2]) in &self.bodies {
            for (k, s) in self.storage.iter_mut().enumerate() {
                *s = if bdf2 {
                    (3.0 * f0[k] - 4.0 * f1[k] + f2[k]) / (2.0 * dtau)
                } else {
                    (f0[k] - f1[k]) / dtau
                };
            }
            residual::feature_transport(
                &sys.rg,
                &sys.active,
                f0,
                &self.storage,
                *speed,
                &mut shift,
            );
        }
        Some(shift)
    }
}

/// The mass balance of the pressurised zone at the evaluated state `st` (kg/s).
fn balance(problem: &TransientProblem, sys: &System, st: &State) -> MassBalance {
    let base = &problem.base;
    let b = base.hertz_half_width;
    let hs = b * b / base.reduced_radius;
    let m = residual::mass_flow(&sys.rg, &sys.fields(st));
    let storage: f64 = match &sys.squeeze {
        Some(s) => {
            (0..sys.n())
                .filter(|&k| sys.active[k] && st.p[k] > 0.0)
                .map(|k| s.c0 * st.rho[k] * st.h[k] - s.history[k])
                .sum::<f64>()
                * sys.area
        }
        None => 0.0,
    };
    // dimensionless flow (rho/rho0) H dY per unit u_e -> kg/s: rho0 u_e (b^2/R) b
    let scale = base.lubricant.density * base.entrainment_speed * hs * b;
    MassBalance {
        inflow: m.inflow * scale,
        outflow: m.outflow * scale,
        side_leakage: m.side_leakage * scale,
        storage: storage * scale,
    }
}
