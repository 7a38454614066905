//! Influence coefficients of the stress in a half-space: the six stress components at depth z
//! caused by a uniform normal pressure and by a uniform tangential (x) traction on one surface
//! cell.
//!
//! # Half-space, rectangular cell (3D)
//!
//! The Boussinesq-Cerruti potentials (Love 1929; Johnson 1985, *Contact Mechanics*, sec. 3.2,
//! eq. 3.5-3.7) write every displacement, hence every stress, through derivatives of one
//! integral over the loaded area,
//!
//! I(x, y, z) = int int Omega(x - x', y - y', z) dx' dy',   Omega = z ln(rho + z) - rho,
//!
//! with rho = sqrt(xi^2 + eta^2 + z^2). Applying Hooke's law to Johnson's displacements and
//! using that Omega is harmonic gives, for a pressure p (compression positive) and, separately,
//! a traction q along +x on the body's surface (`I_abc` = d^(a+b+c) I / dx^a dy^b dz^c; stresses
//! positive in tension, z depth into the body):
//!
//! | stress x 2 pi / load | normal p | tangential q |
//! | --- | --- | --- |
//! | sigma_xx | -I_xxz - 2 nu I_yyz - z I_xxzz | 2 I_xzz - 2 nu I_xyy + z (I_xyyz + I_xzzz) |
//! | sigma_yy | -I_yyz - 2 nu I_xxz - z I_yyzz | 2 nu (I_xyy + I_xzz) - z I_xyyz |
//! | sigma_zz | -I_xxz - I_yyz + z (I_xxzz + I_yyzz) | -z I_xzzz |
//! | tau_yz | -z I_yzzz | -z I_xyzz |
//! | tau_xz | -z I_xzzz | -I_xxz - I_yyz - z I_xxzz |
//! | tau_xy | -(1 - 2 nu) I_xyz - z I_xyzz | 2 nu I_xxy + I_yzz - z I_xxyz |
//!
//! (derived symbolically from Johnson's eq. 3.7 and checked there against Navier's equations,
//! the traction-free surface outside the load and the resultant force; the tests here check the
//! coded kernels the same way, and against Holl's corner formula and the point-load solutions.)
//!
//! For a uniformly loaded rectangle every `I_abc` with a, b >= 1 is a signed sum over the four
//! corners of d^(a-1)(b-1)c Omega; the others follow from harmonicity. The corner functions
//! (xi = x - x', eta = y - y'; s_x = sqrt(xi^2 + z^2), s_y = sqrt(eta^2 + z^2)) are
//!
//! | I_ | corner function | I_ | corner function |
//! | --- | --- | --- | --- |
//! | xxz | atan(xi eta (rho - z) / (xi^2 rho + z eta^2)) | xxzz | -xi eta / (s_x^2 rho) |
//! | yyz | atan(xi eta (rho - z) / (eta^2 rho + z xi^2)) | yyzz | -xi eta / (s_y^2 rho) |
//! | xyz | ln(rho + z) | xzzz | -eta z / (s_x^2 rho) |
//! | xyy | -eta / (rho + z) | yzzz | -xi z / (s_y^2 rho) |
//! | xxy | -xi / (rho + z) | xyzz | 1 / rho |
//! | xzz | asinh(eta / s_x) | xyyz | eta / (rho (rho + z)) |
//! | yzz | asinh(xi / s_y) | xxyz | xi / (rho (rho + z)) |
//!
//! where terms that depend on one of xi, eta only (they cancel in the corner sum) are dropped,
//! which gives each function a definite parity in xi and in eta: a table over one quadrant
//! serves all four. The forms are free of cancellation (rho - z = (xi^2 + eta^2)/(rho + z);
//! asinh replaces ln(eta + rho)). The corner sum over the cell [x'_1, x'_2] x [y'_1, y'_2] is
//! F(x - x'_1, y - y'_1) - F(x - x'_1, y - y'_2) - F(x - x'_2, y - y'_1) + F(x - x'_2, y - y'_2).
//!
//! # Plane strain, strip (2D, infinite line contact)
//!
//! Integrating Flamant's solutions (Johnson eq. 2.15, 2.19) over a strip x' in [x'_1, x'_2]
//! gives F(x - x'_1) - F(x - x'_2) with (u = x - x', r^2 = u^2 + z^2)
//!
//! | | normal p | tangential q |
//! | --- | --- | --- |
//! | sigma_xx pi / load | -atan(u/z) + u z / r^2 | -ln(r^2) - z^2 / r^2 |
//! | sigma_zz pi / load | -atan(u/z) - u z / r^2 | z^2 / r^2 |
//! | tau_xz pi / load | z^2 / r^2 | -atan(u/z) + u z / r^2 |
//!
//! and sigma_yy = nu (sigma_xx + sigma_zz), tau_xy = tau_yz = 0.

