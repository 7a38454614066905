//! Newton's method on the coupled thermal problem of a contact, a line or a 2D one (a ball, a
//! finite roller), steady or one time step of a transient run (the Reynolds rows with their
//! squeeze term, the film rows with their time derivatives): the pressure, h0, the film
//! temperature across z and both surface temperatures solved as one system, as
//! Habchi et al. (Tribol. Lett. 30 (2008) 41) solve thermal EHL, here Jacobian-free
//! (Knoll & Keyes, J. Comput. Phys. 193 (2004) 357).
//!
//! The fixed point of [`super::thermal`] alternates a temperature update with a Reynolds
//! solve. Where pressure and temperature answer each other strongly (a sliding line at high
//! thermal loading: the thick inlet's oil 50 K above the inlet temperature, the viscosity
//! wedge it forms moving the pressure that heats it) that alternation stalls or diverges
//! locally. The fixed point hands its last iterate to [`polish`], which solves
//!
//! * the Reynolds rows, min(P, c F(P, H0; factors(T))) and the load balance
//!   ([`System::merit_vector`]), the generalized Reynolds factors taken from the temperatures;
//! * the film rows T - S(T) and the surface rows T_b - T0 - R_b q_b
//!   (`ThermalContact::coupled_residual`, in units of [`THETA`])
//!
//! by Newton: each step solves J u = -R by GMRES, J v by a forward difference of the whole
//! residual (the Reynolds rows' active set frozen at the step's state), right-preconditioned
//! by the Reynolds solve's own preconditioner on (P, H0) and the identity on the temperature
//! rows (their residual T - S(T) is already the film's solve applied); a backtracking search
//! on ||R||_2 globalises it. The fixed point's stop then judges the result: the polish only
//! supplies a state.

use super::system::{Linear, Preconditioner, State, System, ThermalFactors};
use super::thermal::fields_si;
use super::{StageEnd, Stats, Termination};
use crate::linalg::gmres::{gmres, norm, GmresWork};
use crate::thermal::contact::CoupledFrame;
use crate::thermal::ThermalContact;

/// The temperature unknowns and rows are in units of this (K): the Reynolds rows are relative
/// pressures of order 1, so a film temperature's residual of 0.01 K weighs as a relative
/// residual of 1e-3 in the search.
const THETA: f64 = 10.0;

/// Most Newton steps of a polish.
const MAX_STEPS: usize = 12;

/// GMRES restart length and most iterations per Newton step.
const GMRES_RESTART: usize = 300;
const GMRES_MAX_ITER: usize = 300;

/// Most GMRES iterations per Newton step of a 2D contact (a ball, a finite roller), whose
/// iterations each cost a film solve of every row (~0.1 s at 256 x 256): a step that needs
/// more is far from Newton's regime, and the polish gives up (the fixed point goes on). The
/// 2D polishes that reached a solution took 10-17 a step on average on the robustness scan's
/// Eyring ball (49^2 to 97^2: 29 to 50 in 3 steps); the thesis pit's start, polished early in
/// a trial, 161-215 a step on average for 204 s (docs/thermal.md, "The same for balls and
/// finite rollers").
const GMRES_MAX_ITER_2D: usize = 100;

/// The restart is shortened so that GMRES's Krylov basis and preconditioned directions (two
/// vectors an iteration) hold about this many values (3.2e7: 256 MB; a little more at the
/// floor of [`GMRES_MIN_RESTART`], reached above ~5e5 unknowns): a finite contact of
/// 256 x 256 cells has 2e5 coupled unknowns in its pressure and surfaces and up to 3.3e5 more
/// at the film's interior points (7 across), and 300 iterations' vectors would take 1-2.5 GB.
/// Never below [`GMRES_MIN_RESTART`].
const GMRES_MAX_VALUES: usize = 32_000_000;
const GMRES_MIN_RESTART: usize = 30;

