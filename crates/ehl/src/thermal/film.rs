//! The film across z: the velocity profile of a film whose viscosity and density vary across
//! the film, the generalized Reynolds coefficients (Yang & Wen 1990, J. Tribol. 112: 631-636)
//! and the energy equation along a grid line, with collocation across z
//! ([`super::collocation::Lobatto`]).
//!
//! # Geometry, units and signs
//!
//! SI units, temperatures in K. Surface 1 is at z = 0 and moves at `u1` along +x, surface 2 at
//! z = h and moves at `u2`; zeta = z / h in [0, 1]. Neither surface moves along y.
//!
//! # Velocity profile (generalized Newtonian film)
//!
//! With the thin-film momentum equations d tau_zx / dz = dp/dx, d tau_zy / dz = dp/dy and
//! tau_zx = eta du/dz, tau_zy = eta dv/dz (eta(z) the local, possibly effective, viscosity):
//!
//! tau_zx(z) = tau_a + z dp/dx,  u(z) = u1 + tau_a int_0^z dz'/eta + dp/dx int_0^z z'/eta dz',
//!
//! and u(h) = u2 fixes tau_a = (u2 - u1 - dp/dx F1) / F0 with F0 = int_0^h dz/eta,
//! F1 = int_0^h z dz/eta (Yang & Wen 1990, eq. 3-5). Likewise v with dp/dy, tau_b and no
//! surface speed.
//!
//! # Generalized Reynolds coefficients (Yang & Wen 1990, eq. 7-10)
//!
//! The mass flux q_x = int_0^h rho u dz is, with the integrals above substituted,
//! q_x = u1 h rho_e + tau_a h^2 rho'_e + dp/dx h^3 rho''_e, with rho_e = (1/h) int rho dz,
//! rho'_e = (1/h^2) int rho int_0^z dz'/eta dz, rho''_e = (1/h^3) int rho int_0^z z'/eta dz' dz;
//! inserting tau_a and writing eta_e = h / F0, eta'_e = h^2 / F1 (so F1/F0 = h eta_e / eta'_e):
//!
//! q_x = -(rho/eta)_e h^3 / 12 dp/dx + rho*_x u_e h,   q_y = -(rho/eta)_e h^3 / 12 dp/dy,
//!
//! (rho/eta)_e = 12 (eta_e rho'_e / eta'_e - rho''_e),
//! rho*_x u_e = u1 rho_e + (u2 - u1) eta_e rho'_e,   u_e = (u1 + u2) / 2
//!
//! [derived here; the same as Yang & Wen]. With eta and rho constant across z,
//! rho'_e = rho / (2 eta), rho''_e = rho / (3 eta), so (rho/eta)_e = rho / eta and
//! rho*_x = rho: the classical Reynolds equation.
//!
//! # Surface tractions
//!
//! The x-force per unit area the film exerts on surface 1 is +tau_zx(0) (the film lies above it,
//! on the +z side), on surface 2 it is -tau_zx(h); likewise along y. This is the convention of
//! [`crate::friction`] (whose force on body 2 is -tau_zx(h) = -(h/2) dp/dx + eta (u1 - u2)/h for a
//! Newtonian film): the lubricant's drag pulls the slower surface forward and holds the faster
//! one back.

// index loops over collocation points read like the equations
#![allow(clippy::needless_range_loop)]

use super::collocation::Lobatto;
use crate::lubricant::rheology::LnShearLaw;

/// Errors of the film computations (no result exists).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FilmError {
    /// An argument is out of range (wrong length, non-finite, non-positive film, ...).
    #[error("film: {0}")]
    Input(String),
    /// A lubricant law returned a value that is not positive and finite.
    #[error("film: the {law} is {value} (not positive and finite) at p = {p} Pa, T = {t} K")]
    Law {
        law: &'static str,
        value: f64,
        p: f64,
        t: f64,
    },
    /// The linear system of the energy equation on a line is singular.
    #[error("film: the energy equation of a line could not be factorised (singular)")]
    Singular,
}

impl From<FilmError> for crate::Error {
    fn from(e: FilmError) -> Self {
        crate::Error::Solver(e.to_string())
    }
}

/// The lubricant laws the film needs, as functions of pressure p (Pa) and temperature T (K).
/// Implementations must be pure (they are called from several threads).
pub trait FilmLaws: Sync {
    /// Low-shear viscosity eta(p, T) (Pa s).
    fn viscosity(&self, p: f64, t: f64) -> f64;
    /// [`FilmLaws::viscosity`] at pressure `p` and each temperature of `t` (a column's points),
    /// into `eta`; laws whose pressure part costs override it to form that part once.
    fn viscosities(&self, p: f64, t: &[f64], eta: &mut [f64]) {
        debug_assert_eq!(t.len(), eta.len(), "one viscosity per temperature");
        for (e, &t) in eta.iter_mut().zip(t) {
            *e = self.viscosity(p, t);
        }
    }
    /// Density rho(p, T) (kg/m^3).
    fn density(&self, p: f64, t: f64) -> f64;
    /// d rho / dT at constant p (kg/(m^3 K)); negative for thermal expansion.
    fn density_dt(&self, p: f64, t: f64) -> f64;
    /// The viscosity-temperature coefficient beta = -d ln eta / dT (1/K) of the low-shear
    /// law at (p, T), by a central difference over +-0.5 K (Roelands' beta varies by well under
    /// 1 % over a kelvin); 0 where the viscosity does not fall with T or the law fails there.
    /// For the linearisations of the heating (`film_energy::LineCoefficients::heating_slope`,
    /// the film-body update's softening in `contact`): how fast a warmer film shears less.
    fn viscosity_temperature_coefficient(&self, p: f64, t: f64) -> f64 {
        let beta = (self.viscosity(p, t - 0.5) / self.viscosity(p, t + 0.5)).ln();
        if beta.is_finite() && beta > 0.0 {
            beta
        } else {
            0.0
        }
    }
    /// Effective viscosity tau / gamma_dot (Pa s) at the shear rate magnitude `shear_rate`
    /// (1/s) for the low-shear viscosity `eta`; Newtonian (returns `eta`) unless overridden,
    /// e.g. with [`crate::lubricant::rheology::effective_viscosity`].
    fn effective_viscosity(&self, eta: f64, shear_rate: f64, p: f64, t: f64) -> f64 {
        let _ = (shear_rate, p, t);
        eta
    }
    /// ln eta_eff and its slope d ln eta_eff / d ln gamma_dot at `ln_eta` = ln eta (the
    /// low-shear viscosity) and `ln_shear_rate` = ln |gamma_dot| (-inf: zero shear), for the
    /// Newton iteration of [`shear_thinning_profile`]. The default goes through
    /// [`FilmLaws::effective_viscosity`] and a one-sided difference of relative step 1e-6 in
    /// gamma_dot (slope accurate to ~1e-6); laws with a closed form override it (e.g. with
    /// [`crate::lubricant::rheology::ln_effective_viscosity`]).
    fn ln_effective_viscosity(
        &self,
        ln_eta: f64,
        ln_shear_rate: f64,
        p: f64,
        t: f64,
    ) -> (f64, f64) {
        const STEP: f64 = 1e-6;
        let (eta, g) = (ln_eta.exp(), ln_shear_rate.exp());
        let a = self.effective_viscosity(eta, g, p, t);
        if !(g > 0.0) {
            return (a.ln(), 0.0);
        }
        let b = self.effective_viscosity(eta, g * (1.0 + STEP), p, t);
        let s = (b.ln() - a.ln()) / STEP.ln_1p();
        (a.ln(), if s.is_finite() { s } else { 0.0 })
    }
    /// The law of [`FilmLaws::ln_effective_viscosity`] at (p, T) with its constants formed
    /// once, where it has the closed form of [`LnShearLaw`] (None, the default: the column
    /// iteration calls `ln_effective_viscosity`). Must agree with it.
    fn ln_shear_law(&self, p: f64, t: f64) -> Option<LnShearLaw> {
        let _ = (p, t);
        None
    }
    /// The limiting shear stress tau_L (Pa) at (p, T), if the law has one (None: no limit).
    /// [`super::film_energy::line_coefficients`] caps each column's stress with it.
    fn limiting_shear_stress(&self, p: f64, t: f64) -> Option<f64> {
        let _ = (p, t);
        None
    }
}

