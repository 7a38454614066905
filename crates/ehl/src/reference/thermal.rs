//! Classical thermal references: the inlet-heating reduction of the film, Blok's flash
//! temperature and the exact thermal Couette flow (the sources are in
//! `shared/design/thermal.md`; each was checked there or here).

use std::f64::consts::PI;

/// Thermal loading L = eta0 beta u^2 / k_f (dimensionless): eta0 (Pa s) at the inlet, beta
/// (1/K) the viscosity-temperature coefficient, u (m/s) the mean (entrainment) speed, k_f
/// (W/(m K)) the oil's conductivity (Murch & Wilson 1975; Gupta et al. 1992).
pub fn thermal_loading(eta0: f64, beta: f64, u: f64, k_f: f64) -> f64 {
    eta0 * beta * u * u / k_f
}

/// Murch & Wilson (J. Lubr. Technol. 97 (1975) 212), pure rolling:
/// h_thermal / h_isothermal = 1 / (1 + 0.254 L^0.62).
pub fn murch_wilson(l: f64) -> f64 {
    1.0 / (1.0 + 0.254 * l.powf(0.62))
}

/// Wilson & Sheu (J. Lubr. Technol. 105 (1983) 187), with slip, Z = (u1 - u2)/(u1 + u2) (half
/// the slide-to-roll ratio): 1 / (1 + 0.241 (1 + 14.8 Z^0.83) L^0.64).
pub fn wilson_sheu(l: f64, srr: f64) -> f64 {
    let z = 0.5 * srr.abs();
    1.0 / (1.0 + 0.241 * (1.0 + 14.8 * z.powf(0.83)) * l.powf(0.64))
}

/// Gupta, Cheng, Zhu, Forster & Schrand (Tribol. Trans. 35 (1992) 269), a fit of full thermal
/// line-contact solutions: (1 - 13.2 (p_h/E') L^0.42) / (1 + 0.213 (1 + 2.23 SRR^0.83) L^0.64),
/// p_h the Hertz pressure, E' the reduced modulus.
pub fn gupta(l: f64, srr: f64, ph_over_e: f64) -> f64 {
    (1.0 - 13.2 * ph_over_e * l.powf(0.42))
        / (1.0 + 0.213 * (1.0 + 2.23 * srr.abs().powf(0.83)) * l.powf(0.64))
}

/// Blok's flash temperature of a line contact (K) at high Peclet number, with a semi-elliptic
/// (Hertzian) heat source and Blok's partition of the heat between the surfaces:
///
/// T_f = 1.11 mu w' |sqrt(u1) - sqrt(u2)| / (sqrt(k rho c) sqrt(2 a))
///
/// mu the friction coefficient, w' the load per unit length (N/m), u1, u2 the surface speeds
/// (m/s), a the Hertz half-width (m), k rho c of the (equal) bodies (Blok 1937; ISO/TR 13989-1;
/// thermal.md [derived]).
#[allow(clippy::too_many_arguments)]
pub fn blok_flash(mu: f64, w: f64, u1: f64, u2: f64, a: f64, k: f64, rho: f64, c: f64) -> f64 {
    1.11 * mu * w * (u1.abs().sqrt() - u2.abs().sqrt()).abs()
        / ((k * rho * c).sqrt() * (2.0 * a).sqrt())
}

/// Exact plane Couette flow with shear heating between walls at T0 (thermal.md [derived]):
/// walls a gap h apart, sliding speed u_s, eta = eta_s exp(-beta (T - T0)), conductivity k;
/// with Lambda = beta eta_s u_s^2 / k and s = asinh(sqrt(Lambda / 8)):
///
/// tau / tau_iso = 2 s / sinh(2 s),  T_mid - T0 = (2 / beta) ln cosh s.
///
/// Returns (tau / tau_iso, beta (T_mid - T0)).
pub fn couette(lambda: f64) -> (f64, f64) {
    let s = (lambda / 8.0).sqrt().asinh();
    let ratio = if s > 0.0 {
        2.0 * s / (2.0 * s).sinh()
    } else {
        1.0
    };
    (ratio, 2.0 * s.cosh().ln())
}