/// The GMRES restart for `unknowns` coupled unknowns (see [`GMRES_MAX_VALUES`]).
fn gmres_restart(unknowns: usize) -> usize {
    (GMRES_MAX_VALUES / (2 * unknowns.max(1))).clamp(GMRES_MIN_RESTART, GMRES_RESTART)
}

/// A Newton step whose linear solve ends above this relative residual ends the polish: its
/// direction is no Newton direction (the fixed point goes on instead).
const GMRES_USEFUL: f64 = 0.5;

/// and so do [`SLOW_STEPS`] steps in a row that each left more than [`SLOW_STEP`] of the
/// residual before them: Newton near a regular solution converges faster
const SLOW_STEP: f64 = 0.5;
const SLOW_STEPS: usize = 3;

/// Forward-difference step of a Jacobian product, relative to the state's rms size over the
/// direction's (Knoll & Keyes 2004, eq. 11 with b ~ sqrt(machine epsilon)).
const FD_STEP: f64 = 1e-7;

/// How a polish went.
pub(super) struct Polished {
    /// Newton steps taken
    pub steps: usize,
    /// the Reynolds rows at the end, as a Reynolds solve reports them
    pub end: StageEnd,
    /// the Reynolds factors of the final temperatures (in `sys.thermal` too)
    pub factors: ThermalFactors,
}

/// The coupled residual's work: the frozen frame, the SI fields, the factors.
struct Coupled {
    frame: CoupledFrame,
    ph: f64,
    hs: f64,
    p_si: Vec<f64>,
    h_si: Vec<f64>,
    flow: Vec<f64>,
    couette: Vec<f64>,
}

impl Coupled {
    /// Evaluates `st` (its P and H0 set) with the factors of the scaled temperature unknowns
    /// `xt`, and the temperature rows into `rt` (scaled by 1 / THETA). The Reynolds rows are
    /// the caller's (from `st.f`).
    fn eval(
        &mut self,
        sys: &mut System,
        contact: &mut ThermalContact,
        st: &mut State,
        xt: &[f64],
        rt: &mut [f64],
    ) -> crate::Result<()> {
        sys.eval(st);
        fields_si(sys, st, self.ph, self.hs, &mut self.p_si, &mut self.h_si);
        let tk: Vec<f64> = xt.iter().map(|v| v * THETA).collect();
        contact.coupled_residual(
            &self.frame,
            &self.p_si,
            &self.h_si,
            &sys.active,
            &tk,
            rt,
            &mut self.flow,
            &mut self.couette,
        )?;
        rt.iter_mut().for_each(|v| *v /= THETA);
        sys.thermal = Some(ThermalFactors {
            flow: self.flow.clone(),
            couette: self.couette.clone(),
        });
        sys.eval_film(st);
        Ok(())
    }
}

/// The Reynolds rows of the evaluated `st` with the scaling `c` and the frozen active set
/// `set` (P on it, c F off it) and the load row, into `r` (n + 1).
fn frozen_rows(sys: &System, st: &State, c: &[f64], set: &[bool], r: &mut [f64]) {
    let n = sys.n();
    for k in 0..n {
        r[k] = if !sys.active[k] {
            0.0
        } else if set[k] {
            st.p[k]
        } else {
            c[k] * st.f[k]
        };
    }
    r[n] = sys.load_scale() * (sys.carried(&st.p) - sys.load);
}

fn rms(v: &[f64]) -> f64 {
    norm(v) / (v.len().max(1) as f64).sqrt()
}

