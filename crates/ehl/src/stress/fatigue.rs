//! Rolling-contact fatigue indicator: the Ioannides-Harris stress-weighted volume integral and
//! the life ratio against a reference (smooth) surface.
//!
//! Ioannides & Harris (1985, J. Tribol. 107, 367-378), from Lundberg & Palmgren (1947):
//!
//! ln(1/S) = A N^e int_V <sigma_eq - sigma_u>^c / z^h dV,
//!
//! with S the survival probability after N cycles, <.> the Macaulay bracket (zero below the
//! fatigue limit sigma_u), e the Weibull slope, c the stress exponent and h the depth exponent.
//! At equal survival, lives scale as N ∝ I^(-1/e), so the life of a surface against a reference
//! at the same conditions is
//!
//! L / L_ref = (I_ref / I)^(1/e),
//!
//! in which the unknown material constant A cancels. Defaults: e = 1.1 (Lundberg-Palmgren /
//! Ioannides-Harris for point and line contacts lie at 10/9 and 9/8), c = 31/3 (Lundberg &
//! Palmgren 1947), h = 0 (the volume integral localises the risk itself), sigma_u = 0 (ISO
//! 281:2007 uses a von Mises limit of 900 MPa for bearing steel at p0 = 1.5 GPa), and von Mises as
//! the equivalent stress, the common choice in the surface-defect literature
//! (docs/stress.md).
//!
//! The integral is a sum over the stress grid's cells: each point (i, j, k) stands for the volume
//! dx dy dz_k, dz_k reaching half-way to its neighbouring layers (the first from the surface).
//! The stress enters over [`REFERENCE_STRESS`] (1 GPa) and the depth over [`REFERENCE_DEPTH`]
//! (1 mm), so that the integral is a volume:
//!
//! I = sum <(sigma_eq - sigma_u) / 1 GPa>^c (z / 1 mm)^(-h) dV    (m^3; a line contact: m^2 per
//! metre of length).
//!
//! The constants cancel in the life ratio and keep the integral within floating point: in Pa^c
//! it overflowed from c ~ 31 on a contact at a few GPa (a scan: "summary figure
//! 'fatigue_integral' is not finite" after the whole solve), and z^(-h) in metres from h ~ 50.

use serde::Serialize;

/// The equivalent stress of the integral.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Criterion {
    /// von Mises equivalent stress
    VonMises,
    /// |tau_xz|, the orthogonal shear of Lundberg & Palmgren
    OrthogonalShear,
    /// (sigma_1 - sigma_3) / 2
    MaxShear,
}

/// Parameters of the integral (`[fatigue]`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Params {
    pub criterion: Criterion,
    /// sigma_u (Pa)
    pub fatigue_limit: f64,
    /// e
    pub weibull_slope: f64,
    /// c
    pub stress_exponent: f64,
    /// h
    pub depth_exponent: f64,
    /// `fatigue.dang_van`: the Dang Van indicator over the passage of a transient run
    /// ([`super::passage`]); None: not computed
    pub dang_van: Option<super::passage::DangVan>,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            criterion: Criterion::VonMises,
            fatigue_limit: 0.0,
            weibull_slope: 1.1,
            stress_exponent: 31.0 / 3.0,
            depth_exponent: 0.0,
            dang_van: None,
        }
    }
}

/// The stress the integral's equivalent stress is measured in (Pa): 1 GPa.
pub const REFERENCE_STRESS: f64 = 1e9;

/// The depth the integral's depth weight is measured in (m): 1 mm.
pub const REFERENCE_DEPTH: f64 = 1e-3;

/// Thickness of each layer's slice of volume: from half-way to the layer above (the surface for
/// the first) to half-way to the layer below (the last reaches as far below as half its spacing).
pub fn layer_thickness(z: &[f64]) -> Vec<f64> {
    let n = z.len();
    (0..n)
        .map(|k| {
            let top = if k == 0 { 0.0 } else { 0.5 * (z[k - 1] + z[k]) };
            let bottom = if k + 1 < n {
                0.5 * (z[k] + z[k + 1])
            } else if n > 1 {
                z[k] + 0.5 * (z[k] - z[k - 1])
            } else {
                z[k]
            };
            bottom - top
        })
        .collect()
}

/// The Ioannides-Harris integral (see the module doc: stress over 1 GPa, depth over 1 mm; m^3)
/// of the equivalent stress `eq` (Pa, one value per point, index `(k * ny + j) * nx + i`) at the
/// depths `z` (m), on cells of area `cell_area` (m^2; a line contact: dx times 1 m). Infinite
/// only for exponents far outside the literature's (c of 100 at 1000 GPa).
pub fn integral(eq: &[f32], z: &[f64], cell_area: f64, params: &Params) -> f64 {
    let plane = eq.len() / z.len().max(1);
    let dz = layer_thickness(z);
    let mut total = 0.0;
    for (k, slice) in eq.chunks(plane).enumerate() {
        let weight = cell_area * dz[k] / (z[k] / REFERENCE_DEPTH).powf(params.depth_exponent);
        let s: f64 = slice
            .iter()
            .map(|&v| {
                let excess = (v as f64 - params.fatigue_limit) / REFERENCE_STRESS;
                if excess > 0.0 {
                    excess.powf(params.stress_exponent)
                } else {
                    0.0
                }
            })
            .sum();
        total += weight * s;
    }
    total
}

/// Life against the reference: (I_ref / I)^(1/e); infinite when I = 0 < I_ref, 1 when both are 0.
pub fn life_ratio(reference: f64, integral: f64, weibull_slope: f64) -> f64 {
    if integral == 0.0 {
        return if reference == 0.0 { 1.0 } else { f64::INFINITY };
    }
    (reference / integral).powf(1.0 / weibull_slope)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thickness_sums_to_the_depth_reached() {
        let z = [0.1, 0.3, 0.7, 1.5];
        let t = layer_thickness(&z);
        assert!((t.iter().sum::<f64>() - (1.5 + 0.4)).abs() < 1e-12);
    }

    #[test]
    fn zero_below_the_limit_and_power_law_above() {
        let z = [1.0, 2.0];
        let eq = [1.0e9_f32, 2.0e9, 0.5e9, 3.0e9];
        let p = Params {
            fatigue_limit: 5e9,
            ..Params::default()
        };
        assert_eq!(integral(&eq, &z, 1.0, &p), 0.0);
        // c = 1, h = 0, limit 0: sum of (v / 1 GPa) dV with dz = [1.5, 1.0]
        let p = Params {
            stress_exponent: 1.0,
            ..Params::default()
        };
        let want = 1.5 * 3.0 + 1.0 * 3.5;
        assert!((integral(&eq, &z, 1.0, &p) - want).abs() < 1e-12);
        // h = 1: each layer weighed by (z / 1 mm)^-1
        let p = Params {
            stress_exponent: 1.0,
            depth_exponent: 1.0,
            ..Params::default()
        };
        let want = 1.5 * 3.0 / 1e3 + 1.0 * 3.5 / 2e3;
        assert!((integral(&eq, &z, 1.0, &p) - want).abs() < 1e-12 * want);
        assert_eq!(life_ratio(2.0, 2.0, 1.1), 1.0);
        assert!((life_ratio(2.0, 1.0, 1.0) - 2.0).abs() < 1e-15);
    }
}
