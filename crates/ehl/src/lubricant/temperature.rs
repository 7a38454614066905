//! The lubricant laws with temperature: plain functions of (p, T), for thermal runs (`[thermal]`).
//!
//! * Viscosity (thesis eq. 2.11, Roelands with its temperature term):
//!
//!   ```text
//!   ln(eta/eta0) = (ln eta0 + 9.67) [ -1 + (1 + p/p_r)^Z ((T - 138)/(T0 - 138))^(-S0) ]
//!   ```
//!
//!   T in K, p_r = 1.96e8 Pa, Z as in the isothermal law ([`super::viscosity::roelands_z`]).
//!   At p = 0 the slope d ln(eta)/dT at T0 is -beta with S0 = beta (T0 - 138) / (ln eta0 + 9.67)
//!   (thesis, below eq. 2.11), which is how a given `viscosity_beta` becomes S0.
//!   With Barus piezo-viscosity the temperature term is exponential (the form the classical
//!   inlet-heating factors assume, Murch & Wilson 1975): ln(eta/eta0) = alpha p - beta (T - T0),
//!   a given S0 becoming beta by the same relation.
//! * Density (thesis eq. 2.9, Dowson-Higginson with thermal expansion):
//!   rho = rho0 DH(p) (1 - D (T - T0)), DH the isothermal ratio of [`super::density`], D in 1/K.
//! * Rheology: any parameter of the shear law may be given at several temperatures and is
//!   interpolated linearly in T (held constant beyond the first and last), e.g. the thesis'
//!   Carreau n = 0.57 at 313 K and 0.993 at 373 K (Table 3.7).

use super::viscosity::{ViscosityLaw, ROELANDS_LN_ETA_INF};
use super::{density, Lubricant, Rheology, ViscosityModel};
use serde::Serialize;

/// Roelands' temperature pole (K): the viscosity diverges as T -> 138 K (thesis eq. 2.11).
pub const ROELANDS_T_POLE: f64 = 138.0;

/// How the viscosity falls with temperature (case keys `thermal.viscosity_temperature` (S0) or
/// `thermal.viscosity_beta` (beta, 1/K)); both are kept, each derived from the other at T0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ViscosityTemperature {
    /// Roelands' temperature-viscosity index S0 (dimensionless)
    pub s0: f64,
    /// the slope -d ln(eta)/dT at p = 0, T = T0 (1/K)
    pub beta: f64,
}

impl ViscosityTemperature {
    /// From S0 for a lubricant of ambient viscosity `eta0` (Pa s) at `t0` (K).
    pub fn from_s0(s0: f64, eta0: f64, t0: f64) -> Self {
        let a = eta0.ln() - ROELANDS_LN_ETA_INF;
        ViscosityTemperature {
            s0,
            beta: s0 * a / (t0 - ROELANDS_T_POLE),
        }
    }
    /// From beta (1/K), S0 = beta (T0 - 138) / (ln eta0 + 9.67).
    pub fn from_beta(beta: f64, eta0: f64, t0: f64) -> Self {
        let a = eta0.ln() - ROELANDS_LN_ETA_INF;
        ViscosityTemperature {
            s0: beta * (t0 - ROELANDS_T_POLE) / a,
            beta,
        }
    }
}

/// A rheology parameter given at one or several temperatures: `[(T K, value)]`, sorted by T.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TemperatureTable(pub Vec<(f64, f64)>);

impl TemperatureTable {
    /// Linear interpolation in T, constant beyond the ends.
    pub fn at(&self, t: f64) -> f64 {
        let v = &self.0;
        match v.len() {
            0 => f64::NAN,
            1 => v[0].1,
            _ => {
                if t <= v[0].0 {
                    return v[0].1;
                }
                for w in v.windows(2) {
                    let ((t0, a), (t1, b)) = (w[0], w[1]);
                    if t <= t1 {
                        return a + (b - a) * (t - t0) / (t1 - t0);
                    }
                }
                v[v.len() - 1].1
            }
        }
    }
}

/// The rheology parameters that vary with temperature (None: the value of `lubricant.rheology`).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct RheologyTables {
    pub shear_modulus: Option<TemperatureTable>,
    pub power_law_index: Option<TemperatureTable>,
    pub eyring_stress: Option<TemperatureTable>,
    pub limiting_shear_coefficient: Option<TemperatureTable>,
}

impl RheologyTables {
    /// Whether no parameter varies with temperature.
    pub fn is_empty(&self) -> bool {
        self.shear_modulus.is_none()
            && self.power_law_index.is_none()
            && self.eyring_stress.is_none()
            && self.limiting_shear_coefficient.is_none()
    }

