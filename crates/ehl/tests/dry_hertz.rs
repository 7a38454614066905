//! Dry solver against Hertz: ball on flat (point contact) and the infinite line contact.
mod dry_support;

use ehl::dry::{solve, DryParams, DryProblem};
use ehl::elastic::dense::DenseDeflection;
use ehl::elastic::Deflection;
use ehl::grid::Grid;
use ehl::units;

const E_RED: f64 = 2.2e11;

/// Ball on flat, square grid centred on the contact.
fn ball(
    n: usize,
    half_domain_in_a: f64,
    params: &DryParams,
) -> (Grid, ehl::dry::DryResult, units::HertzPoint) {
    let (r, f) = (0.01, 100.0);
    let hz = units::hertz_point(f, r, E_RED);
    let l = half_domain_in_a * hz.a;
    let grid = Grid::new(n, n, -l, l, -l, l);
    let gap = move |x: f64, y: f64| (x * x + y * y) / (2.0 * r);
    let op = dry_support::half_space(E_RED);
    let res = solve(
        &DryProblem {
            grid,
            gap: &gap,
            operator: &op,
            load: f,
        },
        params,
    );
    (grid, res, hz)
}

#[test]
fn ball_on_flat_matches_hertz() {
    // 160^2 cells on [-1.5a, 1.5a]^2: a spans 53 cells. The brief asks for 1 %. The contact
    // radius read as sqrt(area / pi) of whole cells could err by up to a cell (dx/a ~ 2 %),
    // but the cells the edge cuts fall in and out of contact about evenly, so the error is far
    // smaller (measured: p0 -0.007 %, a +0.044 %, approach -0.001 %).
    let params = DryParams::default();
    let (grid, res, hz) = ball(160, 1.5, &params);
    assert!(res.converged, "{}", res.termination);
    let p0 = res.max_pressure();
    let a = (res.contact_area / std::f64::consts::PI).sqrt();
    let e_p0 = p0 / hz.p0 - 1.0;
    let e_a = a / hz.a - 1.0;
    let e_d = res.approach / hz.approach - 1.0;
    println!(
        "ball 160^2: p0 {:.5e} (Hertz {:.5e}, {:+.3}%), a {:.5e} ({:+.3}%), approach {:.5e} ({:+.3}%), iterations {} (total {}, applications {}), levels {:?}",
        p0, hz.p0, 100.0 * e_p0, a, 100.0 * e_a, res.approach, 100.0 * e_d,
        res.iterations, res.total_iterations, res.applications, res.levels
    );
    assert!(e_p0.abs() < 0.01);
    assert!(e_a.abs() < 0.01);
    assert!(e_d.abs() < 0.01);
    // load balance: the solver re-imposes it every iteration
    let w: f64 = res.pressure.iter().sum::<f64>() * grid.cell_area();
    assert!((w / 100.0 - 1.0).abs() < 1e-8);
    assert!((res.load / 100.0 - 1.0).abs() < 1e-8);
}

#[test]
fn ball_on_flat_is_symmetric() {
    // Square grid centred on the ball: the discrete problem is invariant under x -> -x, y -> -y
    // and x <-> y, and its solution is unique, so the converged pressure must be too. The
    // iteration is symmetric up to FFT rounding; at a residual of 1e-10 the distance to the
    // exact discrete solution is of the order of 1e-10 times the conditioning (~sqrt(n)), so
    // 1e-8 of p0 is a tight but safe bound.
    let params = DryParams::default();
    let (grid, res, _) = ball(96, 1.4, &params);
    assert!(res.converged, "{}", res.termination);
    let n = grid.nx;
    let p = &res.pressure;
    let p0 = res.max_pressure();
    let mut worst = 0.0f64;
    for j in 0..n {
        for i in 0..n {
            let v = p[j * n + i];
            for w in [p[j * n + (n - 1 - i)], p[(n - 1 - j) * n + i], p[i * n + j]] {
                worst = worst.max((v - w).abs());
            }
        }
    }
    println!(
        "ball 96^2 symmetry: max |p - p_mirror| / p0 = {:.2e}",
        worst / p0
    );
    assert!(worst < 1e-8 * p0, "asymmetry {:.3e} of p0", worst / p0);
}

/// Half-width of a symmetric contact from its pressure profile along x: the outermost contact
/// cells' p^2 extrapolated linearly to zero (p^2 falls linearly at a Hertz-type edge, where
/// p ~ sqrt(b - |x|)), averaged over both edges. Resolves the edge to a fraction of a cell.
pub fn half_width(xs: &[f64], p: &[f64]) -> f64 {
    let n = p.len();
    let first = p.iter().position(|&v| v > 0.0).unwrap();
    let last = n - 1 - p.iter().rev().position(|&v| v > 0.0).unwrap();
    let dx = xs[1] - xs[0];
    let edge = |k: usize, inner: usize| {
        let (a, b) = (p[k] * p[k], p[inner] * p[inner]);
        dx * a / (b - a)
    };
    let right = xs[last] + edge(last, last - 1);
    let left = xs[first] - edge(first, first + 1);
    0.5 * (right - left)
}

