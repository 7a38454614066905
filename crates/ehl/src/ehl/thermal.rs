//! Steady thermal EHL: the pressure, film and temperatures of a contact whose lubricant heats up
//! (issue 13), as a fixed point between the Reynolds solve and the temperature solve.
//!
//! One outer iteration:
//!
//! 1. the temperature model ([`crate::thermal::ThermalContact`]) takes the current pressure and
//!    film and solves the energy equation across the film with both bodies' surface
//!    temperatures (Jaeger's moving heat source on each body), iterated between film and bodies;
//! 2. from the temperature across the film it forms the generalized Reynolds coefficients
//!    (Yang & Wen 1990) as per-cell factors on the isothermal ones
//!    (`super::system::ThermalFactors`); the first iteration takes them whole, the later ones
//!    Anderson-mix them with the last iterates ([`ThermalParams::anderson`]), damped unless the
//!    coupling has shown itself weak (`mixing_parameter`); from the second on, a cell not
//!    solved at the update before takes its own whole (`take_new_cells`), and the cells past a
//!    row's film copy its last cell's
//!    ([`copy_past_film`](crate::thermal::contact::copy_past_film));
//! 3. Newton-Krylov solves the Reynolds equation with the load balance again, warm-started
//!    from the last solution (from the second outer iteration on, its first linear solve to
//!    [`super::ETA_WARM`]), the factors frozen, to a tolerance no tighter than the factors are
//!    known and at least a tenth of the mass imbalance the new factors leave
//!    (`reynolds_tolerance`).
//!    Where it fails, shorter plain steps of the factors are tried from the last pressure.
//!
//! The fixed point stops when the last Newton solve converged to the case's tolerance and
//! * the factors' own residual max |ln G(F) - ln F| is below [`ThermalParams::factor_tolerance`]
//!   (G the factors of the temperatures the factors F gave: a measure of the distance to the
//!   fixed point, unlike the change between mixed iterates);
//! * the film temperature is estimated within [`ThermalParams::tolerance_k`] of the fixed point
//!   (from the last change between outer iterations and the contraction of the last two), and
//!   the film within [`ThermalParams::film_tolerance`] of its thinnest value;
//! * the temperature solve's own residual is below `tolerance_k`; near the end it is given
//!   more film iterations ([`ThermalParams::final_film_iterations`]).
//!
//! All are taken where the film is at most 5 times its row's thinnest. A temperature solve
//! that fails (a film temperature running away) starts the solve again with more points
//! across the film ([`ThermalParams::refined_points`]). The first iteration starts from the
//! isothermal solution (all factors 1). A fixed point is the older of the two couplings the
//! literature uses (Yang & Wen 1990; Kim & Sadeghi 1992); the single Newton system of Habchi et
//! al. (Tribol. Lett. 30 (2008) 41) converges faster and is left for later.

use super::system::{Physics, State, System, ThermalFactors};
use super::{
    finish, line_band, solve_from_with, EhlParams, EhlProblem, EhlResult, Stats, Termination,
    ETA_MAX, ETA_WARM,
};
use crate::linalg::anderson::Anderson;
use crate::thermal::contact::{copy_past_film, CONVERGED_FILM_RATIO};
use crate::thermal::ThermalContact;

/// Controls of the thermal fixed point.
#[derive(Debug, Clone, Copy)]
pub struct ThermalParams {
    /// stop when the film temperature is estimated within this of the fixed point (K): the
    /// last change between outer iterations times rho / (1 - rho), rho the ratio of the last
    /// two changes. The change is taken where the film is at most
    /// [`crate::thermal::contact::CONVERGED_FILM_RATIO`] times its row's thinnest; the film
    /// itself must have settled too (`film_tolerance`).
    pub tolerance_k: f64,
    /// and when the film is estimated within this fraction of its thinnest value of the fixed
    /// point (the largest film change between outer iterations, over the thinnest film, times
    /// q / (1 - q), q the ratio of the last two factors' residuals, or the temperature's rho
    /// where the residual did not fall: `film_contraction`): the thick inlet, left out of the
    /// temperature's change, acts through the film
    pub film_tolerance: f64,
    /// most outer iterations
    pub max_outer: usize,
    /// under-relaxation of the Reynolds factors from the second outer iteration on (1: none):
    /// the mixing parameter of the Anderson steps (1 instead where the last two estimates of
    /// the coupling's contraction were at most 0.2, or near the linear regime the last one at
    /// most 0.5, see `mixing_parameter`); a plain relaxed
    /// iteration (`anderson` = 0) halves it, down to `min_relaxation`, whenever the
    /// film-temperature change grows, and so does a Newton solve that needed a shorter step
    pub relaxation: f64,
    /// the smallest relaxation the halving reaches
    pub min_relaxation: f64,
    /// a transient run: most (temperature, Reynolds) passes per time step
    pub max_step_passes: usize,
    /// Anderson mixing of the outer iteration (depth of its history; 0: the plain relaxed
    /// iteration): from the second outer iteration on, the next Reynolds factors combine the
    /// last `anderson` + 1 iterates (on the factors' logarithms, so that they stay positive),
    /// with `relaxation` as the mixing parameter (1 where the coupling has shown itself weak,
    /// `mixing_parameter`; Walker & Ni 2011). Depth 8 settled every
    /// case of the measured map that depth 5 settled, and the Table 3.7 line at SRR 0.3 and
    /// L = 6.8 and 9.5 besides (33 and 48 outer iterations; depth 5 stalled at a factors'
    /// residual of 2e-4; docs/thermal.md, "Left open")
    pub anderson: usize,
    /// and stop only when the factors' own residual, max |ln G(F) - ln F| over the flow and
    /// Couette factors F (G the factors of the temperatures they gave), is below this, taken
    /// where the film is at most [`crate::thermal::contact::CONVERGED_FILM_RATIO`] times its
    /// row's thinnest. Unlike the change between mixed iterates it measures the distance to
    /// the fixed point: with the change alone, the Table 3.7 line (Roelands-Carreau, U =
    /// 2.2e-10, SRR 0.3) stopped with its central film 5.2e-4 off a tightly converged one.
    pub factor_tolerance: f64,
    /// once the fixed point is near its end (the factors' residual within 10 times
    /// `factor_tolerance`, or the one the next update is expected to leave within 3 times:
    /// `near_end`), the temperature solves go on to at most this many film iterations and
    /// twice their body iterations (early outer iterations need only a rough temperature):
    /// their own error otherwise kept the residual above the stop (the same line in pure
    /// rolling at U = 1.1e-10, 11 points across the film: 0.2 K left after 5 film iterations,
    /// residual cycling at 5e-4 to 5e-3)
    pub final_film_iterations: usize,
    /// a steady solve whose temperature solve fails (a film temperature running away, the
    /// density negative) is started again with this many points across the film, where the
    /// contact has fewer (None: no retry); the run's summary warns of it. 7 points resolve
    /// the film temperature where the solve converges (docs/thermal.md); in pure rolling
    /// from L ~ 3-7 the thick inlet's reverse flow ran away at 7 and converged at 11.
    pub refined_points: Option<usize>,
    /// a steady contact whose fixed point is slow (`POLISH_WORTH`, `POLISH_LATE`; a ball or
    /// finite roller only from `POLISH_LATE` on), once it is near (`POLISH_FACTOR_RESIDUAL`,
    /// `POLISH_INNER_RESIDUAL_K`; from `POLISH_LATE` on at any factors' residual), is handed
    /// to Newton's method on the coupled problem of pressure, film and surface temperatures
    /// (`super::thermal_newton`); the fixed point's own stop then judges the result, with an
    /// update whose columns keep the root of their flux match nearest the pressure's
    /// gradient. On the Table 3.7 line's
    /// thermal map (docs/thermal.md) 19 of 20 runs settled instead of 15 when it came, in 483
    /// outer iterations instead of 909 (501 since capped columns carry their flux with the
    /// capped profile), in 10-15 % more time; 18 since the compression's capped gradient
    /// (2026-11-29). The 7 Eyring lines of the robustness scan at 1-2 GPa all settle with it
    /// (2026-12-01; 4 of them did not before). A ball or finite roller is handed over only
    /// from `POLISH_LATE` on when slow there (`PolishSchedule::due`); the robustness scan's
    /// Eyring ball at 5 m/s, unsettled after 80 outer iterations on the fixed point alone,
    /// settles in 22 with it (2026-12-02). A transient time step not settled after its
    /// passes is handed over too (`super::transient`, `STEP_POLISH_CHECKS`).
    pub coupled_newton: bool,
}

impl Default for ThermalParams {
    fn default() -> Self {
        ThermalParams {
            tolerance_k: 0.05,
            film_tolerance: 1e-4,
            max_outer: 80,
            relaxation: 0.5,
            min_relaxation: 0.125,
            max_step_passes: 20,
            anderson: 8,
            factor_tolerance: 1e-4,
            final_film_iterations: 40,
            refined_points: Some(REFINED_POINTS_ACROSS_FILM),
            coupled_newton: true,
        }
    }
}

/// The points across the film a failed steady thermal solve is retried with
/// ([`ThermalParams::refined_points`]).
pub const REFINED_POINTS_ACROSS_FILM: usize = 11;

/// The outer Anderson mixing drops its history after this many outer iterations without the
/// factors' residual falling by 10 %.
const ANDERSON_RESTART: usize = 5;

/// A line contact's fixed point is handed to Newton's method on the coupled problem
/// (`super::thermal_newton`; a finite contact's later, [`PolishSchedule::due`]) not before this
/// outer iteration (its pace is measured over the
/// last three).
const POLISH_FROM: usize = 4;

/// Only a fixed point that would need more than this many further outer iterations is handed
/// over (`remaining_outer`): a polish costs about as much as 15 outer iterations of a line
/// (the example line at L = 0.75 settles in 15 outer iterations, 0.20 s; handed over at the
/// eighth, 0.29 s).
const POLISH_WORTH: f64 = 15.0;

/// and any fixed point not settled after this many outer iterations: its contraction is no
/// guide where its residual wanders (the Table 3.7 line at SRR 1 and L = 13 did not settle
/// with the estimate alone)
const POLISH_LATE: usize = 20;

/// After a polish of a line that failed the next waits this many outer iterations (a finite
/// contact's [`POLISH_EVERY_FINITE`] and longer: [`PolishSchedule::failed`]). After one that
/// reached a solution which the next update did not find settled (the film's extent, frozen in the
/// polish, moved with its pressure) the next outer iteration polishes again. A polish that
/// fails from a wandering fixed point may succeed from the state a few outer iterations on,
/// and a line's costs ~0.1-1 s. Measured (2026-12-05, the scan's Eyring line on Barus's law at
/// 1 GPa, SRR 0.25 / 0.3 / 0.35 on 240 / 256 / 272 cells, whose factors' residual wanders at
/// 3-20), with the expanding oil's compression gradient (`film_energy::compression_gradient`,
/// same commit): with 10, 8 of the 9 settled (the scan's own case, SRR 0.3 on 256 cells,
/// failed its polish at the 20th outer iteration and its Reynolds solve at the 26th; before
/// that gradient it had settled through the rescue of a failed Reynolds solve at its 17th);
/// with 3, all 9, in 21-24 outer iterations. The thermal map: the same 18 of 20 settle, 479
/// outer iterations instead of 508 (522 before the commit); its two unsettled runs (L = 22)
/// take 1.8 times longer in their 80.
const POLISH_EVERY: usize = 3;

