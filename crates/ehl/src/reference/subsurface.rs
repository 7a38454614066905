//! Closed-form stress fields below Hertz contacts, the references of [`crate::stress`].
//!
//! Conventions as in [`crate::stress`]: tension positive, z depth into the body, Voigt order
//! (sigma_xx, sigma_yy, sigma_zz, tau_yz, tau_xz, tau_xy), the tangential traction q = mu p acts
//! on the body along +x.

use std::f64::consts::PI;

/// Stress at (x, z) below a Hertz line contact of half-width `b` and peak pressure `p0`
/// (p = p0 sqrt(1 - x^2/b^2)) with a full-sliding traction q = `mu` p along +x, plane strain
/// with Poisson ratio `nu`. McEwen (1949) for the normal load, Smith & Liu (1953) for the
/// traction (Johnson 1985 sec. 7.1): with A = b^2 - x^2 + z^2, R = sqrt(A^2 + 4 x^2 z^2),
/// m = sqrt((R + A)/2), n = sign(x) sqrt((R - A)/2), D = m^2 + n^2,
///
/// sigma_xx = -(p0/b) [m (1 + (z^2 + n^2)/D) - 2 z] + (mu p0/b) [n (2 - (z^2 - m^2)/D) - 2 x]
/// sigma_zz = -(p0/b) m (1 - (z^2 + n^2)/D) - (mu p0/b) n (m^2 - z^2)/D
/// tau_xz = -(p0/b) n (m^2 - z^2)/D - (mu p0/b) [m (1 + (z^2 + n^2)/D) - 2 z]
/// sigma_yy = nu (sigma_xx + sigma_zz).
///
/// At the surface this gives sigma_zz = -p, tau_xz = -mu p and sigma_xx = -p - 2 mu p0 x / b
/// inside the contact (tested).
pub fn hertz_line_stress(x: f64, z: f64, b: f64, p0: f64, mu: f64, nu: f64) -> [f64; 6] {
    let a = b * b - x * x + z * z;
    let r = (a * a + 4.0 * x * x * z * z).sqrt();
    let m = (0.5 * (r + a)).max(0.0).sqrt();
    let n = x.signum() * (0.5 * (r - a)).max(0.0).sqrt();
    let d = m * m + n * n;
    let (k, kt) = (p0 / b, mu * p0 / b);
    let sxx = -k * (m * (1.0 + (z * z + n * n) / d) - 2.0 * z)
        + kt * (n * (2.0 - (z * z - m * m) / d) - 2.0 * x);
    let szz = -k * m * (1.0 - (z * z + n * n) / d) - kt * n * (m * m - z * z) / d;
    let sxz = -k * n * (m * m - z * z) / d - kt * (m * (1.0 + (z * z + n * n) / d) - 2.0 * z);
    [sxx, nu * (sxx + szz), szz, 0.0, sxz, 0.0]
}

/// Stress on the axis of a Hertz circular contact of radius `a` and peak pressure `p0` at depth
/// `z` (Huber 1904; Johnson 1985 eq. 3.45): (sigma_r = sigma_theta, sigma_zz), Pa:
///
/// sigma_r = p0 [-(1 + nu)(1 - (z/a) atan(a/z)) + 1 / (2 (1 + z^2/a^2))],
/// sigma_zz = -p0 / (1 + z^2/a^2).
pub fn hertz_circle_axis_stress(z: f64, a: f64, p0: f64, nu: f64) -> (f64, f64) {
    let t = z / a;
    let sr = p0 * (-(1.0 + nu) * (1.0 - t * (1.0 / t).atan()) + 0.5 / (1.0 + t * t));
    (sr, -p0 / (1.0 + t * t))
}

