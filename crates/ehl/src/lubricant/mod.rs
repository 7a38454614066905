//! Lubricant laws, each in its own file:
//!
//! * [`density`]: Dowson-Higginson compressibility (thesis eq. 2.10) or constant density;
//! * [`viscosity`]: Roelands (eq. 2.11) or Barus piezo-viscosity;
//! * [`rheology`]: shear-thinning (Carreau eq. 2.15, Eyring) with a limiting shear stress (eq. 2.13-2.14).
//!
//! All functions take the pressure in Pa and treat negative pressure as ambient (cavitated film).

pub mod density;
pub mod rheology;
pub mod viscosity;