use std::f64::consts::PI;

/// Stress components in the order used throughout [`crate::stress`]:
/// sigma_xx, sigma_yy, sigma_zz, tau_yz, tau_xz, tau_xy (Voigt order).
pub const COMPONENTS: [&str; 6] = ["sxx", "syy", "szz", "syz", "sxz", "sxy"];

/// The 14 corner functions of the module table, in this order:
/// xxz, yyz, xyz, xyy, xxy, xzz, yzz, xxzz, yyzz, xzzz, yzzz, xyzz, xyyz, xxyz.
const N_CORNER: usize = 14;

/// Parity of each corner function in (xi, eta): +1 even, -1 odd.
const PARITY: [(f64, f64); N_CORNER] = [
    (-1.0, -1.0), // xxz
    (-1.0, -1.0), // yyz
    (1.0, 1.0),   // xyz
    (1.0, -1.0),  // xyy
    (-1.0, 1.0),  // xxy
    (1.0, -1.0),  // xzz
    (-1.0, 1.0),  // yzz
    (-1.0, -1.0), // xxzz
    (-1.0, -1.0), // yyzz
    (1.0, -1.0),  // xzzz
    (-1.0, 1.0),  // yzzz
    (1.0, 1.0),   // xyzz
    (1.0, -1.0),  // xyyz
    (-1.0, 1.0),  // xxyz
];

/// The corner functions at (xi, eta, z), z > 0.
#[inline]
fn corner_functions(xi: f64, eta: f64, z: f64) -> [f64; N_CORNER] {
    corners(xi, eta, z, |_, sx2, sy2| {
        ((eta / sx2.sqrt()).asinh(), (xi / sy2.sqrt()).asinh())
    })
}

/// The corner functions at xi, eta > 0 (the quadrant of the layer tables), given
/// `half_ln_sx2` = ln(xi^2 + z^2) / 2 and `half_ln_sy2` = ln(eta^2 + z^2) / 2 (one per column,
/// one per row): asinh(eta / s_x) = ln(eta + rho) - ln s_x, exact since sqrt(1 + eta^2 / s_x^2)
/// = rho / s_x, and free of cancellation in the sum for eta > 0 (the difference has the
/// absolute round-off of the ln(rho + z) entry, ~1e-16 of its magnitude). Two logarithms in
/// place of two asinh (each a hypot and a ln_1p): 40 % of the table time.
#[inline]
fn corner_functions_quadrant(
    xi: f64,
    eta: f64,
    z: f64,
    half_ln_sx2: f64,
    half_ln_sy2: f64,
) -> [f64; N_CORNER] {
    corners(xi, eta, z, |rho, _, _| {
        (
            (eta + rho).ln() - half_ln_sx2,
            (xi + rho).ln() - half_ln_sy2,
        )
    })
}

