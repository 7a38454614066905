//! The DC-FFT operator against the O(N^2) direct sum (exact same influence coefficients, so the
//! only difference is floating-point round-off: 1e-10 relative is ~1e4 ulps of headroom over
//! sums of ~1e3 terms), and the deflection under a Hertz pressure against Johnson's closed form.

use ehl::elastic::dense::DenseDeflection;
use ehl::elastic::{guilbault_psi, BodyCompliance, Deflection, EndImages, FftDeflection};
use ehl::grid::Grid;

/// Deterministic pseudo-random pressures in [0, 1) GPa (a small LCG keeps the test self-contained).
fn pressures(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) * 1e9
        })
        .collect()
}

fn max_rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

fn compare(mut fast: impl Deflection, mut slow: impl Deflection, seed: u64) -> f64 {
    let g = *fast.grid();
    let p = pressures(g.len(), seed);
    let (mut a, mut b) = (vec![0.0; g.len()], vec![0.0; g.len()]);
    fast.apply(&p, &mut a);
    slow.apply(&p, &mut b);
    // applying twice must give the same answer (scratch reuse)
    let mut a2 = vec![0.0; g.len()];
    fast.apply(&p, &mut a2);
    assert_eq!(a, a2);
    max_rel_diff(&a, &b)
}

const E_RED: f64 = 2.2e11;

#[test]
fn fft_equals_direct_sum_on_odd_even_and_non_square_grids() {
    for &(nx, ny) in &[(7, 9), (8, 6), (13, 4), (16, 16), (5, 1), (1, 5)] {
        let g = Grid::new(nx, ny, -1e-4, 2e-4, -3e-4, 1e-4);
        let err = compare(
            FftDeflection::half_space(g, E_RED),
            DenseDeflection::new(g, E_RED),
            (nx * 31 + ny) as u64,
        );
        assert!(err < 1e-10, "{nx}x{ny}: {err:e}");
    }
}

#[test]
fn fft_line_operator_equals_direct_sum() {
    for &nx in &[1, 2, 17, 64, 101] {
        let g = Grid::new(nx, 1, -1e-4, 2e-4, -0.5, 0.5);
        let err = compare(
            FftDeflection::line(g, E_RED),
            DenseDeflection::line(g, E_RED),
            nx as u64,
        );
        assert!(err < 1e-10, "line {nx}: {err:e}");
    }
}

#[test]
fn fft_mirror_images_equal_explicit_images() {
    let nu = 0.3;
    let psi = guilbault_psi(nu);
    for &(nx, ny, levels) in &[(9, 12, 1), (10, 7, 2), (6, 11, 3), (8, 8, 0)] {
        let g = Grid::new(nx, ny, -1e-4, 1e-4, -2e-3, 2e-3);
        // body 1: ends at the domain edges; body 2: shorter and offset, its own ends
        let mut b1 = BodyCompliance::new(2.0e11, nu);
        b1.images = Some(EndImages {
            ends: (-2e-3, 2e-3),
            levels,
            psi,
        });
        let mut b2 = BodyCompliance::new(1.1e11, 0.25);
        b2.images = Some(EndImages {
            ends: (-1.7e-3, 1.3e-3),
            levels,
            psi: 1.0,
        });
        let bodies = [b1, b2];
        let err = compare(
            FftDeflection::with_images(g, &bodies),
            DenseDeflection::with_images(g, &bodies),
            (nx * ny * (levels + 1)) as u64,
        );
        assert!(err < 1e-10, "{nx}x{ny} levels {levels}: {err:e}");
    }
}

#[test]
fn images_make_an_end_softer_symmetric_and_decay_with_level() {
    // A uniform load along a roller: the mirror images (weight psi > 1) add deflection that is
    // largest at the ends, the field stays symmetric about mid-length, and each further level
    // changes the result less than the previous one.
    let (nx, ny) = (8, 40);
    let g = Grid::new(nx, ny, -1e-4, 1e-4, -2e-3, 2e-3);
    let p = vec![1e9; g.len()];
    let run = |levels: usize| {
        let mut b = BodyCompliance::new(2e11, 0.3);
        b.images = Some(EndImages {
            ends: (-2e-3, 2e-3),
            levels,
            psi: guilbault_psi(0.3),
        });
        let mut op = FftDeflection::with_images(g, &[b, BodyCompliance::new(2e11, 0.3)]);
        let mut w = vec![0.0; g.len()];
        op.apply(&p, &mut w);
        w
    };
    let (w0, w1, w2, w3) = (run(0), run(1), run(2), run(3));
    let mid = |w: &[f64], j: usize| w[g.idx(nx / 2, j)];
    for j in 0..ny {
        let rel = (mid(&w1, j) - mid(&w1, ny - 1 - j)).abs() / mid(&w1, j);
        assert!(rel < 1e-12, "asymmetric at row {j}: {rel:e}");
    }
    let end_gain = mid(&w1, 0) - mid(&w0, 0);
    let centre_gain = mid(&w1, ny / 2) - mid(&w0, ny / 2);
    assert!(end_gain > 2.0 * centre_gain && centre_gain > 0.0);
    let d1 = (mid(&w1, 0) - mid(&w0, 0)).abs();
    let d2 = (mid(&w2, 0) - mid(&w1, 0)).abs();
    let d3 = (mid(&w3, 0) - mid(&w2, 0)).abs();
    assert!(d2 < d1 && d3 < d2, "{d1:e} {d2:e} {d3:e}");
}

#[test]
fn deflection_under_hertz_pressure_matches_johnson() {
    // Johnson (1985) eq. 4.22 with E* = E'/2: inside the contact,
    // w(r) = pi p0 (2 a^2 - r^2) / (2 a E'). Piecewise-constant cells on a 128^2 grid over
    // [-1.5a, 1.5a]^2 integrate the sqrt rim singularity to O(dx^1.5): 0.5 % is ~4x the error seen.
    let (a, p0) = (1e-4, 1e9);
    let n = 128;
    let g = Grid::new(n, n, -1.5 * a, 1.5 * a, -1.5 * a, 1.5 * a);
    let p: Vec<f64> = (0..g.len())
        .map(|k| {
            let (x, y) = (g.x(k % n), g.y(k / n));
            p0 * (1.0 - (x * x + y * y) / (a * a)).max(0.0).sqrt()
        })
        .collect();
    let mut op = FftDeflection::half_space(g, E_RED);
    let mut w = vec![0.0; g.len()];
    op.apply(&p, &mut w);
    for &(i, j) in &[
        (n / 2, n / 2),
        (n / 2 + 20, n / 2),
        (n / 2 + 10, n / 2 + 15),
    ] {
        let (x, y) = (g.x(i), g.y(j));
        let exact = std::f64::consts::PI * p0 * (2.0 * a * a - x * x - y * y) / (2.0 * a * E_RED);
        let rel = (w[g.idx(i, j)] / exact - 1.0).abs();
        assert!(rel < 5e-3, "({i},{j}): {rel:e}");
    }
}