/// and only once the fixed point is near: the factors' residual at most this, the temperature
/// solve's own residual at most [`POLISH_INNER_RESIDUAL_K`] (a film running away with too
/// few points across it, tens of kelvin, is left to fail and be solved again with more).
/// From [`POLISH_LATE`] on, a fixed point that would not settle in [`POLISH_WORTH`] more outer
/// iterations at its present rate is polished at any factors' residual: one that has not come
/// near by then wanders, and Newton's method is its way to a solution. Measured (2026-12-01,
/// the scan of docs/thermal.md, "Robustness beyond the examples"): Eyring lines at 1-2 GPa
/// (tau_0 = 5 MPa) whose factors' residual wandered at 0.4-2 for 80 outer iterations settle
/// in 21; the thermal map of the Table 3.7 line keeps its 18 settled runs of 20 (522 outer
/// iterations instead of 519, films within 5e-8 and friction within 2.4e-5 of before).
/// Allowed from the start instead (a polish at the fourth outer iteration at any residual),
/// the map took twice as long: at high L a far polish costs 100-300 GMRES iterations a step.
const POLISH_FACTOR_RESIDUAL: f64 = 0.1;
const POLISH_INNER_RESIDUAL_K: f64 = 5.0;

/// A contact polished this many times since its last failed polish, each time to a solution that
/// the update after it did not find settled nor much nearer ([`POLISH_PROGRESS`]), is given back to
/// the fixed point for the rest of the run: a guard against the two methods not solving quite the
/// same equations. They did not where the limiting shear stress capped columns, before the fixed
/// point's flux-driven columns matched their flux after the cap (`film_energy`'s
/// `column_coefficients`): the line was polished again every outer iteration to `max_outer`
/// (measured: the example line at p_h = 2 GPa, U = 1e-11, Lambda = 0.04 and SRR 0.2 to 1, unsettled
/// after 80 outer iterations, where the fixed point alone settled in 20 to 37; with the old
/// matching and this guard the thermal map's results were unchanged to the last digit).
const POLISH_RUN: usize = 3;

/// A finite contact (a ball, a finite roller) whose polish failed is polished again this many outer
/// iterations later, and twice as long after each further failure (5, 10, 20, 40: at most three
/// more failed polishes in the default 80 outer iterations after a first failure at the 20th; a
/// retry that reaches a solution is followed by the repolishes of [`POLISH_RUN`]). A failed 2D
/// polish costs up to [`super::thermal_newton`]'s 100 GMRES iterations a Newton step, each a film
/// solve of every row (a step of 100: ~2 s on a 97^2 ball, ~12 s at 256 x 256). Measured
/// (2026-12-05, the robustness scan's steel ball at 20 m/s and SRR 0.3, L = 6, 97^2): its polish at
/// the 20th outer iteration, from a factors' residual of 2.9, failed; never polished again (the
/// rule before), its fixed point wandered at 0.6-2.3 to the 80th outer iteration. With the retries
/// it settles in 42 outer iterations.
const POLISH_EVERY_FINITE: usize = 5;

/// A polish that reached a solution after which the update found the factors' residual at
/// most this fraction of the residual the polish started from made progress, and is not
/// counted in the run of [`POLISH_RUN`]: a ball at 15 m/s in pure rolling (the robustness
/// scan's steel ball, L = 3.4) was polished at its 20th, 21st and 22nd outer iterations, each
/// time to a solution whose film extent, frozen in the polish, was one cell short at the side
/// of the outlet spike (the residual's cell moving diagonally (79, 42) -> (80, 43) -> (81, 44)
/// -> (82, 45) of 97^2), each polish lowering the residual about tenfold (0.50 -> 3.5e-2 ->
/// 4.2e-3 -> 4.3e-4); handed back to the fixed point there, whose map expands at that
/// solution, it diverged (residual 1.7 by the 32nd) and did not settle in 80. Its polishes'
/// ratios were 0.05-0.12; 0.3 leaves room for a slower approach (not tuned: no other value
/// was tried). Only a residual still above the factors' stop counts as progress,
/// so that polishes not counted are at most log(r0 / stop) / log(1 / 0.3) in a row (8 from
/// a residual of 1 to the default stop of 1e-4).
const POLISH_PROGRESS: f64 = 0.3;

/// When a contact's fixed point is handed to Newton's method on the coupled problem
/// (`super::thermal_newton::polish`): from [`POLISH_FROM`], when slow ([`POLISH_WORTH`],
/// [`POLISH_LATE`]) and near ([`POLISH_FACTOR_RESIDUAL`], or from [`POLISH_LATE`] on a slow
/// one at any factors' residual; [`POLISH_INNER_RESIDUAL_K`]); again
/// at the next outer iteration after a polish that reached a solution (the film's extent,
/// frozen in the polish, may have moved with its pressure, and the update after it shows
/// where), [`POLISH_EVERY`] outer iterations after one that failed ([`POLISH_EVERY_FINITE`]
/// and longer for a finite contact), and never again after [`POLISH_RUN`] polishes since the
/// last failed one that reached a solution the fixed point did not then find settled nor much
/// nearer ([`POLISH_PROGRESS`]).
#[derive(Debug, Clone)]
struct PolishSchedule {
    /// the first outer iteration that may polish
    next: usize,
    /// the last polish reached a solution (which the update after it did not find settled,
    /// or the run would have stopped)
    repolish: bool,
    /// polishes since the last failed one that reached a solution without making progress
    /// (see [`POLISH_RUN`], [`POLISH_PROGRESS`]; not necessarily one after another: polishes
    /// that made progress may come between them)
    reached_in_a_row: usize,
    /// the factors' residual the last polish that reached a solution started from, until the
    /// update after it is seen ([`PolishSchedule::seen`])
    started_from: Option<f64>,
    /// failed polishes of a finite contact so far (see [`POLISH_EVERY_FINITE`])
    finite_failures: u32,
}

impl PolishSchedule {
    fn new() -> Self {
        PolishSchedule {
            next: POLISH_FROM,
            repolish: false,
            reached_in_a_row: 0,
            started_from: None,
            finite_failures: 0,
        }
    }

    /// Whether outer iteration `outer` (of at most `max_outer`) polishes, after its update:
    /// `residuals` the factors' residual of every outer iteration so far (this one's last),
    /// `factor_tol` their stop, `inner_k` the temperature solve's own residual (K). Not at the
    /// last outer iteration: the contact's lines would not see the polished pressure.
    ///
    /// A finite contact (`finite`: a ball, a finite roller) is polished only from
    /// [`POLISH_LATE`] on and when slow there (or again after a polish that reached a
    /// solution): its polish costs far more than a line's, each GMRES iteration a film solve of
    /// every row (measured, 2026-12-02: the thermal thesis pit's steady start at 256 x 256,
    /// whose factors' residual a creeping film end holds at 2.5e-2 for a dozen outer
    /// iterations, was polished at its 8th, 9th and 10th with 861, 484 and 337 GMRES
    /// iterations, 204 s, where its fixed point settles in 24 outer iterations, 43 s).
    fn due(
        &self,
        outer: usize,
        max_outer: usize,
        residuals: &[f64],
        factor_tol: f64,
        inner_k: f64,
        finite: bool,
    ) -> bool {
        let Some(&residual) = residuals.last() else {
            return false;
        };
        let slow = remaining_outer(residuals, factor_tol) > POLISH_WORTH;
        let late = outer >= POLISH_LATE;
        let asked = if finite { late && slow } else { late || slow };
        outer >= self.next
            && outer < max_outer
            && self.reached_in_a_row < POLISH_RUN
            && (self.repolish || asked)
            && (residual <= POLISH_FACTOR_RESIDUAL || (outer >= POLISH_LATE && slow))
            && inner_k <= POLISH_INNER_RESIDUAL_K
    }

    /// The polish at outer iteration `outer`, started at the factors' residual `from`, reached
    /// a solution.
    fn reached(&mut self, outer: usize, from: f64) {
        self.reached_in_a_row += 1;
        self.next = outer + 1;
        self.repolish = true;
        self.started_from = Some(from);
    }

    /// The factors' residual of an outer iteration's update (`factor_tol` its stop): after a
    /// polish that reached a solution, that polish is not counted towards [`POLISH_RUN`] when
    /// the residual fell to at most [`POLISH_PROGRESS`] of the one it started from and is
    /// still above `factor_tol` (below it the run stops unless something else holds it: no
    /// progress a polish can make).
    fn seen(&mut self, residual: f64, factor_tol: f64) {
        if let Some(from) = self.started_from.take() {
            if residual > factor_tol && residual <= POLISH_PROGRESS * from {
                self.reached_in_a_row = self.reached_in_a_row.saturating_sub(1);
            }
        }
    }

    /// The polish at outer iteration `outer` failed (the fixed point goes on from its own
    /// iterate). A line is polished again [`POLISH_EVERY`] outer iterations later, a finite
    /// contact (`finite`) [`POLISH_EVERY_FINITE`] later, twice as long after each further
    /// failure.
    fn failed(&mut self, outer: usize, finite: bool) {
        self.reached_in_a_row = 0;
        self.started_from = None;
        self.next = if finite {
            let wait = POLISH_EVERY_FINITE << self.finite_failures.min(20);
            self.finite_failures += 1;
            outer.saturating_add(wait)
        } else {
            outer + POLISH_EVERY
        };
        self.repolish = false;
    }
}

/// The polish solves the temperature rows to this fraction of
/// [`ThermalParams::tolerance_k`].
const POLISH_TOLERANCE: f64 = 0.02;

/// Shorter steps of the Reynolds factors tried when the Newton solve fails after an update,
/// each a quarter of the last (down to 1/256 of it).
const FACTOR_BACKTRACKS: usize = 4;

/// The largest thermal loading L = eta0 beta u_e^2 / k_f below which the steady thermal solver
/// converged at every slide-to-roll ratio measured (docs/thermal.md, "Left open"). On the thesis
/// Table 3.7 line with the Roelands-Carreau example oil (`ehl_thermal_line.toml`, 512 cells,
/// map of 2026-11-28) it converged in pure rolling and at SRR 0.05 up to L = 22 (from L = 3.2
/// or 6.8 with the retry at 11 points across the film), at SRR 0.3 up to 13, and at SRR 1 up
/// to 3.2 but not at 6.8, where the outer fixed point keeps moving by tenths of a kelvin; with
/// Newton's method on the coupled problem ([`ThermalParams::coupled_newton`]) every run of that
/// map settles up to L = 13 and all but SRR 1 at L = 22, but the limit stays: finite rollers
/// and balls are handed to it only late (from the 20th outer iteration), and on them it was
/// measured at high L only on the robustness scan's steel ball (7-20 m/s, L up to 6, at SRR
/// 0, 0.3 and 1: all 12 settle, the pure-rolling ones at 15 and 20 m/s and 20 m/s at SRR 0.3
/// through the polish; docs/thermal.md, "Polished until it settles"). The glass-disc ball
/// example at 5 m/s and SRR 2 (L = 2.3), below it, did not settle until a row's film end was
/// held against the Reynolds solve's noise ([`crate::thermal::contact::PRESSURISED_FRACTION`];
/// 27 outer iterations). The thesis pit case on the finite rollers (L = 5.3, SRR 0.02)
/// settles at 128 x 128, and at 256 x 256 since the film carries heat along y (without the
/// side flow it did not settle in 80; 27 outer iterations, 19 since the cells past a row's film
/// copy its factors, `copy_past_film`). A run, steady or transient, that fails above it says
/// so in its reason ([`crate::run::thermal::loading_hint`]), and `ehl check` notes it.
pub const CONVERGED_THERMAL_LOADING: f64 = 2.5;

/// The tolerance of a thermal run's isothermal start, steady or transient (or the case's, where
/// looser): the start only seeds the first outer iteration, whose factors then move by several
/// per cent and whose own Reynolds solve goes to at most 1e-3 (`reynolds_tolerance`). Measured
/// 2026-11-28 (steady), two rounds: the thesis roller 256 x 512 with `[thermal]` 9.9-10.3 ->
/// 9.2-9.6 s, 256 x 128 SRR 0.3 Carreau 3.26-3.34 -> 3.15-3.17 s, `ehl_thermal_ball.toml`
/// 0.62-0.63 -> 0.59-0.60 s; the same outer and Newton iterations, central films within 1.5e-8.
/// A transient run's steady start was solved to the case's tolerance until 2026-12-05 (the
/// thermal pit's start at 256^2 then: the same 19 outer iterations and 45 Newton steps, films
/// within 5e-8).
///
/// Looser does not pay (2026-12-05, BENCHMARKS.md "Cheaper wall responses"): at 1e-1 the
/// thesis roller's finest grid (256 x 512) took 3 Newton steps instead of 6 and its outer
/// iterations' Newton steps were the same 10, but three tests failed: a fast ball (20 m/s,
/// SRR 0.3, L = 6) no longer settled in 80 outer iterations, a line held by its limiting shear
/// stress settled without the polish its test exercises, and a slow ball's y-symmetry at SRR 0
/// moved past its bound (2.73e-8 K against 2.69e-8 K): above L ~ 2.5 the fixed point's path
/// depends on its start.
pub const START_TOLERANCE: f64 = 1e-3;