/// The corner functions, with `xzz_yzz(rho, s_x^2, s_y^2)` giving asinh(eta / s_x) and
/// asinh(xi / s_y).
#[inline(always)]
fn corners(
    xi: f64,
    eta: f64,
    z: f64,
    xzz_yzz: impl FnOnce(f64, f64, f64) -> (f64, f64),
) -> [f64; N_CORNER] {
    let (x2, e2, z2) = (xi * xi, eta * eta, z * z);
    let rho = (x2 + e2 + z2).sqrt();
    let rz = rho + z;
    let rho_minus_z = (x2 + e2) / rz;
    let sx2 = x2 + z2;
    let sy2 = e2 + z2;
    let xe = xi * eta;
    let (xzz, yzz) = xzz_yzz(rho, sx2, sy2);
    // both arctangents vanish with xi eta (their denominators only at xi = eta = 0)
    let atan_over = |den: f64| {
        if xe == 0.0 {
            0.0
        } else {
            (xe * rho_minus_z / den).atan()
        }
    };
    [
        atan_over(x2 * rho + z * e2),
        atan_over(e2 * rho + z * x2),
        rz.ln(),
        -eta / rz,
        -xi / rz,
        xzz,
        yzz,
        -xe / (sx2 * rho),
        -xe / (sy2 * rho),
        -eta * z / (sx2 * rho),
        -xi * z / (sy2 * rho),
        1.0 / rho,
        eta / (rho * rz),
        xi / (rho * rz),
    ]
}

/// The six stress components (Voigt order, Pa per Pa of load) from the corner sums `d` of one
/// cell, for a unit normal pressure and a unit +x traction: `(normal, tangential)`.
#[inline]
fn combine(d: &[f64; N_CORNER], z: f64, nu: f64) -> ([f64; 6], [f64; 6]) {
    let [xxz, yyz, xyz, xyy, xxy, xzz, yzz, xxzz, yyzz, xzzz, yzzz, xyzz, xyyz, xxyz] = *d;
    let c = 0.5 / PI;
    let normal = [
        c * (-xxz - 2.0 * nu * yyz - z * xxzz),
        c * (-yyz - 2.0 * nu * xxz - z * yyzz),
        c * (-xxz - yyz + z * (xxzz + yyzz)),
        c * (-z * yzzz),
        c * (-z * xzzz),
        c * (-(1.0 - 2.0 * nu) * xyz - z * xyzz),
    ];
    let tangential = [
        c * (2.0 * xzz - 2.0 * nu * xyy + z * (xyyz + xzzz)),
        c * (2.0 * nu * (xyy + xzz) - z * xyyz),
        c * (-z * xzzz),
        c * (-z * xyzz),
        c * (-xxz - yyz - z * xxzz),
        c * (2.0 * nu * xxy + yzz - z * xxyz),
    ];
    (normal, tangential)
}

/// Stress at (x, y, z) (z > 0, depth) in a half-space of Poisson ratio `nu` due to a uniform
/// unit pressure (first) and a uniform unit +x traction (second) on the rectangle
/// [x1, x2] x [y1, y2] of its surface. Voigt order; Pa per Pa of load. Closed form: see the
/// module documentation.
pub fn rectangle(x: f64, y: f64, z: f64, rect: [f64; 4], nu: f64) -> ([f64; 6], [f64; 6]) {
    let [x1, x2, y1, y2] = rect;
    let mut d = [0.0; N_CORNER];
    for (xi, eta, s) in [
        (x - x1, y - y1, 1.0),
        (x - x1, y - y2, -1.0),
        (x - x2, y - y1, -1.0),
        (x - x2, y - y2, 1.0),
    ] {
        let f = corner_functions(xi, eta, z);
        for (dk, fk) in d.iter_mut().zip(f) {
            *dk += s * fk;
        }
    }
    combine(&d, z, nu)
}

