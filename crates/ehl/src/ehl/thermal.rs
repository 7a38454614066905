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
//!    ([`super::system::ThermalFactors`]), (relaxed against the previous ones when `relaxation` < 1);
//! 3. Newton-Krylov solves the Reynolds equation with the load balance again, warm-started
//!    from the last solution, the factors frozen.
//!
//! The fixed point stops when the film temperature is estimated within
//! [`ThermalParams::tolerance_k`] of the fixed point (from the last change between outer
//! iterations and the contraction of the last two, where the film is at most 5 times its
//! thinnest), the film within [`ThermalParams::film_tolerance`] of its thinnest value, and the
//! last Newton solve converged. The factors are relaxed (0.5, halved when the change grows,
//! doubled back after three contractions). The
//! first iteration starts from the isothermal solution (all factors 1). A relaxed fixed point
//! is the older of the two couplings the literature uses (Yang & Wen 1990; Kim & Sadeghi 1992);
//! the single Newton system of Habchi et al. (Tribol. Lett. 30 (2008) 41) converges faster and
//! is left for later.

use super::system::{Physics, State, System, ThermalFactors};
use super::{finish, line_band, solve_from, EhlParams, EhlProblem, EhlResult, Stats, Termination};
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
    /// the same rho / (1 - rho)): the thick inlet, left out of the temperature's change, acts
    /// through the film
    pub film_tolerance: f64,
    /// most outer iterations
    pub max_outer: usize,
    /// under-relaxation of the Reynolds factors from the second outer iteration on (1: none);
    /// halved, down to `min_relaxation`, whenever the film-temperature change grows
    pub relaxation: f64,
    /// the smallest relaxation the halving reaches
    pub min_relaxation: f64,
    /// a transient run: most (temperature, Reynolds) passes per time step
    pub max_step_passes: usize,
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
        }
    }
}

/// The largest thermal loading L = eta0 beta u_e^2 / k_f at which the steady thermal solver is
/// known to converge in pure rolling (docs/thermal.md). Above it, on the thesis Table 3.7 line
/// (Barus oil, beta = 0.03 1/K, U >= 1.6e-10, L >= 2.6; the Roelands-Carreau example at
/// U = 2.2e-10, L = 6.8), the film temperature in the thick inlet (8-10 times the thinnest
/// film, a reverse flow) zigzags across the 7 collocation points or runs away. Runs with
/// sliding can converge well above it (the groove line at L = 5.3 and SRR 0.3), and coarser
/// grids too (measured on 256 cells; on 128 the groove line's start converged at L = 28). A
/// run, steady or transient, that fails above it says so in its reason
/// ([`crate::run::thermal::loading_hint`]), and `ehl check` notes it.
pub const CONVERGED_THERMAL_LOADING: f64 = 2.5;

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
    rayon::scope(|_| run(problem, params, thermal, start, contact, observer))
}

fn run(
    problem: &EhlProblem,
    params: &EhlParams,
    thermal: &ThermalParams,
    start: &EhlResult,
    contact: &mut ThermalContact,
    observer: &mut (dyn FnMut(usize, f64) + Send),
) -> ThermalResult {
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
            start.pressure[k] / ph
        } else {
            0.0
        };
    }
    st.h0 = start.h0 / hs;
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
    let mut failure = None;
    let mut w = thermal.relaxation;
    let mut shrinking = 0;
    // the film of the last outer iteration (m; infinite where no material)
    let mut h_prev: Vec<f64> = vec![f64::NAN; n];
    let (mut settled, mut film_change) = (false, f64::INFINITY);
    while outer < thermal.max_outer {
        if crate::run::cancel::requested() {
            failure = Some(Termination::Cancelled);
            break;
        }
        outer += 1;
        fields_si(&sys, &st, ph, hs, &mut p_si, &mut h_si);
        change = match contact.update(
            &p_si,
            &h_si,
            &sys.active,
            Some((&factors.flow, &factors.couette)),
        ) {
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
        let rho = if prev.is_finite() && change < prev {
            change / prev
        } else {
            0.99
        };
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
        let estimate = change * rho / (1.0 - rho);
        prev = change;
        film_change = self::film_change(&h_si, &h_prev);
        h_prev.copy_from_slice(&h_si);
        settled = estimate <= thermal.tolerance_k
            && contact.inner_residual() <= thermal.tolerance_k
            && film_change * rho / (1.0 - rho) <= thermal.film_tolerance;
        if settled && end.as_ref().is_some_and(|e: &super::StageEnd| e.converged) {
            break;
        }
        let w = if outer == 1 { 1.0 } else { w };
        relax_factors(contact, &p_si, &sys.active, &mut factors, &mut fresh, w);
        sys.thermal = Some(factors.clone());
        sys.eval(&mut st);
        let e = solve_from(&mut sys, &mut st, params.tolerance, params, &mut stats);
        let ok = e.converged;
        end = Some(e);
        if !ok {
            break;
        }
    }
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
    } else if end.converged && !settled {
        end.converged = false;
        end.reason = Termination::ThermalNotSettled {
            outer,
            change_k: change,
            film_change,
            residual_k: contact.inner_residual(),
        };
    }
    let mut ehl = finish(problem, &mut sys, st, end, &stats);
    contact.fill_laws(
        &ehl.pressure,
        &sys.active,
        &mut ehl.viscosity,
        &mut ehl.density,
    );
    ThermalResult {
        ehl,
        outer_iterations: outer,
        last_change_k: change,
        newton_steps,
    }
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
    for k in 0..factors.flow.len() {
        factors.flow[k] += w * (fresh.flow[k] - factors.flow[k]);
        factors.couette[k] += w * (fresh.couette[k] - factors.couette[k]);
    }
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