/// The thermal solution: the EHL fields (viscosity and density at the mid-film temperature),
/// and how the fixed point went. The temperatures stay in the [`ThermalContact`].
#[derive(Debug, Clone)]
pub struct ThermalResult {
    pub ehl: EhlResult,
    /// outer (Reynolds - temperature) iterations
    pub outer_iterations: usize,
    /// largest film-temperature change of the last outer iteration (K)
    pub last_change_k: f64,
    /// Newton steps over all outer iterations (the isothermal start not included)
    pub newton_steps: usize,
    /// Newton steps of the coupled method (`ThermalParams::coupled_newton`) in the polishes
    /// that reached a solution
    pub coupled_newton_steps: usize,
    /// where the fixed point's wall time went
    pub times: ThermalTimes,
}

/// Where a thermal fixed point spent its wall time (s), phase by phase, over all its outer
/// iterations (and both runs of a solve started again with more points across the film).
/// Issue 13 asks a thermal solve to say where its time goes: the energy equation, the solid
/// temperatures, the coupling.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ThermalTimes {
    /// the film's energy equation: the grid lines' temperature solves across z, their wall
    /// fluxes and each update's set-up (`ThermalContact::update` less its body part)
    pub film_energy_s: f64,
    /// the bodies' surface temperatures: the moving-heat-source responses to the film's
    /// fluxes, matched to the film (`ThermalContact::body_time_s`)
    pub body_temperature_s: f64,
    /// the generalized Reynolds factors from the temperatures
    /// (`ThermalContact::reynolds_factors`; a transient step: with their relaxation,
    /// `relax_factors`)
    pub reynolds_factors_s: f64,
    /// the Newton solves of the Reynolds equation with the factors (the coupling's other
    /// half; the isothermal solve has the same kind of solve)
    pub reynolds_s: f64,
    /// Newton's method on the coupled problem (`ThermalParams::coupled_newton`), everything
    /// in it
    pub coupled_newton_s: f64,
    /// the fixed point's whole wall time (a transient step's: from the step's start to the end
    /// of its passes), these phases and the rest: setting up the Reynolds system and its
    /// elastic operator, evaluating it between solves, the mixing, the residuals and the
    /// final fields
    pub total_s: f64,
}

impl ThermalTimes {
    /// Adds `o`'s phases and total to these.
    pub(crate) fn add(&mut self, o: &ThermalTimes) {
        self.film_energy_s += o.film_energy_s;
        self.body_temperature_s += o.body_temperature_s;
        self.reynolds_factors_s += o.reynolds_factors_s;
        self.reynolds_s += o.reynolds_s;
        self.coupled_newton_s += o.coupled_newton_s;
        self.total_s += o.total_s;
    }
}

/// `contact.update` for the pressure `p` (Pa) and film `h` (m) solved with `factors`, its wall
/// time added to `times`: the bodies' share to `body_temperature_s`, the rest to
/// `film_energy_s`.
pub(super) fn timed_update(
    contact: &mut ThermalContact,
    p: &[f64],
    h: &[f64],
    active: &[bool],
    factors: &ThermalFactors,
    times: &mut ThermalTimes,
) -> crate::Result<f64> {
    let bodies_before = contact.body_time_s();
    let mut update_s = 0.0;
    let updated = timed(&mut update_s, || {
        contact.update(p, h, active, Some((&factors.flow, &factors.couette)))
    });
    let bodies_s = contact.body_time_s() - bodies_before;
    times.body_temperature_s += bodies_s;
    times.film_energy_s += update_s - bodies_s;
    updated
}

/// Runs `f`, adding its wall time (s) to `acc`.
pub(crate) fn timed<T>(acc: &mut f64, f: impl FnOnce() -> T) -> T {
    let clock = std::time::Instant::now();
    let out = f();
    *acc += clock.elapsed().as_secs_f64();
    out
}

/// Solves the thermal problem from the isothermal solution `start` of the same `problem`.
/// `contact` holds the temperature model and keeps the final temperatures. Never panics on a
/// physical input: a failed Newton solve or a fixed point that does not settle is returned with
/// `converged == false` and the reason in `termination`.
pub fn solve_thermal(
    problem: &EhlProblem,
    params: &EhlParams,
    thermal: &ThermalParams,
    start: &EhlResult,
    contact: &mut ThermalContact,
    observer: &mut (dyn FnMut(usize, f64) + Send),
) -> ThermalResult {
    rayon::scope(|_| {
        let first = run(problem, params, thermal, start, contact, observer);
        match (&first.ehl.reason, thermal.refined_points) {
            (Termination::ThermalFailed(why), Some(nz)) if contact.nz() < nz => {
                let why = why.clone();
                contact.retry_with_points_across_film(nz, why);
                let mut second = run(problem, params, thermal, start, contact, observer);
                second.times.add(&first.times);
                second
            }
            _ => first,
        }
    })
}

