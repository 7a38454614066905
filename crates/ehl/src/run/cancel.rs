//! Stopping a solve from outside: the hook behind the Python package's Ctrl-C
//! (KeyboardInterrupt). The CLI does not use it (a signal ends its process).
//!
//! [`solve`] runs [`super::solve`] on a rayon pool of its own whose threads carry a
//! [`CancelToken`]; the solver loops ask [`requested`] once per iteration (the dry solver's
//! conjugate-gradient iteration, the EHL Newton step, the transient time step) and stop when the
//! token is cancelled: the dry level ends "cancelled", Newton ends with
//! [`crate::ehl::Termination::Cancelled`] (every later stage stops at its first check), the time
//! loop stops before its next step. [`solve`] then throws the half-solved result away and
//! returns [`Error::Cancelled`]. The latency is one iteration of the innermost loop that checks:
//! a Newton step (about 0.15 s on 256 x 512 cells), a time step, or a conjugate-gradient
//! iteration (milliseconds).
//!
//! Why a token on the pool's threads rather than an argument: the solver loops run inside
//! rayon on worker threads (see `crate::ehl::solve_steady_observed`), several calls deep below
//! [`super::solve`]; a thread-local set on every thread of the solve's own pool reaches them
//! without a new parameter on every solver function, and outside [`solve`] [`requested`] is
//! always false, so the other callers (the CLI, the tests, the sweep) are unchanged. A pool of
//! its own per solve also keeps two solves on two caller threads (Python threads) from sharing
//! one pool's workers. The pool has as many threads as the global pool
//! (`RAYON_NUM_THREADS` or the number of CPUs), so the arithmetic is the same as
//! [`super::solve`]'s: the results are bit-identical (tested).

use super::{Progress, Solution};
use crate::case::Case;
use crate::{Error, Result};
use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A flag that stops the [`solve`] it was given to. Cheap to clone (clones share the flag);
/// [`CancelToken::cancel`] may be called from any thread.
#[derive(Debug, Clone, Default)]
pub struct CancelToken(Arc<AtomicBool>);

impl CancelToken {
    /// A token that is not cancelled.
    pub fn new() -> Self {
        Self::default()
    }

    /// Asks the solve to stop (it stops within one solver iteration).
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether [`CancelToken::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

thread_local! {
    /// The token of the solve this thread works for (set on the threads of [`solve`]'s pool).
    static CURRENT: RefCell<Option<CancelToken>> = const { RefCell::new(None) };
}

/// True when this thread works for a [`solve`] whose token is cancelled; always false outside
/// [`solve`]. Solver loops call it once per iteration (a thread-local read and an atomic load).
pub fn requested() -> bool {
    CURRENT.with(|c| c.borrow().as_ref().is_some_and(CancelToken::is_cancelled))
}

/// [`super::solve`], stoppable through `token`: [`Error::Cancelled`] when the token was
/// cancelled before or during the solve (the partial result is dropped), else exactly what
/// [`super::solve`] returns.
pub fn solve(case: &Case, progress: &dyn Progress, token: &CancelToken) -> Result<Solution> {
    if token.is_cancelled() {
        return Err(Error::Cancelled);
    }
    let carried = token.clone();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(rayon::current_num_threads())
        .thread_name(|i| format!("ehl-solve-{i}"))
        .start_handler(move |_| CURRENT.with(|c| *c.borrow_mut() = Some(carried.clone())))
        .build()
        .map_err(|e| Error::Solver(format!("cannot start the solver's threads: {e}")))?;
    let out = pool.install(|| super::solve(case, progress));
    if token.is_cancelled() {
        Err(Error::Cancelled)
    } else {
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::Silent;
    use std::time::{Duration, Instant};

    fn example(name: &str, overrides: &[&str]) -> Case {
        let path = format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"));
        let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
        crate::case::load_file(std::path::Path::new(&path), &o).unwrap()
    }

    #[test]
    fn a_token_never_cancelled_changes_nothing() {
        assert!(!requested(), "false outside a solve");
        for case in [
            example("ehl_ball_on_glass.toml", &["grid.nx=48", "grid.ny=48"]),
            example("dry_roller_mirror1_psi.toml", &["grid.nx=64", "grid.ny=64"]),
        ] {
            let a = crate::run::solve(&case, &Silent).unwrap();
            let b = solve(&case, &Silent, &CancelToken::new()).unwrap();
            assert_eq!(a.fields.pressure, b.fields.pressure, "bit-identical");
            assert_eq!(a.fields.film, b.fields.film);
            assert_eq!(a.summary.iterations, b.summary.iterations);
        }
    }

    #[test]
    fn a_cancelled_token_stops_the_solve_promptly() {
        // cancelled before: no work at all
        let token = CancelToken::new();
        token.cancel();
        let case = example("ehl_ball_on_glass.toml", &[]);
        assert!(matches!(
            solve(&case, &Silent, &token),
            Err(Error::Cancelled)
        ));
        // cancelled during a steady EHL solve (1.6 s) and during a transient one (150 steps,
        // 1.5 s): each returns within a fraction of a second of the cancel
        for case in [
            example("ehl_thesis_ch2_roller.toml", &[]),
            example(
                "ehl_thesis_ch3_single_pit.toml",
                &["grid.nx=64", "grid.ny=64", "output.animation=false"],
            ),
        ] {
            let token = CancelToken::new();
            let (out, late) = std::thread::scope(|s| {
                let t = token.clone();
                let case = &case;
                let h = s.spawn(move || {
                    let out = solve(&case, &Silent, &t);
                    (out, Instant::now())
                });
                std::thread::sleep(Duration::from_millis(300));
                let at = Instant::now();
                token.cancel();
                let (out, done) = h.join().unwrap();
                (out, done.saturating_duration_since(at))
            });
            assert!(
                matches!(out, Err(Error::Cancelled)),
                "{:?}",
                out.map(|_| ())
            );
            // measured alone: well under 0.1 s; the bound leaves room for a CI machine whose
            // two cores run the other tests at the same time
            eprintln!("{}: stopped {late:?} after the cancel", case.title);
            assert!(
                late < Duration::from_millis(1500),
                "stopped {late:?} after the cancel"
            );
        }
    }
}
