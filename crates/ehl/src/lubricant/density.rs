//! Pressure-density laws (isothermal).

use super::{DensityModel, Lubricant};

/// Dowson-Higginson constants (thesis eq. 2.10): rho = rho0 (C1 + C2 p) / (C1 + p).
const DH_C1: f64 = 0.59e9; // Pa
const DH_C2: f64 = 1.34;

/// Density (kg/m^3) at pressure `p` (Pa).
///
/// Dowson-Higginson (thesis eq. 2.10): rho(p) = rho0 (0.59e9 + 1.34 p) / (0.59e9 + p), which
/// tends to 1.34 rho0 at high pressure. Negative pressures are treated as ambient.
pub fn density(lub: &Lubricant, p: f64) -> f64 {
    lub.density * relative_density(lub.density_model, p)
}

/// rho / rho0 at pressure `p` (Pa).
#[inline]
pub fn relative_density(model: DensityModel, p: f64) -> f64 {
    match model {
        DensityModel::Constant => 1.0,
        DensityModel::DowsonHigginson => {
            let p = p.max(0.0);
            (DH_C1 + DH_C2 * p) / (DH_C1 + p)
        }
    }
}

/// d(rho/rho0)/dp (1/Pa): C1 (C2 - 1) / (C1 + p)^2 for Dowson-Higginson, 0 for constant.
#[inline]
pub fn relative_density_derivative(model: DensityModel, p: f64) -> f64 {
    match model {
        DensityModel::Constant => 0.0,
        DensityModel::DowsonHigginson => {
            if p < 0.0 {
                0.0
            } else {
                DH_C1 * (DH_C2 - 1.0) / ((DH_C1 + p) * (DH_C1 + p))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dowson_higginson_limits_and_derivative() {
        let m = DensityModel::DowsonHigginson;
        assert_eq!(relative_density(m, 0.0), 1.0);
        assert_eq!(relative_density(m, -1e8), 1.0);
        // 1 GPa: (0.59 + 1.34) / 1.59 = 1.2138...
        assert!((relative_density(m, 1e9) - 1.93 / 1.59).abs() < 1e-12);
        assert!((relative_density(m, 1e15) - 1.34).abs() < 1e-5);
        let (p, h) = (5e8, 1e3);
        let fd = (relative_density(m, p + h) - relative_density(m, p - h)) / (2.0 * h);
        assert!((fd / relative_density_derivative(m, p) - 1.0).abs() < 1e-6);
    }
}