fn run(
    problem: &EhlProblem,
    params: &EhlParams,
    thermal: &ThermalParams,
    start: &EhlResult,
    contact: &mut ThermalContact,
    observer: &mut (dyn FnMut(usize, f64) + Send),
) -> ThermalResult {
    let clock = std::time::Instant::now();
    let mut times = ThermalTimes::default();
    let grid = problem.grid;
    let (b, r, ph) = (
        problem.hertz_half_width,
        problem.reduced_radius,
        problem.hertz_pressure,
    );
    let hs = b * b / r;
    let lub = problem.lubricant;
    let phys = Physics::new(
        lub.clone(),
        ph,
        12.0 * problem.entrainment_speed * lub.viscosity * r * r / (b * b * b * ph),
    );
    let mut sys = System::new(
        grid,
        (problem.operator)(grid),
        problem.gap,
        b,
        r,
        phys,
        problem.load,
        line_band(grid, params.band),
        params.wedge_upwind_order != 1,
    );
    let n = grid.len();
    let mut st = State::new(n);
    for k in 0..n {
        st.p[k] = if sys.active[k] {
            start.fields.pressure[k] / ph
        } else {
            0.0
        };
    }
    st.h0 = start.fields.h0 / hs;
    let mut factors = ThermalFactors {
        flow: vec![1.0; n],
        couette: vec![1.0; n],
    };
    sys.thermal = Some(factors.clone());
    sys.eval(&mut st);

    let mut stats = Stats::default();
    let mut end = None;
    let mut change = f64::INFINITY;
    let mut prev = f64::INFINITY;
    let mut outer = 0;
    let (mut p_si, mut h_si) = (vec![0.0; n], vec![0.0; n]);
    let mut fresh = factors.clone();
    // the cells the last update solved a film for (see take_new_cells)
    let mut solved_before = vec![false; n];
    let mut failure = None;
    let mut w = thermal.relaxation;
    let mut shrinking = 0;
    // the film of the last outer iteration (m; infinite where no material)
    let mut h_prev: Vec<f64> = vec![f64::NAN; n];
    let mut film_change = f64::INFINITY;
    let mut mixing = Anderson::new(thermal.anderson);
    // the smallest factor residual since the last restart of the mixing, and the outer
    // iterations since it last fell by 10 %
    let (mut best_residual, mut stuck) = (f64::INFINITY, 0usize);
    // the Reynolds factors' own residual (see factor_residual)
    let mut residual = f64::INFINITY;
    // the temperature solves' own controls, tightened near the end (final_film_iterations)
    let rough = contact.options;
    // the last Newton solve was to the case's tolerance (see reynolds_tolerance), and the loop
    // stopped on its settled test (not on running out of outer iterations after a solve that
    // no update has checked)
    let (mut tight, mut stopped) = (false, false);
    // the factors of the last outer iteration and the factors of the temperatures they gave,
    // and the map's contraction then (see map_contraction)
    let mut last_pair: Option<(ThermalFactors, ThermalFactors)> = None;
    let mut prev_contraction: Option<f64> = None;
    // the outer map near its linearisation (see mixing_parameter): cleared for good by a
    // Newton solve that needed a shorter step, a restart of the mixing for lack of progress
    // and a coupled-Newton polish (the next estimate would span its jump), and off while the
    // residual is above NEAR_LINEAR_RESIDUAL (cells solved for the first time clear the
    // mixing's history but not this: the thesis roller solves 2 new cells at its second
    // outer iteration)
    let mut near_linear = true;
    // when Newton's method on the coupled problem is tried
    let mut polishing = PolishSchedule::new();
    // the factors' residual of every outer iteration
    let mut residuals: Vec<f64> = Vec::new();
    let mut coupled_steps = 0;
    // the next update checks a polished solution: its flux-driven columns start from the
    // pressure's own gradient, where the coupled residual takes them, and keep the root of
    // their flux match nearest it (`film_energy::LineOptions::nearest_root`)
    let mut check_polish = false;
    // a failed Reynolds solve was handed to the coupled Newton method (once a run)
    let mut rescued = false;
    // a polished line taken as the fixed point's iterate (a polish the schedule asked for, or
    // the rescue of a failed Reynolds solve), and on to the next outer iteration: its factors
    // and Reynolds solve, the next update checking it, and the mixing's history and the
    // near-linear regime dropped (the next estimate would span the polish's jump)
    macro_rules! adopt_polish {
        ($pol:expr) => {{
            let pol = $pol;
            coupled_steps += pol.steps;
            polishing.reached(outer, residual);
            check_polish = true;
            factors = pol.factors;
            end = Some(pol.end);
            tight = true;
            mixing.clear();
            near_linear = false;
            continue;
        }};
    }
    while outer < thermal.max_outer {
        if crate::run::cancel::requested() {
            failure = Some(Termination::Cancelled);
            break;
        }
        outer += 1;
        fields_si(&sys, &st, ph, hs, &mut p_si, &mut h_si);
        // the film's own iteration stopped as far as the residual this update is expected to
        // leave needs, its own stop once the residual nears its end (see film_stop)
        contact.options.line.tol = film_stop(&residuals, rough.line.tol, thermal.factor_tolerance);
        contact.options.surface_tol = first_surface_stop(&residuals, rough.surface_tol);
        contact.options.line.nearest_root = std::mem::take(&mut check_polish);
        solved_before.copy_from_slice(contact.film_cells());
        change = match timed_update(contact, &p_si, &h_si, &sys.active, &factors, &mut times) {
            Ok(c) => c,
            Err(e) => {
                failure = Some(Termination::ThermalFailed(e.to_string()));
                break;
            }
        };
        observer(outer, change);
        // the distance to the fixed point, from the contraction rho of the last two changes:
        // e ~ change rho / (1 - rho) (a linear fixed point; measured rho ~ 0.87 on the thesis
        // Table 3.7 line at SRR 0.3, where the change alone would stop 7x too early)
        // Where a change already within the tolerance did not fall, the factors' residual
        // ratio stands in for it (see film_contraction; the temperatures answer the factors as
        // the film does): near the end the change is the temperature solves' own noise. The
        // thesis roller + `[thermal]` (the example's 512 x 128, pure rolling) changed by
        // 1.20e-3 and then 1.66e-3 K (against a 0.05 K tolerance) while its factors' residual
        // fell 2.5e-4 -> 5.9e-5, and 0.99 held it one more outer iteration. A change above the
        // tolerance that grew (an overshoot, damped below) or followed cells solved for the
        // first time keeps 0.99. A change within the tolerance after cells solved for the first
        // time (whose change is infinite: no ratio) takes the residuals' ratio as well: the
        // factors' residual still measures the distance to the fixed point there, and 0.99
        // asked 99 times the change of the tolerance. `ehl_thermal_ball.toml` solves new cells
        // at its second update; at its third its change was 1.0e-3 K (against 0.05 K) and its
        // residual 5.4e-5 (5.2e-3 before it), and 0.99 held it for a fourth update.
        let falling = prev.is_finite() && change < prev;
        let rho = if falling { change / prev } else { 0.99 };
        let noise = change <= thermal.tolerance_k;
        // a growing change (both finite: an infinite one is a cell solved for the first time)
        // is the coupling overshooting: damp it
        if prev.is_finite() && change.is_finite() && change > prev {
            w = (0.5 * w).max(thermal.min_relaxation.min(thermal.relaxation));
            shrinking = 0;
        } else if change < prev {
            // and three contractions in a row give back what one overshoot took: a relaxation
            // left at its floor by an early overshoot crawls (the thesis Table 3.6 line at
            // SRR 1.0 stalled at 0.05 K, contraction 0.99, with 0.125)
            shrinking += 1;
            if shrinking >= 3 {
                w = (2.0 * w).min(thermal.relaxation);
                shrinking = 0;
            }
        }
        prev = change;
        film_change = self::film_change(&h_si, &h_prev);
        h_prev.copy_from_slice(&h_si);
        timed(&mut times.reynolds_factors_s, || {
            contact.reynolds_factors(&p_si, &sys.active, &mut fresh.flow, &mut fresh.couette)
        });
        residual = factor_residual(grid, &h_si, &factors, &fresh);
        residuals.push(residual);
        polishing.seen(residual, thermal.factor_tolerance);
        // how strongly the temperatures answer the factors, from this outer iteration and the
        // last (see mixing_parameter)
        let contraction = last_pair
            .as_ref()
            .and_then(|(f, g)| map_contraction(grid, &h_si, (f, g), (&factors, &fresh)));
        last_pair = Some((factors.clone(), fresh.clone()));
        let mut last_contraction = std::mem::replace(&mut prev_contraction, contraction);
        let rho_film = film_contraction(&residuals).unwrap_or(rho);
        let rho_t = if falling || !noise { rho } else { rho_film };
        let estimate = change * rho_t / (1.0 - rho_t);
        let settled = estimate <= thermal.tolerance_k
            && residual <= thermal.factor_tolerance
            && contact.inner_residual() <= thermal.tolerance_k
            && film_change * rho_film / (1.0 - rho_film) <= thermal.film_tolerance;
        if settled && tight && end.as_ref().is_some_and(|e: &super::StageEnd| e.converged) {
            stopped = true;
            break;
        }
        // a contact whose fixed point has not settled by now is handed to Newton's
        // method on the coupled problem (see `super::thermal_newton`)
        // (not at the last outer iteration: the contact's lines would not see the polished
        // pressure)
        if thermal.coupled_newton
            && polishing.due(
                outer,
                thermal.max_outer,
                &residuals,
                thermal.factor_tolerance,
                contact.inner_residual(),
                grid.ny > 1,
            )
        {
            let saved = (st.clone(), sys.thermal.clone());
            match timed(&mut times.coupled_newton_s, || {
                polish_coupled(
                    &mut sys, &mut st, contact, ph, hs, params, thermal, &mut stats,
                )
            }) {
                Ok(pol) => adopt_polish!(pol),
                Err(_) => {
                    polishing.failed(outer, grid.ny > 1);
                    st = saved.0;
                    sys.thermal = saved.1;
                    sys.eval(&mut st);
                }
            }
        }
        let at_end = near_end(&residuals, thermal.factor_tolerance);
        if at_end {
            contact.options.line.max_iter = rough.line.max_iter.max(thermal.final_film_iterations);
            contact.options.max_surface_iterations = 2 * rough.max_surface_iterations;
        }
        let (base, st_base) = (factors.clone(), st.clone());
        let step = if outer == 1 { 1.0 } else { w };
        if outer == 1 || thermal.anderson == 0 {
            relax(&mut factors, &base, &fresh, step);
        } else {
            if !change.is_finite() {
                // a cell solved for the first time: the history is of another problem (the
                // contraction's estimates are kept: taken over the cells of both iterations,
                // they still measure how the temperatures answer the factors; the Carreau
                // roller at SRR 0.3 solves new cells until its fourth outer iteration)
                mixing.clear();
            }
            // a history that stopped reducing the residual is dropped (a restart, the usual
            // safeguard of Anderson mixing): measured on the map's 24 cases it settled pure
            // rolling at L = 6.8 in 47 outer iterations instead of 69 and SRR 1 at L = 3.2 in
            // 49 instead of 80, and changed no other case
            if residual < 0.9 * best_residual {
                best_residual = residual;
                stuck = 0;
            } else {
                stuck += 1;
                if stuck >= ANDERSON_RESTART {
                    mixing.clear();
                    stuck = 0;
                    best_residual = residual;
                    // and a stalled iteration is not a weak coupling: two new estimates first
                    prev_contraction = None;
                    last_contraction = None;
                    near_linear = false;
                }
            }
            mix_factors(
                &mut factors,
                &fresh,
                &mut mixing,
                mixing_parameter(
                    thermal,
                    contraction,
                    last_contraction,
                    near_linear
                        && residuals[0] <= NEAR_LINEAR_RESIDUAL
                        && residual <= NEAR_LINEAR_RESIDUAL,
                ),
            );
        }
        if outer > 1 {
            take_new_cells(&mut factors, &fresh, &solved_before, contact.film_cells());
            // past each row's film the factors in use copy its last cell's, as the fresh ones
            // do: the copies are not unknowns of their own. Mixed as if they were, each kept its
            // own history and lagged the cell it copies where the row's film had grown or
            // shrunk: on the thermal pit's steady start at 256^2 with take_new_cells alone, the
            // copy (202, 98) held 0.9504 at the 17th outer iteration against the 0.9523 of the
            // cell it copies and crept up at a ratio of ~0.7 an outer iteration, the largest
            // factors' residual for seven outer iterations (27 in all; 19 with both)
            let (flow, couette) = (&mut factors.flow, &mut factors.couette);
            copy_past_film(grid, flow, couette, contact.film_cells(), &sys.active);
        }
        sys.thermal = Some(factors.clone());
        sys.eval(&mut st);
        // bounded by the mass imbalance the new factors leave at the last pressure (a solve
        // tried again with a shorter step of the factors, below, keeps this tolerance: taken
        // from the shorter step's own imbalance, the thermal map took 525 outer iterations
        // instead of 522, pure rolling at L = 9.5 21 instead of 18)
        let tol = reynolds_tolerance(
            params.tolerance,
            loose_share(grid) * residual,
            at_end,
            start_imbalance(&sys, &st),
        );
        tight = tol <= params.tolerance;
        let first_eta = if outer == 1 { ETA_MAX } else { ETA_WARM };
        let mut e = timed(&mut times.reynolds_s, || {
            solve_from_with(&mut sys, &mut st, tol, first_eta, params, &mut stats)
        });
        // a Newton solve that fails with the new factors is tried again from the last pressure
        // with a shorter plain step of the factors: the first step, which takes them whole,
        // stalled Newton in pure rolling at L >= 3 (the Table 3.7 line, Barus oil, U = 2.2e-10)
        let mut cut = step;
        for _ in 0..FACTOR_BACKTRACKS {
            if e.converged {
                break;
            }
            cut *= 0.25;
            relax(&mut factors, &base, &fresh, cut);
            st = st_base.clone();
            sys.thermal = Some(factors.clone());
            sys.eval(&mut st);
            e = timed(&mut times.reynolds_s, || {
                solve_from_with(&mut sys, &mut st, tol, ETA_MAX, params, &mut stats)
            });
            if e.converged {
                // the iterations after it keep to the step that worked (undamped steps
                // only after two new estimates of a weak coupling)
                w = w.min(cut.max(thermal.min_relaxation.min(thermal.relaxation)));
                mixing.clear();
                prev_contraction = None;
                near_linear = false;
            }
        }
        let ok = e.converged;
        end = Some(e);
        if !ok {
            // a line whose Reynolds solve failed with every shorter step of the factors is
            // handed once to Newton's method on the coupled problem, from the pressure before
            // that solve: the scan's Eyring line on Barus's law at 1 GPa failed so at its 17th
            // outer iteration, before a polish was due (docs/thermal.md, "The Eyring lines
            // settle"); not a 2D contact, whose polish costs a film solve of every row a GMRES
            // iteration (its failed solves were not measured)
            if thermal.coupled_newton && grid.ny == 1 && !rescued {
                rescued = true;
                let failed = (st.clone(), sys.thermal.clone());
                st = st_base.clone();
                sys.thermal = Some(base.clone());
                sys.eval(&mut st);
                if let Ok(pol) = timed(&mut times.coupled_newton_s, || {
                    polish_coupled(
                        &mut sys, &mut st, contact, ph, hs, params, thermal, &mut stats,
                    )
                }) {
                    adopt_polish!(pol);
                }
                st = failed.0;
                sys.thermal = failed.1;
                sys.eval(&mut st);
            }
            break;
        }
    }
    contact.options = rough;
    let newton_steps = stats.newton;
    let mut end = end.unwrap_or(super::StageEnd {
        converged: false,
        reason: Termination::MaxIterations(0),
        residual: f64::INFINITY,
        load_error: f64::INFINITY,
    });
    if let Some(f) = failure {
        end.converged = false;
        end.reason = f;
    } else if end.converged && !stopped {
        end.converged = false;
        end.reason = Termination::ThermalNotSettled {
            outer,
            change_k: change,
            film_change,
            residual_k: contact.inner_residual(),
            factor_residual: Some(residual),
        };
    }
    let mut ehl = finish(problem, &mut sys, st, end, &stats);
    contact.fill_laws(
        &ehl.fields.pressure,
        &sys.active,
        &mut ehl.fields.viscosity,
        &mut ehl.fields.density,
    );
    times.total_s = clock.elapsed().as_secs_f64();
    ThermalResult {
        ehl,
        outer_iterations: outer,
        last_change_k: change,
        newton_steps,
        coupled_newton_steps: coupled_steps,
        times,
    }
}

/// Newton's method on the coupled problem of a contact, steady or in a time step
/// (`super::thermal_newton::polish`), from the state `st` of `sys`, the Reynolds rows to the
/// case's tolerance and the temperature rows to [`POLISH_TOLERANCE`] of
/// [`ThermalParams::tolerance_k`]. The polish freezes the film's extent: from now on its start
/// holds against small moves (see `crate::thermal::contact::INLET_FILM_HYSTERESIS`; a
/// transient step restores the hold it had at its end).
#[allow(clippy::too_many_arguments)]
pub(super) fn polish_coupled(
    sys: &mut System,
    st: &mut State,
    contact: &mut ThermalContact,
    ph: f64,
    hs: f64,
    params: &EhlParams,
    thermal: &ThermalParams,
    stats: &mut Stats,
) -> Result<super::thermal_newton::Polished, String> {
    contact.options.inlet_hysteresis = true;
    super::thermal_newton::polish(
        sys,
        st,
        contact,
        ph,
        hs,
        params.tolerance,
        POLISH_TOLERANCE * thermal.tolerance_k,
        stats,
    )
}

/// The pressure (Pa) and film (m; infinite where there is no material) of the evaluated state
/// `st` of `sys`, for the temperature model (`ph` the pressure scale, `hs` the film scale).
pub(crate) fn fields_si(sys: &System, st: &State, ph: f64, hs: f64, p: &mut [f64], h: &mut [f64]) {
    for k in 0..st.p.len() {
        p[k] = st.p[k] * ph;
        h[k] = if sys.active[k] {
            st.h[k] * hs
        } else {
            f64::INFINITY
        };
    }
}

/// Moves `factors` the fraction `w` of the way to the Reynolds factors of `contact`'s present
/// temperatures at the pressure `p` (Pa); `fresh` is scratch.
pub(crate) fn relax_factors(
    contact: &ThermalContact,
    p: &[f64],
    active: &[bool],
    factors: &mut ThermalFactors,
    fresh: &mut ThermalFactors,
    w: f64,
) {
    contact.reynolds_factors(p, active, &mut fresh.flow, &mut fresh.couette);
    let base = factors.clone();
    relax(factors, &base, fresh, w);
}