/// Stress at (x, z) in plane strain due to a uniform unit pressure (first) and a uniform unit
/// +x traction (second) on the strip [x1, x2]: Voigt order, Pa per Pa of load.
pub fn strip(x: f64, z: f64, x1: f64, x2: f64, nu: f64) -> ([f64; 6], [f64; 6]) {
    let f = |u: f64| {
        let r2 = u * u + z * z;
        let at = (u / z).atan();
        let uz = u * z / r2;
        let zz = z * z / r2;
        // (sxx_n, szz_n, sxz_n, sxx_t, szz_t, sxz_t) times pi
        [-at + uz, -at - uz, zz, -r2.ln() - zz, zz, -at + uz]
    };
    let (a, b) = (f(x - x1), f(x - x2));
    let v: Vec<f64> = a.iter().zip(b).map(|(a, b)| (a - b) / PI).collect();
    let normal = [v[0], nu * (v[0] + v[1]), v[1], 0.0, v[2], 0.0];
    let tangential = [v[3], nu * (v[3] + v[4]), v[4], 0.0, v[5], 0.0];
    (normal, tangential)
}

/// Parity of each stress kernel (Voigt order; normal 0..6, tangential 6..12) in (di, dj): the
/// opposite of its corner functions' parity (the corner sum is a difference across the cell).
/// Checked for every offset by the tests.
pub const KERNEL_PARITY: [(f64, f64); 12] = [
    (1.0, 1.0),   // normal sxx
    (1.0, 1.0),   // normal syy
    (1.0, 1.0),   // normal szz
    (1.0, -1.0),  // normal syz
    (-1.0, 1.0),  // normal sxz
    (-1.0, -1.0), // normal sxy
    (-1.0, 1.0),  // tangential sxx
    (-1.0, 1.0),  // tangential syy
    (-1.0, 1.0),  // tangential szz
    (-1.0, -1.0), // tangential syz
    (1.0, 1.0),   // tangential sxz
    (1.0, -1.0),  // tangential sxy
];

/// Influence tables of one depth layer on a uniform grid of `nx` x `ny` cells of size
/// `dx` x `dy`: for every offset (di, dj), |di| < nx, |dj| < ny, the 6 + 6 stress coefficients at
/// the centre of cell (i, j) due to a unit load on cell (i - di, j - dj). `ny = 1` with an
/// infinite `dy` is the plane-strain strip. Stored over one quadrant (di, dj >= 0); the others
/// follow from each kernel's parity.
pub struct LayerKernel {
    nx: usize,
    ny: usize,
    /// [component 0..12][dj * nx + di], di, dj >= 0; components 0..6 normal, 6..12 tangential
    values: Vec<Vec<f64>>,
}

