//! EHL coupling and the steady driver: film h = h0 + g + deflection (thesis eq. 2.3), the load
//! balance through h0 (thesis fig. 2.3), Newtonian compressible Reynolds (eq. 2.1) with
//! Dowson-Higginson (2.10) or constant density and Roelands (2.11) or Barus viscosity, the
//! Reynolds cavitation condition as a complementarity problem.
//!
//! The problem is solved in the dimensionless form of Venner & Lubrecht (2000):
//! X = x/b, P = p/p_h, H = h R/b^2, lambda = 12 u_e eta0 R^2/(b^3 p_h), by a Jacobian-free
//! Newton-Krylov method (Knoll & Keyes, J. Comput. Phys. 193 (2004) 357-397):
//!
//! * unknowns P (every cell with material) and H0; equations Phi = min(P, c F) = 0 (semismooth
//!   Newton / primal-dual active set for cavitation) and the load balance (see `system`);
//! * each Newton step solves J d = -R by restarted flexible GMRES to a relative tolerance of
//!   1e-1 .. 1e-4 (Eisenstat-Walker forcing, no tighter than the tolerance needs, see
//!   `ETA_MAX` and `ETA_MIN`) in the row-weighted norm of `MERIT_WEIGHT_EXPONENT` (the line
//!   search's too), J v by the exact directional derivative (one elastic operator
//!   application per product), right-preconditioned by the local part of J (the Poiseuille
//!   stencil and the elastic wedge coupling within a band along x, see `line_band`) solved by
//!   one V-cycle of line-relaxation multigrid (a banded LU on a line contact), H0 by a Schur
//!   complement;
//! * the time steps of a transient infinite line contact (ny == 1) are preconditioned instead
//!   by the exact Jacobian held as a hierarchical (HODLR) approximate inverse, factored once
//!   and kept over Newton steps and time steps until the GMRES iterations it costs outweigh a
//!   new factorisation (see `line_jacobian_solve`, `system::LineJacobianPreconditioner`);
//!   their linear solves then go to 1e-3 of
//!   what the tolerance asks, so that one Newton step usually ends the time step;
//! * grid sequencing: every solve starts on grids 2, 4, ... times coarser (from the given start
//!   averaged onto them), each level's solution (to at most 1e-3, `COARSE_TOLERANCE`)
//!   interpolated as the next level's start;
//! * a backtracking line search on ||W R||_2 (P clamped at >= 0), pseudo-transient continuation if
//!   plain Newton fails, and then continuation in the pressure-viscosity coefficient (alpha
//!   scaled by 1/4, 1/2, ... up to 1, each stage started from the previous solution).
//!
//! Results are returned in SI.

mod system;
pub mod thermal;
mod thermal_newton;
pub mod transient;

use crate::case::Lubricant;
use crate::elastic::Deflection;
use crate::geometry::GapSampler;
use crate::grid::Grid;
use crate::linalg::gmres::{gmres, GmresOutcome, GmresWork};
use crate::reference::film;
use crate::reynolds::residual;
use system::{
    jacobian_product, LineJacobianPreconditioner, Linear, Physics, Preconditioner, State, System,
};
pub use transient::{
    solve_transient, solve_transient_observed, solve_transient_thermal, MassBalance, MovingSurface,
    StartObserver, StepResult, StepThermal, TimeScheme, TransientEnd, TransientParams,
    TransientProblem, DENSE_MAX,
};

/// A steady isothermal EHL problem (SI units).
pub struct EhlProblem<'a> {
    pub grid: Grid,
    /// undeformed gap g (m) on the cells of any grid, f64::INFINITY where there is no material
    pub gap: &'a dyn GapSampler,
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
    /// maximum number of Newton steps per continuation stage
    pub max_iterations: usize,
    /// GMRES restart length
    pub gmres_restart: usize,
    /// maximum GMRES iterations per Newton step
    pub max_linear_iterations: usize,
    /// least half-width (cells) of the elastic coupling kept in the line preconditioner; on 2D
    /// grids it is widened to dy / (2 dx) (at most 64), see `line_band`
    pub band: usize,
    /// fall back to continuation in alpha when Newton fails from the start
    pub continuation: bool,
    /// order of the upwind rule for the wedge (Couette) term d(rho h)/dx: 2 (default, the
    /// classical (3 q_i - 4 q_i-1 + q_i-2) / (2 dX)) or 1 (q_i - q_i-1) / dX, first order, as
    /// EHL-FBNS and many older codes use; see `reynolds::residual`
    pub wedge_upwind_order: u8,
    /// initial pseudo-time step (scaled rows: 1 is comparable to the Jacobian diagonal;
    /// f64::INFINITY for plain Newton)
    pub pseudo_time_step: f64,
}

impl Default for EhlParams {
    fn default() -> Self {
        EhlParams {
            tolerance: 1e-6,
            max_iterations: 60,
            gmres_restart: 80,
            max_linear_iterations: 400,
            band: 4,
            continuation: true,
            pseudo_time_step: 1.0,
            wedge_upwind_order: 2,
        }
    }
}

/// The fields of a solved EHL state, in SI units: what a steady solve ([`EhlResult`]) and a
/// time step ([`StepResult`]) both give.
#[derive(Debug, Clone)]
pub struct SolvedFields {
    /// Pa
    pub pressure: Vec<f64>,
    /// m (f64::INFINITY on cells without material)
    pub film: Vec<f64>,
    /// m (both bodies, positive opening the gap)
    pub deflection: Vec<f64>,
    /// Pa s (f64::MAX where the viscosity law overflows)
    pub viscosity: Vec<f64>,
    /// kg/m^3
    pub density: Vec<f64>,
    /// m: the rigid-body film constant
    pub h0: f64,
}

impl SolvedFields {
    /// The fields of the evaluated state `st` of `sys`, scaled back to SI: p p_h, h b^2/R (`hs`;
    /// infinite where there is no material), the deflection likewise, and the isothermal laws
    /// of `lub` at each cell's pressure (a thermal run overwrites viscosity and density with
    /// its temperatures', [`crate::thermal::ThermalContact::fill_laws`]).
    fn of(sys: &System, st: &State, ph: f64, hs: f64, lub: &Lubricant) -> Self {
        let n = st.p.len();
        SolvedFields {
            pressure: st.p.iter().map(|p| p * ph).collect(),
            film: (0..n)
                .map(|k| {
                    if sys.active[k] {
                        st.h[k] * hs
                    } else {
                        f64::INFINITY
                    }
                })
                .collect(),
            deflection: st.def.iter().map(|d| d * hs).collect(),
            viscosity: st
                .p
                .iter()
                .map(|&p| {
                    let v = lub.viscosity * sys.phys.eta(p);
                    if v.is_finite() {
                        v
                    } else {
                        f64::MAX
                    }
                })
                .collect(),
            density: st
                .p
                .iter()
                .map(|&p| lub.density * sys.phys.rho(p))
                .collect(),
            h0: st.h0 * hs,
        }
    }
}