/// Thermal properties of the oil.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OilThermal {
    /// conductivity k_f (W/(m K)) at ambient pressure, k0
    pub conductivity: f64,
    /// specific heat capacity c (J/(kg K)), constant: the volumetric rho c grows with
    /// pressure through the density law (Dowson-Higginson: +22 % at 1 GPa)
    pub heat_capacity: f64,
    /// the conductivity's pressure dependence [a, b] (1/Pa, each >= 0; [0, 0]: constant),
    /// see [`OilThermal::conductivity_at`]
    pub conductivity_pressure: [f64; 2],
}

impl OilThermal {
    /// An oil of constant conductivity `k` (W/(m K)) and heat capacity `c` (J/(kg K)).
    pub fn constant(k: f64, c: f64) -> Self {
        OilThermal {
            conductivity: k,
            heat_capacity: c,
            conductivity_pressure: [0.0; 2],
        }
    }

    /// k_f(p) = k0 (1 + a p / (1 + b p)) (W/(m K)), p in Pa (negative p taken as 0): a
    /// conductivity that grows with pressure and levels off, the behaviour Larsson & Andersson
    /// (2000, Proc. IMechE J 214, 337-342) measured on lubricants to ~1 GPa. a and b are the
    /// oil's own, fitted to its data; with b = 0 the growth is linear.
    pub fn conductivity_at(&self, p: f64) -> f64 {
        let [a, b] = self.conductivity_pressure;
        let p = p.max(0.0);
        self.conductivity * (1.0 + a * p / (1.0 + b * p))
    }
}

/// Values at the points across the film: on the stack up to 16 points (the default is 7, the
/// retry 11; at most 33 are allowed), since a profile is formed once per column per film
/// iteration and its small heap vectors were ~6 % of a thermal transient run (perf, the thesis
/// pit at 128 x 128).
pub type PointValues = smallvec::SmallVec<[f64; 16]>;

/// The velocity and stress profile of one film column and its generalized Reynolds
/// coefficients (see the module documentation). Point values are at the rule's points
/// zeta_k, k = 0..nz.
#[derive(Debug, Clone, PartialEq)]
pub struct FilmProfile {
    /// u(z_k) (m/s)
    pub u: PointValues,
    /// v(z_k) (m/s)
    pub v: PointValues,
    /// tau_zx(z_k) = tau_a + z_k dp/dx (Pa)
    pub tau_zx: PointValues,
    /// tau_zy(z_k) (Pa)
    pub tau_zy: PointValues,
    /// shear heating tau_zx du/dz + tau_zy dv/dz = |tau|^2 / eta (W/m^3)
    pub heating: PointValues,
    /// F0 = int_0^h dz / eta (m/(Pa s))
    pub f0: f64,
    /// F1 = int_0^h z dz / eta (m^2/(Pa s))
    pub f1: f64,
    /// eta_e = h / F0 (Pa s)
    pub eta_e: f64,
    /// eta'_e = h^2 / F1 (Pa s)
    pub eta_e1: f64,
    /// rho_e = (1/h) int rho dz (kg/m^3)
    pub rho_e: f64,
    /// rho'_e = (1/h^2) int rho int_0^z dz'/eta dz (kg/(m^3 Pa s))
    pub rho_e1: f64,
    /// rho''_e = (1/h^3) int rho int_0^z z'/eta dz' dz (kg/(m^3 Pa s))
    pub rho_e2: f64,
    /// (rho/eta)_e = 12 (eta_e rho'_e / eta'_e - rho''_e) (kg/(m^3 Pa s)): the Poiseuille
    /// coefficient, q = -(rho/eta)_e h^3/12 grad p + ...
    pub rho_over_eta_e: f64,
    /// rho*_x u_e = u1 rho_e + (u2 - u1) eta_e rho'_e (kg/(m^2 s)): the Couette flux per unit
    /// film thickness; see [`FilmProfile::rho_star_x`]
    pub rho_star_ue: f64,
    /// q_x = -(rho/eta)_e h^3/12 dp/dx + rho*_x u_e h (kg/(m s))
    pub flux_x: f64,
    /// q_y = -(rho/eta)_e h^3/12 dp/dy (kg/(m s))
    pub flux_y: f64,
    /// (x, y) force per unit area the film exerts on surface 1: (tau_zx(0), tau_zy(0)) (Pa)
    pub traction1: [f64; 2],
    /// (x, y) force per unit area the film exerts on surface 2: -(tau_zx(h), tau_zy(h)) (Pa)
    pub traction2: [f64; 2],
}

impl FilmProfile {
    /// rho*_x = (rho*_x u_e) / u_e (kg/m^3), `None` when u_e = (u1 + u2)/2 = 0 (use
    /// [`FilmProfile::rho_star_ue`] then).
    pub fn rho_star_x(&self, u1: f64, u2: f64) -> Option<f64> {
        let ue = 0.5 * (u1 + u2);
        (ue != 0.0).then(|| self.rho_star_ue / ue)
    }
}

