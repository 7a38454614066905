//! Lubricant laws, each in its own file:
//!
//! * [`density`]: Dowson-Higginson compressibility (thesis eq. 2.10) or constant density;
//! * [`viscosity`]: Roelands (eq. 2.11) or Barus piezo-viscosity;
//! * [`rheology`]: shear-thinning (Carreau eq. 2.15, Eyring) with a limiting shear stress (eq. 2.13-2.14).
//!
//! All functions take the pressure in Pa and treat negative pressure as ambient (cavitated film).
//!
//! The parameter types ([`Lubricant`], [`ViscosityModel`], [`DensityModel`], [`Rheology`]) are
//! plain numbers and live here, with their laws; the case file's `[lubricant]` table is read
//! into them by `crate::case` (which re-exports them), so the laws do not depend on the file
//! format. SI units throughout.

pub mod density;
pub mod rheology;
pub mod temperature;
pub mod viscosity;

use serde::Serialize;

/// The pressure-viscosity law (case key `lubricant.viscosity_model`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ViscosityModel {
    Roelands,
    Barus,
}

/// The pressure-density law (case key `lubricant.density_model`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DensityModel {
    DowsonHigginson,
    Constant,
}

/// The shear law of the film (case key `lubricant.rheology`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "model", rename_all = "kebab-case")]
pub enum Rheology {
    Newtonian,
    /// Carreau (thesis eq. 2.15) with shear modulus G_f (Pa), power-law index n and optional
    /// limiting shear stress tau_L = Lambda p (eq. 2.14)
    Carreau {
        shear_modulus: f64,
        power_law_index: f64,
        limiting_shear_coefficient: Option<f64>,
    },
    /// Eyring (sinh law) with Eyring stress tau_0 (Pa) and optional limiting shear coefficient
    Eyring {
        eyring_stress: f64,
        limiting_shear_coefficient: Option<f64>,
    },
}

/// A lubricant: its ambient properties and its laws (case table `[lubricant]`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Lubricant {
    /// eta0 at ambient pressure (Pa s)
    pub viscosity: f64,
    /// alpha (1/Pa)
    pub pressure_viscosity_coefficient: f64,
    /// rho0 at ambient pressure (kg/m^3)
    pub density: f64,
    pub viscosity_model: ViscosityModel,
    pub density_model: DensityModel,
    pub rheology: Rheology,
}