/// The steady solution (SI) and how it was reached.
#[derive(Debug, Clone)]
pub struct EhlResult {
    /// pressure, film, deflection, viscosity, density, h0
    pub fields: SolvedFields,
    /// Newton steps (all continuation stages)
    pub iterations: usize,
    /// GMRES iterations (all Newton steps)
    pub linear_iterations: usize,
    /// elastic operator applications (the dominant cost)
    pub operator_applications: usize,
    /// Newton runs: grid-sequencing levels and continuation stages (1 = a single run)
    pub continuation_stages: usize,
    /// relative mass imbalance ||min(P/c, F)||_2 / ||d(rho H)/dX||_2 over cells with material
    /// (F the discrete Reynolds residual, c its local diagonal scaling; see `ehl::system`)
    pub residual: f64,
    /// (sum p dA - load) / load
    pub load_error: f64,
    pub converged: bool,
    /// why the solve stopped, in words (`reason.to_string()`)
    pub termination: String,
    /// why the solve stopped
    pub reason: Termination,
    /// mass flows (kg/s; per metre of length for a line contact): through the inlet; through
    /// the outlet and into the cavitated zone; out through the free y-edges
    pub inflow: f64,
    pub outflow: f64,
    pub side_leakage: f64,
}

#[derive(Default)]
struct Stats<'a> {
    newton: usize,
    gmres: usize,
    stages: usize,
    /// operator applications on coarser grids (grid sequencing)
    applies: usize,
    /// told of every evaluated Newton iterate
    observer: Option<NewtonObserver<'a>>,
}

/// Loosest relative tolerance of a Newton step's linear solve (the Eisenstat-Walker forcing
/// term is clamped to [ETA_MIN, ETA_MAX]). Far from the solution the Newton steps are limited by
/// the non-linearity (the cavitation boundary still moving), not by the linear solve: on the
/// thesis roller at 256 x 512 cells ETA_MAX = 0.1 took the same 19 Newton steps as 1e-2 with
/// 121 instead of 138 GMRES iterations on the finest grid (single runs: 2.9 s against 3.3-3.6 s).
const ETA_MAX: f64 = 0.1;

/// Tightest forcing term of the Eisenstat-Walker choice (its lower clamp), and the first step's
/// forcing term in a time step's solve from within sqrt(tol) of its solution
/// (`transient::step_first_eta`); either way the floor in `NewtonRun::evaluate` (a reduction
/// of the (weighted) merit to 0.1 x tolerance / score, no further) loosens it. (A transient line's
/// whole-Jacobian preconditioner starts from 0 instead, with its own floor.)
const ETA_MIN: f64 = 1e-4;

/// The first step's forcing term of a Newton run started next to its solution: the thermal
/// fixed point's Reynolds solves after its first, whose factors move little. ETA_MAX there
/// spent the first of 3 steps a solve on a 7x reduction; with 1e-2 the Newton steps of whole
/// thermal runs fell 19 -> 17 (thesis roller 256 x 512), 19 -> 12 (the same at 256 x 128, SRR
/// 0.3, Carreau) and 24 -> 17 (`ehl_thermal_line.toml`), 5-10 % of their time.
const ETA_WARM: f64 = 1e-2;

/// The Newton steps measure the merit vector R (rows Phi_k = min(P_k, c_k F_k) = c_k min(P_k /
/// c_k, F_k), c_k = 1 / (Poiseuille + |wedge| diagonal), see `System::scaling`, and the load
/// row) in the norm ||W R||_2 with the row weights w_k = (c_max / c_k)^MERIT_WEIGHT_EXPONENT
/// (c_max the largest over the cells of the current state; the load row 1): GMRES minimises
/// that norm (W applied to the Jacobian's rows and undone before the preconditioner, so that
/// W J M^-1 W^-1 keeps the spectrum of J M^-1) and the line search and the forcing terms use
/// it too. Every Reynolds row's weight is at least 1, so the load row counts for less against
/// them than in the unweighted merit (its scale s_L was set to balance them, `system`); H0 is
/// taken by the preconditioner's exact Schur step (the thesis roller's solves, traced, ended
/// with load errors of 1e-14 either way).
///
/// Why: the convergence test is the unscaled relative mass imbalance (rows min(P_k / c_k,
/// F_k) = Phi_k / c_k, see `System::relative_residual`), and near the end of a solve 65-98 %
/// of it sits in the far inlet, where the thick film's Poiseuille diagonal makes c_k small
/// (traced on the thesis roller at 256 x 512: c = 5.6e-9 at x cell 0, 100 times less than at
/// the thermal film's start, x cell 83): the scaled merit (exponent 0) hardly saw those rows,
/// and the last Newton steps of a solve went to them (the finest grid's imbalance 6.3e-2 ->
/// 3.0e-2 over two steps while the merit fell 30-fold). With exponent 1 the merit is the
/// test's own rows, but GMRES then works on W J M^-1 W^-1 with weights over six decades, far
/// from normal: the isothermal roller took 568 GMRES iterations instead of 214. Measured
/// 2026-12-05 (GMRES iterations of whole runs, exponent 0 / 0.25 / 0.5; films and friction
/// within 2.3e-7 relative of exponent 0's; BENCHMARKS.md): the thesis roller 256 x 512
/// 214 / 209 / 186 (and with `[thermal]` the fixed point's 10 Newton steps and 224 GMRES
/// iterations -> 7 and 175 at 0.5, 192 at 0.75), at 512 x 128 80 / 82 / 70, the ball on
/// glass 110 / 88 / 75, `ehl_friction_line.toml` 466 / 408 / 390, the glass ball at 5 m/s
/// with `[thermal]` 668 / 569 / 524, the single pit over 30 steps (256^2) 608 / 610 / 569,
/// the transient ball dent 4166 / 3844 / 3436; the
/// Carreau roller at SRR 0.3 with `[thermal]` 150 / 146 / 159 (one Newton step more), the
/// thermal line 1132 / 1072 / 1121. The transient line contacts' whole-Jacobian path keeps
/// exponent 0 (its GMRES is a few iterations a step).
const MERIT_WEIGHT_EXPONENT: f64 = 0.5;

/// Why a Newton run (or a whole steady solve) stopped. `Display` gives the sentence written to
/// `summary.json`'s `termination`.
#[derive(Debug, Clone, PartialEq)]
pub enum Termination {
    /// relative residual and load error both within the tolerance
    Converged,
    /// a state with NaN or infinity (never returned as the solution: the best state is)
    NonFiniteState,
    /// the Newton step limit (`EhlParams::max_iterations`) was reached
    MaxIterations(usize),
    /// the line preconditioner could not be factored
    SingularPreconditioner,
    /// the merit ||W R|| (`MERIT_WEIGHT_EXPONENT`) fell by less than 0.1 % over the last 8
    /// Newton steps
    Stalled { step: usize, merit: f64 },
    /// plain Newton: no step length along the Newton direction reduced ||W R||
    LineSearchFailed { step: usize },
    /// pseudo-transient continuation: no descent even with a small pseudo-time step
    NoDescent { step: usize },
    /// plain Newton failed, then pseudo-transient continuation from the same start
    NewtonThenPseudoTransient {
        newton: Box<Termination>,
        pseudo_transient: Box<Termination>,
    },
    /// stopped from outside through [`crate::run::cancel`] (the result is thrown away)
    Cancelled,
    /// thermal runs: every Newton solve converged, but over the last of `outer` fixed-point
    /// iterations the film temperature still changed by `change_k` (K; infinite where the last
    /// update solved cells the one before did not: the film's extent still moved) or the film
    /// by `film_change` of its thinnest value
    ThermalNotSettled {
        outer: usize,
        change_k: f64,
        film_change: f64,
        /// the residual the last temperature update left in the film and at the surfaces (K,
        /// [`crate::thermal::ThermalContact::inner_residual`])
        residual_k: f64,
        /// a steady run: the Reynolds factors' own residual, max |ln G(F) - ln F|
        /// ([`crate::ehl::thermal::ThermalParams::factor_tolerance`])
        factor_residual: Option<f64>,
    },
    /// thermal runs: the temperature solve failed (why)
    ThermalFailed(String),
    /// the direct attempt failed and continuation in alpha stalled at `fraction` of alpha
    ContinuationStalled {
        first: Box<Termination>,
        fraction: f64,
        last: Box<Termination>,
    },
}

