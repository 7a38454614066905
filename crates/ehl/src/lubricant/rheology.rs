//! Rheology: the shear stress of the lubricant film as a function of the shear rate, for a given
//! low-shear (pressure-dependent) viscosity eta(p) (isothermal).
//!
//! Models ([`Rheology`], from `[lubricant] rheology` in the case file):
//!
//! * Newtonian (thesis eq. 2.12): tau = eta gamma_dot;
//! * Carreau (Carreau 1972; in EHL form thesis eq. 2.15 after Guilbault 2013):
//!   eta_eff = eta [1 + (eta gamma_dot / G_f)^2]^((n - 1)/2), tau = eta_eff gamma_dot;
//! * Eyring (Eyring 1936; the sinh law of Johnson & Tevaarwerk 1977):
//!   tau = tau_0 asinh(eta gamma_dot / tau_0).
//!
//! Carreau and Eyring take an optional limiting shear stress (Bair & Winer 1979; thesis
//! eq. 2.13-2.14), tau_L = Lambda p, which caps |tau|: this is the `min` of eq. 2.15,
//! eta = min[eta_Carreau, tau_L / gamma_dot]. Carreau with n = 1 and a limit is the Newtonian
//! law with a limiting shear stress of eq. 2.13.
//!
//! Units: eta in Pa s, gamma_dot in 1/s (signed), p in Pa, tau in Pa (signed like gamma_dot).
//! Negative pressure is treated as ambient (p = 0), like the other lubricant laws, so that with a
//! limit a cavitated or ambient-pressure film carries no shear stress (tau_L = Lambda * 0 = 0, the
//! literal reading of eq. 2.14; real lubricants have a small ambient intercept which the case
//! format does not model).
//!
//! Preconditions (checked by the case validation, not here): eta >= 0, G_f > 0, n > 0,
//! tau_0 > 0, Lambda >= 0, all finite. With them and a finite shear rate the functions below
//! never return NaN.

use super::Rheology;

/// Limiting shear stress tau_L = Lambda max(p, 0) (Pa) of thesis eq. 2.14 (Bair & Winer 1979),
/// or `None` when the model has no limit (Newtonian, or Carreau/Eyring without
/// `limiting_shear_coefficient`).
pub fn limiting_shear_stress(model: &Rheology, p: f64) -> Option<f64> {
    let lambda = match model {
        Rheology::Newtonian => None,
        Rheology::Carreau {
            limiting_shear_coefficient,
            ..
        }
        | Rheology::Eyring {
            limiting_shear_coefficient,
            ..
        } => *limiting_shear_coefficient,
    }?;
    Some(lambda * p.max(0.0))
}

/// The shear stress before the limit is applied (Pa, signed like `shear_rate`).
///
/// * Newtonian: eta gamma_dot (eq. 2.12);
/// * Carreau: G_f x [1 + x^2]^((n-1)/2) with x = eta gamma_dot / G_f, i.e. eta gamma_dot times the
///   Carreau factor of eq. 2.15; written with `hypot(1, x)` so that it neither overflows nor
///   underflows at large x (where it tends to the power law G_f x^n);
/// * Eyring: tau_0 asinh(eta gamma_dot / tau_0).
fn unlimited_shear_stress(model: &Rheology, eta: f64, shear_rate: f64) -> f64 {
    let newtonian = eta * shear_rate;
    match *model {
        Rheology::Newtonian => newtonian,
        Rheology::Carreau {
            shear_modulus,
            power_law_index,
            ..
        } => {
            if newtonian == 0.0 {
                return 0.0;
            }
            // x = eta gamma_dot / G_f, formed so that it overflows only when x itself does; for
            // |x| > 1 the law is written G |x|^n (1 + 1/x^2)^((n-1)/2), which stays finite (or
            // +inf, which a limiting shear stress then caps) where x (1 + x^2)^((n-1)/2) would
            // give inf * 0 = NaN once x overflows (a very viscous film at a tiny h)
            let x = (eta / shear_modulus) * shear_rate;
            let ax = x.abs();
            let e = 0.5 * (power_law_index - 1.0);
            let mag = if ax <= 1.0 {
                ax * (1.0 + ax * ax).powf(e)
            } else {
                ax.powf(power_law_index) * (1.0 + 1.0 / (ax * ax)).powf(e)
            };
            shear_modulus * mag.copysign(shear_rate)
        }
        Rheology::Eyring { eyring_stress, .. } => {
            eyring_stress * (newtonian / eyring_stress).asinh()
        }
    }
}

