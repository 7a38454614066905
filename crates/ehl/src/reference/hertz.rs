//! Hertz contact of elastic bodies: complete elliptic integrals by the arithmetic-geometric mean,
//! the exact elliptical point contact, and the Hamrock & Brewe (1983) closed-form approximations.
//!
//! Line contact and circular point contact are in [`crate::units`] (`hertz_line_*`,
//! [`crate::units::hertz_point`]); this module adds the elliptical case.

use std::f64::consts::PI;

/// Complete elliptic integrals of the first and second kind, `(K(m), E(m))`, parameter
/// `m = e^2` in `[0, 1)`:
/// K(m) = int_0^{pi/2} (1 - m sin^2 t)^{-1/2} dt, E(m) = int_0^{pi/2} (1 - m sin^2 t)^{1/2} dt.
///
/// Arithmetic-geometric mean (Abramowitz & Stegun 1964, 17.6): a_0 = 1, b_0 = sqrt(1-m),
/// c_0^2 = m; K = pi / (2 a_N), E = K (1 - sum_n 2^(n-1) c_n^2). Converges quadratically;
/// accurate to rounding. Returns `(inf, 1)` at `m = 1`.
pub fn elliptic_ke(m: f64) -> (f64, f64) {
    if m >= 1.0 {
        return (f64::INFINITY, 1.0);
    }
    let mut a = 1.0_f64;
    let mut b = (1.0 - m).sqrt();
    let mut sum = 0.5 * m; // 2^(-1) c_0^2
    let mut pow = 0.5_f64;
    for _ in 0..64 {
        let c = 0.5 * (a - b);
        let an = 0.5 * (a + b);
        let bn = (a * b).sqrt();
        pow *= 2.0;
        sum += pow * c * c;
        a = an;
        b = bn;
        if c.abs() < 1e-17 * a {
            break;
        }
    }
    let k = PI / (2.0 * a);
    (k, k * (1.0 - sum))
}

/// Hertz elliptical contact of two bodies whose undeformed gap is
/// g = x^2/(2 R_x) + y^2/(2 R_y), under normal load F.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzEllipse {
    /// semi-axis along x, the rolling direction (m)
    pub a_x: f64,
    /// semi-axis along y, the axial direction (m)
    pub a_y: f64,
    /// maximum pressure p0 = 3 F / (2 pi a_x a_y)  (Pa)
    pub p0: f64,
    /// rigid-body approach delta (m)
    pub approach: f64,
    /// ellipticity k = a_y / a_x (Hamrock's convention: transverse over rolling semi-axis)
    pub ellipticity: f64,
    /// parameter m = e^2 = 1 - (minor/major)^2 of the elliptic integrals
    pub m: f64,
}

/// Exact Hertz solution for an elliptical contact: load `f` (N), reduced radii `rx`, `ry` (m)
/// in the x-z and y-z planes, reduced modulus `e_red` = E' (Pa; E* = E'/2 in Johnson's notation).
///
/// With the major semi-axis `a` along the direction of the smaller relative curvature
/// A = 1/(2 R_major), the minor semi-axis `c` along the other (curvature B = 1/(2 R_minor)),
/// `m = 1 - c^2/a^2` and K, E the complete elliptic integrals (Johnson, *Contact Mechanics*
/// 1985, eq. 3.63 and 4.37-4.41):
///
/// * B / A = ((a/c)^2 E - K) / (K - E)            (solved for m by bisection)
/// * a^3 = 3 F (K - E) / (2 pi A E* m),  c = a sqrt(1 - m)
/// * p0 = 3 F / (2 pi a c),  delta = p0 c K / E*
///
/// `rx == ry` reduces to [`crate::units::hertz_point`]. Either radius may be infinite (then the
/// contact is a line and this function is not the right model: returns NaNs).
pub fn hertz_elliptical(f: f64, rx: f64, ry: f64, e_red: f64) -> HertzEllipse {
    let nan = HertzEllipse {
        a_x: f64::NAN,
        a_y: f64::NAN,
        p0: f64::NAN,
        approach: f64::NAN,
        ellipticity: f64::NAN,
        m: f64::NAN,
    };
    if !(rx.is_finite() && ry.is_finite() && rx > 0.0 && ry > 0.0 && f > 0.0 && e_red > 0.0) {
        return nan;
    }
    let e_star = 0.5 * e_red;
    let (r_major, r_minor, major_is_y) = if ry >= rx {
        (ry, rx, true)
    } else {
        (rx, ry, false)
    };
    let ratio = r_major / r_minor; // B/A >= 1
    let m = if ratio - 1.0 < 1e-12 {
        0.0
    } else {
        // f(m) = ((E/(1-m)) - K)/(K - E) - ratio is increasing in m; bisect on q = c/a = sqrt(1-m)
        // in log space so that very slender ellipses are resolved.
        let g = |q: f64| {
            let m = 1.0 - q * q;
            let (k, e) = elliptic_ke(m);
            (e / (q * q) - k) / (k - e) - ratio
        };
        let (mut lo, mut hi) = ((1e-12f64).ln(), (1.0f64 - 1e-9).ln()); // ln q
                                                                        // g decreases as q grows (q = 1 is the circle)
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if g(mid.exp()) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo < 1e-15 {
                break;
            }
        }
        let q = (0.5 * (lo + hi)).exp();
        1.0 - q * q
    };
    let a_curv = 1.0 / (2.0 * r_major);
    let (k, e) = elliptic_ke(m);
    // (K - E)/m -> pi/4 as m -> 0
    let k_minus_e_over_m = if m < 1e-8 {
        PI / 4.0 * (1.0 + 3.0 * m / 8.0)
    } else {
        (k - e) / m
    };
    let a = (3.0 * f * k_minus_e_over_m / (2.0 * PI * a_curv * e_star)).cbrt();
    let c = a * (1.0 - m).sqrt();
    let p0 = 3.0 * f / (2.0 * PI * a * c);
    let approach = p0 * c * k / e_star;
    let (a_x, a_y) = if major_is_y { (c, a) } else { (a, c) };
    HertzEllipse {
        a_x,
        a_y,
        p0,
        approach,
        ellipticity: a_y / a_x,
        m,
    }
}