impl Termination {
    pub fn is_converged(&self) -> bool {
        matches!(self, Termination::Converged)
    }
}

impl std::fmt::Display for Termination {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Termination::Converged => write!(f, "converged"),
            Termination::NonFiniteState => write!(f, "non-finite state"),
            Termination::MaxIterations(n) => write!(f, "no convergence in {n} Newton steps"),
            Termination::SingularPreconditioner => write!(f, "singular preconditioner"),
            Termination::Cancelled => write!(f, "cancelled"),
            Termination::ThermalNotSettled {
                outer,
                change_k,
                film_change,
                residual_k,
                factor_residual,
            } => {
                write!(
                    f,
                    "thermal fixed point not settled: after {outer} outer iterations "
                )?;
                // an infinite change: the last update solved cells the one before did not
                // (the film's extent still moving), not a temperature
                if *change_k != f64::INFINITY {
                    write!(f, "the film temperature still changed by {change_k:.3} K")?;
                } else {
                    write!(f, "the film's extent still moved (cells joined it)")?;
                }
                write!(f, ", the film by {film_change:.1e} of its thinnest")?;
                if let Some(r) = factor_residual {
                    write!(f, ", the Reynolds factors by {r:.1e} (log)")?;
                }
                write!(
                    f,
                    ", and the temperature solve left a residual of {residual_k:.3} K"
                )
            }
            Termination::ThermalFailed(why) => write!(f, "temperature solve failed: {why}"),
            Termination::Stalled { step, merit } => write!(
                f,
                "stalled at Newton step {step}: the weighted merit ||W R|| {merit:.3e} unchanged \
                 over 8 steps"
            ),
            Termination::LineSearchFailed { step } => {
                write!(f, "line search failed at Newton step {step}")
            }
            Termination::NoDescent { step } => write!(
                f,
                "stalled at Newton step {step}: no descent even with a small pseudo-time step"
            ),
            Termination::NewtonThenPseudoTransient {
                newton,
                pseudo_transient,
            } => write!(f, "Newton: {newton}; pseudo-transient: {pseudo_transient}"),
            Termination::ContinuationStalled {
                first,
                fraction,
                last,
            } => write!(
                f,
                "{first}; continuation in alpha stalled at {fraction:.3} alpha: {last}"
            ),
        }
    }
}

/// One Newton iterate, as an observer of the solve sees it (after each evaluation of a new
/// state): for progress bars and residual histories.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonIterate {
    /// Newton steps taken so far in this solve (all stages and grids)
    pub newton_steps: usize,
    /// GMRES iterations so far in this solve
    pub linear_iterations: usize,
    /// relative residual of the state (see [`EhlResult::residual`])
    pub residual: f64,
    /// (sum p dA - load) / load
    pub load_error: f64,
    /// cells of the grid this iterate lives on (grid sequencing solves coarser grids first)
    pub cells: usize,
    /// the tolerance this stage is solved to
    pub tolerance: f64,
}

/// An observer of the Newton iterates ([`solve_steady_observed`]).
pub type NewtonObserver<'a> = &'a mut (dyn FnMut(&NewtonIterate) + Send);

/// Outcome of one Newton run: converged, reason, relative residual, load error.
struct StageEnd {
    converged: bool,
    reason: Termination,
    residual: f64,
    load_error: f64,
}

/// Newton iteration from `st` (evaluated) to `tol`; on return `st` is the best state seen.
///
/// Globalised by pseudo-transient continuation (Kelley & Keyes, SIAM J. Numer. Anal. 35 (1998)
/// 508-523): the Reynolds rows of J get the shift 1/dtau, dtau grows by switched evolution
/// relaxation (dtau_k+1 = dtau_k ||W R_k|| / ||W R_k+1||, the weighted merit of
/// [`MERIT_WEIGHT_EXPONENT`]) so the iteration turns into Newton as the residual falls; each
/// step is then backtracked on ||W R||_2, and a step that does not reduce it is retried with
/// dtau / 4.
///
/// The iteration is run as its phases ([`NewtonRun`]): evaluate the state (and test for
/// convergence), find the direction (one preconditioned GMRES solve), search along it, then
/// accept the step or shrink the pseudo-time step (and test for a stall).
fn newton(
    sys: &mut System,
    st: &mut State,
    tol: f64,
    dtau0: f64,
    first_eta: f64,
    par: &EhlParams,
    stats: &mut Stats,
) -> StageEnd {
    let mut run = NewtonRun::new(sys, st, dtau0, first_eta);
    let end = loop {
        // a cancelled solve stops at once; every later stage (pseudo-time, continuation, the
        // second start) stops at its first check, so the whole solve unwinds in milliseconds
        if crate::run::cancel::requested() {
            break Termination::Cancelled;
        }
        if run.fresh {
            if let Some(t) = run.evaluate(sys, st, tol, stats) {
                break t;
            }
        }
        if run.it >= par.max_iterations {
            break Termination::MaxIterations(par.max_iterations);
        }
        if let Err(t) = run.direction(sys, st, par, stats) {
            break t;
        }
        run.it += 1;
        stats.newton += 1;
        let accepted = run.line_search(sys, st);
        if let Some(t) = run.next(st, accepted) {
            break t;
        }
    };
    run.finish(sys, st, end)
}

/// The state of one Newton run between its phases, and its work vectors.
struct NewtonRun {
    /// row scaling of the current state
    c: Vec<f64>,
    /// Poiseuille share of each row's diagonal (the preconditioner's coarse-grid switch)
    share: Vec<f64>,
    /// active set (cells held at P = 0) of the current state and of the trial state
    set: Vec<bool>,
    set_t: Vec<bool>,
    /// merit vector (scaled residual and load row) of the current state and of the trial
    r: Vec<f64>,
    rt: Vec<f64>,
    /// the merit's row weights at the current state (see [`MERIT_WEIGHT_EXPONENT`]), and
    /// scratch for the preconditioner's unweighted input
    weight: Vec<f64>,
    unweighted: Vec<f64>,
    /// the Newton direction (P, H0)
    u: Vec<f64>,
    /// the scaled H0 column of the Jacobian
    bcol: Vec<f64>,
    e_h0: Vec<f64>,
    trial: State,
    lin: Linear,
    work: GmresWork,
    spare_pc: Option<Preconditioner>,
    /// the best state seen (by max(residual, |load error|)) and its score
    best: Option<(f64, State)>,
    prev_merit: Option<f64>,
    merit: f64,
    /// GMRES forcing term
    eta: f64,
    /// pseudo-time step (infinite: plain Newton)
    dtau: f64,
    /// the current pseudo-time shift 1/dtau of this step's solve
    shift: f64,
    full_step: bool,
    /// ||W R|| of the last steps (stall test)
    recent: Vec<f64>,
    /// Newton steps taken
    it: usize,
    /// the current state is new (evaluate it)
    fresh: bool,
}