#[test]
fn line_contact_matches_hertz() {
    // Infinite line contact, ny == 1 (lead's convention: y in [-0.5, 0.5], dy = 1 m, so the
    // load is per unit length). b spans 50, 100 and 200 cells. Tolerance 0.5 % (the brief) on
    // the maximum pressure and on the half-width: piecewise-constant pressure errs by O(dx/b)
    // only in the edge cells, and the edge estimate above is sub-cell.
    let (r, w) = (0.01, 2.0e5);
    let b = units::hertz_line_half_width(w, r, E_RED);
    let ph = units::hertz_line_pressure(w, r, E_RED);
    let gap = move |x: f64, _y: f64| x * x / (2.0 * r);
    let op = dry_support::line(E_RED);
    let mut errs = Vec::new();
    for &cells_per_b in &[50usize, 100, 200] {
        let nx = 3 * cells_per_b; // domain [-1.5 b, 1.5 b]
        let grid = Grid::new(nx, 1, -1.5 * b, 1.5 * b, -0.5, 0.5);
        let res = solve(
            &DryProblem {
                grid,
                gap: &gap,
                operator: &op,
                load: w,
            },
            &DryParams::default(),
        );
        assert!(res.converged, "{}", res.termination);
        let e_p = res.max_pressure() / ph - 1.0;
        let e_b = half_width(&grid.xs(), &res.pressure) / b - 1.0;
        println!(
            "line, b = {cells_per_b} cells: p_max {:+.4} %, b {:+.4} %, load error {:.1e}, fine iterations {}",
            100.0 * e_p, 100.0 * e_b, (res.load / w - 1.0).abs(), res.iterations
        );
        assert!(e_p.abs() < 0.005, "p_max off by {e_p}");
        assert!(e_b.abs() < 0.005, "half-width off by {e_b}");
        assert!((res.load / w - 1.0).abs() < 1e-8);
        errs.push(e_p.abs());
    }
    // grid convergence: the maximum pressure converges at second order (measured error ratios
    // 4.0 and 4.3 per halving of the cells); a ratio of 3 at least, the edge cells being first
    // order
    for e in errs.windows(2) {
        assert!(e[1] < e[0] / 3.0, "p_max errors {errs:?}");
    }
}

#[test]
fn odd_input_gives_reasons_not_panics() {
    let g = Grid::new(16, 16, -1e-3, 1e-3, -1e-3, 1e-3);
    let gap = |x: f64, y: f64| (x * x + y * y) / 0.02;
    let op = |g: Grid| Box::new(DenseDeflection::new(g, E_RED)) as Box<dyn Deflection>;
    let params = DryParams::default();
    for load in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let r = solve(
            &DryProblem {
                grid: g,
                gap: &gap,
                operator: &op,
                load,
            },
            &params,
        );
        assert!(!r.converged);
        assert!(r.termination.contains("load"), "{}", r.termination);
    }
    let nowhere = |_: f64, _: f64| f64::INFINITY;
    let r = solve(
        &DryProblem {
            grid: g,
            gap: &nowhere,
            operator: &op,
            load: 1.0,
        },
        &params,
    );
    assert!(
        !r.converged && r.termination.contains("no cell"),
        "{}",
        r.termination
    );
    let nan = |x: f64, _: f64| if x > 0.0 { f64::NAN } else { 0.0 };
    let r = solve(
        &DryProblem {
            grid: g,
            gap: &nan,
            operator: &op,
            load: 1.0,
        },
        &params,
    );
    assert!(
        !r.converged && r.termination.contains("NaN"),
        "{}",
        r.termination
    );
    let wrong = |_: Grid| {
        Box::new(DenseDeflection::new(
            Grid::new(3, 3, 0.0, 1.0, 0.0, 1.0),
            E_RED,
        )) as Box<dyn Deflection>
    };
    let r = solve(
        &DryProblem {
            grid: g,
            gap: &gap,
            operator: &wrong,
            load: 1.0,
        },
        &params,
    );
    assert!(
        !r.converged && r.termination.contains("operator"),
        "{}",
        r.termination
    );
    // too few iterations: reported, not hidden
    let few = DryParams {
        max_iterations: 2,
        coarse_start: false,
        ..DryParams::default()
    };
    let r = solve(
        &DryProblem {
            grid: g,
            gap: &gap,
            operator: &op,
            load: 1.0,
        },
        &few,
    );
    assert!(
        !r.converged && r.termination.contains("no convergence"),
        "{}",
        r.termination
    );
    // a flat punch (constant gap) still solves: the whole domain in contact
    let flat = |_: f64, _: f64| 0.0;
    let r = solve(
        &DryProblem {
            grid: g,
            gap: &flat,
            operator: &op,
            load: 1.0,
        },
        &params,
    );
    assert!(r.converged, "{}", r.termination);
    assert!((r.load - 1.0).abs() < 1e-8);
}