/// One film column: the film, the pressure gradient and the surface speeds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Column {
    /// film thickness h (m), positive and finite
    pub h: f64,
    /// dp/dx (Pa/m)
    pub dpdx: f64,
    /// dp/dy (Pa/m)
    pub dpdy: f64,
    /// speed of surface 1 (z = 0) along +x (m/s)
    pub u1: f64,
    /// speed of surface 2 (z = h) along +x (m/s)
    pub u2: f64,
}

impl Column {
    fn check(&self) -> Result<(), FilmError> {
        if !(self.h > 0.0 && self.h.is_finite()) {
            return Err(FilmError::Input(format!(
                "film thickness must be positive and finite, got {}",
                self.h
            )));
        }
        for (name, v) in [
            ("dp/dx", self.dpdx),
            ("dp/dy", self.dpdy),
            ("u1", self.u1),
            ("u2", self.u2),
        ] {
            if !v.is_finite() {
                return Err(FilmError::Input(format!("{name} must be finite, got {v}")));
            }
        }
        Ok(())
    }

    /// (tau_a, tau_b) = the shear stresses at z = 0 for the viscosities `eta` at the points.
    fn wall_stress(&self, rule: &Lobatto, eta: &[f64]) -> (f64, f64, f64, f64) {
        let h = self.h;
        let (mut f0, mut f1) = (0.0, 0.0);
        for k in 0..rule.len() {
            f0 += rule.weights[k] / eta[k];
            f1 += rule.weights[k] * rule.points[k] / eta[k];
        }
        f0 *= h;
        f1 *= h * h;
        let tau_a = (self.u2 - self.u1 - self.dpdx * f1) / f0;
        let tau_b = -self.dpdy * f1 / f0;
        (tau_a, tau_b, f0, f1)
    }
}

fn check_points(rule: &Lobatto, name: &'static str, f: &[f64]) -> Result<(), FilmError> {
    if f.len() != rule.len() {
        return Err(FilmError::Input(format!(
            "{name} has {} values, the rule has {} points",
            f.len(),
            rule.len()
        )));
    }
    if let Some(v) = f.iter().find(|v| !(**v > 0.0 && v.is_finite())) {
        return Err(FilmError::Input(format!(
            "{name} must be positive and finite at every point, got {v}"
        )));
    }
    Ok(())
}

/// Velocity profile and generalized Reynolds coefficients of a column whose viscosity `eta`
/// (Pa s, the local, effective viscosity) and density `rho` (kg/m^3) are given at the rule's
/// points (see the module documentation for the equations, Yang & Wen 1990). The integrals
/// across z are the rule's cumulative integral and quadrature of the interpolants of 1/eta,
/// z/eta, rho / eta ...: exact when those are polynomials of degree < nz, spectrally
/// accurate for smooth profiles.
pub fn velocity_profile(
    rule: &Lobatto,
    col: &Column,
    eta: &[f64],
    rho: &[f64],
) -> Result<FilmProfile, FilmError> {
    col.check()?;
    check_points(rule, "viscosity", eta)?;
    check_points(rule, "density", rho)?;
    let n = rule.len();
    let h = col.h;
    // the integrals' scratch on the stack up to 16 points, the point values written in one
    // loop (this runs once per film column and film iteration; with the in-place cap of
    // `film_energy::capped_profile`: the thesis roller with `[thermal]` at 128 x 256 on one
    // thread 3.27 -> 3.19 s CPU, medians of 5 alternating runs, bit-identical results)
    let (mut stack, mut heap) = ([0.0f64; 2 * 16], Vec::new());
    let work = scratch(&mut stack, &mut heap, 2 * n);
    let (i0, i1) = work.split_at_mut(n);
    let c = column_integrals(rule, h, eta, rho, i0, i1);
    let (f0, f1) = (c.f0, c.f1);
    let tau_a = (col.u2 - col.u1 - col.dpdx * f1) / f0;
    let tau_b = -col.dpdy * f1 / f0;
    let zeros = || PointValues::from_elem(0.0, n);
    let (mut u, mut v, mut tau_zx, mut tau_zy, mut heating) =
        (zeros(), zeros(), zeros(), zeros(), zeros());
    for k in 0..n {
        let z = rule.points[k];
        u[k] = col.u1 + tau_a * i0[k] + col.dpdx * i1[k];
        v[k] = tau_b * i0[k] + col.dpdy * i1[k];
        tau_zx[k] = tau_a + h * z * col.dpdx;
        tau_zy[k] = tau_b + h * z * col.dpdy;
        heating[k] = (tau_zx[k] * tau_zx[k] + tau_zy[k] * tau_zy[k]) / eta[k];
    }
    let rho_star_ue = col.u1 * c.rho_e + (col.u2 - col.u1) * c.eta_e * c.rho_e1;
    let flux_x = -c.rho_over_eta_e * h.powi(3) / 12.0 * col.dpdx + rho_star_ue * h;
    let flux_y = -c.rho_over_eta_e * h.powi(3) / 12.0 * col.dpdy;
    Ok(FilmProfile {
        traction1: [tau_zx[0], tau_zy[0]],
        traction2: [-tau_zx[n - 1], -tau_zy[n - 1]],
        u,
        v,
        tau_zx,
        tau_zy,
        heating,
        f0,
        f1,
        eta_e: c.eta_e,
        eta_e1: c.eta_e1,
        rho_e: c.rho_e,
        rho_e1: c.rho_e1,
        rho_e2: c.rho_e2,
        rho_over_eta_e: c.rho_over_eta_e,
        rho_star_ue,
        flux_x,
        flux_y,
    })
}

/// The integrals across the film that a column's profile and its generalized Reynolds
/// coefficients are built from (Yang & Wen 1990; see the module documentation), for the
/// viscosity `eta` (Pa s) and density `rho` (kg/m^3) at the rule's points of a film `h` (m)
/// thick. They depend on the viscosity and density across the film only, not on the pressure
/// gradient or the surface speeds.
#[derive(Debug, Clone, Copy)]
pub struct ColumnIntegrals {
    /// F0 = int_0^h dz / eta (m/(Pa s))
    pub f0: f64,
    /// F1 = int_0^h z dz / eta (m^2/(Pa s))
    pub f1: f64,
    /// rho_e = (1/h) int rho dz (kg/m^3)
    pub rho_e: f64,
    /// rho'_e (kg/(m^3 Pa s)), see [`FilmProfile::rho_e1`]
    pub rho_e1: f64,
    /// rho''_e (kg/(m^3 Pa s)), see [`FilmProfile::rho_e2`]
    pub rho_e2: f64,
    /// eta_e = h / F0 (Pa s)
    pub eta_e: f64,
    /// eta'_e = h^2 / F1 (Pa s)
    pub eta_e1: f64,
    /// (rho/eta)_e = 12 (eta_e rho'_e / eta'_e - rho''_e) (kg/(m^3 Pa s)), the Poiseuille
    /// coefficient
    pub rho_over_eta_e: f64,
}