impl NewtonRun {
    fn new(sys: &System, st: &State, dtau0: f64, first_eta: f64) -> Self {
        let n = sys.n();
        let mut e_h0 = vec![0.0; n + 1];
        e_h0[n] = 1.0;
        NewtonRun {
            c: vec![0.0; n],
            share: vec![0.0; n],
            set: vec![false; n],
            set_t: vec![false; n],
            r: vec![0.0; n + 1],
            rt: vec![0.0; n + 1],
            weight: vec![1.0; n + 1],
            unweighted: vec![0.0; n + 1],
            u: vec![0.0; n + 1],
            bcol: vec![0.0; n],
            e_h0,
            trial: st.clone(),
            lin: Linear::new(n),
            work: GmresWork::default(),
            spare_pc: None,
            best: None,
            prev_merit: None,
            merit: 0.0,
            // with the whole-Jacobian preconditioner of a transient line (started from the
            // predicted state, in Newton's region of fast convergence) the first step is solved as
            // tightly as the tolerance asks (the floor in `evaluate`), not to ETA_MAX
            eta: if sys.jacobian_reuse { 0.0 } else { first_eta },
            dtau: dtau0,
            shift: 0.0,
            full_step: false,
            recent: Vec::new(),
            it: 0,
            fresh: true,
        }
    }

    /// Evaluates the (new) state: scaling, merit, the best state, the observer, the
    /// convergence test, the next forcing term and pseudo-time step, the H0 column. Some when
    /// the run ends here (converged, or a non-finite state).
    fn evaluate(
        &mut self,
        sys: &mut System,
        st: &State,
        tol: f64,
        stats: &mut Stats,
    ) -> Option<Termination> {
        let n = sys.n();
        if !st.is_finite() {
            return Some(Termination::NonFiniteState);
        }
        sys.scaling(st, &mut self.c, Some(&mut self.share));
        sys.merit_vector(st, &self.c, &mut self.r, &mut self.set);
        self.weigh(sys);
        let res = sys.relative_residual(st, &self.c);
        let lerr = (sys.carried(&st.p) - sys.load) / sys.load;
        let score = res.max(lerr.abs());
        if score.is_finite() && self.best.as_ref().is_none_or(|b| score < b.0) {
            match &mut self.best {
                Some(b) => {
                    b.0 = score;
                    b.1.clone_from(st);
                }
                None => self.best = Some((score, st.clone())),
            }
        }
        if let Some(o) = stats.observer.as_mut() {
            o(&NewtonIterate {
                newton_steps: stats.newton,
                linear_iterations: stats.gmres,
                residual: res,
                load_error: lerr,
                cells: n,
                tolerance: tol,
            });
        }
        if res <= tol && lerr.abs() <= tol {
            return Some(Termination::Converged);
        }
        self.merit = weighted_norm(&self.r, &self.weight);
        let merit = self.merit;
        if let Some(pm) = self.prev_merit {
            // Eisenstat & Walker (1996) choice 2, safeguarded to [ETA_MIN, ETA_MAX]
            self.eta = (0.9 * (merit / pm).powi(2)).clamp(ETA_MIN, ETA_MAX);
            // switched evolution relaxation, at least doubled after a full step
            self.dtau *= (pm / merit)
                .min(100.0)
                .max(if self.full_step { 2.0 } else { 0.0 });
        }
        self.prev_merit = Some(merit);
        // no need to solve far below what the tolerance asks: near the end a reduction of
        // the residual by tol / score (with a safety factor 10) is enough (Kelley 1995,
        // Iterative Methods for Linear and Nonlinear Equations, sec. 6.3). With the whole-Jacobian
        // preconditioner, where one more digit costs about one GMRES iteration and one more
        // Newton step at least two, the factor is 1000: the relative residual (F unscaled)
        // falls some 30 times less than the scaled merit the GMRES tolerance is measured in
        // (transient line, 2048 cells: 4.8e-6 -> 2.9e-8 for a linear reduction of 2e-4),
        // so with 10 the step fell short of 1e-8 and a second Newton step was needed
        let safety = if sys.jacobian_reuse { 1e-3 } else { 0.1 };
        self.eta = self.eta.max((safety * tol / score).min(ETA_MAX));
        // exact H0 column
        sys.directional(st, &self.e_h0, &mut self.lin, &mut self.bcol);
        for k in 0..n {
            self.bcol[k] = if self.set[k] {
                0.0
            } else {
                self.c[k] * self.bcol[k]
            };
        }
        None
    }

    /// The merit's row weights at the current scaling `c` ([`MERIT_WEIGHT_EXPONENT`]; all 1
    /// with a transient line's whole-Jacobian preconditioner).
    fn weigh(&mut self, sys: &System) {
        let n = sys.n();
        if sys.jacobian_reuse {
            self.weight.fill(1.0);
            return;
        }
        let top = self
            .c
            .iter()
            .cloned()
            .filter(|c| c.is_finite())
            .fold(0.0f64, f64::max);
        for (w, &c) in self.weight[..n].iter_mut().zip(&self.c) {
            *w = if c > 0.0 && c.is_finite() {
                (top / c).powf(MERIT_WEIGHT_EXPONENT)
            } else {
                1.0
            };
        }
        self.weight[n] = 1.0;
    }

    /// The Newton direction `u`: J u = -R by preconditioned GMRES (the whole-Jacobian
    /// preconditioner of a transient line when it applies, else the line / multigrid one), with the
    /// pseudo-time shift on the Reynolds rows.
    fn direction(
        &mut self,
        sys: &mut System,
        st: &State,
        par: &EhlParams,
        stats: &mut Stats,
    ) -> Result<(), Termination> {
        self.shift = if self.dtau.is_finite() && self.dtau < 1e12 {
            1.0 / self.dtau
        } else {
            0.0
        };
        let shift = self.shift;
        // (weighted: -W R; the whole-Jacobian path's weights are 1)
        let rhs: Vec<f64> = self
            .r
            .iter()
            .zip(&self.weight)
            .map(|(v, w)| -v * w)
            .collect();
        let dense = if sys.jacobian_reuse && shift == 0.0 {
            line_jacobian_solve(
                sys,
                st,
                &self.c,
                &self.set,
                &self.bcol,
                &rhs,
                &mut self.u,
                self.eta,
                par,
                &mut self.lin,
                &mut self.work,
                stats,
            )
        } else {
            None
        };
        let out = match dense {
            Some(out) => out,
            None => {
                let Some(pc) = Preconditioner::new(
                    sys,
                    st,
                    &self.c,
                    &self.set,
                    &self.share,
                    &self.bcol,
                    shift,
                    self.spare_pc.take(),
                ) else {
                    return Err(Termination::SingularPreconditioner);
                };
                let (c, set, lin) = (&self.c, &self.set, &mut self.lin);
                let (weight, unweighted) = (&self.weight, &mut self.unweighted);
                // W J u = -W R, right-preconditioned by M W^-1 (M approximates J)
                let out = gmres(
                    &mut self.work,
                    &rhs,
                    &mut self.u,
                    par.gmres_restart,
                    par.max_linear_iterations,
                    self.eta,
                    &mut |v, o| {
                        jacobian_product(sys, st, lin, c, set, shift, v, o);
                        o.iter_mut().zip(weight).for_each(|(o, w)| *o *= w);
                    },
                    &mut |v, o| {
                        for ((x, v), w) in unweighted.iter_mut().zip(v).zip(weight) {
                            *x = v / w;
                        }
                        pc.apply(unweighted, o)
                    },
                );
                self.spare_pc = Some(pc);
                out
            }
        };
        stats.gmres += out.iterations;
        Ok(())
    }