/// The contraction of the outer iteration that the film's distance to the fixed point is
/// estimated with ([`ThermalParams::film_tolerance`]): the ratio of the last two factors'
/// residuals (max |ln G - ln F|, a direct measure of the distance to the fixed point, which
/// the film follows through the Reynolds solve), None before two are known or where the
/// residual did not fall (the caller then takes the temperature change's ratio, as before).
/// A lucky drop makes the ratio small, but then the residual itself, which must be below its
/// own stop too, says the factors, and with them the film, are that near the fixed point.
/// The larger of the last two ratios instead (against such drops) held 9 runs of the thermal
/// map and 6 lines of the scan one outer iteration longer (531 outer iterations on the map
/// instead of 522) with films within 1e-8 of these. Before (2026-12-02) the film always took
/// the temperature change's ratio, which near the end is a ratio of the temperature solves'
/// own noise: the ball example's changes of 4.7e-4 and 4.0e-4 K (against a 0.05 K tolerance)
/// gave 0.85 and held a film change of 6.7e-5 five times over the 1e-4 stop for one more
/// outer iteration, where its residuals (3.1e-4 -> 5.6e-5) give 0.18. Measured: the ball
/// example 5 -> 4 outer iterations (its central and minimum film within 2.2e-6 of a solve to
/// 1e-7), the thermal map unchanged to the last digit (522 outer iterations), the scan
/// unchanged but its Barus line (19 -> 18, its films within 7e-5 of the tight solution).
fn film_contraction(residuals: &[f64]) -> Option<f64> {
    match residuals {
        [.., before, now] if before.is_finite() && now < before => Some(now / before),
        _ => None,
    }
}

/// The factors' residual the next update is expected to leave: the last of `residuals` times
/// its last ratio where it fell ([`film_contraction`]), else the last itself (infinite before
/// the first update). Where the coupling is weak the outer map contracts by 30-100 times an
/// iteration once its factors have left the isothermal ones, and the last residual alone
/// tells the end an outer iteration late ([`NEAR_END`]).
fn expected_residual(residuals: &[f64]) -> f64 {
    residuals.last().map_or(f64::INFINITY, |&last| {
        last * film_contraction(residuals).unwrap_or(1.0)
    })
}

/// The outer iterations the fixed point still needs to bring its factors' residual (the last of
/// `residuals`) below `tol`, from its mean contraction over the last three (infinite where it
/// does not contract; 0 before three are known: too early to tell).
fn remaining_outer(residuals: &[f64], tol: f64) -> f64 {
    let k = residuals.len();
    if k < 4 || !residuals[k - 4].is_finite() {
        return 0.0;
    }
    let (now, then) = (residuals[k - 1], residuals[k - 4]);
    if now <= tol {
        return 0.0;
    }
    let rho = (now / then).powf(1.0 / 3.0);
    if rho < 1.0 {
        (tol / now).ln() / rho.ln()
    } else {
        f64::INFINITY
    }
}

/// The Reynolds tolerance of an outer iteration whose factors' residual (max |ln G - ln F|),
/// times [`LOOSE_REYNOLDS`] (a line contact) or [`LOOSE_REYNOLDS_2D`] (a finite roller or a
/// ball), is `loose`: a pressure solved far tighter than its factors are known is work the next
/// temperature update throws away, so `loose`, at most [`LOOSE_REYNOLDS_MAX`] and at most
/// [`REYNOLDS_REDUCTION`] x `start` (the relative mass imbalance the new factors leave at the
/// last pressure), never tighter than the case's `tol`, and `tol` itself `at_end` (the fixed
/// point [`near_end`]): the solve before the fixed point stops is then to the case's tolerance
/// (the driver stops only after such a solve).
fn reynolds_tolerance(tol: f64, loose: f64, at_end: bool, start: f64) -> f64 {
    if at_end {
        tol
    } else {
        loose
            .min(LOOSE_REYNOLDS_MAX)
            .min(REYNOLDS_REDUCTION * start)
            .max(tol)
    }
}

/// The relative mass imbalance of the state `st` of `sys` (evaluated), as a Newton solve
/// measures it (`System::relative_residual`): before an outer iteration's Reynolds solve, what
/// the new factors leave at the last pressure ([`reynolds_tolerance`]).
fn start_imbalance(sys: &System, st: &State) -> f64 {
    super::relative_imbalance(sys, st)
}

/// The least reduction of the mass imbalance that an outer iteration's Reynolds solve makes
/// from where the new factors leave it at the last pressure ([`reynolds_tolerance`]; down to
/// the case's tolerance at most): the pressure must answer the factors' step. The factors'
/// residual is a largest value, often of a few columns, and the Reynolds tolerance a relative
/// imbalance over the whole film (a 2-norm): an Anderson step that moved those columns'
/// factors by 1 % left the imbalance below `LOOSE_REYNOLDS` x `residual`, the solve took no
/// Newton step, the next update saw the same pressure, and the fixed point stalled, up to 5
/// outer iterations in a row at one residual until the mixing restarted (measured 2026-12-02
/// on the scan's ball with the Eyring law at SRR 0.5, docs/thermal.md "Robustness beyond the
/// examples": its factors' residual stalled near 1e-2 for 80 outer iterations; with the
/// reduction it settles in 16, its Eyring neighbour at SRR 1 in 21 instead of 31, the Carreau
/// ball at SRR 1 in 13 instead of 27, two of the scan's lines sooner, the others and the
/// thermal map unchanged to the last digit; of the benchmark cases the thesis roller, the
/// example line and the Carreau roller bit-identical, the example ball within 1e-8).
const REYNOLDS_REDUCTION: f64 = 0.1;

/// The Reynolds tolerance per unit factors' residual before the end on a line contact
/// ([`reynolds_tolerance`], [`loose_share`]): a factor off by r moves the flow coefficient by
/// r, so 1 % of it keeps the pressure's own error well below what the next update changes.
/// Thesis roller 256 x 512 with `[thermal]` (then with this share): the first two Newton
/// solves 10 -> 6 steps, the same outer iterations, central film within 1e-8 of the solves to
/// the case's tolerance.
const LOOSE_REYNOLDS: f64 = 0.01;

/// [`LOOSE_REYNOLDS`] of a 2D contact (a finite roller, a ball), whose Newton steps cost a
/// GMRES solve with two FFT convolutions an iteration (~0.4 s a step on the thesis roller at
/// 256 x 512, against ~0.65 s for a whole temperature update): a tenth of the factors'
/// residual. Thesis roller 256 x 512 with `[thermal]`: the second outer iteration's solve
/// stops after its first Newton step (9.3e-4 against 1e-3; 4.3e-5 after a second, under
/// 2.2e-4 before), 7 -> 6 Newton steps and the same 4 outer iterations, the next factors'
/// residual 6.445e-4 against 6.436e-4, central film within 2.1e-7 (the fixed point's film
/// stop: 1e-4); the Carreau roller at 256 x 128 15 -> 14 Newton steps in its 8 outer
/// iterations, the thermal pit's first 30 steps 130 -> 127, the example ball and the glass
/// ball at 5 m/s unchanged, the robustness scan's balls and rollers in the same outer
/// iterations. Tried before [`REYNOLDS_REDUCTION`] kept every solve moving the pressure, a
/// tenth took the Carreau roller from 8 to 25 outer iterations. A line contact keeps 1 %: its
/// Newton steps cost next to nothing against its updates, and with a tenth one of the thermal
/// map's lines (SRR 0.05, U = 1.512e-10) took 24 outer iterations instead of 16 (the map 455
/// against 446 in all).
const LOOSE_REYNOLDS_2D: f64 = 0.1;

/// The share of the factors' residual an outer Reynolds solve goes to before the end
/// ([`reynolds_tolerance`]): [`LOOSE_REYNOLDS_2D`] on a 2D grid (a finite roller, a ball),
/// [`LOOSE_REYNOLDS`] on a line contact's single row.
fn loose_share(grid: crate::grid::Grid) -> f64 {
    if grid.ny > 1 {
        LOOSE_REYNOLDS_2D
    } else {
        LOOSE_REYNOLDS
    }
}

/// The loosest Reynolds tolerance of an outer iteration (the first, whose factors are taken
/// whole from the isothermal film: a residual of 0.09 on the thesis roller).
const LOOSE_REYNOLDS_MAX: f64 = 1e-3;

/// How many times its stop the factors' residual may be for the fixed point to count as near
/// its end ([`near_end`]): from there each update's film iteration runs with
/// [`ThermalParams::final_film_iterations`] and each Reynolds solve to the case's tolerance
/// ([`reynolds_tolerance`]), since the next update may be the last. The film's stop
/// ([`film_stop`]) takes the film's own stop from the last residual alone within this; where
/// only the expected residual is within [`EXPECTED_NEAR_END`] times the stop, its
/// [`LOOSE_FILM`] x the expected residual is at most 0.3 K x the factors' stop (3e-5 K at the
/// default 1e-4), below the film's own default stop (1e-4 K), which it then takes.
const NEAR_END: f64 = 10.0;

/// How many times its stop the residual the next update is expected to leave
/// ([`expected_residual`]) may be for the fixed point to count as near its end as well
/// ([`near_end`]).
///
/// Where the outer map contracts fast, the last residual tells the end an outer iteration
/// late: `ehl_thermal_ball.toml`'s residuals were 0.16, 5.2e-3 and 5.4e-5 over its first
/// three updates (its stop 1e-4), and its second Reynolds solve, loose since 5.2e-3 is above
/// 10 times the stop, had to be followed by a third to the case's tolerance and a fourth
/// update to check it; its expected residual there was 1.6e-4. A tight solve that is not the
/// last costs one or two Newton steps; one that is saves an update and a Reynolds solve, less
/// the Newton step it takes more itself (on that ball 69 ms saved, 43 ms more: the loop's
/// traced phases 378 -> 352 ms). The ratio of consecutive residuals is a rough estimate of
/// the next one: over the cases traced the next ratio was 3x below it (that ball: 0.032,
/// then 0.0105) or up to 1.6x above it
/// (the Table 3.7 line at its tenth outer iteration 0.24, then 0.39; the Carreau roller at
/// 256 x 128, SRR 0.3, at its fifth 0.21, then 0.32). With 10 (as [`NEAR_END`]) in place of
/// 3 those two took two and one Newton steps more (expected 4.7e-4 and 6.1e-4, and not the
/// last). Measured 2026-12-05 (BENCHMARKS.md, "Near the end one outer iteration sooner").
const EXPECTED_NEAR_END: f64 = 3.0;

/// Whether the fixed point counts as near its end after the factors' `residuals` so far, with
/// the stop `factor_tol`: the last residual within [`NEAR_END`] times the stop, or the one the
/// next update is expected to leave within [`EXPECTED_NEAR_END`] times it.
fn near_end(residuals: &[f64], factor_tol: f64) -> bool {
    let last = residuals.last().copied().unwrap_or(f64::INFINITY);
    last <= NEAR_END * factor_tol || expected_residual(residuals) <= EXPECTED_NEAR_END * factor_tol
}