/// [`ColumnIntegrals`] of a column; `i0`, `i1` (rule.len() values each) receive the cumulative
/// integrals int_0^z dz'/eta and int_0^z z' dz'/eta at the points (m/(Pa s), m^2/(Pa s)).
pub fn column_integrals(
    rule: &Lobatto,
    h: f64,
    eta: &[f64],
    rho: &[f64],
    i0: &mut [f64],
    i1: &mut [f64],
) -> ColumnIntegrals {
    let n = rule.len();
    let (mut stack, mut heap) = ([0.0f64; 2 * 16], Vec::new());
    let work = scratch(&mut stack, &mut heap, 2 * n);
    let (inv, zinv) = work.split_at_mut(n);
    for k in 0..n {
        inv[k] = 1.0 / eta[k];
        zinv[k] = inv[k] * rule.points[k];
    }
    rule.apply(&rule.cumulative, inv, i0);
    rule.apply(&rule.cumulative, zinv, i1);
    i0.iter_mut().for_each(|v| *v *= h);
    i1.iter_mut().for_each(|v| *v *= h * h);
    let (f0, f1) = (i0[n - 1], i1[n - 1]);
    let rho_e = rule.integrate(rho);
    let rho_e1 = (0..n)
        .map(|k| rule.weights[k] * rho[k] * i0[k])
        .sum::<f64>()
        / h;
    let rho_e2 = (0..n)
        .map(|k| rule.weights[k] * rho[k] * i1[k])
        .sum::<f64>()
        / (h * h);
    let eta_e = h / f0;
    let eta_e1 = h * h / f1;
    ColumnIntegrals {
        f0,
        f1,
        rho_e,
        rho_e1,
        rho_e2,
        eta_e,
        eta_e1,
        rho_over_eta_e: 12.0 * (eta_e * rho_e1 / eta_e1 - rho_e2),
    }
}

/// `len` zeros for a column's scratch: the start of `stack` where they fit (no allocation in the
/// column loops, which run once per column and film iteration), else `heap` grown to them.
pub(crate) fn scratch<'a>(
    stack: &'a mut [f64],
    heap: &'a mut Vec<f64>,
    len: usize,
) -> &'a mut [f64] {
    if len <= stack.len() {
        let s = &mut stack[..len];
        s.fill(0.0);
        s
    } else {
        heap.clear();
        heap.resize(len, 0.0);
        heap
    }
}

/// Options of the shear-thinning iteration of [`shear_thinning_profile`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearOptions {
    /// tolerance on max_k |ln eta_eff,k - ln eta_law(gamma_k)| (relative viscosity mismatch)
    pub tol: f64,
    /// at most this many Newton iterations
    pub max_iter: usize,
}

impl Default for ShearOptions {
    fn default() -> Self {
        ShearOptions {
            tol: 1e-10,
            max_iter: 50,
        }
    }
}

/// A shear-thinning column: the profile at the converged effective viscosity and how the
/// iteration went.
#[derive(Debug, Clone, PartialEq)]
pub struct ShearThinningProfile {
    pub profile: FilmProfile,
    /// effective viscosity at the points (Pa s)
    pub eta_eff: PointValues,
    /// Newton iterations done (0: the law is Newtonian at this state)
    pub iterations: usize,
    /// final max_k |ln eta_eff,k - ln eta_law(gamma_k)|
    pub residual: f64,
    /// residual <= tol
    pub converged: bool,
}

/// Velocity profile of a generalized-Newtonian column: the effective viscosity at each point
/// depends on the local shear rate gamma = |tau| / eta_eff, which depends on the whole profile.
/// Starts from the low-shear viscosity; [`shear_thinning_profile_from`] takes a start.
#[allow(clippy::too_many_arguments)]
pub fn shear_thinning_profile<L: FilmLaws + ?Sized>(
    rule: &Lobatto,
    laws: &L,
    col: &Column,
    p: f64,
    t: &[f64],
    eta: &[f64],
    rho: &[f64],
    opts: ShearOptions,
) -> Result<ShearThinningProfile, FilmError> {
    shear_thinning_profile_from(rule, laws, col, p, t, eta, rho, opts, None)
}