    /// Backtracking line search on ||W R||_2 (same scaling c and weights W) along `u`, P
    /// clamped at >= 0: true when a step length was accepted (the trial state holds it).
    fn line_search(&mut self, sys: &mut System, st: &State) -> bool {
        let n = sys.n();
        let shift = self.shift;
        let mut lam = 1.0;
        let accepted = self.u.iter().all(|v| v.is_finite())
            && loop {
                for k in 0..n {
                    self.trial.p[k] = (st.p[k] + lam * self.u[k]).max(0.0);
                }
                self.trial.h0 = st.h0 + lam * self.u[n];
                sys.eval(&mut self.trial);
                // a negative film under pressure is the spurious branch eps = 0: not a step
                let trial = &self.trial;
                let film_ok = || (0..n).all(|k| trial.p[k] <= 0.0 || trial.h[k] > 0.0);
                if trial.is_finite() && film_ok() {
                    sys.merit_vector(trial, &self.c, &mut self.rt, &mut self.set_t);
                    let m = weighted_norm(&self.rt, &self.weight);
                    if m.is_finite() && m <= (1.0 - 1e-4 * lam) * self.merit {
                        break true;
                    }
                }
                lam *= 0.5;
                if lam < if shift == 0.0 { 1e-3 } else { 0.1 } {
                    break false;
                }
            };
        self.full_step = accepted && lam == 1.0;
        accepted
    }

    /// After the search: the stall test, then the accepted step becomes the state, or the
    /// pseudo-time step shrinks (plain Newton: the run ends). Some when the run ends here.
    fn next(&mut self, st: &mut State, accepted: bool) -> Option<Termination> {
        let (it, merit) = (self.it, self.merit);
        // stalled: ||W R|| has not fallen by 0.1 % over the last 8 steps
        self.recent.push(merit);
        let k = self.recent.len();
        if k > 8 && merit > 0.999 * self.recent[k - 9] {
            return Some(Termination::Stalled { step: it, merit });
        }
        if accepted {
            std::mem::swap(st, &mut self.trial);
            self.fresh = true;
        } else if self.shift == 0.0 {
            return Some(Termination::LineSearchFailed { step: it });
        } else {
            self.dtau *= 0.25;
            self.fresh = false;
            if self.dtau < 1e-8 {
                return Some(Termination::NoDescent { step: it });
            }
        }
        None
    }

    /// Ends the run: a failed run returns its best state; a converged one gets its active set
    /// exactly at P = 0 (so the mass flows see a clean cavitation boundary); the final
    /// residual and load error.
    fn finish(mut self, sys: &mut System, st: &mut State, end: Termination) -> StageEnd {
        let n = sys.n();
        let converged = end.is_converged();
        if !converged {
            if let Some((_, b)) = self.best {
                *st = b;
            }
        } else {
            sys.scaling(st, &mut self.c, None);
            sys.merit_vector(st, &self.c, &mut self.r, &mut self.set);
            if (0..n).any(|k| self.set[k] && st.p[k] != 0.0) {
                for k in 0..n {
                    if self.set[k] {
                        st.p[k] = 0.0;
                    }
                }
                sys.eval(st);
            }
        }
        sys.scaling(st, &mut self.c, None);
        StageEnd {
            converged,
            reason: end,
            residual: sys.relative_residual(st, &self.c),
            load_error: (sys.carried(&st.p) - sys.load) / sys.load,
        }
    }
}

/// Most GMRES iterations a lagged whole-Jacobian preconditioner may take before it is refactored at
/// the current state and the solve is repeated.
const DENSE_STALE_MAX: usize = 20;

/// A lagged whole-Jacobian preconditioner is refactored before the next Newton step once the GMRES
/// iterations it has cost beyond two per solve (what fresh dense LU factors took) add up to
/// more than this: the rent-or-buy rule, with the price of a factorisation in GMRES iterations. With
/// dense LU factors (1025 unknowns 35 ms against 0.36 ms per solve, 2049 260 ms against 2.5
/// ms) the price was about 100 at both sizes. In HODLR form both are cheaper, the solves more
/// so (2049: ~40 ms against ~0.1 ms; a GMRES iteration then costs about as much again in the
/// Jacobian product). The waviness example (2048 cells, 2000 steps; solve time, 2-core
/// machine) took 7.7 s with a budget of 50, 6.3-6.6 s with 100, 5.9-6.1 s with 200 (5.6
/// GMRES iterations per step) and 5.9-6.0 s with 400 (6.8 per step).
const DENSE_REFRESH: usize = 200;

/// One Newton step's linear solve J u = rhs preconditioned by the exact Jacobian kept in
/// `sys` (see [`system::LineJacobianPreconditioner`]): the kept factors are used as long as they
/// serve (at most [`DENSE_STALE_MAX`] iterations to reach `eta`), else refactored here and the
/// solve repeated; they are marked for a refresh at the next step by the budget
/// [`DENSE_REFRESH`]. None if the matrix could not be factored (the caller falls back to the
/// banded preconditioner). The GMRES iterations of a discarded attempt are counted in `stats`.
#[allow(clippy::too_many_arguments)]
fn line_jacobian_solve(
    sys: &mut System,
    st: &State,
    c: &[f64],
    set: &[bool],
    bcol: &[f64],
    rhs: &[f64],
    u: &mut [f64],
    eta: f64,
    par: &EhlParams,
    lin: &mut Linear,
    work: &mut GmresWork,
    stats: &mut Stats,
) -> Option<GmresOutcome> {
    let mut kept = if sys.jacobian_stale {
        None
    } else {
        sys.line_jacobian_pc.take()
    };
    sys.line_jacobian_pc = None;
    loop {
        let fresh = kept.is_none();
        let pc = match kept.take() {
            Some(pc) => pc,
            None => {
                sys.dense_builds += 1;
                LineJacobianPreconditioner::new(sys, st, c, set, bcol, 0.0, true)?
            }
        };
        let max = if fresh {
            par.max_linear_iterations
        } else {
            DENSE_STALE_MAX.min(par.max_linear_iterations)
        };
        let out = gmres(
            work,
            rhs,
            u,
            par.gmres_restart,
            max,
            eta,
            &mut |v, o| jacobian_product(sys, st, lin, c, set, 0.0, v, o),
            &mut |v, o| pc.apply(v, o),
        );
        // (NaN: not reached)
        let reached = out.relative_residual <= eta;
        if !fresh && !reached {
            stats.gmres += out.iterations;
            continue;
        }
        if fresh {
            sys.jacobian_extra = 0;
        } else {
            sys.jacobian_extra += out.iterations.saturating_sub(2);
        }
        sys.jacobian_stale = sys.jacobian_extra > DENSE_REFRESH;
        sys.line_jacobian_pc = Some(pc);
        return Some(out);
    }
}