impl LayerKernel {
    /// Builds the tables for depth `z` (m), Poisson ratio `nu`.
    pub fn new(nx: usize, ny: usize, dx: f64, dy: f64, z: f64, nu: f64) -> Self {
        let mut values = vec![vec![0.0; nx * ny]; 12];
        if ny == 1 && !dy.is_finite() {
            for di in 0..nx {
                let (n, t) = strip(di as f64 * dx, z, -0.5 * dx, 0.5 * dx, nu);
                for k in 0..6 {
                    values[k][di] = n[k];
                    values[6 + k][di] = t[k];
                }
            }
            return LayerKernel { nx, ny, values };
        }
        // corner functions at the vertices xi = (k - 1/2) dx, eta = (l - 1/2) dy, k = 0..=nx,
        // l = 0..=ny (k = 0 is xi = -dx/2, l = 0 eta = -dy/2: the parity of each function gives
        // them from k = 1, l = 1), formed one vertex row at a time: two rows (l = dj, dj + 1)
        // give the cells of row dj, and the table stays in cache
        let vx = nx + 1;
        let half_ln = |t: f64| 0.5 * (t * t + z * z).ln();
        let lsx: Vec<f64> = (0..vx).map(|k| half_ln((k as f64 - 0.5) * dx)).collect();
        let vertex_row = |l: usize, row: &mut [[f64; N_CORNER]]| {
            let eta = (l as f64 - 0.5) * dy;
            let lsy = half_ln(eta);
            for k in 1..vx {
                row[k] = corner_functions_quadrant((k as f64 - 0.5) * dx, eta, z, lsx[k], lsy);
            }
            row[0] = std::array::from_fn(|f| PARITY[f].0 * row[1][f]);
        };
        let mut hi = vec![[0.0; N_CORNER]; vx];
        let mut lo = vec![[0.0; N_CORNER]; vx];
        vertex_row(1, &mut hi);
        for (v, s) in lo.iter_mut().zip(&hi) {
            *v = std::array::from_fn(|f| PARITY[f].1 * s[f]);
        }
        for dj in 0..ny {
            if dj > 0 {
                std::mem::swap(&mut lo, &mut hi);
                vertex_row(dj + 1, &mut hi);
            }
            for di in 0..nx {
                // the cell spans xi in [(di - 1/2) dx, (di + 1/2) dx]: vertices di, di + 1
                let (a, b, c, e) = (&hi[di + 1], &lo[di + 1], &hi[di], &lo[di]);
                let d: [f64; N_CORNER] = std::array::from_fn(|f| a[f] - b[f] - c[f] + e[f]);
                let (n, t) = combine(&d, z, nu);
                let at = dj * nx + di;
                for k in 0..6 {
                    values[k][at] = n[k];
                    values[6 + k][at] = t[k];
                }
            }
        }
        LayerKernel { nx, ny, values }
    }

    /// Coefficient of component `k` (0..6 normal, 6..12 tangential) at offset (di, dj).
    #[inline]
    pub fn get(&self, k: usize, di: isize, dj: isize) -> f64 {
        let (sx, sy) = KERNEL_PARITY[k];
        let s = if di < 0 { sx } else { 1.0 } * if dj < 0 { sy } else { 1.0 };
        s * self.values[k][dj.unsigned_abs() * self.nx + di.unsigned_abs()]
    }

    /// The quadrant di, dj >= 0 of component `k` (row-major, `nx` per row) and its parity in
    /// (di, dj).
    pub fn quadrant(&self, k: usize) -> (&[f64], (f64, f64)) {
        (&self.values[k], KERNEL_PARITY[k])
    }

    /// Grid size the table was built for.
    pub fn size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::subsurface::{boussinesq_point, cerruti_point};

    /// Holl's vertical stress under the corner of a uniformly loaded l x b rectangle.
    fn holl(l: f64, b: f64, z: f64) -> f64 {
        let r = (l * l + b * b + z * z).sqrt();
        -((l * b / (z * r)).atan()
            + l * b * z / r * (1.0 / (l * l + z * z) + 1.0 / (b * b + z * z)))
            / (2.0 * PI)
    }

    #[test]
    fn corner_stress_matches_holl() {
        for &(l, b, z) in &[(1.0, 2.0, 0.5), (0.3, 0.7, 2.0), (5.0, 1.0, 0.01)] {
            let (n, _) = rectangle(0.0, 0.0, z, [0.0, l, 0.0, b], 0.3);
            let h = holl(l, b, z);
            assert!((n[2] - h).abs() < 1e-14, "{} vs {h}", n[2]);
        }
    }