/// [`shear_thinning_profile`] from a start `start` (the effective viscosity at the points, Pa s;
/// e.g. the last solution of a neighbouring state, which cuts the Newton iterations to one or
/// two; `None`: the low-shear viscosity `eta`).
///
/// Unknowns y_k = ln eta_eff,k; residual R_k = y_k - ln eta_law(eta_k, gamma_k(y), p, T_k)
/// ([`FilmLaws::ln_effective_viscosity`]); Newton's method with the Jacobian
///   dR_k/dy_j = delta_kj - s_k (-delta_kj + d ln|tau_k| / dy_j),
/// s_k = d ln eta_law / d ln gamma at point k (the law's only contribution, from the same call
/// as its value), tau_k = (tau_a + z_k dp/dx, tau_b + z_k dp/dy) with tau_a, tau_b functions of
/// all y through F0 = h sum w_j e^{-y_j} and F1 = h^2 sum w_j zeta_j e^{-y_j}; a halving line
/// search on max |R|. A Newtonian law gives R = 0 at y = ln eta: 0 iterations.
/// Non-convergence within `opts.max_iter` (or where the line search's shortest step, below
/// 1e-3 of the full one, cannot be evaluated either) is reported in the result, not as an
/// error; a start the law fails at is an error. (Before 2026-11-29 such a stall was an error,
/// which sent a thermal run to its retry at more points across the film.)
///
/// `eta` is the low-shear viscosity at the points (Pa s), `rho` the density (kg/m^3), `p` the
/// pressure (Pa), `t` the temperature at the points (K).
#[allow(clippy::too_many_arguments)]
pub fn shear_thinning_profile_from<L: FilmLaws + ?Sized>(
    rule: &Lobatto,
    laws: &L,
    col: &Column,
    p: f64,
    t: &[f64],
    eta: &[f64],
    rho: &[f64],
    opts: ShearOptions,
    start: Option<&[f64]>,
) -> Result<ShearThinningProfile, FilmError> {
    col.check()?;
    check_points(rule, "viscosity", eta)?;
    check_points(rule, "temperature", t)?;
    if let Some(s) = start {
        check_points(rule, "start viscosity", s)?;
    }
    let n = rule.len();
    // each point's law with its constants formed once (the temperatures are fixed here)
    let closed: smallvec::SmallVec<[Option<LnShearLaw>; 16]> =
        t.iter().map(|&tk| laws.ln_shear_law(p, tk)).collect();
    // a Newtonian film at every point: eta_eff = eta, R = 0 from the start whatever it is
    // (skips 3 transcendental functions a point: 5-8 % of a Newtonian thermal run)
    if closed
        .iter()
        .all(|l| matches!(l, Some(LnShearLaw::Newtonian)))
    {
        return Ok(ShearThinningProfile {
            profile: velocity_profile(rule, col, eta, rho)?,
            eta_eff: PointValues::from_slice(eta),
            iterations: 0,
            residual: 0.0,
            converged: true,
        });
    }
    let h = col.h;
    // every per-point vector in one buffer, on the stack up to 16 points: this runs once per
    // film column per film iteration, and its ~15 small vectors were 11 % of a thermal
    // transient run (perf, the thesis pit at 128 x 128)
    // (a plain array, not a SmallVec: building and moving its 2 KB was 1 % of a run)
    let (mut stack, mut heap) = ([0.0f64; 16 * 16], Vec::new());
    let work = scratch(&mut stack, &mut heap, 16 * n);
    let (ln_eta, rest) = work.split_at_mut(n);
    let (mut eta_eff, rest) = rest.split_at_mut(n);
    let (mut y, rest) = rest.split_at_mut(n);
    let (mut r, rest) = rest.split_at_mut(n);
    let (mut slope, rest) = rest.split_at_mut(n);
    let (mut yp, rest) = rest.split_at_mut(n);
    let (mut rp, rest) = rest.split_at_mut(n);
    let (mut sp, rest) = rest.split_at_mut(n);
    let (mut scratch, rest) = rest.split_at_mut(n);
    let (dta, rest) = rest.split_at_mut(n);
    let (dtb, rest) = rest.split_at_mut(n);
    let (tau_x, rest) = rest.split_at_mut(n);
    let (tau_y, rest) = rest.split_at_mut(n);
    let (delta, rest) = rest.split_at_mut(n);
    let (wa, wb) = rest.split_at_mut(n);
    for (l, e) in ln_eta.iter_mut().zip(eta) {
        *l = e.ln();
    }
    let ln_eta: &[f64] = ln_eta;
    // the residual R(y) into r and the law's slopes into s
    let residual = |y: &[f64], eta_eff: &mut [f64], r: &mut [f64], s: &mut [f64]| {
        for k in 0..n {
            eta_eff[k] = y[k].exp();
        }
        let (ta, tb, _, _) = col.wall_stress(rule, eta_eff);
        for k in 0..n {
            let z = h * rule.points[k];
            let (tx, ty) = (ta + z * col.dpdx, tb + z * col.dpdy);
            // ln |tau| = ln(tau_x^2 + tau_y^2) / 2 (no overflow: stresses below 1e150 Pa)
            let ln_tau = 0.5 * (tx * tx + ty * ty).ln();
            let (law, slope) = match &closed[k] {
                Some(l) => l.eval(ln_eta[k], ln_tau - y[k]),
                None => laws.ln_effective_viscosity(ln_eta[k], ln_tau - y[k], p, t[k]),
            };
            if !law.is_finite() {
                return Err(FilmError::Law {
                    law: "effective viscosity",
                    value: law.exp(),
                    p,
                    t: t[k],
                });
            }
            r[k] = y[k] - law;
            s[k] = slope;
        }
        Ok(())
    };
    let norm = |r: &[f64]| r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    match start {
        Some(s) => y.iter_mut().zip(s).for_each(|(y, e)| *y = e.ln()),
        None => y.copy_from_slice(ln_eta),
    }
    residual(y, eta_eff, r, slope)?;
    let mut res = norm(r);
    let mut iterations = 0;
    // (eta_eff holds exp(y) from here on: the residual's evaluation at y wrote it, and an
    // accepted trial point's is swapped in with it)
    while res > opts.tol && iterations < opts.max_iter {
        iterations += 1;
        let (ta, tb, f0, _) = col.wall_stress(rule, eta_eff);
        for j in 0..n {
            let e = rule.weights[j] / eta_eff[j];
            let d0 = -h * e;
            let d1 = -h * h * rule.points[j] * e;
            dta[j] = (-col.dpdx * d1 - ta * d0) / f0;
            dtb[j] = (-col.dpdy * d1 - tb * d0) / f0;
        }
        for k in 0..n {
            let z = h * rule.points[k];
            tau_x[k] = ta + z * col.dpdx;
            tau_y[k] = tb + z * col.dpdy;
        }
        if !newton_step(r, slope, (tau_x, tau_y), (dta, dtb), delta, (wa, wb)) {
            // singular Jacobian: a plain fixed-point step y <- ln eta_law
            delta.iter_mut().zip(r.iter()).for_each(|(d, v)| *d = -v);
        }
        // a trial point where the law fails (an effective viscosity that is not finite: a
        // step far past the solution at an extreme shear rate) is a step too long, not a
        // failure of the column: halved like one that does not lower the residual
        let mut lambda = 1.0;
        let mut stalled = false;
        loop {
            for k in 0..n {
                yp[k] = y[k] + lambda * delta[k];
            }
            let rn = match residual(yp, scratch, rp, sp) {
                Ok(()) => norm(rp),
                Err(_) => f64::INFINITY,
            };
            if rn < res || (lambda < 1e-3 && rn.is_finite()) {
                std::mem::swap(&mut y, &mut yp);
                std::mem::swap(&mut eta_eff, &mut scratch);
                std::mem::swap(&mut r, &mut rp);
                std::mem::swap(&mut slope, &mut sp);
                res = rn;
                break;
            }
            if lambda < 1e-3 {
                // no step along delta is evaluable: stop with the last iterate, unconverged
                stalled = true;
                break;
            }
            lambda *= 0.5;
        }
        if stalled {
            break;
        }
    }
    let profile = velocity_profile(rule, col, eta_eff, rho)?;
    Ok(ShearThinningProfile {
        profile,
        eta_eff: PointValues::from_slice(eta_eff),
        iterations,
        residual: res,
        converged: res <= opts.tol,
    })
}