/// Boussinesq's compressive unit point load at the origin of a half-space z > 0 (Johnson 1985
/// sec. 3.2, Cartesian form), stress per newton (1/m^2), Voigt order, tension positive:
/// sigma_zz = -3 z^3 / (2 pi rho^5), tau_xz = -3 x z^2 / (2 pi rho^5), tau_yz likewise,
/// sigma_xx = (1/2pi) [(1 - 2 nu) ((1 - z/rho)(x^2 - y^2)/r^4 + z y^2/(rho^3 r^2)) - 3 z x^2/rho^5],
/// tau_xy = (1/2pi) [(1 - 2 nu) x y (2 rho + z)/(rho^3 (rho + z)^2) - 3 x y z/rho^5],
/// with r^2 = x^2 + y^2 and rho^2 = r^2 + z^2. Not defined on the z axis at z = 0.
pub fn boussinesq_point(x: f64, y: f64, z: f64, nu: f64) -> [f64; 6] {
    let r2 = x * x + y * y;
    let rho = (r2 + z * z).sqrt();
    let (c, m) = (0.5 / PI, 1.0 - 2.0 * nu);
    let r3 = rho * rho * rho;
    let r5 = r3 * rho * rho;
    // (1 - z/rho) / r^2 = 1 / (rho (rho + z)), without the cancellation near the axis
    let f = 1.0 / (rho * (rho + z));
    let (sxx, syy) = if r2 > 0.0 {
        (
            c * (m * (f * (x * x - y * y) / r2 + z * y * y / (r3 * r2)) - 3.0 * z * x * x / r5),
            c * (m * (f * (y * y - x * x) / r2 + z * x * x / (r3 * r2)) - 3.0 * z * y * y / r5),
        )
    } else {
        // on the axis (r -> 0) both tend to (1 - 2 nu) / (4 pi z^2) (tested)
        let v = c * m * 0.5 / (z * z);
        (v, v)
    };
    [
        sxx,
        syy,
        -3.0 * c * z * z * z / r5,
        -3.0 * c * y * z * z / r5,
        -3.0 * c * x * z * z / r5,
        c * (m * x * y * (2.0 * rho + z) / (r3 * (rho + z).powi(2)) - 3.0 * x * y * z / r5),
    ]
}

/// Cerruti's unit point force along +x at the origin of a half-space z > 0 (Johnson 1985 sec.
/// 3.2; Love 1927), stress per newton (1/m^2), Voigt order, tension positive; with
/// rho^2 = x^2 + y^2 + z^2 and A = rho + z:
/// sigma_xx = (1/2pi) [-3 x^3/rho^5 + (1 - 2 nu)(x/rho^3 - 3x/(rho A^2) + x^3/(rho^3 A^2) + 2 x^3/(rho^2 A^3))],
/// sigma_yy = (1/2pi) [-3 x y^2/rho^5 + (1 - 2 nu)(x/rho^3 - x/(rho A^2) + x y^2/(rho^3 A^2) + 2 x y^2/(rho^2 A^3))],
/// sigma_zz = -3 x z^2/(2 pi rho^5), tau_yz = -3 x y z/(2 pi rho^5), tau_xz = -3 x^2 z/(2 pi rho^5),
/// tau_xy = (1/2pi) [-3 x^2 y/rho^5 + (1 - 2 nu)(-y/(rho A^2) + x^2 y/(rho^3 A^2) + 2 x^2 y/(rho^2 A^3))].
pub fn cerruti_point(x: f64, y: f64, z: f64, nu: f64) -> [f64; 6] {
    let rho = (x * x + y * y + z * z).sqrt();
    let a = rho + z;
    let (c, m) = (0.5 / PI, 1.0 - 2.0 * nu);
    let (r3, r5) = (rho.powi(3), rho.powi(5));
    let (a2, a3) = (a * a, a * a * a);
    [
        c * (-3.0 * x.powi(3) / r5
            + m * (x / r3 - 3.0 * x / (rho * a2)
                + x.powi(3) / (r3 * a2)
                + 2.0 * x.powi(3) / (rho * rho * a3))),
        c * (-3.0 * x * y * y / r5
            + m * (x / r3 - x / (rho * a2)
                + x * y * y / (r3 * a2)
                + 2.0 * x * y * y / (rho * rho * a3))),
        -3.0 * c * x * z * z / r5,
        -3.0 * c * x * y * z / r5,
        -3.0 * c * x * x * z / r5,
        c * (-3.0 * x * x * y / r5
            + m * (-y / (rho * a2) + x * x * y / (r3 * a2) + 2.0 * x * x * y / (rho * rho * a3))),
    ]
}