    #[test]
    fn far_field_matches_point_loads() {
        // a small cell seen from far away acts as a point load of its area; the error of the
        // point approximation is O((h / distance)^2) ~ 1e-5 here
        let (h, nu) = (1e-3, 0.3);
        for &(x, y, z) in &[(0.3, -0.2, 0.5), (0.1, 0.4, 0.3), (-0.5, 0.15, 0.2)] {
            let (n, t) = rectangle(x, y, z, [-h, h, -h, h], nu);
            let (bn, bt) = (boussinesq_point(x, y, z, nu), cerruti_point(x, y, z, nu));
            let scale = bn.iter().chain(&bt).fold(0.0_f64, |m, v| m.max(v.abs()));
            for k in 0..6 {
                let (gn, gt) = (n[k] / (4.0 * h * h), t[k] / (4.0 * h * h));
                assert!(
                    (gn - bn[k]).abs() < 1e-5 * scale,
                    "normal {k}: {gn} vs {}",
                    bn[k]
                );
                assert!(
                    (gt - bt[k]).abs() < 1e-5 * scale,
                    "tangential {k}: {gt} vs {}",
                    bt[k]
                );
            }
        }
    }

    #[test]
    fn surface_tractions_are_the_loads() {
        // just below the surface, inside the cell: sigma_zz = -p, tau_xz = -q, tau_yz = 0;
        // outside it: all three vanish. The error is O(z / cell size).
        let z = 1e-7;
        let rect = [-1.0, 1.0, -0.5, 0.5];
        let (n, t) = rectangle(0.3, 0.1, z, rect, 0.3);
        assert!((n[2] + 1.0).abs() < 1e-6 && n[4].abs() < 1e-6 && n[3].abs() < 1e-6);
        assert!((t[4] + 1.0).abs() < 1e-6 && t[2].abs() < 1e-6 && t[3].abs() < 1e-6);
        let (n, t) = rectangle(1.7, -0.9, z, rect, 0.3);
        for k in [2, 3, 4] {
            assert!(
                n[k].abs() < 1e-6 && t[k].abs() < 1e-6,
                "{k}: {} {}",
                n[k],
                t[k]
            );
        }
        let (n, t) = strip(0.3, z, -1.0, 1.0, 0.3);
        assert!((n[2] + 1.0).abs() < 1e-6 && n[4].abs() < 1e-6);
        assert!((t[4] + 1.0).abs() < 1e-6 && t[2].abs() < 1e-6);
    }

    #[test]
    fn rectangle_field_is_in_equilibrium() {
        // d sigma_ij / d x_j = 0 by central differences (error O(h^2) ~ 1e-8 of the stress)
        let rect = [-0.4, 0.6, -0.3, 0.2];
        let h = 1e-4;
        for &(x, y, z) in &[(0.1, 0.05, 0.2), (0.9, -0.4, 0.35), (-0.6, 0.5, 0.1)] {
            for which in 0..2 {
                let s = |x: f64, y: f64, z: f64| {
                    let (n, t) = rectangle(x, y, z, rect, 0.27);
                    if which == 0 {
                        n
                    } else {
                        t
                    }
                };
                let d = |k: usize, axis: usize| {
                    let mut p = [x, y, z];
                    let mut m = [x, y, z];
                    p[axis] += h;
                    m[axis] -= h;
                    (s(p[0], p[1], p[2])[k] - s(m[0], m[1], m[2])[k]) / (2.0 * h)
                };
                // Voigt: 0 xx, 1 yy, 2 zz, 3 yz, 4 xz, 5 xy
                let div = [
                    d(0, 0) + d(5, 1) + d(4, 2),
                    d(5, 0) + d(1, 1) + d(3, 2),
                    d(4, 0) + d(3, 1) + d(2, 2),
                ];
                for v in div {
                    assert!(v.abs() < 1e-6, "load {which} at ({x}, {y}, {z}): div = {v}");
                }
            }
        }
    }

