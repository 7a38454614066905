//! Pressure-viscosity laws (isothermal).

use super::{Lubricant, ViscosityModel};

/// Roelands reference pressure p_r = 1/5.1e-9 = 1.96e8 Pa (thesis eq. 2.11).
pub const ROELANDS_PR: f64 = 1.96e8;
/// Roelands constant: ln(eta_inf) = -9.67 with eta in Pa s (thesis eq. 2.11).
pub const ROELANDS_LN_ETA_INF: f64 = -9.67;

/// Roelands pressure-viscosity index z = alpha p_r / (ln eta0 + 9.67), chosen so that the
/// initial slope d ln(eta)/dp at p = 0 equals alpha (thesis eq. 2.11).
pub fn roelands_z(eta0: f64, alpha: f64) -> f64 {
    alpha * ROELANDS_PR / (eta0.ln() - ROELANDS_LN_ETA_INF)
}

/// ln(eta/eta0) at pressure `p` (Pa); negative pressure is treated as ambient.
///
/// * Roelands (thesis eq. 2.11, isothermal): (ln eta0 + 9.67) [(1 + p/p_r)^z - 1];
/// * Barus: alpha p.
#[inline]
pub fn log_relative_viscosity(lub: &Lubricant, p: f64) -> f64 {
    let p = p.max(0.0);
    match lub.viscosity_model {
        ViscosityModel::Barus => lub.pressure_viscosity_coefficient * p,
        ViscosityModel::Roelands => {
            let z = roelands_z(lub.viscosity, lub.pressure_viscosity_coefficient);
            (lub.viscosity.ln() - ROELANDS_LN_ETA_INF) * ((1.0 + p / ROELANDS_PR).powf(z) - 1.0)
        }
    }
}

/// Low-shear viscosity (Pa s) at pressure `p` (Pa): eta0 exp(log_relative_viscosity).
pub fn viscosity(lub: &Lubricant, p: f64) -> f64 {
    lub.viscosity * log_relative_viscosity(lub, p).exp()
}

/// d ln(eta)/dp (1/Pa) at pressure `p`: alpha for Barus, z (ln eta0 + 9.67)/p_r (1 + p/p_r)^(z-1)
/// for Roelands; 0 below ambient.
pub fn log_viscosity_derivative(lub: &Lubricant, p: f64) -> f64 {
    if p < 0.0 {
        return 0.0;
    }
    match lub.viscosity_model {
        ViscosityModel::Barus => lub.pressure_viscosity_coefficient,
        ViscosityModel::Roelands => {
            let z = roelands_z(lub.viscosity, lub.pressure_viscosity_coefficient);
            z * (lub.viscosity.ln() - ROELANDS_LN_ETA_INF) / ROELANDS_PR
                * (1.0 + p / ROELANDS_PR).powf(z - 1.0)
        }
    }
}

/// (ln(eta/eta0), d ln(eta)/dp in 1/Pa) at pressure `p` (Pa): [`log_relative_viscosity`] and
/// [`log_viscosity_derivative`] together (thesis eq. 2.11 for Roelands, the same laws and
/// constants), with one power evaluation for Roelands: the EHL solver needs both at every cell
/// of every state.
pub fn log_viscosity_and_derivative(lub: &Lubricant, p: f64) -> (f64, f64) {
    match lub.viscosity_model {
        ViscosityModel::Barus => {
            let a = lub.pressure_viscosity_coefficient;
            (a * p.max(0.0), if p < 0.0 { 0.0 } else { a })
        }
        ViscosityModel::Roelands => {
            let a = lub.viscosity.ln() - ROELANDS_LN_ETA_INF;
            let z = roelands_z(lub.viscosity, lub.pressure_viscosity_coefficient);
            let t = 1.0 + p.max(0.0) / ROELANDS_PR;
            let tz = t.powf(z);
            let d = if p < 0.0 {
                0.0
            } else {
                z * a / ROELANDS_PR * tz / t
            };
            (a * (tz - 1.0), d)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lubricant::{DensityModel, Rheology};

    fn lub(model: ViscosityModel) -> Lubricant {
        Lubricant {
            viscosity: 0.04,
            pressure_viscosity_coefficient: 15.9e-9,
            density: 846.0,
            viscosity_model: model,
            density_model: DensityModel::DowsonHigginson,
            rheology: Rheology::Newtonian,
        }
    }

    #[test]
    fn roelands_initial_slope_is_alpha() {
        let l = lub(ViscosityModel::Roelands);
        assert!((log_viscosity_derivative(&l, 0.0) / 15.9e-9 - 1.0).abs() < 1e-12);
        let h = 1e3;
        let fd =
            (log_relative_viscosity(&l, 1e3 + h) - log_relative_viscosity(&l, 1e3 - h)) / (2.0 * h);
        assert!((fd / 15.9e-9 - 1.0).abs() < 1e-4);
    }

    #[test]
    fn roelands_below_barus_at_high_pressure() {
        // Roelands' z < 1 here, so (1 + p/pr)^z - 1 grows slower than z p / pr: a known property.
        let (r, b) = (lub(ViscosityModel::Roelands), lub(ViscosityModel::Barus));
        assert!(roelands_z(0.04, 15.9e-9) < 1.0);
        assert!(viscosity(&r, 1e9) < viscosity(&b, 1e9));
        assert_eq!(viscosity(&r, 0.0), 0.04);
        assert!((viscosity(&b, 1e8) / (0.04 * (15.9e-9f64 * 1e8).exp()) - 1.0).abs() < 1e-12);
    }

    /// The combined evaluation equals the separate functions (to round-off), both laws, both
    /// sides of ambient.
    #[test]
    fn combined_matches_separate() {
        for model in [ViscosityModel::Barus, ViscosityModel::Roelands] {
            let l = lub(model);
            for p in [-1e6, 0.0, 1e7, 3e8, 1.2e9, 3e9] {
                let (ln, d) = log_viscosity_and_derivative(&l, p);
                let (ln0, d0) = (
                    log_relative_viscosity(&l, p),
                    log_viscosity_derivative(&l, p),
                );
                assert!((ln - ln0).abs() <= 1e-13 * ln0.abs().max(1.0), "{p}");
                assert!((d - d0).abs() <= 1e-13 * d0.abs().max(1e-30), "{p}");
            }
        }
    }
}