/// Shear stress tau (Pa, signed like `shear_rate`) of the film at shear rate `shear_rate` (1/s)
/// for the low-shear viscosity `eta` (Pa s) at pressure `p` (Pa).
///
/// tau = tau_model(eta, gamma_dot) (see the module documentation: thesis eq. 2.12, Carreau
/// eq. 2.15, Eyring), then, when the model has a limiting shear coefficient Lambda,
/// |tau| <= tau_L = Lambda max(p, 0) (thesis eq. 2.13-2.14). tau is odd in `shear_rate` and
/// non-decreasing in it.
pub fn shear_stress(model: &Rheology, eta: f64, shear_rate: f64, p: f64) -> f64 {
    let limit = limiting_shear_stress(model, p);
    if let Some(tau_l) = limit {
        if shear_rate.is_infinite() {
            // the limit of tau as |gamma_dot| -> inf is the cap itself
            return tau_l.copysign(shear_rate);
        }
    }
    let tau = unlimited_shear_stress(model, eta, shear_rate);
    match limit {
        Some(tau_l) if tau.abs() > tau_l => tau_l.copysign(shear_rate),
        _ => tau,
    }
}

/// Effective viscosity eta_eff = tau / gamma_dot (Pa s) at shear rate `shear_rate` (1/s) for the
/// low-shear viscosity `eta` (Pa s) at pressure `p` (Pa); the left side of thesis eq. 2.15.
///
/// At zero shear rate it returns the limit gamma_dot -> 0: `eta` for every model, except with a
/// limiting shear stress at p <= 0, where tau_L = 0 makes eta_eff = 0.
pub fn effective_viscosity(model: &Rheology, eta: f64, shear_rate: f64, p: f64) -> f64 {
    if shear_rate == 0.0 {
        return match limiting_shear_stress(model, p) {
            Some(tau_l) if tau_l <= 0.0 => 0.0,
            _ => eta,
        };
    }
    shear_stress(model, eta, shear_rate, p) / shear_rate
}

/// The unlimited law in logarithms, for Newton iterations across the film: ln eta_eff and its
/// slope s = d ln eta_eff / d ln gamma_dot at `ln_eta` = ln eta (eta in Pa s) and
/// `ln_shear_rate` = ln |gamma_dot| (gamma_dot in 1/s; -inf for zero shear). The limiting shear
/// stress is NOT applied (the film model caps per column, `thermal::film_energy`).
///
/// * Newtonian: (ln eta, 0);
/// * Carreau (thesis eq. 2.15): ln eta_eff = ln eta + (n - 1)/2 ln(1 + x^2), x = eta gamma_dot /
///   G_f, s = (n - 1) x^2 / (1 + x^2);
/// * Eyring (Eyring 1936; Johnson & Tevaarwerk 1977): ln eta_eff = ln eta + ln(asinh(x) / x),
///   x = eta gamma_dot / tau_0, s = x / (sqrt(1 + x^2) asinh x) - 1.
///
/// Units: eta, eta_eff in Pa s, gamma_dot in 1/s, G_f and tau_0 in Pa; s dimensionless.
///
/// x is formed as ln x, so nothing overflows however viscous the film: at ln x = 700 (where
/// x itself overflows) Carreau gives ln eta + (n - 1) ln x. Same values as
/// [`effective_viscosity`] (to round-off, tested) at one `exp`, one `ln_1p` and one `ln` per
/// call instead of `powf` and `ln`, and with the slope analytic.
pub fn ln_effective_viscosity(model: &Rheology, ln_eta: f64, ln_shear_rate: f64) -> (f64, f64) {
    LnShearLaw::of(model).eval(ln_eta, ln_shear_rate)
}

/// The unlimited shear law of [`ln_effective_viscosity`] with its constants formed once (the
/// logarithms of G_f and tau_0): the film's Newton iteration evaluates it several times per
/// point with the law fixed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LnShearLaw {
    Newtonian,
    /// e = (n - 1) / 2, ln G_f (G_f in Pa)
    Carreau {
        e: f64,
        ln_g: f64,
    },
    /// ln tau_0 (tau_0 in Pa)
    Eyring {
        ln_tau0: f64,
    },
}

impl LnShearLaw {
    pub fn of(model: &Rheology) -> Self {
        match *model {
            Rheology::Newtonian => LnShearLaw::Newtonian,
            Rheology::Carreau {
                shear_modulus,
                power_law_index,
                ..
            } => LnShearLaw::Carreau {
                e: 0.5 * (power_law_index - 1.0),
                ln_g: shear_modulus.ln(),
            },
            Rheology::Eyring { eyring_stress, .. } => LnShearLaw::Eyring {
                ln_tau0: eyring_stress.ln(),
            },
        }
    }