/// Whether residual `a` is better (smaller) than `b`, a NaN losing to any number.
pub(crate) fn better(a: f64, b: f64) -> bool {
    a < b || (b.is_nan() && !a.is_nan())
}

/// Plain Newton from `st`; if it fails, pseudo-transient continuation from the same start.
fn solve_from(
    sys: &mut System,
    st: &mut State,
    tol: f64,
    par: &EhlParams,
    stats: &mut Stats,
) -> StageEnd {
    solve_from_with(sys, st, tol, ETA_MAX, par, stats)
}

/// The relative mass imbalance of the evaluated state `st` of `sys`, as a Newton run measures
/// it (`System::relative_residual` with the state's own row scaling).
fn relative_imbalance(sys: &System, st: &State) -> f64 {
    let mut c = vec![0.0; sys.n()];
    sys.scaling(st, &mut c, None);
    sys.relative_residual(st, &c)
}

/// The measure a Newton run's convergence test takes of the evaluated state `st` of `sys`
/// (`NewtonRun::evaluate`'s score): the larger of the relative mass imbalance and the relative
/// load error.
fn newton_score(sys: &System, st: &State) -> f64 {
    let lerr = (sys.carried(&st.p) - sys.load) / sys.load;
    relative_imbalance(sys, st).max(lerr.abs())
}

/// [`solve_from`] with the first Newton step's linear solve forced to `first_eta` (and, as
/// every step's, no tighter than the tolerance needs): [`ETA_WARM`] for the steady thermal
/// fixed point's later solves, [`ETA_MIN`] for a time step's solve from within sqrt(tol) of
/// its solution (`transient::step_first_eta`).
fn solve_from_with(
    sys: &mut System,
    st: &mut State,
    tol: f64,
    first_eta: f64,
    par: &EhlParams,
    stats: &mut Stats,
) -> StageEnd {
    let start = st.clone();
    let e = newton(sys, st, tol, f64::INFINITY, first_eta, par, stats);
    if e.converged || !par.pseudo_time_step.is_finite() {
        return e;
    }
    let mut st2 = start;
    let e2 = newton(
        sys,
        &mut st2,
        tol,
        par.pseudo_time_step,
        ETA_MAX,
        par,
        stats,
    );
    let reason = Termination::NewtonThenPseudoTransient {
        newton: Box::new(e.reason.clone()),
        pseudo_transient: Box::new(e2.reason.clone()),
    };
    // (a NaN residual loses to any other)
    if e2.converged || better(e2.residual, e.residual) {
        *st = st2;
        StageEnd { reason, ..e2 }
    } else {
        StageEnd { reason, ..e }
    }
}

/// Whether the gap describes a point contact (it grows along y, a roller's does not).
fn is_point(p: &EhlProblem) -> bool {
    let g = p.grid;
    if g.ny == 1 {
        return false;
    }
    let (b, r) = (p.hertz_half_width, p.reduced_radius);
    let ymid = 0.5 * (g.y_min + g.y_max());
    let g0 = p.gap.at(0.0, ymid);
    let ge = p.gap.at(0.0, g.y(0));
    ge.is_finite() && g0.is_finite() && (ge - g0) * r / (b * b) > 0.5
}

/// Classical central film h_c / R to place H0 at the start (Moes for lines, Hamrock-Dowson for
/// points); only a starting value, Newton fixes H0 by the load balance.
fn film_guess(p: &EhlProblem, alpha: f64, point: bool) -> f64 {
    let (e, r) = (p.reduced_modulus, p.reduced_radius);
    let u = p.lubricant.viscosity * p.entrainment_speed / (e * r);
    let g = alpha * e;
    if point {
        film::hamrock_dowson_central(p.load / (e * r * r), u, g, 1.0)
    } else {
        let wl = if p.grid.ny == 1 {
            p.load
        } else {
            p.load / (p.grid.y_max() - p.grid.y_min)
        };
        film::moes_line_central_film(wl / (e * r), u, g)
    }
}

/// The starting state: the given or a Hertz pressure scaled to the load, H0 from the classical
/// film at the pressure maximum.
fn start(problem: &EhlProblem, sys: &mut System, init: Option<&[f64]>, alpha: f64) -> State {
    let grid = sys.grid;
    let b = problem.hertz_half_width;
    let n = grid.len();
    let point = is_point(problem);
    let mut st = State::new(n);
    match init {
        Some(p0) if p0.len() == n && p0.iter().any(|v| v.is_finite() && *v > 0.0) => {
            for k in 0..n {
                st.p[k] = if sys.active[k] && p0[k].is_finite() {
                    (p0[k] / problem.hertz_pressure).max(0.0)
                } else {
                    0.0
                };
            }
        }
        _ => {
            let ymid = 0.5 * (grid.y_min + grid.y_max());
            for j in 0..grid.ny {
                for i in 0..grid.nx {
                    let k = grid.idx(i, j);
                    let x = grid.x(i) / b;
                    let y = if point { (grid.y(j) - ymid) / b } else { 0.0 };
                    let s = 1.0 - x * x - y * y;
                    st.p[k] = if sys.active[k] && s > 0.0 {
                        s.sqrt()
                    } else {
                        0.0
                    };
                }
            }
        }
    }
    let carried = sys.carried(&st.p);
    if carried > 0.0 {
        let s = sys.load / carried;
        st.p.iter_mut().for_each(|p| *p *= s);
    }
    st.h0 = 0.0;
    sys.eval(&mut st);
    let hc = film_guess(problem, alpha, point) * problem.reduced_radius
        / (b * b / problem.reduced_radius);
    let kmax = (0..n)
        .filter(|&k| sys.active[k])
        .max_by(|&a, &b| st.p[a].total_cmp(&st.p[b]))
        .unwrap_or(0);
    st.h0 = if hc.is_finite() {
        hc - st.h[kmax]
    } else {
        -st.h[kmax]
    };
    sys.eval_film(&mut st);
    st
}

/// Solve the steady isothermal EHL problem (thesis ch. 2) by Newton-Krylov.
///
/// Never panics on a physical input and never returns NaN: when Newton fails (even with
/// continuation) or does not reach the tolerance within `max_iterations` steps, the best
/// state seen is returned with `converged == false` and the reason in `termination`.
pub fn solve_steady(problem: &EhlProblem, params: &EhlParams) -> EhlResult {
    solve_steady_observed(problem, params, &mut |_| {})
}

/// [`solve_steady`], telling `observer` of every Newton iterate (all grids and stages): for a
/// progress bar or a residual history.
pub fn solve_steady_observed(
    problem: &EhlProblem,
    params: &EhlParams,
    observer: NewtonObserver,
) -> EhlResult {
    // run the whole solve on a rayon worker: the many small parallel loops of a Newton step then
    // start by work stealing, not by injecting a job from outside the pool and putting the
    // calling thread to sleep until it is done (256 x 512 roller, means of 5 runs: system time
    // 1.4 -> 0.9 s, wall 3.8 -> 3.4 s)
    rayon::scope(|_| {
        let mut stats = Stats {
            observer: Some(observer),
            ..Stats::default()
        };
        let (mut sys, st, end) = solve_grid(
            problem,
            problem.grid,
            problem.initial_pressure,
            params,
            &mut stats,
        );
        finish(problem, &mut sys, st, end, &stats)
    })
}