/// The Newton step J delta = -r of [`shear_thinning_profile_from`]'s residual
/// R_k(y) = y_k - ln eta_law(ln |tau_k| - y_k), y = ln eta_eff at the points across the film.
/// Its Jacobian is diagonal plus rank two: with s_k the law's slope d ln eta_law / d ln gamma,
/// the wall stress (tau_a, tau_b) depending on y through dta_j = d tau_a / d y_j and
/// dtb_j = d tau_b / d y_j, and tau_k = (tau_x, tau_y)_k the stress at point k,
///
/// J_kj = (1 + s_k) delta_kj - s_k (tau_x,k dta_j + tau_y,k dtb_j) / |tau_k|^2 = D - U V^T,
///
/// U = s (tau_x, tau_y) / |tau|^2 and V = (dta, dtb) (n x 2 each). Solved by
/// Sherman-Morrison-Woodbury in O(n): delta = z + W (I - V^T W)^-1 V^T z with z = -D^-1 r and
/// W = D^-1 U (the dense LU it replaces was 12 % of a thermal run). `wa`, `wb` hold W.
/// False where D or the 2 x 2 capacitance matrix is singular or not finite.
fn newton_step(
    r: &[f64],
    slope: &[f64],
    (tau_x, tau_y): (&[f64], &[f64]),
    (dta, dtb): (&[f64], &[f64]),
    delta: &mut [f64],
    (wa, wb): (&mut [f64], &mut [f64]),
) -> bool {
    // C = I - V^T W (2 x 2), g = V^T z
    let (mut c11, mut c12, mut c21, mut c22) = (1.0, 0.0, 0.0, 1.0);
    let (mut g1, mut g2) = (0.0, 0.0);
    for k in 0..r.len() {
        let d = 1.0 + slope[k];
        if d == 0.0 || !d.is_finite() {
            return false;
        }
        let mag2 = tau_x[k] * tau_x[k] + tau_y[k] * tau_y[k];
        let (ua, ub) = if mag2 > 0.0 {
            (slope[k] * tau_x[k] / mag2, slope[k] * tau_y[k] / mag2)
        } else {
            (0.0, 0.0)
        };
        wa[k] = ua / d;
        wb[k] = ub / d;
        delta[k] = -r[k] / d;
        c11 -= dta[k] * wa[k];
        c12 -= dta[k] * wb[k];
        c21 -= dtb[k] * wa[k];
        c22 -= dtb[k] * wb[k];
        g1 += dta[k] * delta[k];
        g2 += dtb[k] * delta[k];
    }
    let det = c11 * c22 - c12 * c21;
    if det == 0.0 || !det.is_finite() {
        return false;
    }
    let (y1, y2) = ((c22 * g1 - c12 * g2) / det, (c11 * g2 - c21 * g1) / det);
    for k in 0..r.len() {
        delta[k] += wa[k] * y1 + wb[k] * y2;
    }
    delta.iter().all(|d| d.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The O(n) Woodbury step equals the dense solve of the assembled Jacobian (the form it
    /// replaced) to rounding, on 9 points with mixed-sign stresses, slopes of a shear-thinning
    /// law (-1 < s < 0) and a point where the stress vanishes; and it refuses a singular
    /// diagonal (s = -1).
    #[test]
    fn the_rank_two_newton_step_equals_the_dense_solve() {
        let n = 9;
        let f = |k: usize, a: f64| (a * (k as f64 + 1.0)).sin();
        let r: Vec<f64> = (0..n).map(|k| f(k, 1.3)).collect();
        let slope: Vec<f64> = (0..n).map(|k| -0.45 + 0.4 * f(k, 0.7)).collect();
        let mut tx: Vec<f64> = (0..n).map(|k| 2e6 * f(k, 2.1)).collect();
        let ty: Vec<f64> = (0..n).map(|k| 5e5 * f(k, 0.4)).collect();
        tx[4] = 0.0;
        let mut ty = ty;
        ty[4] = 0.0;
        let dta: Vec<f64> = (0..n).map(|k| 3e5 * f(k, 1.7)).collect();
        let dtb: Vec<f64> = (0..n).map(|k| 1e5 * f(k, 0.9)).collect();
        let mut jac = vec![0.0; n * n];
        for k in 0..n {
            let mag2 = tx[k] * tx[k] + ty[k] * ty[k];
            for j in 0..n {
                let dln = if mag2 > 0.0 {
                    (tx[k] * dta[j] + ty[k] * dtb[j]) / mag2
                } else {
                    0.0
                };
                let own = if j == k { 1.0 } else { 0.0 };
                jac[k * n + j] = own - slope[k] * (-own + dln);
            }
        }
        let mut dense: Vec<f64> = r.iter().map(|v| -v).collect();
        assert!(crate::linalg::dense::solve_small(&mut jac, &mut dense, n));
        let (mut delta, mut wa, mut wb) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        assert!(newton_step(
            &r,
            &slope,
            (&tx, &ty),
            (&dta, &dtb),
            &mut delta,
            (&mut wa, &mut wb)
        ));
        let scale = dense.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in delta.iter().zip(&dense) {
            assert!((a - b).abs() < 1e-12 * scale, "{delta:?} against {dense:?}");
        }
        let mut singular = slope.clone();
        singular[2] = -1.0;
        assert!(!newton_step(
            &r,
            &singular,
            (&tx, &ty),
            (&dta, &dtb),
            &mut delta,
            (&mut wa, &mut wb)
        ));
    }

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs().max(1e-300)
    }

    /// Constant eta and rho: the classical film. Every quantity is a polynomial of degree <= 2
    /// in z (u is parabolic), so with nz = 5 the rule is exact and the tolerance is rounding
    /// (1e-12 relative, ~1e4 ulp for sums of a handful of O(1) terms with cancellation).
    #[test]
    fn constant_properties_give_the_classical_film() {
        let rule = Lobatto::new(5);
        let (eta, rho) = (0.04, 870.0);
        let col = Column {
            h: 2e-7,
            dpdx: -3e12,
            dpdy: 1e12,
            u1: 1.3,
            u2: 0.7,
        };
        let f = velocity_profile(&rule, &col, &[eta; 5], &[rho; 5]).unwrap();
        assert!(rel(f.rho_over_eta_e, rho / eta) < 1e-12);
        assert!(rel(f.rho_star_x(col.u1, col.u2).unwrap(), rho) < 1e-12);
        assert!(rel(f.rho_e, rho) < 1e-14);
        assert!(rel(f.eta_e, eta) < 1e-14 && rel(f.eta_e1, 2.0 * eta) < 1e-14);
        let h = col.h;
        for (k, zeta) in rule.points.iter().enumerate() {
            let z = zeta * h;
            let u =
                col.dpdx / (2.0 * eta) * (z * z - z * h) + col.u1 * (1.0 - zeta) + col.u2 * zeta;
            let v = col.dpdy / (2.0 * eta) * (z * z - z * h);
            assert!((f.u[k] - u).abs() < 1e-12, "u {k}: {} vs {u}", f.u[k]);
            assert!((f.v[k] - v).abs() < 1e-12, "v {k}: {} vs {v}", f.v[k]);
            let tzx = col.dpdx * (z - h / 2.0) + eta * (col.u2 - col.u1) / h;
            assert!(rel(f.tau_zx[k], tzx) < 1e-12);
            assert!(rel(f.heating[k], (tzx.powi(2) + f.tau_zy[k].powi(2)) / eta) < 1e-12);
        }
        // the classical flux and crate::friction's surface stress on body 2
        let q = -rho * h.powi(3) / (12.0 * eta) * col.dpdx + rho * 0.5 * (col.u1 + col.u2) * h;
        assert!(rel(f.flux_x, q) < 1e-12);
        assert!(rel(f.flux_y, -rho * h.powi(3) / (12.0 * eta) * col.dpdy) < 1e-12);
        let tau2 = -(h / 2.0) * col.dpdx + eta * (col.u1 - col.u2) / h;
        assert!(rel(f.traction2[0], tau2) < 1e-12);
        assert!(
            rel(
                f.traction1[0],
                -(h / 2.0) * col.dpdx + eta * (col.u2 - col.u1) / h
            ) < 1e-12
        );
    }

    /// Sign convention: with no pressure gradient the faster surface 1 is held back
    /// (traction1 < 0) and the slower surface 2 pulled forward (traction2 > 0), by equal and
    /// opposite forces.
    #[test]
    fn drag_pulls_the_slower_surface_forward() {
        let rule = Lobatto::new(7);
        let eta: Vec<f64> = rule.points.iter().map(|z| 0.1 * (2.0 * z).exp()).collect();
        let col = Column {
            h: 1e-6,
            dpdx: 0.0,
            dpdy: 0.0,
            u1: 2.0,
            u2: 1.0,
        };
        let f = velocity_profile(&rule, &col, &eta, &[800.0; 7]).unwrap();
        assert!(f.traction1[0] < 0.0 && f.traction2[0] > 0.0);
        assert_eq!(f.traction1[0], -f.traction2[0]);
        let col = Column {
            u1: 1.0,
            u2: 2.0,
            ..col
        };
        let f = velocity_profile(&rule, &col, &eta, &[800.0; 7]).unwrap();
        assert!(f.traction1[0] > 0.0 && f.traction2[0] < 0.0);
    }

    /// eta = eta0 exp(a zeta), rho = rho0 (1 + b zeta): the flux by quadrature of rho u from the
    /// profile equals the formula (an algebraic identity of the discrete integrals: rounding,
    /// 1e-12), the profile meets both surface speeds (to rounding), F0 and F1 converge
    /// spectrally to their closed forms, and so does the flux (nz = 7 against nz = 21).
    #[test]
    fn variable_properties_flux_and_convergence() {
        let (eta0, a, rho0, b) = (0.05, 1.5, 850.0, -0.2);
        let col = Column {
            h: 5e-7,
            dpdx: 4e11,
            dpdy: -2e11,
            u1: 0.4,
            u2: 1.9,
        };
        let run = |nz: usize| {
            let rule = Lobatto::new(nz);
            let eta: Vec<f64> = rule.points.iter().map(|z| eta0 * (a * z).exp()).collect();
            let rho: Vec<f64> = rule.points.iter().map(|z| rho0 * (1.0 + b * z)).collect();
            let f = velocity_profile(&rule, &col, &eta, &rho).unwrap();
            let ru: Vec<f64> = (0..nz).map(|k| rho[k] * f.u[k]).collect();
            let rv: Vec<f64> = (0..nz).map(|k| rho[k] * f.v[k]).collect();
            let qx = col.h * rule.integrate(&ru);
            let qy = col.h * rule.integrate(&rv);
            assert!(rel(qx, f.flux_x) < 1e-12, "nz {nz}: {qx} vs {}", f.flux_x);
            assert!(rel(qy, f.flux_y) < 1e-12, "nz {nz}: {qy} vs {}", f.flux_y);
            assert!((f.u[0] - col.u1).abs() < 1e-14 && (f.u[nz - 1] - col.u2).abs() < 1e-13);
            assert!(f.v[0] == 0.0 && f.v[nz - 1].abs() < 1e-13);
            f
        };
        let h = col.h;
        let f0 = h * (1.0 - (-a).exp()) / (a * eta0);
        let f1 = h * h * (1.0 - (1.0 + a) * (-a).exp()) / (a * a * eta0);
        let reference = run(21);
        let mut previous = f64::INFINITY;
        for nz in [3usize, 5, 7, 9] {
            let f = run(nz);
            let err = rel(f.f0, f0).max(rel(f.f1, f1));
            // spectral: each step of 2 points gains more than a factor 30
            assert!(err < previous / 30.0, "nz {nz}: {err} after {previous}");
            previous = err;
            if nz == 7 {
                assert!(rel(f.flux_x, reference.flux_x) < 1e-8);
            }
        }
        assert!(previous < 1e-9);
    }

    /// A trial point of the column's Newton iteration where the law cannot be evaluated is a
    /// step too long, halved by the line search, not the column's failure (before, the error
    /// of the trial point ended the whole temperature solve with "the effective viscosity is
    /// NaN": an Eyring line at p_h = 2 GPa, 5 m/s, SRR 0.5, and an Eyring ball at 5 m/s).
    /// The law is extreme by design, to reach that point on a column of fixed temperature: a
    /// law thinning nearly to a constant stress (Carreau, n = 0.01) on a very viscous column
    /// (eta = 1e10 Pa s) whose pressure-flow stress (5e7 Pa at the walls) is ten times G. A
    /// Newton step from the low-shear viscosity, ~ -R / (1 + s) with 1 + s ~ n, takes
    /// ln eta_eff down by hundreds, where e^y underflows to 0 and the law fails. Found by a
    /// scan over eta and dp/dx: at dp/dx = 1e15 Pa/m the iteration without the shortening
    /// stopped with an error; with it the column converges, the law holding at every point
    /// (1e-9 relative; the iteration's tolerance is 1e-10 in ln eta).
    #[test]
    fn a_trial_step_where_the_law_fails_is_shortened() {
        let rule = Lobatto::new(7);
        let laws = Carreau { g: 4.5e6, n: 0.01 };
        let (t, rho, eta) = ([350.0; 7], [850.0; 7], [1e10; 7]);
        let col = Column {
            h: 1e-7,
            dpdx: 1e15,
            dpdy: 0.0,
            u1: 2.0,
            u2: 1.0,
        };
        let opts = ShearOptions {
            tol: 1e-10,
            max_iter: 200,
        };
        let s = shear_thinning_profile(&rule, &laws, &col, 1e9, &t, &eta, &rho, opts).unwrap();
        assert!(s.converged, "{s:?}");
        let f = &s.profile;
        for k in 0..7 {
            let gamma = f.tau_zx[k].abs() / s.eta_eff[k];
            let law = laws.effective_viscosity(eta[k], gamma, 0.0, 0.0);
            assert!(
                rel(s.eta_eff[k], law) < 1e-9,
                "{} against {law}",
                s.eta_eff[k]
            );
        }
    }

    /// A Carreau law (eta_eff = eta [1 + (eta gamma / G)^2]^((n - 1)/2)) in the tests.
    struct Carreau {
        g: f64,
        n: f64,
    }

    impl FilmLaws for Carreau {
        fn viscosity(&self, _: f64, _: f64) -> f64 {
            unreachable!()
        }
        fn density(&self, _: f64, _: f64) -> f64 {
            unreachable!()
        }
        fn density_dt(&self, _: f64, _: f64) -> f64 {
            unreachable!()
        }
        fn effective_viscosity(&self, eta: f64, gamma: f64, _: f64, _: f64) -> f64 {
            eta * (1.0 + (eta * gamma / self.g).powi(2)).powf(0.5 * (self.n - 1.0))
        }
    }

    /// Shear thinning. Plane Couette flow with uniform eta has the exact solution of a uniform
    /// effective viscosity at gamma = (u2 - u1)/h (checked to 1e-10, the iteration's
    /// tolerance); with a pressure gradient and a viscosity varying across z the converged
    /// state satisfies the law at every point (1e-10 relative, the tolerance) and the surface
    /// speeds; a Newtonian law takes 0 iterations; an iteration cut short reports it.
    #[test]
    fn shear_thinning_column() {
        let rule = Lobatto::new(9);
        let laws = Carreau { g: 4.5e6, n: 0.57 };
        let t = [350.0; 9];
        let rho = [850.0; 9];
        let eta = [1e4; 9];
        let col = Column {
            h: 1e-7,
            dpdx: 0.0,
            dpdy: 0.0,
            u1: 2.0,
            u2: 1.0,
        };
        let s = shear_thinning_profile(
            &rule,
            &laws,
            &col,
            1e9,
            &t,
            &eta,
            &rho,
            ShearOptions::default(),
        )
        .unwrap();
        assert!(s.converged, "{s:?}");
        let exact = laws.effective_viscosity(1e4, 1.0 / col.h, 0.0, 0.0);
        assert!(
            exact < 0.05 * 1e4,
            "the case must be strongly shear-thinning"
        );
        for e in &s.eta_eff {
            assert!(rel(*e, exact) < 1e-10, "{e} vs {exact}");
        }
        // pressure flow + sliding + a viscosity varying across z
        let eta: Vec<f64> = rule.points.iter().map(|z| 1e4 * (-1.5 * z).exp()).collect();
        // the pressure-flow stress h dp/dx ~ 1e9 Pa is of the order of the sliding stress
        let col = Column {
            dpdx: 1e16,
            dpdy: 5e15,
            ..col
        };
        let s = shear_thinning_profile(
            &rule,
            &laws,
            &col,
            1e9,
            &t,
            &eta,
            &rho,
            ShearOptions::default(),
        )
        .unwrap();
        // Newton with the exact (semi-analytic) Jacobian converges quadratically: a wrong
        // Jacobian still reaches the tolerance through the line search, but in many more steps
        assert!(
            s.converged && s.iterations > 2 && s.iterations <= 12,
            "{}: {}",
            s.iterations,
            s.residual
        );
        let f = &s.profile;
        for k in 0..9 {
            let gamma = f.tau_zx[k].hypot(f.tau_zy[k]) / s.eta_eff[k];
            let law = laws.effective_viscosity(eta[k], gamma, 0.0, 0.0);
            assert!(rel(s.eta_eff[k], law) < 1e-10);
        }
        assert!((f.u[8] - col.u2).abs() < 1e-12 && f.v[8].abs() < 1e-12);
        // a start: from the solution itself no iteration; from a start 30 % off the same
        // solution (to the tolerance, 1e-10 in ln eta) in fewer iterations than from eta
        let again = |start: &[f64]| {
            let o = ShearOptions::default();
            shear_thinning_profile_from(&rule, &laws, &col, 1e9, &t, &eta, &rho, o, Some(start))
                .unwrap()
        };
        let same = again(&s.eta_eff);
        assert_eq!((same.iterations, &same.eta_eff), (0, &s.eta_eff));
        let off: Vec<f64> = s.eta_eff.iter().map(|e| 1.3 * e).collect();
        let warm = again(&off);
        assert!(warm.converged && warm.iterations < s.iterations, "{warm:?}");
        for (a, b) in warm.eta_eff.iter().zip(&s.eta_eff) {
            assert!(rel(*a, *b) < 1e-9);
        }
        let short = ShearOptions {
            tol: 1e-10,
            max_iter: 1,
        };
        let s = shear_thinning_profile(&rule, &laws, &col, 1e9, &t, &eta, &rho, short).unwrap();
        assert!(!s.converged && s.iterations == 1);
        // a Newtonian law; `named`: it says so through its closed form (LnShearLaw::Newtonian,
        // as ThermalLaws does), else only through the default effective viscosity
        struct Newtonian {
            named: bool,
        }
        impl FilmLaws for Newtonian {
            fn viscosity(&self, _: f64, _: f64) -> f64 {
                1.0
            }
            fn density(&self, _: f64, _: f64) -> f64 {
                1.0
            }
            fn density_dt(&self, _: f64, _: f64) -> f64 {
                0.0
            }
            fn ln_shear_law(&self, _: f64, _: f64) -> Option<LnShearLaw> {
                self.named.then_some(LnShearLaw::Newtonian)
            }
        }
        let (plain, named) = (Newtonian { named: false }, Newtonian { named: true });
        let s = shear_thinning_profile(&rule, &plain, &col, 1e9, &t, &eta, &rho, short).unwrap();
        assert!(s.converged && s.iterations == 0);
        // the named law skips the residual: the same profile as the general path, from any start
        let o = ShearOptions::default();
        let fast =
            shear_thinning_profile_from(&rule, &named, &col, 1e9, &t, &eta, &rho, o, Some(&off))
                .unwrap();
        let general = shear_thinning_profile(&rule, &plain, &col, 1e9, &t, &eta, &rho, o).unwrap();
        // (to rounding: the general path's eta_eff is exp(ln eta))
        assert_eq!((fast.iterations, general.iterations), (0, 0));
        let (a, b) = (&fast.profile, &general.profile);
        for k in 0..9 {
            assert!(rel(fast.eta_eff[k], general.eta_eff[k]) < 1e-14);
            assert!(rel(fast.eta_eff[k], eta[k]) == 0.0);
            for (x, y) in [
                (a.u[k], b.u[k]),
                (a.tau_zx[k], b.tau_zx[k]),
                (a.heating[k], b.heating[k]),
            ] {
                assert!((x - y).abs() <= 1e-13 * y.abs().max(1.0), "{x} vs {y}");
            }
        }
        assert!(rel(a.rho_over_eta_e, b.rho_over_eta_e) < 1e-13);
    }
}