    /// (ln eta_eff, d ln eta_eff / d ln gamma_dot) at `ln_eta`, `ln_shear_rate`: see
    /// [`ln_effective_viscosity`].
    #[inline]
    pub fn eval(&self, ln_eta: f64, ln_shear_rate: f64) -> (f64, f64) {
        match *self {
            LnShearLaw::Newtonian => (ln_eta, 0.0),
            LnShearLaw::Carreau { e, ln_g } => {
                let lx = ln_eta + ln_shear_rate - ln_g;
                // l = ln(1 + x^2), r = x^2 / (1 + x^2), each without forming x^2
                let (l, r) = if lx <= 0.0 {
                    let q = (2.0 * lx).exp();
                    (q.ln_1p(), q / (1.0 + q))
                } else {
                    let q = (-2.0 * lx).exp();
                    (2.0 * lx + q.ln_1p(), 1.0 / (1.0 + q))
                };
                (ln_eta + e * l, 2.0 * e * r)
            }
            LnShearLaw::Eyring { ln_tau0 } => {
                let lx = ln_eta + ln_shear_rate - ln_tau0;
                if lx < -9.0 {
                    // asinh(x)/x = 1 - x^2/6 + 3 x^4/40: the x^4 term is below 1e-17 here
                    let x2 = (2.0 * lx).exp();
                    (ln_eta + (-x2 / 6.0).ln_1p(), -x2 / 3.0)
                } else if lx > 300.0 {
                    // asinh(x) = ln 2 + ln x + O(1/x^2), sqrt(1 + x^2) = x (1 + O(1/x^2))
                    let a = std::f64::consts::LN_2 + lx;
                    (ln_eta + a.ln() - lx, 1.0 / a - 1.0)
                } else {
                    let x = lx.exp();
                    let a = x.asinh();
                    (ln_eta + (a / x).ln(), x / (1.0f64.hypot(x) * a) - 1.0)
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CARREAU: Rheology = Rheology::Carreau {
        shear_modulus: 4.5e6,
        power_law_index: 0.57,
        limiting_shear_coefficient: None,
    };

    #[test]
    fn newtonian_is_eta_gamma_dot() {
        let m = Rheology::Newtonian;
        assert_eq!(shear_stress(&m, 0.04, 1e6, 1e9), 4e4);
        assert_eq!(shear_stress(&m, 0.04, -1e6, 1e9), -4e4);
        assert_eq!(effective_viscosity(&m, 0.04, 3e5, 0.0), 0.04);
        assert_eq!(effective_viscosity(&m, 0.04, 0.0, 0.0), 0.04);
    }

    #[test]
    fn carreau_small_and_large_shear_rate_limits() {
        // small x = eta gamma_dot / G: factor [1 + x^2]^((n-1)/2) = 1 + (n-1)/2 x^2 + O(x^4),
        // so the relative deviation from Newtonian is (1-n)/2 x^2 to within x^4 (Taylor).
        let (eta, g, n) = (0.04, 4.5e6, 0.57);
        let gd = 1e-3 * g / eta; // x = 1e-3
        let tau = shear_stress(&CARREAU, eta, gd, 0.0);
        let dev = 1.0 - tau / (eta * gd);
        assert!(
            (dev / ((1.0 - n) / 2.0 * 1e-6) - 1.0).abs() < 1e-5,
            "dev {dev}"
        );
        // large x: tau = G x^n (1 + 1/x^2)^((n-1)/2) -> G x^n; at x = 1e8 the relative
        // difference is (1-n)/2 / x^2 ~ 2e-17, below round-off: compare to 1e-12 (powf
        // round-off at this magnitude).
        for &x in &[1e8, 1e20, 1e200] {
            let tau = shear_stress(&CARREAU, eta, x * g / eta, 0.0);
            let power_law = g * x.powf(n);
            assert!(
                (tau / power_law - 1.0).abs() < 1e-12,
                "x {x}: {tau} vs {power_law}"
            );
        }
    }

    #[test]
    fn carreau_with_overflowing_shear_is_capped_not_nan() {
        // eta gamma_dot overflows f64 (a very viscous film at a tiny h): the Carreau stress is
        // +inf, not NaN, and a limiting shear stress caps it (the old form gave inf * 0 = NaN)
        let limited = Rheology::Carreau {
            shear_modulus: 4.5e6,
            power_law_index: 0.57,
            limiting_shear_coefficient: Some(0.06),
        };
        for (eta, gd) in [(1e300, 1e100), (1e42, 1e290), (f64::MAX, 1.0)] {
            assert_eq!(shear_stress(&limited, eta, gd, 1e9), 0.06 * 1e9);
            assert_eq!(shear_stress(&limited, eta, -gd, 1e9), -0.06 * 1e9);
            assert!(!shear_stress(&CARREAU, eta, gd, 1e9).is_nan());
        }
    }

    #[test]
    fn eyring_small_and_large_stress_limits() {
        let m = Rheology::Eyring {
            eyring_stress: 5e6,
            limiting_shear_coefficient: None,
        };
        // asinh(s)/s = 1 - s^2/6 + O(s^4): at s = 1e-3 the deviation is 1.667e-7 to 1e-12
        let gd = 1e-3 * 5e6 / 0.04;
        let dev = 1.0 - shear_stress(&m, 0.04, gd, 0.0) / (0.04 * gd);
        assert!((dev / (1e-6 / 6.0) - 1.0).abs() < 1e-5, "dev {dev}");
        // large s: asinh(s) = ln(2 s) + 1/(4 s^2) + ...; at s = 1e6 the correction is 2.5e-13
        let s = 1e6;
        let tau = shear_stress(&m, 0.04, s * 5e6 / 0.04, 0.0);
        assert!((tau / (5e6 * (2.0 * s).ln()) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn limit_caps_the_stress_and_is_odd() {
        let m = Rheology::Carreau {
            shear_modulus: 4.5e6,
            power_law_index: 0.57,
            limiting_shear_coefficient: Some(0.06),
        };
        let p = 1e9;
        assert_eq!(shear_stress(&m, 100.0, 1e9, p), 0.06 * p);
        assert_eq!(shear_stress(&m, 100.0, -1e9, p), -0.06 * p);
        assert_eq!(shear_stress(&m, 100.0, f64::INFINITY, p), 0.06 * p);
        // below the limit the cap does nothing
        let low = shear_stress(&CARREAU, 1e-3, 1.0, p);
        assert_eq!(shear_stress(&m, 1e-3, 1.0, p), low);
        // ambient or cavitated film: tau_L = 0
        assert_eq!(shear_stress(&m, 0.04, 1e6, -5.0), 0.0);
        assert_eq!(effective_viscosity(&m, 0.04, 0.0, 0.0), 0.0);
        assert_eq!(effective_viscosity(&m, 0.04, 0.0, 1e6), 0.04);
    }

    #[test]
    fn ln_effective_viscosity_matches_the_law_and_its_slope() {
        // against exp-space `effective_viscosity` (no limit) to 1e-12 relative, and the slope
        // against a central difference in ln gamma (step 1e-5: truncation ~1e-10, round-off
        // ~1e-11 / 1e-5 = 1e-6 at worst; tolerance 1e-5 absolute) over 24 decades of x.
        let models = [
            Rheology::Newtonian,
            CARREAU,
            Rheology::Carreau {
                shear_modulus: 4.5e6,
                power_law_index: 0.993,
                limiting_shear_coefficient: None,
            },
            Rheology::Eyring {
                eyring_stress: 5e6,
                limiting_shear_coefficient: None,
            },
        ];
        let eta: f64 = 0.04;
        for m in &models {
            for dec in -12..=12 {
                let x = 10f64.powi(dec) * 1.37;
                let gd = x * 4.5e6 / eta;
                let (l, s) = ln_effective_viscosity(m, eta.ln(), gd.ln());
                let direct = effective_viscosity(m, eta, gd, 0.0);
                assert!((l.exp() / direct - 1.0).abs() < 1e-12, "{m:?} x {x}");
                let d: f64 = 1e-5;
                let up = effective_viscosity(m, eta, gd * d.exp(), 0.0).ln();
                let down = effective_viscosity(m, eta, gd * (-d).exp(), 0.0).ln();
                let fd = (up - down) / (2.0 * d);
                assert!((s - fd).abs() < 1e-5, "{m:?} x {x}: slope {s} vs {fd}");
            }
            // zero shear: the low-shear viscosity, no slope
            assert_eq!(
                ln_effective_viscosity(m, eta.ln(), f64::NEG_INFINITY),
                (eta.ln(), 0.0)
            );
        }
        // where x overflows f64 the logarithm stays finite: Carreau tends to the power law
        let (l, s) = ln_effective_viscosity(&CARREAU, 700.0, 50.0);
        let lx = 750.0 - 4.5e6f64.ln();
        assert!((l - (700.0 + (0.57 - 1.0) * lx)).abs() < 1e-9 && (s - (0.57 - 1.0)).abs() < 1e-12);
    }
}
