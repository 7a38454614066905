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
    fn strip_difference_matches_log_kernel() {
        // d/dx of the strip kernel = -2 ln|x+a| + 2 ln|x-a|
        let (a, x, h) = (0.5, 3.0, 1e-5);
        let d = (strip(x + h, a) - strip(x - h, a)) / (2.0 * h);
        let expected = -2.0 * ((x + a).abs().ln() - (x - a).abs().ln());
        assert!((d - expected).abs() < 1e-6);
    }
}
