//! The scales of a contact, in one place: reduced modulus E', reduced radius R, Hertz half-width
//! and pressure, the Dowson-Higginson groups W, U, G and the Moes groups M, L.
//!
//! Sources: Johnson, *Contact Mechanics* (1985) ch. 4; Hamrock, Schmid & Jacobson,
//! *Fundamentals of Machine Elements*; thesis eq. 2.5-2.8 for the radii; Moes (1992) for M, L.

use std::f64::consts::PI;

/// Reduced (effective) modulus E' = 2 / ((1-nu1^2)/E1 + (1-nu2^2)/E2)  (Pa).
///
/// With this convention the half-space deflection is w = 2/(pi E') \int p / r dA (thesis eq. 1.6).
pub fn reduced_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    2.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)
}

/// Reduced radius 1/R = 1/R1 + 1/R2 (m) (thesis eq. 2.8). An infinite radius (a flat) is allowed.
pub fn reduced_radius(r1: f64, r2: f64) -> f64 {
    1.0 / (1.0 / r1 + 1.0 / r2)
}

/// Hertz line contact: half-width b = sqrt(8 w' R / (pi E'))  (m), w' load per unit length (N/m).
pub fn hertz_line_half_width(w_per_len: f64, r: f64, e_red: f64) -> f64 {
    (8.0 * w_per_len * r / (PI * e_red)).sqrt()
}

/// Hertz line contact: maximum pressure p_h = sqrt(w' E' / (2 pi R))  (Pa).
pub fn hertz_line_pressure(w_per_len: f64, r: f64, e_red: f64) -> f64 {
    (w_per_len * e_red / (2.0 * PI * r)).sqrt()
}

/// Load per unit length that gives the Hertz line pressure `ph`: w' = 2 pi R ph^2 / E'  (N/m).
pub fn line_load_for_pressure(ph: f64, r: f64, e_red: f64) -> f64 {
    2.0 * PI * r * ph * ph / e_red
}

/// Hertz circular point contact (sphere of reduced radius R on a flat).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzPoint {
    /// contact radius a = (3 F R / (2 E'))^(1/3)  (m)
    pub a: f64,
    /// maximum pressure p0 = 3 F / (2 pi a^2)  (Pa)
    pub p0: f64,
    /// rigid-body approach delta = a^2 / R  (m)
    pub approach: f64,
}

/// Hertz circular point contact for load `f` (N), reduced radius `r` (m) and modulus `e_red` (Pa).
/// Johnson (1985) eq. 4.22-4.24 with E* = E'/2.
pub fn hertz_point(f: f64, r: f64, e_red: f64) -> HertzPoint {
    let a = (3.0 * f * r / (2.0 * e_red)).cbrt();
    HertzPoint {
        a,
        p0: 3.0 * f / (2.0 * PI * a * a),
        approach: a * a / r,
    }
}

/// Load that gives a circular Hertz pressure `p0`: F = (2 pi/3) p0 a^2 with a = pi p0 R / E'.
pub fn point_load_for_pressure(p0: f64, r: f64, e_red: f64) -> f64 {
    let a = PI * p0 * r / e_red;
    2.0 * PI / 3.0 * p0 * a * a
}

/// Dimensionless speed U = eta0 u_e / (E' R).
pub fn speed_parameter(eta0: f64, u_e: f64, e_red: f64, r: f64) -> f64 {
    eta0 * u_e / (e_red * r)
}

/// Dimensionless material parameter G = alpha E'.
pub fn material_parameter(alpha: f64, e_red: f64) -> f64 {
    alpha * e_red
}

/// Line-contact load parameter W = w' / (E' R).
pub fn line_load_parameter(w_per_len: f64, e_red: f64, r: f64) -> f64 {
    w_per_len / (e_red * r)
}

/// Point-contact load parameter W = F / (E' R^2).
pub fn point_load_parameter(f: f64, e_red: f64, r: f64) -> f64 {
    f / (e_red * r * r)
}

/// Moes line-contact groups (Moes 1992; Venner & Lubrecht 2000 ch. 4) from the mean-speed
/// groups W, U, G of this module: M = W (2U)^(-1/2), L = G (2U)^(1/4). Moes' speed group is
/// built on the sum speed u1 + u2 = 2 u_e, hence the 2.
pub fn moes_line(w: f64, u: f64, g: f64) -> (f64, f64) {
    let u2 = 2.0 * u;
    (w / u2.sqrt(), g * u2.powf(0.25))
}

/// Moes point-contact groups: M = W (2U)^(-3/4), L = G (2U)^(1/4) (W = F/(E' R_x^2)).
pub fn moes_point(w: f64, u: f64, g: f64) -> (f64, f64) {
    let u2 = 2.0 * u;
    (w * u2.powf(-0.75), g * u2.powf(0.25))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hertz_line_is_self_consistent() {
        // load per length recovered from b and ph: w' = pi b ph / 2
        let (w, r, e) = (1.0e6, 0.01, 2.2e11);
        let b = hertz_line_half_width(w, r, e);
        let ph = hertz_line_pressure(w, r, e);
        assert!((PI * b * ph / 2.0 / w - 1.0).abs() < 1e-12);
        assert!((line_load_for_pressure(ph, r, e) / w - 1.0).abs() < 1e-12);
    }

    #[test]
    fn hertz_point_is_self_consistent() {
        let h = hertz_point(15.0, 0.0125, 1.1e11);
        assert!((point_load_for_pressure(h.p0, 0.0125, 1.1e11) / 15.0 - 1.0).abs() < 1e-12);
        // p0 = E' a / (pi R) for a sphere on a flat
        assert!((h.p0 / (1.1e11 * h.a / (PI * 0.0125)) - 1.0).abs() < 1e-12);
    }
}