    /// `base` with its temperature-dependent parameters evaluated at `t` (K).
    pub fn at(&self, base: &Rheology, t: f64) -> Rheology {
        let or = |tab: &Option<TemperatureTable>, v: f64| tab.as_ref().map_or(v, |x| x.at(t));
        let orl = |v: Option<f64>| {
            self.limiting_shear_coefficient
                .as_ref()
                .map(|x| x.at(t))
                .or(v)
        };
        match *base {
            Rheology::Newtonian => Rheology::Newtonian,
            Rheology::Carreau {
                shear_modulus,
                power_law_index,
                limiting_shear_coefficient,
            } => Rheology::Carreau {
                shear_modulus: or(&self.shear_modulus, shear_modulus),
                power_law_index: or(&self.power_law_index, power_law_index),
                limiting_shear_coefficient: orl(limiting_shear_coefficient),
            },
            Rheology::Eyring {
                eyring_stress,
                limiting_shear_coefficient,
            } => Rheology::Eyring {
                eyring_stress: or(&self.eyring_stress, eyring_stress),
                limiting_shear_coefficient: orl(limiting_shear_coefficient),
            },
        }
    }
}

/// The thermal properties of the lubricant and the inlet (case table `[thermal]`), SI units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ThermalLubricant {
    /// T0 (K): the oil and both bodies far from the contact; eta0, rho0 are at T0
    pub inlet_temperature: f64,
    pub viscosity_temperature: ViscosityTemperature,
    /// D (1/K) of thesis eq. 2.9
    pub thermal_expansion: f64,
    /// k_f (W/(m K)) at ambient pressure
    pub conductivity: f64,
    /// its pressure dependence [a, b] (1/Pa): k_f (1 + a p / (1 + b p))
    /// ([`crate::thermal::film::OilThermal::conductivity_at`]); [0, 0]: constant
    pub conductivity_pressure: [f64; 2],
    /// c_f (J/(kg K))
    pub heat_capacity: f64,
    /// collocation points across the film (ends included)
    pub points_across_film: usize,
    /// rheology parameters given at several temperatures
    pub rheology: RheologyTables,
}

/// The laws of one lubricant at (p, T), their constants evaluated once.
#[derive(Debug, Clone)]
pub struct ThermalLaws {
    pub lubricant: Lubricant,
    pub thermal: ThermalLubricant,
    iso: ViscosityLaw,
    /// ln eta0 + 9.67
    a: f64,
}

impl ThermalLaws {
    pub fn new(lubricant: &Lubricant, thermal: &ThermalLubricant) -> Self {
        ThermalLaws {
            lubricant: lubricant.clone(),
            thermal: thermal.clone(),
            iso: ViscosityLaw::of(lubricant),
            a: lubricant.viscosity.ln() - ROELANDS_LN_ETA_INF,
        }
    }

    /// ln(eta/eta0) at pressure `p` (Pa) and temperature `t` (K); negative pressure is ambient.
    /// Roelands (thesis eq. 2.11) or Barus-exponential, see the module docs. Below the Roelands
    /// pole (t <= 138 K) the temperature is clamped just above it.
    #[inline]
    pub fn log_relative_viscosity(&self, p: f64, t: f64) -> f64 {
        let th = &self.thermal;
        match self.iso {
            ViscosityLaw::Barus { alpha } => {
                alpha * p.max(0.0) - th.viscosity_temperature.beta * (t - th.inlet_temperature)
            }
            ViscosityLaw::Roelands { a, z } => {
                a * (-1.0 + Self::roelands_pressure(p, z) * self.roelands_temperature(t))
            }
        }
    }

    /// eta (Pa s) at (p, T).
    #[inline]
    pub fn viscosity(&self, p: f64, t: f64) -> f64 {
        self.lubricant.viscosity * self.log_relative_viscosity(p, t).exp()
    }

    /// eta (Pa s) at pressure `p` (Pa) and each temperature of `t` (K), into `eta` (as long as
    /// `t`): [`Self::viscosity`] point by point, with Roelands' pressure factor
    /// (1 + p / p_r)^Z formed once (a column of the film shares its pressure; the same values
    /// to the last bit).
    pub fn viscosities(&self, p: f64, t: &[f64], eta: &mut [f64]) {
        debug_assert_eq!(t.len(), eta.len(), "one viscosity per temperature");
        match self.iso {
            ViscosityLaw::Barus { .. } => {
                for (e, &t) in eta.iter_mut().zip(t) {
                    *e = self.viscosity(p, t);
                }
            }
            ViscosityLaw::Roelands { a, z } => {
                let pressure = Self::roelands_pressure(p, z);
                for (e, &t) in eta.iter_mut().zip(t) {
                    let ratio = self.roelands_temperature(t);
                    *e = self.lubricant.viscosity * (a * (-1.0 + pressure * ratio)).exp();
                }
            }
        }
    }