/// [`solve_steady`] with the start chosen for the contact and a second start if the first
/// fails: the better of the two results is returned. `problem.initial_pressure` is the dry
/// pressure (or None); `on_second` is called before a second start.
///
/// Either start is grid-sequenced (solved on coarser grids first). Measured: the Hertz start is
/// the robust route for the infinite line (the thesis ch. 2 line at 1024 cells converges in
/// 0.4 s, and failed from the dry start unsequenced), the dry start for finite contacts (the
/// 512 x 128 thesis roller fails from the Hertz profile; the 256 x 512 one converges in 11 s
/// from the dry start sequenced, 115 s unsequenced).
pub fn solve_steady_with_fallback(
    problem: &EhlProblem,
    params: &EhlParams,
    on_second: &dyn Fn(),
) -> EhlResult {
    solve_steady_with_fallback_observed(problem, params, on_second, &mut |_| {})
}

/// [`solve_steady_with_fallback`], telling `observer` of every Newton iterate of both starts.
pub fn solve_steady_with_fallback_observed(
    problem: &EhlProblem,
    params: &EhlParams,
    on_second: &dyn Fn(),
    observer: NewtonObserver,
) -> EhlResult {
    let dry = problem.initial_pressure;
    let order = if problem.grid.ny == 1 {
        [None, dry]
    } else {
        [dry, None]
    };
    let mut with = |start: Option<&[f64]>| {
        solve_steady_observed(
            &EhlProblem {
                initial_pressure: start,
                ..*problem
            },
            params,
            &mut *observer,
        )
    };
    let first = with(order[0]);
    if first.converged || order[0] == order[1] || crate::run::cancel::requested() {
        return first;
    }
    on_second();
    let second = with(order[1]);
    if second.converged || second.residual < first.residual {
        second
    } else {
        first
    }
}

/// Half-width of the elastic coupling along x kept in the line preconditioner: at least
/// `least`, and dy / (2 dx) (at most 64) on 2D grids. A cell much longer in y than in x acts
/// along its row like a strip: its influence coefficients decay only logarithmically until the
/// distance reaches its length dy, so a fixed band of a few cells misses most of the coupling
/// within a line. Measured on straight rollers of 10 mm, b = 55 um, 256 x 128 cells
/// (dy / dx = 60): with 4 cells GMRES stalled (relative residual 0.97 after 400 iterations)
/// and the run did not converge in 5 min; with 32 cells 5-7 GMRES iterations per Newton step,
/// converged in 1.4 s. On near-square cells a wider band only costs time (thesis roller
/// 256 x 512, dy / dx = 1.8: 11.6 s with 4, 26 s with 32).
fn line_band(grid: Grid, least: usize) -> usize {
    let wide = if grid.ny > 1 {
        ((grid.dy / (2.0 * grid.dx)).ceil() as usize).min(64)
    } else {
        0
    };
    least.max(wide).max(1)
}

/// The grid with half the cells (rounded up) along x, and along y unless ny == 1, same extents,
/// if the grid is fine enough for grid sequencing: at least 256 cells on a line, 128 x 64 on
/// a 2D grid (coarser grids do not resolve the contact well enough to be a useful start).
fn coarser(g: Grid) -> Option<Grid> {
    let min_nx = if g.ny == 1 { 256 } else { 128 };
    let ok = g.nx >= min_nx && (g.ny == 1 || g.ny >= 64);
    ok.then(|| {
        Grid::new(
            g.nx.div_ceil(2),
            if g.ny == 1 { 1 } else { g.ny.div_ceil(2) },
            g.x_min,
            g.x_max(),
            g.y_min,
            g.y_max(),
        )
    })
}

/// Bilinear interpolation of a cell-centred field from `cg` to `fg` (same extents; either may
/// be the finer), constant beyond the outermost cell centres.
fn interpolate(cg: &Grid, v: &[f64], fg: &Grid, out: &mut [f64]) {
    let pos = |x: f64, x0: f64, d: f64, n: usize| -> (usize, usize, f64) {
        let s = ((x - x0) / d - 0.5).clamp(0.0, (n - 1) as f64);
        let i = (s.floor() as usize).min(n - 1);
        let i1 = (i + 1).min(n - 1);
        (i, i1, s - i as f64)
    };
    for j in 0..fg.ny {
        let (j0, j1, ty) = if fg.ny == 1 {
            (0, 0, 0.0)
        } else {
            pos(fg.y(j), cg.y_min, cg.dy, cg.ny)
        };
        for i in 0..fg.nx {
            let (i0, i1, tx) = pos(fg.x(i), cg.x_min, cg.dx, cg.nx);
            let a = v[cg.idx(i0, j0)] * (1.0 - tx) + v[cg.idx(i1, j0)] * tx;
            let b = v[cg.idx(i0, j1)] * (1.0 - tx) + v[cg.idx(i1, j1)] * tx;
            out[fg.idx(i, j)] = a * (1.0 - ty) + b * ty;
        }
    }
}

/// A fine-grid field on the coarse grid `cg` (same extents): the average of each 2 x 2
/// (2 x 1 for a line) block of cells when the grids nest exactly, else bilinear sampling.
fn restrict(fg: &Grid, v: &[f64], cg: &Grid) -> Vec<f64> {
    let mut out = vec![0.0; cg.len()];
    let sy = if fg.ny == 1 { 1 } else { 2 };
    if fg.nx != 2 * cg.nx || fg.ny != sy * cg.ny {
        interpolate(fg, v, cg, &mut out);
        return out;
    }
    let w = 1.0 / (2 * sy) as f64;
    for j in 0..cg.ny {
        for i in 0..cg.nx {
            let mut s = 0.0;
            for jj in 0..sy {
                for ii in 0..2 {
                    s += v[fg.idx(2 * i + ii, sy * j + jj)];
                }
            }
            out[cg.idx(i, j)] = s * w;
        }
    }
    out
}

/// The loosest tolerance a coarse grid of the grid sequencing ([`solve_grid`]) is solved to.
/// Its solution is only the finer grid's start, and interpolated there it leaves a relative
/// mass imbalance of order 1 to 10 (the thesis roller 256 x 512: 16 on its finest grid, 11 on
/// the one before), whatever the coarse tolerance: the digits past 1e-3 were thrown away. A
/// steady thermal run's isothermal start has solved every grid to 1e-3 since 2026-11-28, a
/// transient thermal run's since 2026-12-05 ([`thermal::START_TOLERANCE`]). Measured
/// 2026-12-05 (Newton steps of the whole solve; the results within 1e-9 of the coarse grids
/// solved to the case's 1e-6): the thesis roller 256 x 512 19 -> 18, the same at the
/// example's 512 x 128 15 -> 12, the glass ball 129^2 15 -> 13, `ehl_friction_line.toml`
/// 16 -> 13 (BENCHMARKS.md).
const COARSE_TOLERANCE: f64 = 1e-3;

