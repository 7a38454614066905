//! Legendre-Gauss-Lobatto collocation on the film coordinate zeta = z / h in [0, 1].
//!
//! The nz points are the end points 0 and 1 and the nz - 2 roots of P'_{N} (N = nz - 1,
//! P_N the Legendre polynomial, mapped from [-1, 1] by zeta = (1 + x) / 2), found by Newton's
//! iteration on the three-term recurrence (Canuto, Hussaini, Quarteroni & Zang 2006,
//! *Spectral Methods: Fundamentals in Single Domains*, sec. 2.3; the iteration of von
//! Winckel's `lglnodes`). On this set:
//!
//! * quadrature weights w_k = 1 / (N (N + 1) P_N(x_k)^2) (the [-1, 1] weights 2 / (N (N + 1)
//!   P_N^2) halved by the map): exact for polynomials of degree <= 2 nz - 3;
//! * the first differentiation matrix from the barycentric weights
//!   lambda_j = 1 / prod_{m != j} (zeta_j - zeta_m): D_ij = (lambda_j / lambda_i) / (zeta_i - zeta_j),
//!   D_ii = -sum_{j != i} D_ij (Berrut & Trefethen 2004, SIAM Rev. 46, eq. 9.4; the "negative sum
//!   trick" makes every row sum exactly zero, so constants are differentiated to exactly 0);
//! * the second: D2_ij = 2 D_ij (D_ii - 1 / (zeta_i - zeta_j)), D2_ii = -sum_{j != i} D2_ij
//!   (Baltensperger & Trummer 2003, SIAM J. Sci. Comput. 24);
//!   both exact for polynomials of degree <= nz - 1;
//! * the cumulative integral C_ij = int_0^{zeta_i} l_j(s) ds (l_j the Lagrange basis), so that
//!   (C f)_i = int_0^{zeta_i} f: computed with the Lobatto rule itself on [0, zeta_i]
//!   (l_j has degree nz - 1 <= 2 nz - 3, so the rule is exact); exact for polynomials of degree
//!   <= nz - 1, and the last row is the quadrature weights.
//!
//! Matrices are row-major `nz x nz`.

// index loops over collocation points read like the equations
#![allow(clippy::needless_range_loop)]

/// Lobatto points, weights and differentiation / integration matrices on [0, 1].
#[derive(Debug, Clone)]
pub struct Lobatto {
    nz: usize,
    /// points zeta_k, ascending, zeta_0 = 0, zeta_{nz-1} = 1
    pub points: Vec<f64>,
    /// quadrature weights (sum 1)
    pub weights: Vec<f64>,
    /// barycentric weights lambda_j
    pub bary: Vec<f64>,
    /// first derivative d/dzeta, row-major nz x nz
    pub d1: Vec<f64>,
    /// second derivative d2/dzeta2, row-major nz x nz
    pub d2: Vec<f64>,
    /// cumulative integral int_0^{zeta_i}, row-major nz x nz
    pub cumulative: Vec<f64>,
}

