//! Finite straight roller on a flat (plain half-space, no mirror images): at mid-length the
//! pressure is the Hertz line contact for the load per unit length carried there.
mod dry_support;

use ehl::dry::{solve, DryParams, DryProblem};
use ehl::grid::Grid;
use ehl::units;

const E_RED: f64 = 2.2e11;

#[test]
fn long_roller_mid_length_matches_hertz_line_contact_and_converges_with_grid() {
    // Roller R = 5 mm, L = 10 mm on a flat (the flat overhangs: no material beyond the ends,
    // gap infinite). Load 2 kN: nominal b = 0.11 mm, L = 90 b (>= 40 b, so the ends do not reach
    // mid-length: their influence decays over a few b). Domain x in [-1.6 b, 1.6 b],
    // y over 1.04 L. Tolerance 1 % (the brief): at mid-length the section is in plane strain up
    // to terms of order b/L, and the piecewise-constant discretisation errs by O(dx/b).
    let (r, len, f) = (0.005, 0.010, 2000.0);
    let b_nom = units::hertz_line_half_width(f / len, r, E_RED);
    let gap = move |x: f64, y: f64| {
        if y.abs() <= 0.5 * len {
            x * x / (2.0 * r)
        } else {
            f64::INFINITY
        }
    };
    let op = dry_support::half_space(E_RED);
    let mut errors = Vec::new();
    for &(nx, ny) in &[(32usize, 104usize), (64, 208), (128, 416)] {
        let xl = 1.6 * b_nom;
        let yl = 0.52 * len;
        let grid = Grid::new(nx, ny, -xl, xl, -yl, yl);
        let res = solve(
            &DryProblem {
                grid,
                gap: &gap,
                operator: &op,
                load: f,
            },
            &DryParams::default(),
        );
        assert!(res.converged, "{}", res.termination);
        assert!((res.load / f - 1.0).abs() < 1e-8);
        // mid-length: the two rows either side of y = 0 (ny even), averaged
        let j = ny / 2;
        let row = |j: usize| &res.pressure[j * nx..(j + 1) * nx];
        let mid: Vec<f64> = row(j - 1)
            .iter()
            .zip(row(j))
            .map(|(a, b)| 0.5 * (a + b))
            .collect();
        let w_mid: f64 = mid.iter().sum::<f64>() * grid.dx;
        let ph = units::hertz_line_pressure(w_mid, r, E_RED);
        let b = units::hertz_line_half_width(w_mid, r, E_RED);
        let pmax = mid.iter().cloned().fold(0.0, f64::max);
        let e_p = pmax / ph - 1.0;
        let e_b = half_width(&grid.xs(), &mid) / b - 1.0;
        println!(
            "roller {nx}x{ny} (b = {:.1} cells): w'_mid = {:.4e} N/m (nominal {:.4e}), p_max {:+.3} %, b {:+.3} % of Hertz line, fine iterations {}",
            b / grid.dx, w_mid, f / len, 100.0 * e_p, 100.0 * e_b, res.iterations
        );
        assert!(e_p.abs() < 0.01, "p_max off by {e_p}");
        assert!(e_b.abs() < 0.01, "half-width off by {e_b}");
        errors.push(e_p.abs());
    }
    // grid convergence: the pressure error shrinks with each refinement
    assert!(errors[1] < errors[0] && errors[2] < errors[1], "{errors:?}");
}

/// Half-width from the edge cells' p^2 extrapolated linearly to zero (see dry_hertz.rs).
fn half_width(xs: &[f64], p: &[f64]) -> f64 {
    let n = p.len();
    let first = p.iter().position(|&v| v > 0.0).unwrap();
    let last = n - 1 - p.iter().rev().position(|&v| v > 0.0).unwrap();
    let dx = xs[1] - xs[0];
    let edge = |k: usize, inner: usize| {
        let (a, b) = (p[k] * p[k], p[inner] * p[inner]);
        dx * a / (b - a)
    };
    0.5 * ((xs[last] + edge(last, last - 1)) - (xs[first] - edge(first, first + 1)))
}

#[test]
fn end_peak_with_mirror_images_and_psi_is_lower_and_stops_growing() {
    // Two equal straight rollers R1 = R2 = 10 mm, L = 4 mm, 30 kN, E = 200 GPa, nu = 0.3 (thesis
    // Table 1.1), ends aligned, both with mirror images about their ends. Without the free-end correction the
    // half-space model puts a stress singularity at the sharp end, so the end peak grows without
    // bound as the grid is refined (the issue quotes 6.6, 9.2, 12.9 GPa from another half-space
    // code). One mirror level with Guilbault's psi (eq. 1.13) models the roller's free end:
    // the peak is lower and settles. Checked: (a) at every grid the corrected peak is below the
    // plain one; (b) the plain peak grows by > 5 % per refinement (a singularity, the growth in
    // the quoted numbers is ~40 %); (c) the corrected peak changes by < 1 % over the last
    // refinement (measured: 7.378, 7.391, 7.392 GPa with one level, 7.442, 7.455, 7.457 with
    // two; plain 24.7, 34.6, 48.6 GPa, +40 % per refinement as in the quoted numbers).
    // (A roller on a flat that overhangs it keeps a genuine edge singularity: with images on the
    // roller only, its peak still grows, ~16 % per refinement.)
    let (r, len, f, e, nu) = (0.005, 0.004, 30_000.0, 2.0e11, 0.3); // R = reduced radius
    let e_red = units::reduced_modulus(e, nu, e, nu);
    let b = units::hertz_line_half_width(f / len, r, e_red);
    let gap = move |x: f64, y: f64| {
        if y.abs() <= 0.5 * len {
            x * x / (2.0 * r)
        } else {
            f64::INFINITY
        }
    };
    let psi = ehl::elastic::operator::guilbault_psi(nu);
    let plain = dry_support::half_space(e_red);
    let mirrored = dry_support::rollers(e, nu, (-0.5 * len, 0.5 * len), 1, psi, true);
    let mut peaks = Vec::new();
    for &(nx, ny) in &[(24usize, 64usize), (48, 128), (96, 256)] {
        // y exactly on the roller: the end sits on the domain edge, cells of length L / ny
        let grid = Grid::new(nx, ny, -1.6 * b, 1.6 * b, -0.5 * len, 0.5 * len);
        let mut row = Vec::new();
        for op in [
            &plain as &(dyn Fn(Grid) -> Box<dyn ehl::elastic::Deflection> + Sync),
            &mirrored,
        ] {
            let res = solve(
                &DryProblem {
                    grid,
                    gap: &gap,
                    operator: op,
                    load: f,
                },
                &DryParams::default(),
            );
            assert!(res.converged, "{}", res.termination);
            row.push(res.max_pressure());
        }
        println!(
            "roller L = 4 mm, 30 kN, {nx}x{ny} (dy = {:.1} um): end peak plain {:.3} GPa, mirror + psi {:.3} GPa",
            grid.dy * 1e6, row[0] / 1e9, row[1] / 1e9
        );
        assert!(row[1] < row[0]);
        peaks.push(row);
    }
    for k in 1..3 {
        assert!(
            peaks[k][0] > 1.05 * peaks[k - 1][0],
            "plain peak should keep growing: {peaks:?}"
        );
    }
    let growth_plain = peaks[2][0] / peaks[1][0] - 1.0;
    let growth_mirror = (peaks[2][1] / peaks[1][1] - 1.0).abs();
    assert!(
        growth_mirror < 0.01 && growth_mirror < 0.5 * growth_plain,
        "{peaks:?}"
    );
}