    /// Roelands' pressure factor (1 + p / p_r)^Z at `p` (Pa; negative is ambient), p_r =
    /// 1.96e8 Pa (thesis eq. 2.11).
    #[inline]
    fn roelands_pressure(p: f64, z: f64) -> f64 {
        (1.0 + p.max(0.0) / super::viscosity::ROELANDS_PR).powf(z)
    }

    /// Roelands' temperature factor ((T - 138) / (T0 - 138))^-S0 at `t` (K), the temperature
    /// clamped just above the pole (138 K).
    #[inline]
    fn roelands_temperature(&self, t: f64) -> f64 {
        let th = &self.thermal;
        let pole = ROELANDS_T_POLE;
        ((t - pole).max(1e-3) / (th.inlet_temperature - pole)).powf(-th.viscosity_temperature.s0)
    }

    /// rho (kg/m^3) at (p, T): thesis eq. 2.9.
    #[inline]
    pub fn density(&self, p: f64, t: f64) -> f64 {
        density::density(&self.lubricant, p) * self.expansion(t)
    }

    /// d rho / dT (kg/(m^3 K)) at (p, T).
    #[inline]
    pub fn density_dt(&self, p: f64, _t: f64) -> f64 {
        -density::density(&self.lubricant, p) * self.thermal.thermal_expansion
    }

    /// 1 - D (T - T0), the thermal factor of the density.
    #[inline]
    pub fn expansion(&self, t: f64) -> f64 {
        1.0 - self.thermal.thermal_expansion * (t - self.thermal.inlet_temperature)
    }

    /// The shear law at temperature `t` (K).
    pub fn rheology(&self, t: f64) -> Rheology {
        self.thermal.rheology.at(&self.lubricant.rheology, t)
    }

    /// The isothermal viscosity law at the inlet temperature (what the isothermal solver uses).
    pub fn isothermal(&self) -> &ViscosityLaw {
        &self.iso
    }

    /// ln eta0 + 9.67
    pub fn roelands_a(&self) -> f64 {
        self.a
    }
}