    #[test]
    fn long_rectangle_tends_to_the_plane_strain_strip() {
        // a rectangle 2 x 2000 seen at its middle: the ends are 1000 away, O(z / L) = 1e-3
        let nu = 0.3;
        for &(x, z) in &[(0.2, 0.5), (1.4, 0.3), (-0.7, 1.5)] {
            let (n3, t3) = rectangle(x, 0.0, z, [-1.0, 1.0, -1000.0, 1000.0], nu);
            let (n2, t2) = strip(x, z, -1.0, 1.0, nu);
            for k in 0..6 {
                assert!(
                    (n3[k] - n2[k]).abs() < 2e-3,
                    "normal {k}: {} vs {}",
                    n3[k],
                    n2[k]
                );
                // sigma_xx of a tangential strip load has a logarithmic far field (the strip's
                // net force): a finite rectangle has it too, so compare sigma_xx at 1e-2
                let tol = if k == 0 || k == 1 { 1e-2 } else { 2e-3 };
                assert!(
                    (t3[k] - t2[k]).abs() < tol,
                    "tangential {k}: {} vs {}",
                    t3[k],
                    t2[k]
                );
            }
        }
    }

    #[test]
    fn layer_table_is_the_strip_formula() {
        let (nx, dx, z, nu) = (6, 0.3, 0.2, 0.3);
        let k = LayerKernel::new(nx, 1, dx, f64::INFINITY, z, nu);
        for di in -5..6isize {
            let (n, t) = strip(di as f64 * dx, z, -0.5 * dx, 0.5 * dx, nu);
            for c in 0..6 {
                assert!((k.get(c, di, 0) - n[c]).abs() < 1e-14, "n{c} {di}");
                assert!((k.get(6 + c, di, 0) - t[c]).abs() < 1e-14, "t{c} {di}");
            }
        }
    }

    #[test]
    fn layer_table_is_the_rectangle_formula() {
        // the quadrant table with parity reproduces direct corner sums for every offset sign
        let (nx, ny, dx, dy, z, nu) = (5, 4, 0.3, 0.5, 0.2, 0.3);
        let k = LayerKernel::new(nx, ny, dx, dy, z, nu);
        for dj in -3..4isize {
            for di in -4..5isize {
                let (x, y) = (di as f64 * dx, dj as f64 * dy);
                let (n, t) = rectangle(x, y, z, [-0.5 * dx, 0.5 * dx, -0.5 * dy, 0.5 * dy], nu);
                for c in 0..6 {
                    assert!((k.get(c, di, dj) - n[c]).abs() < 1e-13, "n{c} {di} {dj}");
                    assert!(
                        (k.get(6 + c, di, dj) - t[c]).abs() < 1e-13,
                        "t{c} {di} {dj}"
                    );
                }
            }
        }
    }

    /// The tangential sigma_zz table is the normal tau_xz table bit for bit (both -z I_xzzz /
    /// 2 pi; plane strain z^2 / (pi r^2)): the field computes one spectrum for both.
    #[test]
    fn tangential_szz_is_normal_sxz() {
        for k in [
            LayerKernel::new(7, 5, 0.3, 0.5, 0.2, 0.3),
            LayerKernel::new(9, 1, 0.3, f64::INFINITY, 0.2, 0.3),
        ] {
            assert_eq!(k.quadrant(4), k.quadrant(8));
        }
    }

    /// The quadrant form of the corner functions (logarithms in place of asinh) is the general
    /// one to f64 round-off, over offsets from 1e-3 to 1e3 depths.
    #[test]
    fn quadrant_corner_functions_are_the_general_ones() {
        let z = 0.7;
        for &xi in &[1e-3, 0.05, 0.7, 3.0, 40.0, 700.0] {
            for &eta in &[2e-3, 0.3, 1.1, 25.0, 900.0] {
                let h = |t: f64| 0.5 * (t * t + z * z).ln();
                let a = corner_functions_quadrant(xi, eta, z, h(xi), h(eta));
                let b = corner_functions(xi, eta, z);
                for f in 0..N_CORNER {
                    let tol = 4e-16 * (1.0 + b[f].abs() + (xi + eta + z).ln().abs());
                    assert!(
                        (a[f] - b[f]).abs() <= tol,
                        "{f} at ({xi}, {eta}): {} vs {}",
                        a[f],
                        b[f]
                    );
                }
            }
        }
    }
}
