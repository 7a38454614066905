//! Scalar measures of a stress tensor (Voigt order sigma_xx, sigma_yy, sigma_zz, tau_yz, tau_xz,
//! tau_xy; Pa; tension positive).

/// Von Mises equivalent stress sqrt(((s1 - s2)^2 + (s2 - s3)^2 + (s3 - s1)^2)/2
/// + 3 (tau_yz^2 + tau_xz^2 + tau_xy^2)) (Pa).
#[inline]
pub fn von_mises(s: &[f64; 6]) -> f64 {
    let [a, b, c, yz, xz, xy] = *s;
    (0.5 * ((a - b).powi(2) + (b - c).powi(2) + (c - a).powi(2))
        + 3.0 * (yz * yz + xz * xz + xy * xy))
        .sqrt()
}

/// Hydrostatic stress (s_xx + s_yy + s_zz) / 3 (Pa).
#[inline]
pub fn hydrostatic(s: &[f64; 6]) -> f64 {
    (s[0] + s[1] + s[2]) / 3.0
}

/// Principal stresses, descending (Pa): the eigenvalues of the symmetric tensor, by the
/// trigonometric solution of the characteristic cubic (Smith 1961), accurate to round-off of the
/// tensor's norm.
pub fn principal(s: &[f64; 6]) -> [f64; 3] {
    let [a, b, c, yz, xz, xy] = *s;
    let off = yz * yz + xz * xz + xy * xy;
    let m = (a + b + c) / 3.0;
    if off == 0.0 {
        let mut v = [a, b, c];
        v.sort_by(|x, y| y.total_cmp(x));
        return v;
    }
    let (da, db, dc) = (a - m, b - m, c - m);
    let p2 = (da * da + db * db + dc * dc + 2.0 * off) / 6.0;
    let p = p2.sqrt();
    if p == 0.0 {
        return [m; 3];
    }
    // det((S - m I) / p) / 2
    let det = da * (db * dc - yz * yz) - xy * (xy * dc - yz * xz) + xz * (xy * yz - db * xz);
    let r = (det / (2.0 * p2 * p)).clamp(-1.0, 1.0);
    let phi = r.acos() / 3.0;
    let e1 = m + 2.0 * p * phi.cos();
    let e3 = m + 2.0 * p * (phi + 2.0 * std::f64::consts::PI / 3.0).cos();
    [e1, 3.0 * m - e1 - e3, e3]
}

/// Maximum shear stress (s_1 - s_3) / 2 (Pa), the Tresca measure.
#[inline]
pub fn max_shear(s: &[f64; 6]) -> f64 {
    let p = principal(s);
    0.5 * (p[0] - p[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn principal_of_a_rotated_diagonal_tensor() {
        // R diag(3, -1, 0.5) R^T for a rotation about (1, 2, 2)/3 by 0.7 rad
        let d = [3.0, -1.0, 0.5];
        let (ux, uy, uz) = (1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0);
        let (c, s) = (0.7f64.cos(), 0.7f64.sin());
        let r = [
            [
                c + ux * ux * (1.0 - c),
                ux * uy * (1.0 - c) - uz * s,
                ux * uz * (1.0 - c) + uy * s,
            ],
            [
                uy * ux * (1.0 - c) + uz * s,
                c + uy * uy * (1.0 - c),
                uy * uz * (1.0 - c) - ux * s,
            ],
            [
                uz * ux * (1.0 - c) - uy * s,
                uz * uy * (1.0 - c) + ux * s,
                c + uz * uz * (1.0 - c),
            ],
        ];
        let t = |i: usize, j: usize| (0..3).map(|k| r[i][k] * d[k] * r[j][k]).sum::<f64>();
        let s6 = [t(0, 0), t(1, 1), t(2, 2), t(1, 2), t(0, 2), t(0, 1)];
        let p = principal(&s6);
        for (a, b) in p.iter().zip([3.0, 0.5, -1.0]) {
            assert!((a - b).abs() < 1e-13, "{p:?}");
        }
        assert!((max_shear(&s6) - 2.0).abs() < 1e-13);
        // von Mises is invariant
        assert!((von_mises(&s6) - von_mises(&[3.0, -1.0, 0.5, 0.0, 0.0, 0.0])).abs() < 1e-13);
    }
}