/// Surface temperature rise of a half-space under a uniform flux q on a disc of radius a, at
/// rest (Carslaw & Jaeger 1959, sec. 10.5): (centre, mean over the disc) = (q a / k, 8/(3 pi) q a / k).
pub fn stationary_disc(q: f64, a: f64, k: f64) -> (f64, f64) {
    (q * a / k, 8.0 / (3.0 * PI) * q * a / k)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// thermal.md: in pure rolling Murch-Wilson and Gupta agree within about 5 % (Gupta with
    /// p_h/E' = 0.003, p_h ~ 0.7 GPa on steel; at 0.005 the two part by 6.4 % at L = 3, Gupta's
    /// pressure term growing with L^0.42); with slip Wilson-Sheu falls well below Gupta
    /// (L = 1, SRR = 0.5: 0.42 against 0.63, the latter at p_h/E' = 0.005).
    #[test]
    fn the_inlet_heating_fits_agree_as_thermal_md_says() {
        for l in [0.1, 0.3, 1.0, 3.0] {
            let (m, g) = (murch_wilson(l), gupta(l, 0.0, 0.003));
            assert!((m / g - 1.0).abs() < 0.05, "L {l}: {m} vs {g}");
        }
        let (ws, g) = (wilson_sheu(1.0, 0.5), gupta(1.0, 0.5, 0.005));
        assert!(
            (ws - 0.42).abs() < 0.01 && (g - 0.63).abs() < 0.01,
            "{ws} {g}"
        );
    }

    /// The Couette closed form against a shooting solution of k T'' = -eta u'^2 (tau constant
    /// across the film: tau = eta(T) u'), T(0) = T(h) = T0, by RK4 on 2000 steps.
    #[test]
    fn couette_closed_form_against_a_direct_solve() {
        for lambda in [1.0f64, 10.0] {
            // nondimensional: theta = beta (T - T0), z in [0, 1], u in units of u_s:
            // theta'' = -Lambda t^2 exp(theta), t = tau / tau_iso, and int_0^1 exp(theta) dz = 1/t
            // (u(1) - u(0) = t int exp(theta) = 1). Symmetric: theta'(1/2) = 0.
            let (want_t, want_mid) = couette(lambda);
            // shoot on the mid value theta_m: integrate from the middle to the wall
            let wall = |tm: f64, t: f64| -> (f64, f64) {
                let n = 2000;
                let dz = 0.5 / n as f64;
                let (mut th, mut d, mut int) = (tm, 0.0, 0.0);
                let f = |th: f64| -lambda * t * t * th.exp();
                for _ in 0..n {
                    let (k1, l1) = (d, f(th));
                    let (k2, l2) = (d + 0.5 * dz * l1, f(th + 0.5 * dz * k1));
                    let (k3, l3) = (d + 0.5 * dz * l2, f(th + 0.5 * dz * k2));
                    let (k4, l4) = (d + dz * l3, f(th + dz * k3));
                    let e0 = th.exp();
                    th += dz / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
                    d += dz / 6.0 * (l1 + 2.0 * l2 + 2.0 * l3 + l4);
                    int += 0.5 * dz * (e0 + th.exp());
                }
                (th, 2.0 * int)
            };
            // the lower branch for a given t: the first mid value, scanning up from 0, whose
            // wall value turns positive, refined by bisection; None past the turning point
            let lower = |t: f64| -> Option<(f64, f64)> {
                let step = 0.01;
                let mut m = 0.0;
                while wall(m + step, t).0 <= 0.0 {
                    m += step;
                    if m > 8.0 {
                        return None;
                    }
                }
                let (mut lo, mut hi) = (m, m + step);
                for _ in 0..50 {
                    let mid = 0.5 * (lo + hi);
                    if wall(mid, t).0 > 0.0 {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                let tm = 0.5 * (lo + hi);
                Some((tm, t * wall(tm, t).1 - 1.0))
            };
            // t such that the speed condition t int exp(theta) = 1 holds (bisection: above the
            // root, or past the turning point, the residual is positive or there is no branch)
            let (mut lo, mut hi) = (1e-3, (3.5 / lambda).sqrt().min(1.0));
            for _ in 0..45 {
                let mid = 0.5 * (lo + hi);
                match lower(mid) {
                    Some((_, r)) if r <= 0.0 => lo = mid,
                    _ => hi = mid,
                }
            }
            let t = 0.5 * (lo + hi);
            let tm = lower(t).expect("a lower branch below the turning point").0;
            assert!(
                (t - want_t).abs() < 1e-6,
                "Lambda {lambda}: {t} vs {want_t}"
            );
            assert!(
                (tm - want_mid).abs() < 1e-6,
                "Lambda {lambda}: {tm} vs {want_mid}"
            );
        }
    }
}