/// Solve on `grid` from the pressure `init` on it (None: a Hertz profile). Grid sequencing when
/// the grid is fine enough: solve on the grid twice as coarse (from `init` averaged onto it),
/// interpolate, and finish with Newton here; if that fails, or the grid is coarse, Newton from
/// `init` directly, with continuation in alpha.
fn solve_grid(
    problem: &EhlProblem,
    grid: Grid,
    init: Option<&[f64]>,
    params: &EhlParams,
    stats: &mut Stats,
) -> (System, State, StageEnd) {
    let b = problem.hertz_half_width;
    let r = problem.reduced_radius;
    let ph = problem.hertz_pressure;
    let lub = problem.lubricant;
    let lambda = 12.0 * problem.entrainment_speed * lub.viscosity * r * r / (b * b * b * ph);
    let phys = Physics::new(lub.clone(), ph, lambda);
    let init = init.filter(|p| p.len() == grid.len());
    if let Some(cg) = coarser(grid) {
        let cinit = init.map(|p| restrict(&grid, p, &cg));
        // the coarse solve is only a start: no continuation in alpha there (when a coarse grid
        // is too coarse for the contact, that costs minutes and saves nothing), and no tighter
        // than COARSE_TOLERANCE
        let cpar = EhlParams {
            continuation: false,
            tolerance: params.tolerance.max(COARSE_TOLERANCE),
            ..*params
        };
        let (csys, cst, cend) = solve_grid(problem, cg, cinit.as_deref(), &cpar, stats);
        stats.applies += csys.applies;
        if cend.converged {
            let op = (problem.operator)(grid);
            let mut sys = System::new(
                grid,
                op,
                problem.gap,
                b,
                r,
                phys.clone(),
                problem.load,
                line_band(grid, params.band),
                params.wedge_upwind_order != 1,
            );
            let mut st = State::new(grid.len());
            interpolate(&cg, &cst.p, &grid, &mut st.p);
            st.h0 = cst.h0;
            // keep the load exact on the new grid
            let carried = sys.carried(&st.p);
            if carried > 0.0 {
                let s = sys.load / carried;
                st.p.iter_mut().for_each(|p| *p *= s);
            }
            sys.eval(&mut st);
            stats.stages += 1;
            let end = solve_from(&mut sys, &mut st, params.tolerance, params, stats);
            if end.converged {
                return (sys, st, end);
            }
        }
    }
    solve_direct(problem, grid, init, phys, params, stats)
}

/// Solve on `grid` from the Hertz/dry start, with continuation in alpha if Newton fails.
fn solve_direct(
    problem: &EhlProblem,
    grid: Grid,
    init: Option<&[f64]>,
    phys: Physics,
    params: &EhlParams,
    stats: &mut Stats,
) -> (System, State, StageEnd) {
    let b = problem.hertz_half_width;
    let r = problem.reduced_radius;
    let alpha = problem.lubricant.pressure_viscosity_coefficient;
    let op = (problem.operator)(grid);
    let mut sys = System::new(
        grid,
        op,
        problem.gap,
        b,
        r,
        phys,
        problem.load,
        line_band(grid, params.band),
        params.wedge_upwind_order != 1,
    );

    let mut st = start(problem, &mut sys, init, alpha);
    let initial = st.clone();
    stats.stages += 1;
    let mut end = solve_from(&mut sys, &mut st, params.tolerance, params, stats);
    // (a cancelled solve skips the continuation: every stage would stop at once anyway)
    if !end.converged && params.continuation && alpha > 0.0 && !crate::run::cancel::requested() {
        // continuation in alpha from the start: stages alpha f, f -> 1, the increment halved
        // after a failed stage and grown after a successful one
        let first_reason = end.reason.clone();
        let mut done: f64 = 0.0;
        let mut step: f64 = 0.25;
        let mut from = initial.clone();
        let mut fresh = true;
        loop {
            let f = (done + step).min(1.0);
            let last = f >= 1.0;
            sys.phys.set_alpha(alpha * f);
            let mut cur = if fresh {
                start(problem, &mut sys, init, alpha * f)
            } else {
                let mut s = from.clone();
                sys.eval(&mut s);
                s
            };
            stats.stages += 1;
            let tol = if last {
                params.tolerance
            } else {
                params.tolerance.max(1e-3)
            };
            let e = solve_from(&mut sys, &mut cur, tol, params, stats);
            if e.converged {
                done = f;
                from = cur;
                fresh = false;
                if last {
                    st = from.clone();
                    end = e;
                    break;
                }
                step *= 1.5;
            } else {
                step *= 0.5;
                if step < 1.0 / 64.0 {
                    end = StageEnd {
                        reason: Termination::ContinuationStalled {
                            first: Box::new(first_reason.clone()),
                            fraction: done,
                            last: Box::new(e.reason.clone()),
                        },
                        ..e
                    };
                    // the best full-alpha state is the direct attempt's
                    sys.phys.set_alpha(alpha);
                    st = initial.clone();
                    let _ = solve_from(&mut sys, &mut st, params.tolerance, params, stats);
                    break;
                }
            }
        }
        sys.phys.set_alpha(alpha);
        sys.eval(&mut st);
    }
    (sys, st, end)
}

fn finish(
    problem: &EhlProblem,
    sys: &mut System,
    mut st: State,
    end: StageEnd,
    stats: &Stats,
) -> EhlResult {
    let b = problem.hertz_half_width;
    let r = problem.reduced_radius;
    let ph = problem.hertz_pressure;
    let lub = problem.lubricant;
    let hs = b * b / r;
    sys.eval(&mut st);
    let fin = |v: f64| if v.is_finite() { v } else { f64::MAX };
    let mut out = EhlResult {
        fields: SolvedFields::of(sys, &st, ph, hs, lub),
        iterations: stats.newton,
        linear_iterations: stats.gmres,
        operator_applications: sys.applies + stats.applies,
        continuation_stages: stats.stages,
        residual: fin(end.residual),
        load_error: fin(end.load_error),
        converged: end.converged,
        termination: end.reason.to_string(),
        reason: end.reason,
        inflow: 0.0,
        outflow: 0.0,
        side_leakage: 0.0,
    };
    let m = residual::mass_flow(&sys.rg, &sys.fields(&st));
    // dimensionless flow (rho/rho0) H dY per unit u_e -> kg/s: rho0 u_e (b^2/R) b
    let q = lub.density * problem.entrainment_speed * hs * b;
    out.inflow = m.inflow * q;
    out.outflow = m.outflow * q;
    out.side_leakage = m.side_leakage * q;
    out
}

/// ||W r||_2, W = diag(`w`).
fn weighted_norm(r: &[f64], w: &[f64]) -> f64 {
    r.iter()
        .zip(w)
        .map(|(a, b)| (a * b) * (a * b))
        .sum::<f64>()
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::Termination;

    /// An unsettled thermal fixed point names what still moved: a temperature change in K, or,
    /// where the last update solved cells the one before did not (an infinite change), the
    /// film's extent, never "inf K".
    #[test]
    fn an_unsettled_thermal_fixed_point_says_what_still_moved() {
        let text = |change_k| {
            Termination::ThermalNotSettled {
                outer: 80,
                change_k,
                film_change: 1e-3,
                residual_k: 0.5,
                factor_residual: Some(2.0),
            }
            .to_string()
        };
        let a = text(0.25);
        assert!(a.contains("changed by 0.250 K"), "{a}");
        let b = text(f64::INFINITY);
        assert!(!b.contains("inf"), "{b}");
        assert!(b.contains("extent still moved"), "{b}");
        assert!(b.contains("Reynolds factors by 2.0e0"), "{b}");
    }
}
