//! Amplitude reduction of harmonic waviness passing through an EHL contact in pure rolling
//! (Venner, Couhier, Lubrecht & Greenwood, Tribology Series 32 (1997) 103-112; Venner &
//! Lubrecht, Multilevel Methods in Lubrication, 2000, ch. 13).
//!
//! A waviness of undeformed amplitude A_i and wavelength lambda on one surface leaves in the
//! centre of the contact (X = 0) a film modulation of amplitude A_d. For A_i below the film,
//! A_d / A_i depends on the operating conditions only through one group,
//!
//! ```text
//!   nabla = (lambda / b) M^(3/4) / L^(1/2)       (line contact)
//! ```
//!
//! with Moes' M = W (2U)^(-1/2), L = G (2U)^(1/4) (U on the mean speed, so 2U is the sum
//! speed's group); short waves (nabla << 1) pass nearly undeformed, long ones are flattened.

/// The line-contact group nabla = (lambda / b) M^(3/4) / L^(1/2).
pub fn line_nabla(wavelength_over_b: f64, m: f64, l: f64) -> f64 {
    wavelength_over_b * m.powf(0.75) / l.sqrt()
}

/// The fitted amplitude ratio of a line contact, A_d / A_i = 1 / (1 + 0.17 nabla + 0.03 nabla^2)
/// (dimensionless), the fit to numerical solutions that the project's issue 9 quotes for Venner
/// et al. 1997 / Venner & Lubrecht 2000. Its coefficients and the (M, L) range it was fitted
/// over are not checked here against the paper. Our solutions follow it within 2.8 % at L = 10,
/// M = 100-200 and lie above it at lower load (7-14 % at M = 20, L = 10; 12-33 % at L = 5):
/// the collapse onto nabla holds in the piezoviscous-elastic regime (docs/pits.md).
pub fn line_amplitude_ratio(nabla: f64) -> f64 {
    1.0 / (1.0 + 0.17 * nabla + 0.03 * nabla * nabla)
}
