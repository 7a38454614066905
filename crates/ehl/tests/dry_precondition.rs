//! The preconditioned conjugate gradient solves the same problem as the plain one, in fewer
//! iterations: the preconditioner changes the path, never the answer.

mod dry_support;

use ehl::dry::{solve, DryParams, DryProblem};
use ehl::grid::Grid;

fn ball(n: usize, precondition: bool, coarse_start: bool) -> ehl::dry::DryResult {
    let (r, e_red, f) = (0.01, 2.2e11, 100.0);
    let a = ehl::units::hertz_point(f, r, e_red).a;
    let grid = Grid::new(n, n, -1.5 * a, 1.5 * a, -1.5 * a, 1.5 * a);
    let gap = move |x: f64, y: f64| (x * x + y * y) / (2.0 * r);
    let op = dry_support::half_space(e_red);
    solve(
        &DryProblem {
            grid,
            gap: &gap,
            operator: &op,
            load: f,
        },
        &DryParams {
            precondition,
            coarse_start,
            ..DryParams::default()
        },
    )
}

#[test]
fn preconditioning_keeps_the_answer_and_cuts_iterations() {
    // Both runs converge to 1e-10; the pressures then agree to ~1e-9 of p0 (the residual
    // tolerance times the conditioning), so 1e-7 of p0 is a safe, still meaningful bound.
    let plain = ball(128, false, false);
    let pre = ball(128, true, false);
    assert!(plain.converged && pre.converged);
    let p0 = plain.max_pressure();
    let diff = plain
        .pressure
        .iter()
        .zip(&pre.pressure)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(diff < 1e-7 * p0, "max difference {diff:e} of p0 {p0:e}");
    // measured 25 vs ~130: demand at least a factor 2
    assert!(
        2 * pre.iterations < plain.iterations,
        "preconditioned {} vs plain {}",
        pre.iterations,
        plain.iterations
    );
}