/// Gauss-Legendre nodes and weights on [-1, 1], `n` points (Newton's iteration on P_n from the
/// asymptotic first guess cos(pi (i - 1/4)/(n + 1/2)); Abramowitz & Stegun 25.4.29). Exact for
/// polynomials of degree 2n - 1. `n` >= 1.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    assert!(n >= 1, "a Gauss-Legendre rule needs a point");
    let mut rule = Vec::with_capacity(n);
    for i in 1..=n {
        let mut t = (PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // P_n(t) and P_n'(t) by the three-term recurrence
            let (mut p0, mut p1) = (1.0, t);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * t * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            // p1 = P_n, p0 = P_{n-1}; P_n' = n (t P_n - P_{n-1}) / (t^2 - 1)
            dp = n as f64 * (t * p1 - p0) / (t * t - 1.0);
            let step = p1 / dp;
            t -= step;
            if step.abs() < 1e-16 {
                break;
            }
        }
        rule.push((t, 2.0 / ((1.0 - t * t) * dp * dp)));
    }
    rule
}

/// Stress at (x, y, z) below a Hertz circular contact of radius `a` and peak pressure `p0`
/// (p = p0 sqrt(1 - r^2/a^2)) carrying a full-sliding traction q = `mu` p along +x, Pa, Voigt
/// order, tension positive, z > 0 the depth. The reference of the sliding sphere (Hamilton &
/// Goodman 1966; Hamilton 1983), computed here by quadrature of the exact point-load fields
/// ([`boussinesq_point`], [`cerruti_point`]) over the contact disc, so that it shares nothing with
/// the rectangle coefficients and the FFT of [`crate::stress`]:
///
/// sigma(x, y, z) = int_disc [p(xi, eta) G_B(x - xi, y - eta, z) + q(xi, eta) G_C(x - xi, y - eta, z)] dxi deta,
///
/// in polar coordinates about (x, y): along each ray, s = s1 + (s2 - s1)(1 - cos phi)/2 takes
/// out the square-root edges of the load and clusters nodes where the kernel peaks (s ~ z);
/// Gauss-Legendre in phi, and in theta the trapezoidal rule (periodic, for points above the
/// disc) or Gauss-Legendre with the same cosine map (the rays that hit the disc, for points
/// outside it). `n` nodes each way: 96 gives about 1e-9 p0 at z >= 0.05 a (tested against
/// Huber's axis and against 2n).
pub fn hertz_circle_stress(
    x: f64,
    y: f64,
    z: f64,
    a: f64,
    p0: f64,
    mu: f64,
    nu: f64,
    n: usize,
) -> [f64; 6] {
    let gl = gauss_legendre(n.max(1));
    let r0 = (x * x + y * y).sqrt();
    let mut out = [0.0; 6];
    // one ray at angle theta from (x, y), weight w_theta: adds int_{s1}^{s2} (...) s ds
    let mut ray = |theta: f64, w_theta: f64| {
        let (c, s) = (theta.cos(), theta.sin());
        let b = x * c + y * s;
        let disc = b * b - (r0 * r0 - a * a);
        if disc <= 0.0 {
            return;
        }
        let root = disc.sqrt();
        let (s1, s2) = ((-b - root).max(0.0), -b + root);
        if s2 <= s1 {
            return;
        }
        let half = 0.5 * (s2 - s1);
        for &(t, w) in &gl {
            let phi = 0.5 * PI * (t + 1.0);
            let sv = s1 + half * (1.0 - phi.cos());
            let jac = half * phi.sin() * 0.5 * PI * w;
            let (xi, eta) = (x + sv * c, y + sv * s);
            let p = p0 * (1.0 - (xi * xi + eta * eta) / (a * a)).max(0.0).sqrt();
            let gb = boussinesq_point(x - xi, y - eta, z, nu);
            let gc = cerruti_point(x - xi, y - eta, z, nu);
            let f = w_theta * jac * sv * p;
            for k in 0..6 {
                out[k] += f * (gb[k] + mu * gc[k]);
            }
        }
    };
    if r0 < a {
        let m = 2 * n;
        for i in 0..m {
            ray(2.0 * PI * i as f64 / m as f64, 2.0 * PI / m as f64);
        }
    } else {
        // the rays towards the disc: theta = theta_c - alpha cos(psi), psi in [0, pi]
        let theta_c = (-y).atan2(-x);
        let alpha = (a / r0).min(1.0).asin();
        for &(t, w) in &gl {
            let psi = 0.5 * PI * (t + 1.0);
            ray(
                theta_c - alpha * psi.cos(),
                alpha * psi.sin() * 0.5 * PI * w,
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stress::derived::{max_shear, von_mises};

    #[test]
    fn line_surface_values() {
        let (b, p0, mu, nu) = (1.0, 1.0, 0.2, 0.3);
        for &x in &[-0.9, -0.3, 0.0, 0.4, 0.8] {
            let s = hertz_line_stress(x, 0.0, b, p0, mu, nu);
            let p = p0 * (1.0 - x * x).sqrt();
            assert!((s[2] + p).abs() < 1e-12, "szz {x}");
            assert!((s[4] + mu * p).abs() < 1e-12, "sxz {x}");
            assert!(
                (s[0] - (-p - 2.0 * mu * p0 * x / b)).abs() < 1e-12,
                "sxx {x}"
            );
        }
        // outside the contact sigma_xx = -2 mu p0 (x/b -+ sqrt(x^2/b^2 - 1)) (Johnson 1985 sec. 7.1):
        // tension behind (2 mu p0 at the trailing edge), compression ahead
        for &x in &[-1.5, -1.0 - 1e-12, 1.5] {
            let s = hertz_line_stress(x, 0.0, b, p0, mu, nu);
            let want = -2.0 * mu * p0 * (x / b - x.signum() * (x * x / (b * b) - 1.0).sqrt());
            assert!((s[0] - want).abs() < 1e-6, "{x}: {} vs {want}", s[0]);
            assert!(s[2].abs() < 1e-12 && s[4].abs() < 1e-12);
        }
    }

    #[test]
    fn line_frictionless_maxima() {
        // Johnson sec. 4.2: max shear 0.300 p0 at z = 0.786 b; von Mises 0.557 p0 at 0.70 b;
        // |tau_xz| 0.250 p0 at x = 0.866 b, z = 0.5 b. The literature quotes three figures: the
        // tolerance is half a unit of the last one plus the 5e-4 b scan step.
        let (b, p0, nu) = (1.0, 1.0, 0.3);
        let (mut best_t, mut zt, mut best_v, mut zv) = (0.0, 0.0, 0.0, 0.0);
        for k in 1..4000 {
            let z = k as f64 * 5e-4;
            let s = hertz_line_stress(0.0, z, b, p0, 0.0, nu);
            if max_shear(&s) > best_t {
                (best_t, zt) = (max_shear(&s), z);
            }
            if von_mises(&s) > best_v {
                (best_v, zv) = (von_mises(&s), z);
            }
        }
        assert!(
            (best_t - 0.300).abs() < 5e-4 && (zt - 0.786).abs() < 1e-3,
            "{best_t} at {zt}"
        );
        assert!(
            (best_v - 0.557).abs() < 1e-3 && (zv - 0.70).abs() < 6e-3,
            "{best_v} at {zv}"
        );
        let s = hertz_line_stress(0.866, 0.5, b, p0, 0.0, nu);
        assert!((s[4].abs() - 0.250).abs() < 5e-4, "{}", s[4]);
    }

    #[test]
    fn gauss_legendre_is_exact_to_degree_2n_minus_1() {
        for n in [1, 2, 5, 12, 40] {
            let rule = gauss_legendre(n);
            for k in 0..=(2 * n) {
                let q: f64 = rule.iter().map(|&(t, w)| w * t.powi(k as i32)).sum();
                let exact = if k % 2 == 1 {
                    0.0
                } else {
                    2.0 / (k + 1) as f64
                };
                if k < 2 * n {
                    assert!((q - exact).abs() < 1e-13, "n {n}, t^{k}: {q} vs {exact}");
                } else if n <= 12 {
                    // (the error of t^2n falls like 4^-n: past n = 12 it is below round-off)
                    assert!(
                        (q - exact).abs() > 1e-12,
                        "n {n}: t^{k} should not be exact"
                    );
                }
            }
        }
    }

    #[test]
    fn point_loads_on_the_axis_are_their_limits() {
        // Boussinesq's sigma_xx = sigma_yy -> (1 - 2 nu)/(4 pi z^2) as r -> 0
        let (z, nu) = (0.7, 0.3);
        let axis = boussinesq_point(0.0, 0.0, z, nu);
        let near = boussinesq_point(1e-9, 2e-9, z, nu);
        for k in 0..6 {
            assert!(
                (axis[k] - near[k]).abs() < 1e-7,
                "{k}: {} vs {}",
                axis[k],
                near[k]
            );
        }
    }

    /// The quadrature of the frictionless circle on its axis is Huber's closed form, and off
    /// the axis, with sliding, it is settled: n and 2n nodes agree. This is what makes it a
    /// reference for the FFT stress of a sliding ball (tests/stress.rs).
    #[test]
    fn circle_quadrature_against_huber_and_itself() {
        let (a, p0, nu) = (1.0, 1.0, 0.3);
        for &z in &[0.05, 0.2, 0.48, 1.0, 2.5] {
            let s = hertz_circle_stress(0.0, 0.0, z, a, p0, 0.0, nu, 96);
            let (sr, sz) = hertz_circle_axis_stress(z, a, p0, nu);
            assert!(
                (s[0] - sr).abs() < 1e-9 && (s[1] - sr).abs() < 1e-9,
                "z {z}: {} vs {sr}",
                s[0]
            );
            assert!((s[2] - sz).abs() < 1e-9, "z {z}: {} vs {sz}", s[2]);
            assert!(s[3].abs() < 1e-9 && s[4].abs() < 1e-9 && s[5].abs() < 1e-9);
        }
        for &(x, y, z) in &[
            (0.3, -0.2, 0.1),
            (-0.8, 0.5, 0.3),
            (1.3, 0.4, 0.25),
            (-1.6, -0.9, 0.6),
        ] {
            let s1 = hertz_circle_stress(x, y, z, a, p0, 0.3, nu, 96);
            let s2 = hertz_circle_stress(x, y, z, a, p0, 0.3, nu, 192);
            for k in 0..6 {
                assert!(
                    (s1[k] - s2[k]).abs() < 1e-9,
                    "({x}, {y}, {z}) {k}: {} vs {}",
                    s1[k],
                    s2[k]
                );
            }
        }
    }

    #[test]
    fn sliding_circle_meets_its_surface_tractions() {
        // just below the contact, sigma_zz -> -p and tau_xz -> -mu p, tau_yz -> 0; outside the
        // contact all three vanish. Error O(z/a) from the load's variation over a depth.
        let (a, p0, mu, nu, z) = (1.0, 1.0, 0.3, 0.3, 2e-3);
        for &(x, y) in &[(0.0, 0.0), (0.4, -0.3), (-0.6, 0.2)] {
            let s = hertz_circle_stress(x, y, z, a, p0, mu, nu, 400);
            let p = p0 * (1.0 - (x * x + y * y) / (a * a)).sqrt();
            assert!(
                (s[2] + p).abs() < 1e-2 && (s[4] + mu * p).abs() < 1e-2 && s[3].abs() < 1e-2,
                "{s:?}"
            );
        }
        let s = hertz_circle_stress(1.4, 0.3, z, a, p0, mu, nu, 400);
        assert!(
            s[2].abs() < 1e-2 && s[4].abs() < 1e-2 && s[3].abs() < 1e-2,
            "{s:?}"
        );
    }

    #[test]
    fn circle_axis_von_mises_maximum() {
        // Johnson: |sigma_z - sigma_r| peaks at 0.62 p0 at z = 0.48 a (nu = 0.3)
        let (mut best, mut at) = (0.0, 0.0);
        for k in 1..3000 {
            let z = k as f64 * 1e-3;
            let (sr, sz) = hertz_circle_axis_stress(z, 1.0, 1.0, 0.3);
            if (sz - sr).abs() > best {
                (best, at) = ((sz - sr).abs(), z);
            }
        }
        assert!(
            (best - 0.62).abs() < 5e-3 && (at - 0.48).abs() < 1e-2,
            "{best} at {at}"
        );
    }
}
