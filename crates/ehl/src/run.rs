//! From a validated case to a solution: builds the grid, the gap and the operators, dispatches to
//! the dry or EHL solver and fills the summary. No file I/O here.

use crate::case::Case;
use crate::solution::Solution;
use crate::{Error, Result};

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

/// Solves `case`. A solver that does not converge still returns a solution with
/// `summary.converged == false`; errors are reserved for cases that cannot be solved at all.
pub fn solve(case: &Case, progress: &dyn Progress) -> Result<Solution> {
    let _ = (case, progress);
    Err(Error::Solver("not built yet".into()))
}

/// The text `ehl check` prints: derived quantities, dimensionless groups, classical film
/// estimates, grid resolution.
pub fn check_text(case: &Case) -> String {
    crate::reference::check_report(case).to_string()
}
