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

/// A pressure-viscosity law with its constants evaluated once: plain numbers, no case types
/// (the solvers build one per lubricant and evaluate it at every cell of every state).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ViscosityLaw {
    /// Barus: ln(eta/eta0) = alpha p (alpha in 1/Pa)
    Barus { alpha: f64 },
    /// Roelands (thesis eq. 2.11, isothermal): ln(eta/eta0) = a [(1 + p/p_r)^z - 1] with
    /// a = ln eta0 + 9.67 (eta0 in Pa s) and z = alpha p_r / a ([`roelands_z`])
    Roelands { a: f64, z: f64 },
}

impl ViscosityLaw {
    /// The law of `model` for eta0 (Pa s) and alpha (1/Pa).
    pub fn new(model: ViscosityModel, eta0: f64, alpha: f64) -> Self {
        match model {
            ViscosityModel::Barus => ViscosityLaw::Barus { alpha },
            ViscosityModel::Roelands => ViscosityLaw::Roelands {
                a: eta0.ln() - ROELANDS_LN_ETA_INF,
                z: roelands_z(eta0, alpha),
            },
        }
    }

    /// The law of a lubricant.
    pub fn of(lub: &Lubricant) -> Self {
        Self::new(
            lub.viscosity_model,
            lub.viscosity,
            lub.pressure_viscosity_coefficient,
        )
    }

    /// ln(eta/eta0) at pressure `p` (Pa); negative pressure is treated as ambient.
    #[inline]
    pub fn log_relative(&self, p: f64) -> f64 {
        let p = p.max(0.0);
        match *self {
            ViscosityLaw::Barus { alpha } => alpha * p,
            ViscosityLaw::Roelands { a, z } => a * ((1.0 + p / ROELANDS_PR).powf(z) - 1.0),
        }
    }

    /// d ln(eta)/dp (1/Pa) at pressure `p`; 0 below ambient.
    #[inline]
    pub fn log_derivative(&self, p: f64) -> f64 {
        if p < 0.0 {
            return 0.0;
        }
        match *self {
            ViscosityLaw::Barus { alpha } => alpha,
            ViscosityLaw::Roelands { a, z } => {
                z * a / ROELANDS_PR * (1.0 + p / ROELANDS_PR).powf(z - 1.0)
            }
        }
    }

    /// ([`Self::log_relative`], [`Self::log_derivative`]) with one power evaluation.
    #[inline]
    pub fn log_and_derivative(&self, p: f64) -> (f64, f64) {
        match *self {
            ViscosityLaw::Barus { alpha } => {
                (alpha * p.max(0.0), if p < 0.0 { 0.0 } else { alpha })
            }
            ViscosityLaw::Roelands { a, z } => {
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
}

/// ln(eta/eta0) at pressure `p` (Pa); negative pressure is treated as ambient.
///
/// * Roelands (thesis eq. 2.11, isothermal): (ln eta0 + 9.67) [(1 + p/p_r)^z - 1];
/// * Barus: alpha p.
#[inline]
pub fn log_relative_viscosity(lub: &Lubricant, p: f64) -> f64 {
    ViscosityLaw::of(lub).log_relative(p)
}

/// Low-shear viscosity (Pa s) at pressure `p` (Pa): eta0 exp(log_relative_viscosity).
pub fn viscosity(lub: &Lubricant, p: f64) -> f64 {
    lub.viscosity * log_relative_viscosity(lub, p).exp()
}

/// d ln(eta)/dp (1/Pa) at pressure `p`: alpha for Barus, z (ln eta0 + 9.67)/p_r (1 + p/p_r)^(z-1)
/// for Roelands; 0 below ambient.
pub fn log_viscosity_derivative(lub: &Lubricant, p: f64) -> f64 {
    ViscosityLaw::of(lub).log_derivative(p)
}

/// (ln(eta/eta0), d ln(eta)/dp in 1/Pa) at pressure `p` (Pa): [`log_relative_viscosity`] and
/// [`log_viscosity_derivative`] together, with one power evaluation for Roelands.
pub fn log_viscosity_and_derivative(lub: &Lubricant, p: f64) -> (f64, f64) {
    ViscosityLaw::of(lub).log_and_derivative(p)
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