/// The film iteration's stop (K) for the next update, from the factors' residuals so far:
/// `rough` (the film's own stop) once the last residual is within [`NEAR_END`] times its stop
/// `factor_tol`, else [`LOOSE_FILM`] x the residual the update is expected to leave (the last
/// residual times its last ratio, [`film_contraction`], where it fell), at most
/// [`LOOSE_FILM_MAX`] (the first update's, before any residual is known) and at least `rough`.
///
/// The expected residual, not the last one: where the coupling is weak the outer map contracts
/// far faster than a stop taken from the last residual assumes. The thesis roller 256 x 512
/// in pure rolling went from 2.2e-2 to 6.4e-4 in one outer iteration (a 34-fold fall) with
/// its film stopped at 2.2e-3 K, and the film's own error (about beta dT, beta ~0.06 per K
/// there) left the next residual at 1.34e-4, above the 1e-4 stop: a fifth update and a fourth
/// Reynolds solve. The last ratio catches part of such a fall only (0.26 = 2.2e-2 / 8.4e-2
/// there, the stop 5.8e-4 K), enough for it to settle at its fourth update (residual 4.3e-5).
/// Measured 2026-12-05 with the binary built both ways (BENCHMARKS.md): the roller at 256 x
/// 512, 256 x 128 and 192 x 384 5 -> 4 outer iterations, 128 x 512 5 both; the thermal map
/// 453 -> 454 outer iterations in all (the same 18 of 20 settled), the robustness scan 577 ->
/// 556 (all 31 settled), the example line, ball and the Carreau roller as many as before. The
/// stop is never looser than the last residual's: a small ratio costs film iterations, not
/// accuracy.
fn film_stop(residuals: &[f64], rough: f64, factor_tol: f64) -> f64 {
    let Some(&last) = residuals.last() else {
        return rough.max(LOOSE_FILM_MAX);
    };
    if last <= NEAR_END * factor_tol {
        return rough;
    }
    let expected = expected_residual(residuals);
    rough.max((LOOSE_FILM * expected).min(LOOSE_FILM_MAX))
}

/// The film-body iteration's stop (K, the largest surface change of an iteration) for the next
/// update: at the first (no `residuals` yet), as loose as the film's own stop there
/// ([`LOOSE_FILM_MAX`]), else `rough`. The first update answers the isothermal pressure, whose
/// factors it then moves by several per cent (16 % on `ehl_thermal_ball.toml`), so its
/// surfaces to 1e-3 K are work the next update throws away. Measured 2026-12-05 (BENCHMARKS.md,
/// "The ball's thermal run"): that ball 3 -> 2 surface iterations at its first update, the
/// same 4 outer iterations, 7 -> 5 Newton steps (its third outer iteration's residual 3.2e-4 ->
/// 5.4e-5); the thesis roller 256 x 512 and the example line as before. The later updates keep
/// `rough`: loosened like the film's stop ([`film_stop`]), the ball took 5 outer iterations
/// instead of 4 (its second update's surfaces left 7e-3 K off, the third outer iteration's
/// residual 1.7e-3).
fn first_surface_stop(residuals: &[f64], rough: f64) -> f64 {
    if residuals.is_empty() {
        rough.max(LOOSE_FILM_MAX)
    } else {
        rough
    }
}

/// The film iteration's stop (K, the largest temperature change of a film iteration) per unit
/// factors' residual the next update is expected to leave ([`film_stop`]), in place of its
/// own 1e-4 K: a film temperature off by dT moves ln of the factors by about beta dT (beta =
/// -d ln eta / dT, 0.03-0.1 per K for a mineral oil), so 0.1 K per unit residual keeps the
/// film's own error at a few per cent of what the factors still have to move. Measured
/// 2026-11-28, per unit of the last residual then (the thesis roller 256 x 512 with
/// `[thermal]` at SRR 0.3, Carreau): 17.4 -> 14.1 s (medians of 3), the same 10 outer
/// iterations; 1 and 0.3 per unit were faster still but lost the Table 3.7 line at SRR 0.3 and
/// L = 13 from the thermal map (14 of 20 settled instead of 15); 0.1 keeps the map's 15.
const LOOSE_FILM: f64 = 0.1;
/// The loosest film stop (K): the first update, from the inlet temperature, whose factors'
/// residual is not known yet (1.3 -> 0.7 s on the pure-rolling roller at 256 x 512).
const LOOSE_FILM_MAX: f64 = 0.1;

/// The mixing parameter of an Anderson step of the outer iteration: 1 (undamped) where the
/// last two estimates of the outer map's local contraction ([`map_contraction`]) are both at
/// most [`WEAK_COUPLING`], or near the linear regime the last one at most
/// [`NEAR_LINEAR_CONTRACTION`], else [`ThermalParams::relaxation`].
///
/// Where the temperatures barely answer the factors (a weak coupling: pure rolling, a fast
/// body), G(F) hardly moves once the first outer iteration has taken the isothermal pressure to
/// a thermal one, and a damped step only halves the distance to it: the damping, not the
/// coupling, then sets the pace. The thesis roller 256 x 512 in pure rolling measured a
/// contraction of 0.21, 0.043, 0.036 over its first outer iterations and took 8 of them with
/// the damping throughout. One estimate is along one direction of the factors only: with one
/// alone (0.2), the Table 3.7 line at SRR 0.3 and U = 3.0e-10 (a strong coupling, the
/// estimates 0.17 at first and 0.4-1.9 after) took 72 outer iterations instead of 52; with
/// two in a row it took its 52. With 0.35 for one, the thermal map lost two cases.
///
/// Near the linear regime (`near_linear`: the factors' residual of the first update and of
/// this one at most [`NEAR_LINEAR_RESIDUAL`], and since the start no Newton solve that needed
/// a shorter step, no restart of the mixing for lack of progress and no coupled-Newton polish)
/// one estimate of at most [`NEAR_LINEAR_CONTRACTION`] suffices:
/// the step it was measured along is then small, so the estimate is the map's local
/// contraction along it, and for a linear map with a positive eigenvalue c < 1 the undamped
/// step reduces the error by c, the step damped by w only by 1 - w (1 - c) (0.75 at c = 0.5,
/// w = 0.5). A norm ratio cannot tell c from -c (for -0.5 the damped step is the better, 0.25)
/// and sees one direction only, so the rule rests on the cases measured as much as on this
/// argument. The thesis roller 256 x 512 in pure rolling (first residual 0.093, estimates
/// 0.21, 0.034, 0.090): 6 -> 5 outer iterations; `ehl_thermal_ball.toml` (0.16): 5 -> 4. The
/// coupled cases of the thermal map start from residuals of 1 to 4.5 and are not affected.
fn mixing_parameter(
    thermal: &ThermalParams,
    contraction: Option<f64>,
    last_contraction: Option<f64>,
    near_linear: bool,
) -> f64 {
    match (contraction, last_contraction) {
        // (a NaN estimate is no weak coupling)
        (Some(c), _) if near_linear && c <= NEAR_LINEAR_CONTRACTION => 1.0,
        (Some(c), Some(l)) if c <= WEAK_COUPLING && l <= WEAK_COUPLING => 1.0,
        _ => thermal.relaxation,
    }
}

/// The largest factors' residual max |ln G - ln F| (of the first update, from the isothermal
/// factors, and of the present one) at which the outer map counts as near its linearisation
/// ([`mixing_parameter`]): the temperatures moved the Reynolds factors by at most ~20 %.
const NEAR_LINEAR_RESIDUAL: f64 = 0.2;

/// The largest single estimate of the local contraction at which a near-linear outer map's
/// Anderson steps are undamped ([`mixing_parameter`]).
const NEAR_LINEAR_CONTRACTION: f64 = 0.5;

/// The largest local contraction of the outer map at which its Anderson steps are undamped
/// ([`mixing_parameter`]).
const WEAK_COUPLING: f64 = 0.2;

/// The local contraction of the outer map, ||ln G(F_k) - ln G(F_(k-1))|| / ||ln F_k -
/// ln F_(k-1)|| (2-norms over the flow and Couette factors where the film `h` is at most
/// [`CONVERGED_FILM_RATIO`] times its row's thinnest), from the last pair (F, G(F)) and this
/// one; None when the factors did not move.
fn map_contraction(
    grid: crate::grid::Grid,
    h: &[f64],
    last: (&ThermalFactors, &ThermalFactors),
    now: (&ThermalFactors, &ThermalFactors),
) -> Option<f64> {
    let d = |a: &[f64], b: &[f64], k: usize| (ln(a[k]) - ln(b[k])).powi(2);
    let (mut df, mut dg) = (0.0f64, 0.0f64);
    for_converged_cells(grid, h, |k| {
        df += d(&now.0.flow, &last.0.flow, k) + d(&now.0.couette, &last.0.couette, k);
        dg += d(&now.1.flow, &last.1.flow, k) + d(&now.1.couette, &last.1.couette, k);
    });
    (df > 0.0).then(|| (dg / df).sqrt())
}

/// Calls `f` with each cell where the film `h` (m; infinite where no material) is at most
/// [`CONVERGED_FILM_RATIO`] times its row's thinnest: the region the fixed point's tests are
/// taken over.
fn for_converged_cells(grid: crate::grid::Grid, h: &[f64], mut f: impl FnMut(usize)) {
    for j in 0..grid.ny {
        let row = j * grid.nx..(j + 1) * grid.nx;
        let thin = h[row.clone()]
            .iter()
            .cloned()
            .filter(|h| h.is_finite() && *h > 0.0)
            .fold(f64::INFINITY, f64::min);
        for k in row {
            if h[k].is_finite() && h[k] <= CONVERGED_FILM_RATIO * thin {
                f(k);
            }
        }
    }
}

/// `factors` = `base` + `w` (`fresh` - `base`).
fn relax(factors: &mut ThermalFactors, base: &ThermalFactors, fresh: &ThermalFactors, w: f64) {
    for k in 0..factors.flow.len() {
        factors.flow[k] = base.flow[k] + w * (fresh.flow[k] - base.flow[k]);
        factors.couette[k] = base.couette[k] + w * (fresh.couette[k] - base.couette[k]);
    }
}

/// A cell the last update solved a film for and the one before did not (`now` and not
/// `before`: new, or back after a gap) takes its fresh factors `fresh` whole, not mixed: its
/// factors in use were not its own but a copy of its row's last solved cell's (past a row's
/// film the cells copy it), or the isothermal 1. Traced on the thermal pit's steady start at
/// 256^2: cell (201, 98) joined its row's film at the 12th outer iteration with the copy 0.9276
/// in use against its own 0.9523, and it and the copies past it crept up at a ratio of ~0.7
/// an outer iteration (the factors' residual 2.0e-3 -> 1.8e-4 over the 17th to 23rd). With
/// this alone the cell settled at once but its copies still crept (27 outer iterations, as
/// before); with the copies past the film copying too (`copy_past_film`), 19.
fn take_new_cells(
    factors: &mut ThermalFactors,
    fresh: &ThermalFactors,
    before: &[bool],
    now: &[bool],
) {
    for k in 0..now.len() {
        if now[k] && !before[k] {
            factors.flow[k] = fresh.flow[k];
            factors.couette[k] = fresh.couette[k];
        }
    }
}

/// One Anderson step (`mixing`, mixing parameter `w`) of the fixed point ln F = ln G(F) on the
/// Reynolds factors: `factors` F in, the next iterate out, `fresh` G(F). In logarithms, so
/// that an extrapolating step keeps the factors positive.
fn mix_factors(
    factors: &mut ThermalFactors,
    fresh: &ThermalFactors,
    mixing: &mut Anderson,
    w: f64,
) {
    let n = factors.flow.len();
    let x: Vec<f64> = factors
        .flow
        .iter()
        .chain(&factors.couette)
        .map(|&v| ln(v))
        .collect();
    let f: Vec<f64> = fresh
        .flow
        .iter()
        .chain(&fresh.couette)
        .zip(&x)
        .map(|(&g, &x)| ln(g) - x)
        .collect();
    let next = mixing.next(&x, &f, w);
    for k in 0..n {
        factors.flow[k] = next[k].exp();
        factors.couette[k] = next[n + k].exp();
    }
}

/// ln of a factor (positive; guarded against an underflowed 0).
fn ln(v: f64) -> f64 {
    v.max(f64::MIN_POSITIVE).ln()
}

