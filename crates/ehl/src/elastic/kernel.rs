//! Influence coefficients: deflection at a point due to uniform unit pressure on one cell.

use std::f64::consts::PI;

/// Half-space compliance factor 2/(pi E') (m/Pa per unit of the geometric kernel), thesis eq. 1.12
/// summed over both bodies: k = (1-nu1^2)/(pi E1) + (1-nu2^2)/(pi E2) = 2/(pi E').
pub fn compliance(e_red: f64) -> f64 {
    2.0 / (PI * e_red)
}

/// Odd-odd antiderivative of 1/r: f(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|), with
/// d^2 f / dX dY = 1/sqrt(X^2 + Y^2) and f(0, Y) = f(X, 0) = 0. The asinh form avoids the
/// cancellation of the logarithms of eq. 1.11 far from the cell.
#[inline]
fn antiderivative(x: f64, y: f64) -> f64 {
    let mut f = 0.0;
    if x != 0.0 {
        f += x * (y / x.abs()).asinh();
    }
    if y != 0.0 {
        f += y * (x / y.abs()).asinh();
    }
    f
}

/// Geometric part of Love's (1929) rectangle solution (thesis eq. 1.11; Johnson 1985 eq. 3.25):
/// the integral of 1/r over the rectangle |x'| <= a, |y'| <= b seen from the point (x, y), in m.
/// Multiply by [`compliance`] and the pressure to get the deflection:
///
/// w(x, y) = 2/(pi E') p \int\int dx' dy' / sqrt((x-x')^2 + (y-y')^2).
///
/// `a`, `b` are the half-sizes of the cell along x and y.
#[inline]
pub fn rectangle(x: f64, y: f64, a: f64, b: f64) -> f64 {
    antiderivative(x + a, y + b) - antiderivative(x + a, y - b) - antiderivative(x - a, y + b)
        + antiderivative(x - a, y - b)
}

/// [`rectangle`] for every offset `(di, dj)` with |di| < nx, |dj| < ny between cells of size
/// `dx * dy`, the source shifted by `t` along y: entry `(dj + ny - 1) * (2 nx - 1) + di + nx - 1`
/// holds `rectangle(di dx, dj dy - t, dx/2, dy/2)`.
///
/// Neighbouring rectangles share corners, so the antiderivative is evaluated once per corner of
/// the offset lattice ((2 nx) (2 ny) evaluations instead of 4 (2 nx - 1)(2 ny - 1)).
pub fn rectangle_table(nx: usize, ny: usize, dx: f64, dy: f64, t: f64) -> Vec<f64> {
    use rayon::prelude::*;
    let (cx, cy) = (2 * nx, 2 * ny);
    // corner c along x sits at (c - nx + 0.5) dx, i.e. offsets -(nx-1)-1/2 .. nx-1/2
    let xs: Vec<f64> = (0..cx).map(|c| (c as f64 - nx as f64 + 0.5) * dx).collect();
    let mut corners = vec![0.0; cx * cy];
    corners.par_chunks_mut(cx).enumerate().for_each(|(r, row)| {
        let y = (r as f64 - ny as f64 + 0.5) * dy - t;
        for (v, &x) in row.iter_mut().zip(&xs) {
            *v = antiderivative(x, y);
        }
    });
    let (wx, wy) = (2 * nx - 1, 2 * ny - 1);
    let mut table = vec![0.0; wx * wy];
    table.par_chunks_mut(wx).enumerate().for_each(|(r, row)| {
        let (lo, hi) = (
            &corners[r * cx..(r + 1) * cx],
            &corners[(r + 1) * cx..(r + 2) * cx],
        );
        for (c, v) in row.iter_mut().enumerate() {
            *v = hi[c + 1] - lo[c + 1] - hi[c] + lo[c];
        }
    });
    table
}

/// Plane-strain deflection kernel for the infinite line contact: the integral of -2 ln|x - s|
/// over the strip |s| <= a, seen from x, in m. The deflection of both bodies under strip pressures
/// is w(x) = 2/(pi E') p \int -2 ln|x - s| ds + const (Johnson 1985 eq. 2.25 summed over both
/// bodies); the constant is absorbed in the approach / h0.
#[inline]
pub fn strip(x: f64, a: f64) -> f64 {
    let g = |t: f64| if t == 0.0 { 0.0 } else { t * t.abs().ln() - t };
    -2.0 * (g(x + a) - g(x - a))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangle_centre_matches_closed_form() {
        // Centre of a square 2a x 2a: 8 a asinh(1) = 4 a ln((1+sqrt2)/(sqrt2-1))... (Johnson 3.26)
        let a = 0.5;
        let expected = 8.0 * a * (1.0f64).asinh();
        assert!((rectangle(0.0, 0.0, a, a) - expected).abs() < 1e-14);
    }

    #[test]
    fn rectangle_far_field_is_point_load() {
        // Far away the cell acts as a point load of area 4ab: integral -> 4ab / r.
        let (a, b, x, y): (f64, f64, f64, f64) = (0.5, 0.25, 300.0, 400.0);
        let r = (x * x + y * y).sqrt();
        let rel = rectangle(x, y, a, b) / (4.0 * a * b / r) - 1.0;
        assert!(rel.abs() < 1e-6, "{rel}");
    }

    #[test]
    fn rectangle_symmetries() {
        let (a, b) = (0.3, 0.7);
        for &(x, y) in &[(0.1, 0.2), (1.3, -2.0), (5.0, 0.0)] {
            let v = rectangle(x, y, a, b);
            assert!((rectangle(-x, y, a, b) - v).abs() < 1e-13);
            assert!((rectangle(x, -y, a, b) - v).abs() < 1e-13);
            // swapping axes swaps the cell
            assert!((rectangle(y, x, b, a) - v).abs() < 1e-13);
        }
    }

    #[test]
    fn rectangle_table_matches_rectangle() {
        let (nx, ny, dx, dy, t) = (5, 4, 0.3, 0.7, 0.45);
        let table = rectangle_table(nx, ny, dx, dy, t);
        for dj in -(ny as isize - 1)..ny as isize {
            for di in -(nx as isize - 1)..nx as isize {
                let k = (dj + ny as isize - 1) as usize * (2 * nx - 1)
                    + (di + nx as isize - 1) as usize;
                let direct = rectangle(di as f64 * dx, dj as f64 * dy - t, dx / 2.0, dy / 2.0);
                assert!(
                    (table[k] - direct).abs() < 1e-13 * (1.0 + direct.abs()),
                    "{di} {dj}"
                );
            }
        }
    }

    #[test]
    fn strip_difference_matches_log_kernel() {
        // d/dx of the strip kernel = -2 ln|x+a| + 2 ln|x-a|
        let (a, x, h) = (0.5, 3.0, 1e-5);
        let d = (strip(x + h, a) - strip(x - h, a)) / (2.0 * h);
        let expected = -2.0 * ((x + a).abs().ln() - (x - a).abs().ln());
        assert!((d - expected).abs() < 1e-6);
    }
}