/// Solves the coupled problem from the Reynolds state `st` (evaluated) and the contact's
/// temperatures of its last update, to the Reynolds tolerance `tol` and temperature residuals
/// below `tol_k` (K). On success `st`, `sys.thermal` and the contact's temperatures hold the
/// solution; on failure the contact is untouched and the caller restores `st` and
/// `sys.thermal`. Err says why it failed.
#[allow(clippy::too_many_arguments)]
pub(super) fn polish(
    sys: &mut System,
    st: &mut State,
    contact: &mut ThermalContact,
    ph: f64,
    hs: f64,
    tol: f64,
    tol_k: f64,
    stats: &mut Stats,
) -> Result<Polished, String> {
    let frame = contact
        .coupled_frame()
        .ok_or("not a contact with a solved film")?;
    let n = sys.n();
    let m = contact.coupled_len(&frame);
    let big = n + 1 + m;
    let max_iter = if contact.grid().ny > 1 {
        GMRES_MAX_ITER_2D
    } else {
        GMRES_MAX_ITER
    };
    let mut cp = Coupled {
        frame,
        ph,
        hs,
        p_si: vec![0.0; n],
        h_si: vec![0.0; n],
        flow: vec![1.0; n],
        couette: vec![1.0; n],
    };
    let mut x = vec![0.0; big];
    x[..n].copy_from_slice(&st.p);
    x[n] = st.h0;
    contact.coupled_unknowns(&cp.frame, &mut x[n + 1..]);
    x[n + 1..].iter_mut().for_each(|v| *v /= THETA);

    let (mut c, mut share, mut set) = (vec![0.0; n], vec![0.0; n], vec![false; n]);
    let mut r = vec![0.0; big];
    let mut trial = st.clone();
    let mut rt = vec![0.0; big];
    let mut lin = Linear::new(n);
    let mut work = GmresWork::default();
    let mut e_h0 = vec![0.0; n + 1];
    e_h0[n] = 1.0;
    let mut bcol = vec![0.0; n];
    let mut u = vec![0.0; big];
    let mut prev_merit: Option<f64> = None;
    let mut slow = 0;
    let err = |e: crate::Error| e.to_string();

    // the state, its scaling and its residual
    cp.eval(sys, contact, st, &x[n + 1..], &mut r[n + 1..])
        .map_err(err)?;
    for step in 0..=MAX_STEPS {
        // a cancelled run stops here; the driver then stops at its next check
        if crate::run::cancel::requested() {
            return Err("cancelled".into());
        }
        sys.scaling(st, &mut c, Some(&mut share));
        sys.merit_vector(st, &c, &mut r[..n + 1], &mut set);
        let res = sys.relative_residual(st, &c);
        let lerr = (sys.carried(&st.p) - sys.load) / sys.load;
        let rk = r[n + 1..].iter().fold(0.0f64, |a, v| a.max(v.abs())) * THETA;
        if !(res.is_finite() && rk.is_finite()) {
            return Err("a non-finite residual".into());
        }
        if res <= tol && lerr.abs() <= tol && rk <= tol_k {
            let factors = sys.thermal.clone().expect("the factors were set");
            contact.set_coupled(
                &cp.frame,
                &x[n + 1..].iter().map(|v| v * THETA).collect::<Vec<_>>(),
            );
            return Ok(Polished {
                steps: step,
                end: StageEnd {
                    converged: true,
                    reason: Termination::Converged,
                    residual: res,
                    load_error: lerr,
                },
                factors,
            });
        }
        if step == MAX_STEPS {
            return Err(format!(
                "{MAX_STEPS} Newton steps: Reynolds residual {res:.2e}, load {lerr:.1e}, temperature {rk:.2e} K"
            ));
        }
        let merit = norm(&r);
        // Newton near its solution more than halves the residual each step
        slow = match prev_merit {
            Some(pm) if merit > SLOW_STEP * pm => slow + 1,
            _ => 0,
        };
        if slow >= SLOW_STEPS {
            return Err(format!(
                "{slow} steps in a row reduced the residual by less than half (step {}: {merit:.2e})",
                step
            ));
        }
        // Eisenstat & Walker (1996) choice 2, within [1e-3, 0.1]
        let eta = prev_merit.map_or(0.1, |pm| (0.9 * (merit / pm).powi(2)).clamp(1e-3, 0.1));
        prev_merit = Some(merit);
        // the preconditioner of the Reynolds rows at this state
        sys.directional(st, &e_h0, &mut lin, &mut bcol);
        for k in 0..n {
            bcol[k] = if set[k] { 0.0 } else { c[k] * bcol[k] };
        }
        let pc = Preconditioner::new(sys, st, &c, &set, &share, &bcol, 0.0, None)
            .ok_or("a singular Reynolds preconditioner")?;
        let base_factors = sys.thermal.clone();
        let rhs: Vec<f64> = r.iter().map(|v| -v).collect();
        let xs = rms(&x);
        let mut failed: Option<String> = None;
        let out = {
            let (c, set, r, x) = (&c, &set, &r, &x);
            let mut matvec = |v: &[f64], o: &mut [f64]| {
                let vs = rms(v);
                if vs == 0.0 || failed.is_some() || crate::run::cancel::requested() {
                    o.iter_mut().for_each(|a| *a = 0.0);
                    return;
                }
                let e = FD_STEP * xs.max(1.0) / vs;
                for k in 0..n {
                    trial.p[k] = x[k] + e * v[k];
                }
                trial.h0 = x[n] + e * v[n];
                let xt: Vec<f64> = (n + 1..big).map(|k| x[k] + e * v[k]).collect();
                if let Err(er) = cp.eval(sys, contact, &mut trial, &xt, &mut o[n + 1..]) {
                    failed = Some(er.to_string());
                    o.iter_mut().for_each(|a| *a = 0.0);
                    return;
                }
                frozen_rows(sys, &trial, c, set, &mut o[..n + 1]);
                for k in 0..big {
                    o[k] = (o[k] - r[k]) / e;
                }
            };
            let mut precond = |v: &[f64], o: &mut [f64]| {
                pc.apply(&v[..n + 1], &mut o[..n + 1]);
                o[n + 1..].copy_from_slice(&v[n + 1..]);
            };
            gmres(
                &mut work,
                &rhs,
                &mut u,
                gmres_restart(big),
                max_iter,
                eta,
                &mut matvec,
                &mut precond,
            )
        };
        sys.thermal = base_factors;
        stats.gmres += out.iterations;
        if let Some(f) = failed {
            return Err(format!("a Jacobian product: {f}"));
        }
        if !u.iter().all(|v| v.is_finite()) {
            return Err("a non-finite Newton direction".into());
        }
        if out.relative_residual > GMRES_USEFUL {
            return Err(format!(
                "the linear solve of step {} reached only {:.1e} in {} iterations",
                step + 1,
                out.relative_residual,
                out.iterations
            ));
        }
        // backtracking on ||R|| (the same scaling)
        let mut lam = 1.0;
        let mut xn = vec![0.0; big];
        loop {
            for k in 0..big {
                xn[k] = x[k] + lam * u[k];
            }
            for v in &mut xn[..n] {
                *v = v.max(0.0);
            }
            trial.p.copy_from_slice(&xn[..n]);
            trial.h0 = xn[n];
            let ok = cp
                .eval(sys, contact, &mut trial, &xn[n + 1..], &mut rt[n + 1..])
                .is_ok()
                && trial.is_finite()
                && (0..n).all(|k| trial.p[k] <= 0.0 || trial.h[k] > 0.0);
            if ok {
                let mut set_t = vec![false; n];
                sys.merit_vector(&trial, &c, &mut rt[..n + 1], &mut set_t);
                let mt = norm(&rt);
                if mt.is_finite() && mt <= (1.0 - 1e-4 * lam) * merit {
                    break;
                }
            }
            lam *= 0.5;
            if lam < 1.0 / 64.0 {
                return Err(format!(
                    "no descent along the Newton direction (step {}, GMRES {} iterations to {:.1e})",
                    step + 1,
                    out.iterations,
                    out.relative_residual
                ));
            }
        }
        stats.newton += 1;
        x.copy_from_slice(&xn);
        std::mem::swap(st, &mut trial);
        r[n + 1..].copy_from_slice(&rt[n + 1..]);
        // `st` is evaluated with its own factors (the search's last evaluation)
    }
    unreachable!("the loop returns")
}