/// The fixed-point residual of the Reynolds factors, max |ln G - ln F| over the flow and
/// Couette factors (`factors` F in use, `fresh` G those of the temperatures F gave), taken
/// where the film `h` (m; infinite where no material) is at most
/// [`crate::thermal::contact::CONVERGED_FILM_RATIO`] times its row's thinnest: the region the
/// film-temperature change is taken over. Beyond it, in the thick inlet, a residual of a few
/// 1e-3 crept on through 80 outer iterations while the films had settled to 1e-6 (the thesis
/// single pit with `[thermal]` at 256 x 256, cells at 10-20 times the thinnest film).
fn factor_residual(
    grid: crate::grid::Grid,
    h: &[f64],
    factors: &ThermalFactors,
    fresh: &ThermalFactors,
) -> f64 {
    let mut r = 0.0f64;
    for_converged_cells(grid, h, |k| {
        r = r
            .max((ln(fresh.flow[k]) - ln(factors.flow[k])).abs())
            .max((ln(fresh.couette[k]) - ln(factors.couette[k])).abs());
    });
    r
}

/// The largest change between two films (m; infinite where no material) over the thinnest
/// positive film of `now`; infinite when `before` has no value yet (NaN).
pub(crate) fn film_change(now: &[f64], before: &[f64]) -> f64 {
    let thin = now
        .iter()
        .cloned()
        .filter(|h| h.is_finite() && *h > 0.0)
        .fold(f64::INFINITY, f64::min);
    let mut d = 0.0f64;
    for (a, b) in now.iter().zip(before) {
        if a.is_finite() {
            if b.is_nan() {
                return f64::INFINITY;
            }
            d = d.max((a - b).abs());
        }
    }
    if thin.is_finite() {
        d / thin
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Grid;

    fn factors(flow: &[f64], couette: &[f64]) -> ThermalFactors {
        ThermalFactors {
            flow: flow.to_vec(),
            couette: couette.to_vec(),
        }
    }

    /// A cell with a film now and none before takes its fresh factors whole; the others (a
    /// film before and now, neither, or before only) keep the mixed ones.
    #[test]
    fn a_cell_solved_for_the_first_time_takes_its_fresh_factors() {
        let mut f = factors(&[1.0; 4], &[2.0; 4]);
        let fresh = factors(&[1.5, 1.6, 1.7, 1.8], &[2.5, 2.6, 2.7, 2.8]);
        let before = [true, false, false, true];
        take_new_cells(&mut f, &fresh, &before, &[true, true, false, false]);
        assert_eq!(f.flow, [1.0, 1.6, 1.0, 1.0]);
        assert_eq!(f.couette, [2.0, 2.6, 2.0, 2.0]);
    }

    #[test]
    fn map_contraction_is_the_slope_of_a_linear_map() {
        // G(F) = exp(g + c (ln F - f)) per cell: a map of contraction c in logarithms, whose
        // secant estimate from two iterates is c exactly, whatever the iterates. The thick
        // inlet cell (film 20 times the row's thinnest) is left out: there G moves 10 times
        // as much, and counted it would give ~10.
        let grid = Grid::new(4, 2, 0.0, 4.0, 0.0, 2.0);
        let h = [1.0, 1.0, 1.5, 20.0, 2.0, 1.0, 1.2, f64::INFINITY];
        for c in [0.03, 0.2, 0.9, 1.7] {
            let map = |f: &ThermalFactors| {
                let g = |v: &[f64], s: f64| -> Vec<f64> {
                    v.iter()
                        .enumerate()
                        .map(|(k, &x)| {
                            let slope = if k == 3 { 10.0 * c } else { c };
                            (0.1 * s + slope * (x.ln() + 0.02 * k as f64)).exp()
                        })
                        .collect()
                };
                factors(&g(&f.flow, 1.0), &g(&f.couette, -1.0))
            };
            let f1 = factors(
                &[1.0, 0.9, 1.1, 1.0, 0.8, 1.2, 1.0, 1.0],
                &[1.0, 1.0, 0.97, 1.0, 1.02, 1.0, 0.99, 1.0],
            );
            let f2 = factors(
                &[0.95, 0.93, 1.0, 1.3, 0.85, 1.1, 1.02, 1.0],
                &[0.99, 1.01, 0.98, 0.9, 1.0, 1.0, 1.0, 1.0],
            );
            let (g1, g2) = (map(&f1), map(&f2));
            let est = map_contraction(grid, &h, (&f1, &g1), (&f2, &g2)).unwrap();
            assert!((est - c).abs() < 1e-12 * c, "c {c}: estimated {est}");
            // and a map that did not move its factors gives no estimate
            assert!(map_contraction(grid, &h, (&f1, &g1), (&f1, &g2)).is_none());
        }
    }

    #[test]
    fn only_two_weak_contractions_in_a_row_undamp_the_mixing() {
        let p = ThermalParams::default();
        let w = p.relaxation;
        let m = |c, l| mixing_parameter(&p, c, l, false);
        assert_eq!(m(Some(0.05), Some(0.1)), 1.0);
        assert_eq!(m(Some(WEAK_COUPLING), Some(WEAK_COUPLING)), 1.0);
        assert_eq!(m(Some(0.05), Some(0.3)), w);
        assert_eq!(m(Some(0.3), Some(0.05)), w);
        assert_eq!(m(Some(0.05), None), w);
        assert_eq!(m(None, None), w);
        assert_eq!(m(Some(f64::NAN), Some(0.05)), w);
        assert_eq!(m(Some(0.05), Some(f64::NAN)), w);
    }

    /// Near the linear regime one estimate of at most NEAR_LINEAR_CONTRACTION undamps the
    /// mixing, whatever came before; above it, or with no estimate, the two-estimate rule
    /// holds.
    #[test]
    fn near_the_linear_regime_one_estimate_undamps_the_mixing() {
        let p = ThermalParams::default();
        let w = p.relaxation;
        let m = |c, l| mixing_parameter(&p, c, l, true);
        assert_eq!(m(Some(0.21), None), 1.0);
        assert_eq!(m(Some(NEAR_LINEAR_CONTRACTION), Some(0.9)), 1.0);
        assert_eq!(m(Some(0.6), None), w);
        assert_eq!(m(Some(0.6), Some(0.05)), w);
        assert_eq!(m(None, Some(0.05)), w);
        assert_eq!(m(Some(f64::NAN), None), w);
        // (only the near-linear rule undamps this one)
        assert_eq!(m(Some(0.3), Some(0.9)), 1.0);
    }

    /// The outer Reynolds solve's tolerance: the loose share of the factors' residual (1 % on a
    /// line, 10 % on a 2D contact), at most 1e-3, at most a tenth of the imbalance the new
    /// factors leave, never below the case's tolerance, and the case's own near the end.
    #[test]
    fn the_outer_reynolds_tolerance_answers_the_factors_step() {
        let tol = 1e-6;
        // loose: 1 % of the residual where the start is large, at most 1e-3
        let line = |r: f64| LOOSE_REYNOLDS * r;
        assert_eq!(reynolds_tolerance(tol, line(0.05), false, 1.0), 0.01 * 0.05);
        assert_eq!(
            reynolds_tolerance(tol, line(0.5), false, 1.0),
            LOOSE_REYNOLDS_MAX
        );
        // a 2D contact: 10 % (the thesis roller's second solve: residual 2.19e-2, start 2.3e-2,
        // capped at 1e-3; a residual of 5e-3 pins the share)
        let roller = Grid::new(8, 4, -1.0, 1.0, -1.0, 1.0);
        let row = Grid::new(8, 1, -1.0, 1.0, -0.5, 0.5);
        assert_eq!(loose_share(roller), 0.1);
        assert_eq!(loose_share(row), 0.01);
        let plane = |r: f64| loose_share(roller) * r;
        assert_eq!(reynolds_tolerance(tol, plane(5e-3), false, 1.0), 0.1 * 5e-3);
        assert_eq!(reynolds_tolerance(tol, plane(2.19e-2), false, 2.3e-2), 1e-3);
        // a small start imbalance: at least 90 % of it removed
        assert_eq!(reynolds_tolerance(tol, line(0.05), false, 1e-3), 0.1 * 1e-3);
        // never below the case's tolerance
        assert_eq!(reynolds_tolerance(tol, line(0.05), false, 1e-7), tol);
        // near the end: the case's tolerance whatever the start
        assert_eq!(reynolds_tolerance(tol, line(5e-4), true, 1.0), tol);
        // a NaN start (no film measured) leaves the other bounds
        assert_eq!(
            reynolds_tolerance(tol, line(0.05), false, f64::NAN),
            0.01 * 0.05
        );
    }

    /// Near the end: the last residual within 10 times the stop, or the next one expected
    /// within 3 times it (the ball example's second outer iteration: 5.2e-3 after 0.163,
    /// expected 1.66e-4), but not the Table 3.7 line's tenth (1.97e-3 after 8.25e-3, expected
    /// 4.7e-4), nor a residual that did not fall.
    #[test]
    fn near_the_end_from_the_last_or_the_expected_residual() {
        let stop = 1e-4;
        assert!(near_end(&[1e-2, 9e-4], stop));
        assert!(near_end(&[5e-4, 9e-4], stop));
        assert!(near_end(&[0.163, 5.2e-3], stop));
        assert!(!near_end(&[8.25e-3, 1.97e-3], stop));
        assert!(!near_end(&[1e-3, 5.2e-3], stop));
        assert!(!near_end(&[5.2e-3], stop));
        assert!(!near_end(&[], stop));
        assert!(!near_end(&[f64::INFINITY, 2e-3], stop));
        assert!(!near_end(&[f64::NAN], stop));
        assert!(!near_end(&[1e-2, f64::NAN], stop));
    }

    /// The remaining outer iterations of a geometric residual sequence are its own count:
    /// 0.125 -> 1e-4 at a contraction of 0.5 takes ln(8e-4) / ln(0.5) = 10.29; a sequence that
    /// does not contract never arrives; too short a history or a residual already below the
    /// stop asks for none (which keeps the fixed point going).
    #[test]
    fn remaining_outer_iterations_of_a_geometric_sequence() {
        let r = [1.0, 0.5, 0.25, 0.125];
        let k = remaining_outer(&r, 1e-4);
        assert!((k - (8e-4f64).ln() / 0.5f64.ln()).abs() < 1e-12, "{k}");
        assert_eq!(remaining_outer(&[1.0, 1.0, 1.1, 1.2], 1e-4), f64::INFINITY);
        assert_eq!(remaining_outer(&[0.5, 0.25, 0.125], 1e-4), 0.0);
        assert_eq!(
            remaining_outer(&[f64::INFINITY, 0.5, 0.25, 0.125], 1e-4),
            0.0
        );
        assert_eq!(remaining_outer(&[1.0, 0.1, 1e-3, 1e-5], 1e-4), 0.0);
    }

    /// The film's contraction estimate: the ratio of the last two factors' residuals, only
    /// where both are known and the residual fell.
    #[test]
    fn the_film_contraction_is_the_last_residual_ratio() {
        assert_eq!(film_contraction(&[1.0, 1e-2, 1e-3]), Some(1e-3 / 1e-2));
        assert_eq!(film_contraction(&[1e-2, 1e-3]), Some(1e-3 / 1e-2));
        assert_eq!(
            film_contraction(&[f64::INFINITY, 1e-2, 1e-3]),
            Some(1e-3 / 1e-2)
        );
        assert_eq!(film_contraction(&[1e-3, 1e-2]), None);
        assert_eq!(film_contraction(&[1e-3, 1e-3]), None);
        assert_eq!(film_contraction(&[f64::INFINITY, 1e-3]), None);
        assert_eq!(film_contraction(&[1e-3]), None);
        assert_eq!(film_contraction(&[]), None);
    }

    /// The expected residual is the last one times the last ratio where it fell, the last one
    /// where it did not, and infinite before any update.
    #[test]
    fn the_expected_residual_follows_the_last_ratio() {
        let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-12;
        assert!(close(
            expected_residual(&[0.163, 5.2e-3]),
            5.2e-3 * 5.2e-3 / 0.163
        ));
        assert_eq!(expected_residual(&[1e-3, 5.2e-3]), 5.2e-3);
        assert_eq!(expected_residual(&[f64::INFINITY, 5.2e-3]), 5.2e-3);
        assert_eq!(expected_residual(&[5.2e-3]), 5.2e-3);
        assert_eq!(expected_residual(&[]), f64::INFINITY);
    }

    /// The film's stop follows the residual the next update is expected to leave: the thesis
    /// roller's residuals 8.4e-2 and 2.2e-2 (ratio 0.26) give 0.1 x 0.26 x 2.2e-2 K, not the
    /// 2.2e-3 K of the last residual alone; a residual that grew is taken as it is; the first
    /// update is at LOOSE_FILM_MAX; near the end, and wherever the expected residual asks for
    /// less, the film's own stop.
    #[test]
    fn the_film_stop_follows_the_expected_residual() {
        let (rough, tol) = (1e-4, 1e-4);
        let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-12;
        assert_eq!(film_stop(&[], rough, tol), LOOSE_FILM_MAX);
        assert!(close(film_stop(&[8.4e-2], rough, tol), 8.4e-3));
        let weak = film_stop(&[8.4e-2, 2.2e-2], rough, tol);
        assert!(close(weak, 0.1 * 2.2e-2 * (2.2e-2 / 8.4e-2)), "{weak}");
        assert!(close(film_stop(&[1e-2, 2e-2], rough, tol), 2e-3));
        assert!(close(film_stop(&[5.0, 4.0], rough, tol), LOOSE_FILM_MAX));
        assert_eq!(film_stop(&[1e-2, 9e-4], rough, tol), rough);
        assert_eq!(film_stop(&[1e-2, 1.1e-3], rough, tol), rough);
        assert!(close(
            film_stop(&[1e-2, 1.1e-3], 1e-6, tol),
            0.1 * 1.1e-3 * 0.11
        ));
        // a first residual that was infinite (cells solved for the first time) gives no
        // ratio, nor does a NaN
        assert!(close(film_stop(&[f64::INFINITY, 1e-2], rough, tol), 1e-3));
        assert_eq!(film_stop(&[f64::NAN], rough, tol), LOOSE_FILM_MAX);
    }

    /// A far fixed point that wanders (factors' residual ~1, as an Eyring line's at 1 GPa or
    /// the Eyring ball's at 5 m/s) is not polished before POLISH_LATE, and is from it on.
    fn wandering_is_polished_from_late(s: &PolishSchedule, finite: bool) {
        let (tol, inner, max) = (1e-4, 0.1, 80);
        let wandering: Vec<f64> = (0..max).map(|k| 1.0 + 0.5 * (k as f64).sin()).collect();
        let due = |o: usize| s.due(o, max, &wandering[..o], tol, inner, finite);
        assert!(!due(POLISH_LATE - 1) && due(POLISH_LATE), "finite {finite}");
    }

    /// The guard POLISH_RUN: a line whose polishes keep reaching solutions that the fixed point
    /// does not then find settled nor much nearer is polished POLISH_RUN times in a row and then
    /// left to the fixed point for the rest of the run; a failed polish starts the count again,
    /// after POLISH_EVERY outer iterations. The schedule's other conditions: not before
    /// POLISH_FROM, not at the last outer iteration, not while far (the factors' residual above
    /// POLISH_FACTOR_RESIDUAL, the temperature solve's own above POLISH_INNER_RESIDUAL_K), not
    /// while the fixed point is fast.
    #[test]
    fn a_line_polished_without_settling_goes_back_to_the_fixed_point() {
        let (tol, inner, max) = (1e-4, 0.1, 80);
        // a slow fixed point: contraction 0.9 an outer iteration, ~60 more to its stop
        let slow: Vec<f64> = (0..max).map(|k| 0.05 * 0.9f64.powi(k as i32)).collect();
        let due =
            |s: &PolishSchedule, outer: usize| s.due(outer, max, &slow[..outer], tol, inner, false);
        let mut s = PolishSchedule::new();
        // (a history long enough for the pace estimate, so that only POLISH_FROM holds it back)
        assert!((1..POLISH_FROM).all(|outer| !s.due(outer, max, &slow[..10], tol, inner, false)));
        let first = POLISH_FROM;
        for k in 0..POLISH_RUN {
            assert!(due(&s, first + k), "polish {k} of the run");
            s.reached(first + k, 0.01);
        }
        let after = first + POLISH_RUN;
        assert!(
            (after..max).all(|outer| !due(&s, outer)),
            "polished again after {POLISH_RUN} unsettled polishes"
        );

        // a failed polish: the next one POLISH_EVERY outer iterations later, the count anew
        let mut s = PolishSchedule::new();
        s.reached(first, 0.01);
        s.reached(first + 1, 0.01);
        s.failed(first + 2, false);
        let next = first + 2 + POLISH_EVERY;
        assert!((first + 3..next).all(|outer| !due(&s, outer)));
        assert!(due(&s, next));
        for k in 0..POLISH_RUN {
            assert!(due(&s, next + k), "polish {k} after the failure");
            s.reached(next + k, 0.01);
        }
        assert!(!due(&s, next + POLISH_RUN));

        // the other conditions
        let s = PolishSchedule::new();
        assert!(
            !s.due(max, max, &slow, tol, inner, false),
            "the last outer iteration"
        );
        let far: Vec<f64> = slow.iter().map(|r| r * 10.0).collect();
        assert!(
            !s.due(first, max, &far[..first], tol, inner, false),
            "residual {}",
            far[first - 1]
        );
        // a far fixed point that wanders (factors' residual ~1, as an Eyring line's at 1 GPa):
        // not before POLISH_LATE, from it on
        wandering_is_polished_from_late(&s, false);
        // but not one that is far and contracts fast (0.3 an iteration: 7 more to its stop)
        let closing: Vec<f64> = (0..POLISH_LATE)
            .map(|k| 0.5 * 0.3f64.powi(k as i32 + 1 - POLISH_LATE as i32))
            .collect();
        assert!(!s.due(POLISH_LATE, max, &closing, tol, inner, false));
        assert!(!s.due(
            first,
            max,
            &slow[..first],
            tol,
            2.0 * POLISH_INNER_RESIDUAL_K,
            false
        ));
        let fast: Vec<f64> = (0..max).map(|k| 0.05 * 0.3f64.powi(k as i32)).collect();
        assert!(
            !s.due(first, max, &fast[..first], tol, inner, false),
            "a fast fixed point"
        );
        // a fast fixed point is polished again at the next outer iteration after a polish that
        // reached a solution, not after one that failed
        let mut s = PolishSchedule::new();
        s.reached(first, 0.01);
        assert!(s.due(first + 1, max, &fast[..first + 1], tol, inner, false));
        s.failed(first + 1, false);
        let next = first + 1 + POLISH_EVERY;
        assert!(!s.due(next, max, &fast[..first + 1], tol, inner, false));
        // a fast fixed point (contraction 0.3) still short of its stop: polished only from
        // POLISH_LATE on
        let late = |outer: usize| -> Vec<f64> {
            (0..outer)
                .map(|k| 0.05 * 0.3f64.powi(k as i32 + 4 - outer as i32).min(1.0))
                .collect()
        };
        assert!(!s.due(
            POLISH_LATE - 1,
            max,
            &late(POLISH_LATE - 1),
            tol,
            inner,
            false
        ));
        assert!(s.due(POLISH_LATE, max, &late(POLISH_LATE), tol, inner, false));
    }

    /// A polish after whose update the factors' residual is at most POLISH_PROGRESS of the one
    /// it started from made progress and is not counted in the run of POLISH_RUN: a contact
    /// whose polishes each lower the residual tenfold (each to a film extent one cell short,
    /// as the fast ball's) is polished on, line or finite; one whose polishes lower it by
    /// less is given back to the fixed point after POLISH_RUN of them.
    #[test]
    fn polishes_that_make_progress_are_not_counted_in_the_run() {
        // (a stop far below the residuals: every polish of the tenfold run stays above it)
        let (tol, inner, max) = (1e-12, 0.1, 80);
        // wandering slowly (contraction 0.95) at ~0.2 by POLISH_LATE
        let slow: Vec<f64> = (0..max).map(|k| 0.5 * 0.95f64.powi(k as i32)).collect();
        for (gain, polished) in [(0.1, 3 * POLISH_RUN), (0.5, POLISH_RUN)] {
            for finite in [false, true] {
                let mut s = PolishSchedule::new();
                let mut hist = slow[..POLISH_LATE].to_vec();
                let mut count = 0;
                for outer in POLISH_LATE..POLISH_LATE + 3 * POLISH_RUN {
                    if !s.due(outer, max, &hist, tol, inner, finite) {
                        break;
                    }
                    count += 1;
                    let from = *hist.last().unwrap();
                    s.reached(outer, from);
                    // the next update
                    hist.push(gain * from);
                    s.seen(gain * from, tol);
                }
                assert_eq!(count, polished, "gain {gain}, finite {finite}");
            }
        }
        // a failed polish forgets the one before it
        let mut s = PolishSchedule::new();
        s.reached(POLISH_LATE, 0.2);
        s.failed(POLISH_LATE + 1, false);
        s.seen(1e-3, 1e-4);
        assert_eq!(s.reached_in_a_row, 0);
        // a residual that fell below the stop is no progress a polish can make
        let mut s = PolishSchedule::new();
        s.reached(POLISH_LATE, 0.2);
        s.seen(5e-5, 1e-4);
        assert_eq!(s.reached_in_a_row, 1);
    }

    /// A finite contact is polished only from POLISH_LATE on, and only when slow there (its
    /// polish costs a film solve of every row a GMRES iteration), or again at the next outer
    /// iteration after a polish that reached a solution, or POLISH_EVERY_FINITE outer
    /// iterations after a failed one and twice as long after each further failure; a line is
    /// polished earlier.
    #[test]
    fn a_finite_contact_is_polished_only_late_and_slow() {
        let (tol, inner, max) = (1e-4, 0.1, 80);
        // slow (contraction 0.9, ~60 more outer iterations) and near (residual <= 0.05)
        let slow: Vec<f64> = (0..max).map(|k| 0.05 * 0.9f64.powi(k as i32)).collect();
        let s = PolishSchedule::new();
        let first = POLISH_FROM;
        assert!(
            s.due(first, max, &slow[..first], tol, inner, false),
            "a line"
        );
        assert!(
            (first..POLISH_LATE).all(|o| !s.due(o, max, &slow[..o], tol, inner, true)),
            "a finite contact before POLISH_LATE"
        );
        assert!(s.due(POLISH_LATE, max, &slow[..POLISH_LATE], tol, inner, true));
        // late, but closing fast (contraction 0.3: 2 more to its stop): a line, not a finite
        // contact
        let fast: Vec<f64> = (0..POLISH_LATE)
            .map(|k| 0.05 * 0.3f64.powi(k as i32 + 4 - POLISH_LATE as i32).min(1.0))
            .collect();
        assert!(s.due(POLISH_LATE, max, &fast, tol, inner, false));
        assert!(!s.due(POLISH_LATE, max, &fast, tol, inner, true));
        // far and wandering (an Eyring ball at 5 m/s): from POLISH_LATE on
        wandering_is_polished_from_late(&s, true);
        // again after a polish that reached a solution, however fast
        let mut s = PolishSchedule::new();
        s.reached(POLISH_LATE, 0.01);
        let mut closing = fast.clone();
        closing.push(fast[POLISH_LATE - 1] * 0.3);
        assert!(s.due(POLISH_LATE + 1, max, &closing, tol, inner, true));
        // after a failed one, POLISH_EVERY_FINITE outer iterations later, then twice as long
        // after each further failure (a fixed point that keeps wandering)
        let slow = vec![0.5; max];
        let mut failed_at = POLISH_LATE + 1;
        for wait in [1, 2, 4, 8].map(|k| k * POLISH_EVERY_FINITE) {
            s.failed(failed_at, true);
            let next = failed_at + wait;
            assert!(
                (failed_at + 1..next.min(max)).all(|o| !s.due(
                    o,
                    max,
                    &slow[..o],
                    tol,
                    inner,
                    true
                )),
                "polished again before {next}"
            );
            if next >= max {
                assert!((failed_at + 1..max).all(|o| !s.due(o, max, &slow[..o], tol, inner, true)));
                break;
            }
            assert!(
                s.due(next, max, &slow[..next], tol, inner, true),
                "at {next}"
            );
            failed_at = next;
        }
    }
}