/// Hamrock & Brewe (1983) closed-form approximations for an elliptical contact with radius ratio
/// `alpha_r = R_y / R_x` (J. Tribology 105, 171-177; also Hamrock, *Fundamentals of Fluid Film
/// Lubrication*, 1994, ch. 3):
/// k = alpha_r^(2/pi), E = 1 + q_a / alpha_r, F = pi/2 + q_a ln(alpha_r), q_a = pi/2 - 1.
/// With these, a_y = (6 k^2 E W R / (pi E'))^(1/3), a_x = (6 E W R / (pi k E'))^(1/3),
/// delta = F (9 / (2 E R) (W / (pi k E'))^2)^(1/3), 1/R = 1/R_x + 1/R_y.
/// Returns `(k, E, F)`. Meant for comparison; [`hertz_elliptical`] is exact.
pub fn hamrock_brewe(alpha_r: f64) -> (f64, f64, f64) {
    let qa = PI / 2.0 - 1.0;
    (
        alpha_r.powf(2.0 / PI),
        1.0 + qa / alpha_r,
        PI / 2.0 + qa * alpha_r.ln(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elliptic_integrals_match_tables_and_legendre() {
        // Abramowitz & Stegun Table 17.5 (m = 0.5): K = 1.8540746773, E = 1.3506438810
        let (k, e) = elliptic_ke(0.5);
        assert!((k - 1.854_074_677_3).abs() < 1e-9);
        assert!((e - 1.350_643_881_0).abs() < 1e-9);
        // m = 0: K = E = pi/2
        let (k0, e0) = elliptic_ke(0.0);
        assert!((k0 - PI / 2.0).abs() < 1e-15 && (e0 - PI / 2.0).abs() < 1e-15);
        // Legendre's relation E K' + E' K - K K' = pi/2 (exact identity), K' = K(1-m)
        for &m in &[0.01, 0.1, 0.3, 0.7, 0.95, 0.999] {
            let (k, e) = elliptic_ke(m);
            let (kp, ep) = elliptic_ke(1.0 - m);
            let lhs = e * kp + ep * k - k * kp;
            assert!((lhs - PI / 2.0).abs() < 1e-12, "m = {m}: {lhs}");
        }
    }

    #[test]
    fn circular_limit_is_hertz_point() {
        let (f, r, e) = (15.0, 0.0125, 1.1e11);
        let c = crate::units::hertz_point(f, r / 2.0, e);
        // reduced radius r/2 in both planes (a ball of radius r on a ball of radius r)
        let h = hertz_elliptical(f, r / 2.0, r / 2.0 * (1.0 + 1e-9), e);
        assert!((h.a_x / c.a - 1.0).abs() < 1e-6);
        assert!((h.a_y / c.a - 1.0).abs() < 1e-6);
        assert!((h.p0 / c.p0 - 1.0).abs() < 1e-6);
        assert!((h.approach / c.approach - 1.0).abs() < 1e-6);
    }

    #[test]
    fn hamrock_brewe_within_their_accuracy() {
        // Hamrock & Brewe's closed forms are engineering approximations good to a few per cent
        // for 1 <= alpha_r <= 100. Their largest deviation from the exact solution here is 3.9 %
        // (k at alpha_r = 10; the exact k = 4.4994 was confirmed during development by an
        // independent Simpson quadrature of K and E), so 5 % is required on k, the semi-axes
        // and the approach. The exact solution itself is checked against the elastic operator
        // in `tests/reference_hertz.rs`.
        let (f, rx, e_red) = (100.0, 0.01, 2.2e11);
        for &alpha in &[1.5, 3.0, 10.0, 30.0, 100.0] {
            let ry = alpha * rx;
            let h = hertz_elliptical(f, rx, ry, e_red);
            let (k, ee, ff) = hamrock_brewe(alpha);
            let r = 1.0 / (1.0 / rx + 1.0 / ry);
            let ay = (6.0 * k * k * ee * f * r / (PI * e_red)).cbrt();
            let ax = (6.0 * ee * f * r / (PI * k * e_red)).cbrt();
            let delta = ff * (9.0 / (2.0 * ee * r) * (f / (PI * k * e_red)).powi(2)).cbrt();
            assert!(
                (h.ellipticity / k - 1.0).abs() < 0.05,
                "k at {alpha}: {} vs {k}",
                h.ellipticity
            );
            assert!((h.a_y / ay - 1.0).abs() < 0.05, "a_y at {alpha}");
            assert!((h.a_x / ax - 1.0).abs() < 0.05, "a_x at {alpha}");
            assert!(
                (h.approach / delta - 1.0).abs() < 0.05,
                "delta at {alpha}: {} vs {delta}",
                h.approach
            );
            // load balance of the Hertz ellipse
            assert!((2.0 / 3.0 * PI * h.p0 * h.a_x * h.a_y / f - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn orientation_follows_the_larger_radius() {
        let h = hertz_elliptical(50.0, 0.01, 0.05, 2.2e11);
        let g = hertz_elliptical(50.0, 0.05, 0.01, 2.2e11);
        assert!(h.a_y > h.a_x);
        assert!((h.a_x - g.a_y).abs() < 1e-15 && (h.a_y - g.a_x).abs() < 1e-15);
        assert!((h.p0 - g.p0).abs() < 1e-6 * h.p0);
    }
}
