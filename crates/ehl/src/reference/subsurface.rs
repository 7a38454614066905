//! Closed-form stress fields below Hertz contacts, the references of [`crate::stress`].
//!
//! Conventions as in [`crate::stress`]: tension positive, z depth into the body, Voigt order
//! (sigma_xx, sigma_yy, sigma_zz, tau_yz, tau_xz, tau_xy), the tangential traction q = mu p acts
//! on the body along +x.


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
    let sxx = -k * (m * (1.0 + (z * z + n * n) / d) - 2.0 * z) + kt * (n * (2.0 - (z * z - m * m) / d) - 2.0 * x);
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
            assert!((s[0] - (-p - 2.0 * mu * p0 * x / b)).abs() < 1e-12, "sxx {x}");
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
        assert!((best_t - 0.300).abs() < 5e-4 && (zt - 0.786).abs() < 1e-3, "{best_t} at {zt}");
        assert!((best_v - 0.557).abs() < 1e-3 && (zv - 0.70).abs() < 6e-3, "{best_v} at {zv}");
        let s = hertz_line_stress(0.866, 0.5, b, p0, 0.0, nu);
        assert!((s[4].abs() - 0.250).abs() < 5e-4, "{}", s[4]);
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
        assert!((best - 0.62).abs() < 5e-3 && (at - 0.48).abs() < 1e-2, "{best} at {at}");
    }
}