impl Lobatto {
    /// The rule with `nz` points (nz >= 2; nz = 2 is the trapezoidal rule with linear
    /// interpolation, which has no interior point).
    pub fn new(nz: usize) -> Lobatto {
        assert!(nz >= 2, "Lobatto collocation needs at least 2 points");
        let n = nz - 1;
        // Newton on (1 - x^2) P'_N = N (P_{N-1} - x P_N), from the Chebyshev-Lobatto guess
        let mut x: Vec<f64> = (0..nz)
            .map(|j| (std::f64::consts::PI * j as f64 / n as f64).cos())
            .collect();
        let legendre = |x: f64| -> (f64, f64) {
            // (P_N(x), P_{N-1}(x))
            let (mut p0, mut p1) = (1.0, x);
            if n == 0 {
                return (1.0, 0.0);
            }
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            (p1, p0)
        };
        for xj in x.iter_mut().take(n).skip(1) {
            for _ in 0..100 {
                let (pn, pn1) = legendre(*xj);
                let dx = (*xj * pn - pn1) / ((n + 1) as f64 * pn);
                *xj -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
        }
        x[0] = 1.0;
        x[n] = -1.0;
        // ascending zeta = (1 + x)/2; symmetrise so that the set is exactly symmetric
        let mut points: Vec<f64> = x.iter().rev().map(|&x| 0.5 * (1.0 + x)).collect();
        for j in 0..nz / 2 {
            let a = 0.5 * (points[j] + (1.0 - points[nz - 1 - j]));
            points[j] = a;
            points[nz - 1 - j] = 1.0 - a;
        }
        if nz % 2 == 1 {
            points[nz / 2] = 0.5;
        }
        points[0] = 0.0;
        points[n] = 1.0;
        let weights: Vec<f64> = points
            .iter()
            .map(|&z| {
                let (pn, _) = legendre(2.0 * z - 1.0);
                1.0 / ((n * (n + 1)) as f64 * pn * pn)
            })
            .collect();
        let bary: Vec<f64> = (0..nz)
            .map(|j| {
                1.0 / (0..nz)
                    .filter(|&m| m != j)
                    .map(|m| points[j] - points[m])
                    .product::<f64>()
            })
            .collect();
        let mut d1 = vec![0.0; nz * nz];
        let mut d2 = vec![0.0; nz * nz];
        for i in 0..nz {
            let (mut s1, mut s2) = (0.0, 0.0);
            for j in 0..nz {
                if i != j {
                    d1[i * nz + j] = (bary[j] / bary[i]) / (points[i] - points[j]);
                    s1 += d1[i * nz + j];
                }
            }
            d1[i * nz + i] = -s1;
            for j in 0..nz {
                if i != j {
                    d2[i * nz + j] =
                        2.0 * d1[i * nz + j] * (d1[i * nz + i] - 1.0 / (points[i] - points[j]));
                    s2 += d2[i * nz + j];
                }
            }
            d2[i * nz + i] = -s2;
        }
        let mut rule = Lobatto {
            nz,
            points,
            weights,
            bary,
            d1,
            d2,
            cumulative: vec![0.0; nz * nz],
        };
        let mut basis = vec![0.0; nz];
        for i in 0..nz {
            let zi = rule.points[i];
            for m in 0..nz {
                rule.lagrange(zi * rule.points[m], &mut basis);
                for j in 0..nz {
                    rule.cumulative[i * nz + j] += zi * rule.weights[m] * basis[j];
                }
            }
        }
        // the last row is the rule itself (exactly, rather than to rounding)
        let w = rule.weights.clone();
        rule.cumulative[(nz - 1) * nz..].copy_from_slice(&w);
        rule
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.nz
    }

    /// Always false (a rule has at least two points).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The Lagrange basis l_j(s), j = 0..nz, at `s` (barycentric formula, second form).
    pub fn lagrange(&self, s: f64, out: &mut [f64]) {
        if let Some(m) = self.points.iter().position(|&z| z == s) {
            out.iter_mut().for_each(|v| *v = 0.0);
            out[m] = 1.0;
            return;
        }
        let mut den = 0.0;
        for j in 0..self.nz {
            out[j] = self.bary[j] / (s - self.points[j]);
            den += out[j];
        }
        out.iter_mut().for_each(|v| *v /= den);
    }

    /// The interpolant of the nodal values `f` at `s`.
    pub fn interpolate(&self, f: &[f64], s: f64) -> f64 {
        let mut b = vec![0.0; self.nz];
        self.lagrange(s, &mut b);
        b.iter().zip(f).map(|(a, b)| a * b).sum()
    }

    /// int_0^1 f dzeta by the rule.
    pub fn integrate(&self, f: &[f64]) -> f64 {
        self.weights.iter().zip(f).map(|(w, f)| w * f).sum()
    }

    /// out = M f for a row-major nz x nz matrix `m` (one of the fields).
    pub fn apply(&self, m: &[f64], f: &[f64], out: &mut [f64]) {
        let n = self.nz;
        for i in 0..n {
            out[i] = m[i * n..(i + 1) * n]
                .iter()
                .zip(f)
                .map(|(a, b)| a * b)
                .sum();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// zeta^p at the points
    fn mono(r: &Lobatto, p: i32) -> Vec<f64> {
        r.points.iter().map(|z| z.powi(p)).collect()
    }

    /// Tolerance: every operation is exact in exact arithmetic for the degrees tested; the
    /// residue is rounding, which grows like the matrices' norms (D ~ nz^2, D2 ~ nz^4, here
    /// at most ~ 2e4 for nz = 17) times 1e-16, so 1e-11 absolute on O(1) values (with an
    /// extra nz^2 for D2) can only be missed by a wrong formula.
    #[test]
    fn exact_for_polynomials() {
        for nz in [2usize, 3, 4, 5, 7, 9, 13, 17] {
            let r = Lobatto::new(nz);
            assert_eq!(r.points[0], 0.0);
            assert_eq!(r.points[nz - 1], 1.0);
            let scale = (nz * nz) as f64;
            // quadrature, degree <= 2 nz - 3
            for p in 0..=(2 * nz as i32 - 3) {
                let q = r.integrate(&mono(&r, p));
                assert!(
                    (q - 1.0 / (p + 1) as f64).abs() < 1e-14,
                    "nz {nz} p {p}: {q}"
                );
            }
            // and not beyond (the rule's degree is what it claims): a test that can fail
            // (2 zeta - 1)^p, p even, integrates to 1 / (p + 1); (x^p on [-1, 1], whose Lobatto
            // error is (N! stuff) ~ 4^-N: 7e-3 at nz = 5, 4e-10 at nz = 17; zeta^p would hide it
            // behind a further 2^-p)
            let p = 2 * nz as i32 - 2;
            let f: Vec<f64> = r.points.iter().map(|z| (2.0 * z - 1.0).powi(p)).collect();
            let q = r.integrate(&f);
            assert!(
                (q - 1.0 / (p + 1) as f64).abs() > 1e-10,
                "nz {nz}: degree too high?"
            );
            let mut out = vec![0.0; nz];
            for p in 0..nz as i32 {
                let f = mono(&r, p);
                r.apply(&r.d1, &f, &mut out);
                for (k, z) in r.points.iter().enumerate() {
                    let exact = if p == 0 {
                        0.0
                    } else {
                        p as f64 * z.powi(p - 1)
                    };
                    assert!((out[k] - exact).abs() < 1e-11 * scale, "D1 nz {nz} p {p}");
                }
                r.apply(&r.d2, &f, &mut out);
                for (k, z) in r.points.iter().enumerate() {
                    let exact = if p < 2 {
                        0.0
                    } else {
                        (p * (p - 1)) as f64 * z.powi(p - 2)
                    };
                    assert!(
                        (out[k] - exact).abs() < 1e-11 * scale * scale,
                        "D2 nz {nz} p {p}: {} vs {exact}",
                        out[k]
                    );
                }
                r.apply(&r.cumulative, &f, &mut out);
                for (k, z) in r.points.iter().enumerate() {
                    let exact = z.powi(p + 1) / (p + 1) as f64;
                    assert!((out[k] - exact).abs() < 1e-13, "C nz {nz} p {p}");
                }
            }
        }
    }

    /// The cumulative integral of a smooth non-polynomial function converges spectrally:
    /// int_0^zeta exp(2 s) ds with 13 points to 1e-10 (the interpolation error of exp(2 s)
    /// with 13 points is ~ 2^13 / 13! ~ 1e-6 times the node polynomial, ~ 1e-12 in practice).
    #[test]
    fn cumulative_of_exponential() {
        let r = Lobatto::new(13);
        let f: Vec<f64> = r.points.iter().map(|z| (2.0 * z).exp()).collect();
        let mut out = vec![0.0; 13];
        r.apply(&r.cumulative, &f, &mut out);
        for (k, z) in r.points.iter().enumerate() {
            let exact = 0.5 * ((2.0 * z).exp() - 1.0);
            assert!((out[k] - exact).abs() < 1e-10, "{k}: {} vs {exact}", out[k]);
        }
    }
}
