//! Dry solver against Hertz: ball on flat (point contact) and the infinite line contact.
mod dry_support;

use ehl::dry::{solve, DryParams, DryProblem};
use ehl::elastic::dense::DenseDeflection;
use ehl::elastic::Deflection;
use ehl::grid::Grid;
use ehl::units;

const E_RED: f64 = 2.2e11;

#[test]
fn support_fft_operator_equals_dense_sum() {
    // The stand-in FFT operator must equal the direct sum to rounding (1e-12 relative to the
    // largest deflection: the FFT's error is ~1e-16 log N times the sum of |terms|).
    for &(nx, ny) in &[(7, 5), (8, 8), (12, 1), (9, 16)] {
        let g = Grid::new(nx, ny, -1e-3, 2e-3, -0.5e-3, 0.5e-3);
        let mut dense = if ny == 1 { DenseDeflection::line(g, E_RED) } else { DenseDeflection::new(g, E_RED) };
        let mut fft = dry_support::FftOp::new(dense.clone());
        let p: Vec<f64> = (0..g.len()).map(|k| 1e9 * (((k * 7919) % 101) as f64 / 101.0)).collect();
        let (mut a, mut b) = (vec![0.0; g.len()], vec![0.0; g.len()]);
        dense.apply(&p, &mut a);
        fft.apply(&p, &mut b);
        let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for k in 0..g.len() {
            assert!((a[k] - b[k]).abs() < 1e-12 * scale, "{nx}x{ny} cell {k}: {} vs {}", a[k], b[k]);
        }
    }
}

/// Ball on flat, square grid centred on the contact.
fn ball(n: usize, half_domain_in_a: f64, params: &DryParams) -> (Grid, ehl::dry::DryResult, units::HertzPoint) {
    let (r, f) = (0.01, 100.0);
    let hz = units::hertz_point(f, r, E_RED);
    let l = half_domain_in_a * hz.a;
    let grid = Grid::new(n, n, -l, l, -l, l);
    let gap = move |x: f64, y: f64| (x * x + y * y) / (2.0 * r);
    let op = dry_support::half_space(E_RED);
    let res = solve(&DryProblem { grid, gap: &gap, operator: &op, load: f }, params);
    (grid, res, hz)
}

#[test]
fn ball_on_flat_matches_hertz() {
    // 160^2 cells on [-1.5a, 1.5a]^2: a spans 53 cells. Discretisation errors (piecewise-constant
    // pressure, contact edge resolved to one cell) are O(dx/a) ~ 2 % on the contact radius read
    // as sqrt(area / pi) of whole cells and ~0.5 % on p0 and approach; the brief asks for 1 %.
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