/// Whether a lubricant's viscosity law is Roelands (the temperature term is then Roelands').
pub fn is_roelands(lub: &Lubricant) -> bool {
    lub.viscosity_model == ViscosityModel::Roelands
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lubricant::DensityModel;

    fn oil(model: ViscosityModel) -> Lubricant {
        Lubricant {
            viscosity: 0.04,
            pressure_viscosity_coefficient: 2e-8,
            density: 870.0,
            viscosity_model: model,
            density_model: DensityModel::DowsonHigginson,
            rheology: Rheology::Carreau {
                shear_modulus: 4.5e6,
                power_law_index: 0.57,
                limiting_shear_coefficient: Some(0.07),
            },
        }
    }

    fn thermal(s0: f64) -> ThermalLubricant {
        ThermalLubricant {
            inlet_temperature: 313.0,
            viscosity_temperature: ViscosityTemperature::from_s0(s0, 0.04, 313.0),
            thermal_expansion: 6.5e-4,
            conductivity: 0.14,
            conductivity_pressure: [0.0; 2],
            heat_capacity: 2000.0,
            points_across_film: 7,
            rheology: RheologyTables {
                power_law_index: Some(TemperatureTable(vec![(313.0, 0.57), (373.0, 0.993)])),
                ..Default::default()
            },
        }
    }

    /// At T0 the thermal laws are the isothermal ones (to round-off), for both viscosity models.
    #[test]
    fn inlet_temperature_gives_the_isothermal_laws() {
        for m in [ViscosityModel::Roelands, ViscosityModel::Barus] {
            let lub = oil(m);
            let laws = ThermalLaws::new(&lub, &thermal(1.1));
            for p in [0.0, 1e8, 5e8, 1.5e9] {
                let iso = crate::lubricant::viscosity::viscosity(&lub, p);
                let th = laws.viscosity(p, 313.0);
                assert!((th / iso - 1.0).abs() < 1e-13, "{m:?} p {p}: {th} vs {iso}");
                let r = crate::lubricant::density::density(&lub, p);
                assert_eq!(laws.density(p, 313.0), r);
            }
        }
    }

    /// A column's viscosities (the pressure factor formed once) are the point-by-point law's to
    /// the last bit, for both viscosity models, at pressures from below ambient (clamped) to
    /// 2 GPa and temperatures from below the Roelands pole (clamped) to 200 K above the inlet,
    /// and the film's laws (`FilmLaws`) use them.
    #[test]
    fn a_columns_viscosities_are_the_pointwise_law() {
        use crate::thermal::film::FilmLaws;
        // (100 K: below the Roelands pole, clamped)
        let t = [100.0, 290.0, 313.0, 313.5, 350.0, 420.0, 513.0];
        for m in [ViscosityModel::Roelands, ViscosityModel::Barus] {
            let laws = ThermalLaws::new(&oil(m), &thermal(1.1));
            for p in [-1e6, 0.0, 3e8, 1e9, 2e9] {
                let (mut eta, mut film) = ([0.0; 7], [0.0; 7]);
                laws.viscosities(p, &t, &mut eta);
                // and the film's laws take this route
                FilmLaws::viscosities(&laws, p, &t, &mut film);
                for ((e, f), &ti) in eta.iter().zip(&film).zip(&t) {
                    assert_eq!(*e, laws.viscosity(p, ti), "{m:?} p {p} T {ti}");
                    assert_eq!(f, e, "{m:?} p {p} T {ti}: FilmLaws");
                }
            }
        }
    }

    /// The slope d ln(eta)/dT at p = 0, T0 is -S0 (ln eta0 + 9.67)/(T0 - 138) (thermal.md), by a
    /// central difference (its error ~ h^2 ln eta'''/6 ~ 1e-9 relative at h = 1e-3 K).
    #[test]
    fn roelands_temperature_slope() {
        let lub = oil(ViscosityModel::Roelands);
        let s0 = 1.1;
        let laws = ThermalLaws::new(&lub, &thermal(s0));
        let h = 1e-3;
        let d = (laws.log_relative_viscosity(0.0, 313.0 + h)
            - laws.log_relative_viscosity(0.0, 313.0 - h))
            / (2.0 * h);
        let want = -s0 * (0.04f64.ln() + 9.67) / (313.0 - 138.0);
        assert!((d / want - 1.0).abs() < 1e-7, "{d} vs {want}");
        // and beta derived from S0 is that slope; the round trip beta -> S0 is exact
        let vt = laws.thermal.viscosity_temperature;
        assert!((vt.beta + want).abs() < 1e-14);
        let back = ViscosityTemperature::from_beta(vt.beta, 0.04, 313.0);
        assert!((back.s0 - s0).abs() < 1e-14);
    }

    /// Barus-exponential: ln(eta/eta0) = alpha p - beta (T - T0) exactly; the viscosity falls
    /// with temperature and rises with pressure for both models.
    #[test]
    fn viscosity_falls_with_temperature() {
        let lub = oil(ViscosityModel::Barus);
        let laws = ThermalLaws::new(&lub, &thermal(1.1));
        let beta = laws.thermal.viscosity_temperature.beta;
        let v = laws.log_relative_viscosity(3e8, 333.0);
        assert!((v - (2e-8 * 3e8 - beta * 20.0)).abs() < 1e-12);
        let lr = ThermalLaws::new(&oil(ViscosityModel::Roelands), &thermal(1.1));
        for laws in [&laws, &lr] {
            for p in [0.0, 5e8] {
                assert!(laws.viscosity(p, 330.0) < laws.viscosity(p, 313.0));
                assert!(laws.viscosity(p, 300.0) > laws.viscosity(p, 313.0));
            }
        }
    }

    /// Thesis eq. 2.9: rho(p, T) = rho_DH(p) (1 - D (T - T0)); its T-derivative by difference.
    #[test]
    fn density_expands_with_temperature() {
        let lub = oil(ViscosityModel::Roelands);
        let laws = ThermalLaws::new(&lub, &thermal(1.1));
        let p = 4e8;
        let rho = laws.density(p, 353.0);
        let want = crate::lubricant::density::density(&lub, p) * (1.0 - 6.5e-4 * 40.0);
        assert!((rho / want - 1.0).abs() < 1e-14);
        let d = (laws.density(p, 353.5) - laws.density(p, 352.5)) / 1.0;
        assert!((d / laws.density_dt(p, 353.0) - 1.0).abs() < 1e-12);
    }

    /// The thesis' Carreau index, 0.57 at 313 K and 0.993 at 373 K, interpolated linearly and
    /// held beyond the ends.
    #[test]
    fn rheology_parameters_interpolate_in_temperature() {
        let lub = oil(ViscosityModel::Roelands);
        let laws = ThermalLaws::new(&lub, &thermal(1.1));
        let n = |t| match laws.rheology(t) {
            Rheology::Carreau {
                power_law_index, ..
            } => power_law_index,
            _ => unreachable!(),
        };
        assert_eq!(n(300.0), 0.57);
        assert!((n(343.0) - (0.57 + 0.423 * 0.5)).abs() < 1e-14);
        assert_eq!(n(400.0), 0.993);
    }
}
