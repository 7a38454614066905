//! The energy equation of the film along one grid line (fixed y), with Lobatto collocation
//! across the film ([`super::collocation`]) and upwind differences along x.
//!
//! # Equation
//!
//! Steady, in-plane conduction neglected (Yang & Wen 1990; Kim & Sadeghi 1992):
//!
//! rho c (u dT/dx + w dT/dz) - k_f d2T/dz2 = S - (T/rho)(d rho/dT)(u dp/dx + v dp/dy),
//!
//! S = tau_zx du/dz + tau_zy dv/dz the shear heating (W/m^3). In the film coordinate
//! zeta = z / h(x), dT/dx at fixed z = dT/dx at fixed zeta - (zeta h'/h) dT/dzeta (the stretching
//! of the coordinate), and the across-film velocity w, from continuity
//! d(rho u)/dx + d(rho w)/dz = 0 with w = 0 on surface 1, combines with the stretching into the
//! mass flux across the surfaces zeta = const:
//!
//! J = rho (w - zeta h' u) = -dQ/dx at fixed zeta,   Q(x, zeta) = h int_0^zeta rho u dzeta',
//!
//! so that the equation, multiplied by h, reads
//!
//! c m dT/dx|_zeta + c J dT/dzeta - (k_f / h) d2T/dzeta2 + h a T = h S,
//!
//! with m = h rho u (kg/(m s), the mass flux per unit zeta) and
//! a = (1/rho)(d rho/dT)(u dp/dx + v dp/dy) (W/(m^3 K)). Keeping J (rather than the stretching term alone, which is what the
//! equation without w gives) is what makes the scheme conserve energy: with J, the convective
//! terms are c [d(m T)/dx + d(J T)/dzeta] minus T times the continuity equation.
//!
//! # Discretisation
//!
//! * Across z: Lobatto collocation (nz points, the two end points carry the surface
//!   temperatures T1, T2, given); the equation holds at the nz - 2 interior points.
//! * Along x: cells i = 0..nx of width dx. At each collocation point the convection is the
//!   first-order upwind difference of the conservative flux minus T_i times its divergence,
//!   (1/dx) [m_{i+1/2}^- (T_{i+1} - T_i) + m_{i-1/2}^+ (T_i - T_{i-1})], m^+ = max(m, 0),
//!   m^- = min(m, 0), with the face flux m_{i+1/2} = (m_i + m_{i+1})/2 (the end faces take
//!   their cell's value): the upwind side is chosen per point by the sign of the flow there, and
//!   wherever the flow enters the line (at the inlet i = 0 with u > 0, or reverse flow at the
//!   outlet) the upstream temperature is the inlet temperature T_in. First order: a
//!   second-order upwind scheme is not monotone along x and was not attempted.
//! * J at cell i is -(Q_{i+1/2} - Q_{i-1/2}) / dx, Q_{face} the rule's cumulative integral of
//!   the face flux m_face, so that dJ/dzeta matches the upwind divergence (to the rule's
//!   accuracy): the discrete energy balance then telescopes (see [`LineEnergy`]).
//! * In the thick inlet, where the film is more than [`PECLET_BOUND_FILM_RATIO`] times the line's
//!   thinnest, a column's conduction across the film is raised so that no point's Peclet number
//!   c |J| h dzeta / k exceeds [`MAX_CROSS_FILM_PECLET`] ([`cell_conductivity`]). There, where a
//!   reverse flow turns, J is the x-difference of column fluxes over dx and reaches Peclet numbers
//!   of ~160 on fine grids; with the oil's conductivity the collocated c J dT/dzeta oscillated
//!   across the film (measured: -900 K at the first cells of the Table 3.7 line at 1024 cells,
//!   dx = 2 um, and on the thesis roller at 256 x 256: the run ended with a negative density). The
//!   artificial conduction is uniform across the column, so the balance still telescopes; a
//!   first-order upwind difference across z, tried first, stabilised it as well but put the balance
//!   of a pure-rolling line 0.6 % off.
//! * Along y (the side flow of a finite contact, [`SideFlow`]): the same upwind difference of
//!   the y mass flux per unit zeta m_y = h rho v between the line and its neighbours at
//!   y -+ dy, (1/dy) [m_n^- (T_N - T) + m_s^+ (T - T_S)] (faces n = j + 1/2, s = j - 1/2), and
//!   the y-divergence (m_n - m_s)/dy in J. It couples the lines: the caller passes the
//!   neighbours' temperatures and the face fluxes (lagged: its last iterate, or for the
//!   temperatures a neighbour solved just before, `crate::thermal::contact`), the line's own
//!   T implicit. With J carrying the divergence, the convection is the conservative
//!   difference of the upwinded flux minus T times continuity, as along x, and the enthalpy a
//!   line exchanges with its neighbours, [`LineEnergy::side_out`], cancels between lines up to
//!   the lag.
//! * Unknowns theta = T - T_in (a line with no heating whose surfaces and inlet are at T_in
//!   gives exactly theta = 0), ordered i-major (cell by cell, nz - 2 per cell): one banded
//!   system with nz - 2 sub- and super-diagonals, [`crate::linalg::banded::Banded`].
//! * dx = +inf makes a line without x-variation: every column is independent and convection
//!   drops out (m / dx = 0), e.g. the plane Couette test.
//!
//! # Fixed point
//!
//! The laws depend on T: [`solve_line`] iterates laws -> profile ([`super::film`], with the
//! shear-thinning Newton iteration per column, started from the column's last solution) ->
//! heating -> linear solve, with relaxation or Anderson mixing ([`LineOptions::anderson`],
//! [`crate::linalg::anderson`]), until the largest temperature change is below the tolerance.
//! [`solve_lines`] runs lines in parallel (rayon).
//!
//! # Signs and units
//!
//! Heat flux into body 1: q1 = +k_f dT/dz at z = 0; into body 2: q2 = -k_f dT/dz at z = h;
//! positive when the film heats the body (W/m^2).

// index loops over collocation points read like the equations
#![allow(clippy::needless_range_loop)]

use super::collocation::Lobatto;
use super::film::{
    column_integrals, shear_thinning_profile_from, Column, FilmError, FilmLaws, FilmProfile,
    OilThermal, ShearOptions, ShearThinningProfile,
};
use crate::linalg::anderson::Anderson;
use crate::linalg::banded::Banded;
use rayon::prelude::*;

/// One grid line along x (fixed y): cells i = 0..nx, point values i-major (`i * nz + k`).
#[derive(Debug, Clone, Copy)]
pub struct Line<'a> {
    /// cell width dx (m), positive; +inf for a line without x-variation (independent columns)
    pub dx: f64,
    /// film thickness h (m), per cell, positive and finite
    pub h: &'a [f64],
    /// pressure p (Pa), per cell (for the laws)
    pub p: &'a [f64],
    /// dp/dx (Pa/m), per cell
    pub dpdx: &'a [f64],
    /// dp/dy (Pa/m), per cell
    pub dpdy: &'a [f64],
    /// speed of surface 1 (z = 0) along +x (m/s)
    pub u1: f64,
    /// speed of surface 2 (z = h) along +x (m/s)
    pub u2: f64,
    /// temperature of surface 1 (K), per cell
    pub t1: &'a [f64],
    /// temperature of surface 2 (K), per cell
    pub t2: &'a [f64],
    /// temperature of the oil flowing into the line at either end (K)
    pub t_in: f64,
    /// the pressure-flow (Poiseuille) part of the x mass flux per unit width,
    /// -(rho/eta)_e h^3/12 dp/dx (kg/(m s)), each column must carry, per cell; `None`: the
    /// columns take `dpdx` as given. With it, `dpdx` is only the start: each column's pressure
    /// gradient is re-solved for this flux with its viscosity across z (see
    /// [`line_coefficients`]).
    pub poiseuille_flux_x: Option<&'a [f64]>,
    /// a time step of a transient run (`None`: steady), see [`LineTransient`]
    pub transient: Option<LineTransient<'a>>,
    /// the side flow to and from the neighbouring lines (`None`: none, a line contact or an
    /// independent line), see [`SideFlow`]
    pub side: Option<SideFlow<'a>>,
}

/// The convection along y between a line and its neighbours at y + dy (north) and y - dy
/// (south), per point (nx * nz, i-major), given: the neighbours' temperatures and the mass
/// fluxes are the caller's (its last iterate, or a neighbour solved just before, see
/// `crate::thermal::contact`). The surfaces do not move along y, so the fluxes at the wall
/// points k = 0 and nz - 1 are zero.
#[derive(Debug, Clone, Copy)]
pub struct SideFlow<'a> {
    /// 1 / dy (1/m)
    pub inv_dy: f64,
    /// the mass flux per unit zeta, h rho v (kg/(m s)), through the face towards +y
    pub north: &'a [f64],
    /// the same through the face towards -y (positive along +y, i.e. into the line)
    pub south: &'a [f64],
    /// the temperature beyond the north face (K): the neighbour's, or the inlet temperature
    /// where the neighbour has no film
    pub t_north: &'a [f64],
    /// the temperature beyond the south face (K)
    pub t_south: &'a [f64],
}

impl SideFlow<'_> {
    /// (m_s^+ - m_n^-) / dy (kg/(m^2 s)): the coefficient of the point's own T in the upwind
    /// difference, and the rest, (m_n^- T_N - m_s^+ T_S) / dy with temperatures taken from
    /// `t_in` (kg K/(m^2 s)): the upwind difference is c (leave T + rest) with T - t_in.
    fn upwind(&self, at: usize, t_in: f64) -> (f64, f64) {
        let (n, s) = (self.north[at], self.south[at]);
        (
            (s.max(0.0) - n.min(0.0)) * self.inv_dy,
            (n.min(0.0) * (self.t_north[at] - t_in) - s.max(0.0) * (self.t_south[at] - t_in))
                * self.inv_dy,
        )
    }

    /// (m_n - m_s) / dy (kg/(m^2 s)): the side flow's part of the film's mass balance.
    fn divergence(&self, at: usize) -> f64 {
        (self.north[at] - self.south[at]) * self.inv_dy
    }
}

/// The time derivatives of a transient line, by backward Euler over one step dt:
///
/// * the film's heat storage h rho c dT/dt at every collocation point, rho c (T - T_old) / dt
///   per unit volume (the mapped form at fixed zeta = z / h);
/// * its mass storage d(h rho)/dt, which enters the cross-film flux from continuity,
///   J(zeta) = -int_0^zeta (dm/dx + d(h rho)/dt) dzeta', so that the energy balance still
///   telescopes with a film that thickens or thins in time (a pit passing).
#[derive(Debug, Clone, Copy)]
pub struct LineTransient<'a> {
    /// 1 / dt (1/s)
    pub inv_dt: f64,
    /// the temperature at the previous time level (K), nx * nz, i-major; NaN on a point that
    /// had no film then (no heat storage there: quasi-steady)
    pub t_old: &'a [f64],
    /// h rho at the previous time level (kg/m^2), nx * nz; NaN on a point that had no film
    /// then (its mass storage is taken as zero)
    pub rho_h_old: &'a [f64],
}

impl Line<'_> {
    fn nx(&self) -> usize {
        self.h.len()
    }

    fn check(&self, nz: usize) -> Result<(), FilmError> {
        let nx = self.nx();
        if nx == 0 {
            return Err(FilmError::Input("a line needs at least one cell".into()));
        }
        for (name, f) in [
            ("p", self.p),
            ("dp/dx", self.dpdx),
            ("dp/dy", self.dpdy),
            ("t1", self.t1),
            ("t2", self.t2),
        ] {
            if f.len() != nx {
                return Err(FilmError::Input(format!(
                    "{name} has {} values, the line has {nx} cells",
                    f.len()
                )));
            }
            if let Some(v) = f.iter().find(|v| !v.is_finite()) {
                return Err(FilmError::Input(format!("{name} must be finite, got {v}")));
            }
        }
        if let Some(sf) = &self.side {
            let fields = [sf.north, sf.south, sf.t_north, sf.t_south];
            if !(sf.inv_dy > 0.0 && sf.inv_dy.is_finite())
                || fields
                    .iter()
                    .any(|f| f.len() != nx * nz || f.iter().any(|v| !v.is_finite()))
            {
                return Err(FilmError::Input(format!(
                    "a side flow needs a finite 1/dy > 0 and {} finite fluxes and temperatures",
                    nx * nz
                )));
            }
        }
        if let Some(tr) = &self.transient {
            if !(tr.inv_dt >= 0.0 && tr.inv_dt.is_finite())
                || tr.t_old.len() != nx * nz
                || tr.rho_h_old.len() != nx * nz
                || tr.t_old.iter().any(|v| v.is_infinite())
            {
                return Err(FilmError::Input(format!(
                    "a transient line needs a finite 1/dt >= 0 and {} previous temperatures and h rho",
                    nx * nz
                )));
            }
        }
        if self.dx.is_nan() || self.dx <= 0.0 {
            return Err(FilmError::Input(format!(
                "dx must be positive, got {}",
                self.dx
            )));
        }
        if !(self.t_in.is_finite() && self.u1.is_finite() && self.u2.is_finite()) {
            return Err(FilmError::Input("t_in, u1 and u2 must be finite".into()));
        }
        Ok(())
    }

    fn column(&self, i: usize) -> Column {
        Column {
            h: self.h[i],
            dpdx: self.dpdx[i],
            dpdy: self.dpdy[i],
            u1: self.u1,
            u2: self.u2,
        }
    }
}

/// The coefficients of one linear solve of a line (point values, nx * nz, i-major).
#[derive(Debug, Clone, PartialEq)]
pub struct LineCoefficients {
    /// m = h rho u (kg/(m s)): the x mass flux per unit zeta
    pub mass_flux: Vec<f64>,
    /// the heat source S (W/m^3): shear heating
    pub heating: Vec<f64>,
    /// a = (1/rho)(d rho/dT)(u dp/dx + v dp/dy) (W/(m^3 K)): the compression source is -a T
    pub compression: Vec<f64>,
    /// rho (kg/m^3)
    pub density: Vec<f64>,
    /// d(h rho)/dt (kg/(m^2 s)) of a transient line (zero when steady)
    pub mass_storage: Vec<f64>,
    /// beta S (W/(m^3 K)), beta = -d ln eta / dT of the low-shear law at the point (1/K,
    /// [`FilmLaws::viscosity_temperature_coefficient`]): how fast the shear heating falls as
    /// the point warms, for the linear solve's source linearisation (see
    /// [`solve_line_linear`]); zero on a plain step
    pub heating_slope: Vec<f64>,
    /// the temperature the coefficients were taken at (K)
    pub temperature: Vec<f64>,
    /// column profile solves these coefficients took (one per column, and the re-solves of
    /// the flux-driven columns: [`FLUX_RESOLVES`], [`WARM_FLUX_RESOLVES`])
    pub profile_solves: usize,
}

/// Energy accounting of a line for a temperature field and the coefficients it was solved
/// with. Per unit length along y.
///
/// Balance: sum_i dx (generated_i - q1_i - q2_i - stored_i - side_out_i) =
/// `enthalpy_flux[nx]` - `enthalpy_flux[0]`.
///
/// The wall heat fluxes `q1`, `q2` are the *consistent* fluxes (Gresho, Lee & Sani 1987, the
/// flux recovered from the discrete balance): the gradient flux k_f dT/dz of the collocation
/// polynomial at the wall ([`LineEnergy::q1_gradient`]) minus the end weight times the
/// equation's residual at the wall point (the wall points are not collocation points, so the
/// equation does not hold there). Summing the interior equations with the quadrature weights
/// shows that with these fluxes the balance closes up to (i) the rule's error in integrating
/// J dT/dzeta by parts and in d/dzeta of the cumulative flux (zero when the profiles are
/// polynomials of low enough degree; spectrally small otherwise) and (ii) the enthalpy carried
/// through surface 2 by a flow that does not conserve mass (J(1) (T2 - T_in) != 0; zero when
/// the pressure solves the generalized Reynolds equation, or when T2 = T_in). The gradient
/// fluxes converge to the same values spectrally in nz, but miss the balance by their
/// collocation error (measured: 10 % at nz = 5, 0.1 % at nz = 9 on a line with thermal
/// boundary layers at the inlet).
#[derive(Debug, Clone, PartialEq)]
pub struct LineEnergy {
    /// int_0^h (S - a T) dz per cell (W/m^2): shear heating and compression
    pub generated: Vec<f64>,
    /// heat flux into body 1, +k_f dT/dz at z = 0, per cell (W/m^2), consistent (see above)
    pub q1: Vec<f64>,
    /// heat flux into body 2, -k_f dT/dz at z = h, per cell (W/m^2), consistent
    pub q2: Vec<f64>,
    /// +k_f dT/dz at z = 0 from the collocation polynomial (W/m^2)
    pub q1_gradient: Vec<f64>,
    /// -k_f dT/dz at z = h from the collocation polynomial (W/m^2)
    pub q2_gradient: Vec<f64>,
    /// c int rho u (T_upwind - T_in) dz through the nx + 1 cell faces, positive along +x (W/m):
    /// face 0 is the line's start, face nx its end
    pub enthalpy_flux: Vec<f64>,
    /// the rate of change of the enthalpy the film holds, per cell (W/m^2; zero when steady):
    /// sum_k w_k c [h rho (T - T_old) / dt + (T - T_in) d(h rho)/dt]
    pub stored: Vec<f64>,
    /// the enthalpy the side flow carries out of each cell's column through its two y-faces,
    /// c sum_k w_k (F_n - F_s) / dy with the upwinded face fluxes F = m_y^+ (T_up - T_in) +
    /// m_y^- (T_down - T_in) (W/m^2; zero without [`Line::side`])
    pub side_out: Vec<f64>,
}

impl LineEnergy {
    /// (sum_i dx (generated - q1 - q2 - stored - side_out), `enthalpy_flux[nx]` -
    /// `enthalpy_flux[0]`) (W/m); with dx = +inf, the sum of (generated - q1 - q2 - stored -
    /// side_out) (W/m^2) and 0.
    pub fn balance(&self, dx: f64) -> (f64, f64) {
        let per: f64 = (0..self.q1.len())
            .map(|i| {
                self.generated[i] - self.q1[i] - self.q2[i] - self.stored[i] - self.side_out[i]
            })
            .sum();
        if dx.is_infinite() {
            (per, 0.0)
        } else {
            let n = self.enthalpy_flux.len() - 1;
            (per * dx, self.enthalpy_flux[n] - self.enthalpy_flux[0])
        }
    }
}

/// Options of [`solve_line`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineOptions {
    /// stop when the largest temperature change of an iteration is below this (K)
    pub tol: f64,
    /// at most this many fixed-point iterations
    pub max_iter: usize,
    /// relaxation omega in (0, 1]: T <- T + omega (T_solved - T); halved (down to a quarter
    /// of it) whenever the change grows from one iteration to the next
    pub relaxation: f64,
    /// Anderson mixing depth m (0: the plain relaxed iteration): each iterate combines the
    /// last m + 1 (Walker & Ni 2011, "Anderson acceleration for fixed-point iterations",
    /// SIAM J. Numer. Anal. 49: 1715), with `relaxation` as its mixing parameter; the history is
    /// dropped whenever the change grows
    pub anderson: usize,
    /// the shear-thinning iteration per column
    pub shear: ShearOptions,
    /// include the shear heating (false: only compression heats)
    pub shear_heating: bool,
    /// take a step that would go too far (more than 1/beta, or past the laws' limits) again
    /// with the heating's fall with temperature implicit ([`LineCoefficients::heating_slope`];
    /// see [`solve_line_from`]); false: the plain iteration throughout, for comparison
    pub linearise_heating: bool,
    /// solve the columns of the line in parallel ([`line_coefficients_from`]); [`solve_lines`]
    /// turns it off where its lines alone keep every thread busy (a 2D contact: nested tasks
    /// add no parallel work there, only their overhead; the parallel version of this loop
    /// costs such a contact 1.5-2.5 % of CPU time as it is, BENCHMARKS.md)
    pub parallel_columns: bool,
    /// every flux-driven column (`Line::poiseuille_flux_x`) takes the root of its flux match
    /// nearest the pressure's own gradient, as an unstable one does ([`UNSTABLE_FLUX_SLOPE`]),
    /// instead of the plain re-solves from its warm start: at a solution of the coupled problem
    /// (whose columns take the pressure's gradient) that root is the pressure's gradient
    /// itself, so the update that checks such a solution starts on it
    /// (`crate::ehl::thermal`); false by default
    pub nearest_root: bool,
}

impl Default for LineOptions {
    fn default() -> Self {
        LineOptions {
            tol: 1e-6,
            max_iter: 200,
            relaxation: 0.7,
            anderson: 0,
            shear: ShearOptions::default(),
            shear_heating: true,
            linearise_heating: true,
            parallel_columns: true,
            nearest_root: false,
        }
    }
}

/// The solution of a line (point values nx * nz, i-major, the surfaces included).
#[derive(Debug, Clone)]
pub struct LineSolution {
    /// T (K) at every point; k = 0 and k = nz - 1 are the surface temperatures
    pub t: Vec<f64>,
    /// the profiles per cell with the laws at the temperature the last solve started from
    pub profiles: Vec<FilmProfile>,
    /// the coefficients of the last linear solve
    pub coefficients: LineCoefficients,
    /// the energy accounting of `t` with `coefficients` (see [`LineEnergy`])
    pub energy: LineEnergy,
    /// how each cell's wall fluxes answer its own surface temperatures ([`wall_response`])
    pub wall_response: Vec<[f64; 4]>,
    /// fixed-point iterations done
    pub iterations: usize,
    /// the largest temperature change of the last iteration (K)
    pub change: f64,
    /// per cell, the largest temperature change across the film of the last iteration (K,
    /// nx values): the residual of the film's fixed point, cell by cell
    pub cell_change: Vec<f64>,
    /// change <= tol
    pub converged: bool,
    /// columns whose shear-thinning iteration did not converge in the last iteration
    pub shear_unconverged: usize,
    /// the shear-thinning factors eta_eff / eta of the last coefficients (nx * nz), a start
    /// for the next solve of the line ([`solve_line_from`])
    pub thinning: Vec<f64>,
    /// the Poiseuille coefficients (rho/eta)_e of the last coefficients' columns (nx), the
    /// other half of that start: each column's profile solve's own, before the limiting
    /// shear stress's cap (where the cap acts, the profile in `profiles` is the capped one)
    pub poiseuille: Vec<f64>,
}

/// Re-solves of a flux-driven shear-thinning column (`line_coefficients_from`) started from
/// the line's pressure gradient: its pressure gradient g = q_P / a(g), a = -(rho/eta)_e
/// h^3/12, is a fixed point (a depends on g through the shear thinning).
pub const FLUX_RESOLVES: usize = 3;

/// and started from the gradient its last Poiseuille coefficient gives: the fixed point goes
/// on across the film iterations, each starting where the last stopped. Measured (2026-11-27,
/// the Table 3.7 line at SRR 0.3 and the thesis roller 256 x 128 with Carreau at SRR 0.3):
/// 3.6 -> 1.9 profile solves per column and 20-24 % off the whole thermal run, the central
/// film, friction and largest film temperature within 1e-7 of the solution with the
/// gradient's fixed point converged to 1e-10 in every column (the 3 cold re-solves: 1.2e-7).
/// With none (the gradient lagged by one film iteration): one solve per column, 12-36 % off
/// the roller, but 2e-6 off on the line, and the thermal map of docs/thermal.md (the Table
/// 3.7 line over SRR and L) settled in 1 of its 20 runs instead of 15.
pub const WARM_FLUX_RESOLVES: usize = 1;

/// The slopes d ln |q_P| / d ln |g| of a flux-driven column's Poiseuille flux q_P = a(g) g
/// (a = -(rho/eta)_e h^3/12) between which its plain re-solve g <- q_P / a(g) contracts (its
/// gain is |1 - slope|; a Newtonian column's slope is 1, a Carreau column's between 1 and 1/n).
/// Outside, the column's gradient is the root of a(g) g = q_P nearest the pressure's own
/// gradient. Measured on an Eyring line at 1 GPa (tau_0 = 5 MPa, SRR 0.1; docs/thermal.md,
/// "Robustness beyond the examples", "The Eyring lines settle"): at the outlet's pressure spike the
/// Poiseuille stress h |dp/dx| / 2 is several tau_0, and with sliding the Poiseuille coefficient of
/// the secant viscosities falls as the gradient grows (slope -3 there), so a(g) g = q_P has a
/// second root at 2.4 times the pressure's gradient; the plain re-solves drifted to it over the
/// film iterations, and the temperature solve ran away (3990 K). The lower bound lies below the
/// contraction's, 0: a column capped by the limiting shear stress, whose flux barely moves with g
/// (slope ~0), keeps its plain re-solves, as before.
const UNSTABLE_FLUX_SLOPE: (f64, f64) = (-0.5, 2.0);

/// The least step in ln |g| between two re-solves over which their slope is taken
/// ([`UNSTABLE_FLUX_SLOPE`]): a column near its root moves by the profile solve's noise
/// (1e-10 in ln eta, more for an Eyring column), and a slope over such a step is noise too.
const SLOPE_LEAST_STEP: f64 = 1e-6;

/// The root search of an unstable flux-driven column ([`UNSTABLE_FLUX_SLOPE`]): steps in
/// ln |g| to either side of the pressure's gradient, the first [`ROOT_FIRST_STEP`], each next
/// twice the last, [`ROOT_BRACKET_STEPS`] on each side (reaching 0.05 (2^10 - 1) = 51 in
/// ln |g|: a profile solve that fails out there, or an infinite coefficient, ends the search
/// with the column as it was), to the first sign change of ln |a g / q_P| (the nearest root,
/// within a factor 2 in distance), then at most [`ROOT_REFINE_STEPS`] Illinois steps to
/// |ln |a g / q_P|| <= [`ROOT_TOLERANCE`] (each profile solve of the search starts from the
/// same shear-thinning state, so ln |a g / q_P| is a smooth function of ln |g| to well below
/// the profile's own tolerance, 1e-10 in ln eta: with 1e-9 a strongly thinning Carreau column
/// of `a_flux_driven_line_started_warm_is_where_it_was`, slope near 2, ended 2e-8 off its flux
/// where the plain re-solves reach 3e-9).
const ROOT_FIRST_STEP: f64 = 0.05;
const ROOT_BRACKET_STEPS: usize = 10;
const ROOT_REFINE_STEPS: usize = 30;
const ROOT_TOLERANCE: f64 = 1e-12;

/// Where the column iterations of a line start ([`line_coefficients_from`]), one line's worth,
/// e.g. the [`LineSolution`]'s `thinning` and `poiseuille` of its last solve.
#[derive(Debug, Clone, Copy)]
pub struct ColumnStart<'a> {
    /// the shear-thinning factors eta_eff / eta (nx * nz)
    pub thinning: &'a [f64],
    /// the Poiseuille coefficients (rho/eta)_e (kg/(m^3 Pa s), nx; NaN: none)
    pub poiseuille: &'a [f64],
}

/// The coefficients of a line at the temperature `t` (K, nx * nz, i-major): the laws at each
/// point, the profile per column ([`super::film::shear_thinning_profile`]), the mass flux,
/// heating and compression coefficient. Also returns the profiles and the number of columns whose
/// shear-thinning iteration did not converge.
pub fn line_coefficients<L: FilmLaws + ?Sized>(
    rule: &Lobatto,
    laws: &L,
    line: &Line,
    t: &[f64],
    opts: &LineOptions,
) -> Result<(LineCoefficients, Vec<FilmProfile>, usize), FilmError> {
    let mut thinning = vec![f64::NAN; t.len()];
    let mut poiseuille = vec![f64::NAN; line.nx()];
    line_coefficients_from(rule, laws, line, t, opts, &mut thinning, &mut poiseuille)
}

/// [`line_coefficients`] with the shear-thinning iteration of each column started from the
/// factors eta_eff / eta in `thinning` (nx * nz, i-major; a column with a non-finite or
/// non-positive factor starts from the low-shear viscosity), which are overwritten with this
/// solution's factors. Between the film iterations of a line the factors move little, and a
/// column started from the last ones needs one or two Newton iterations instead of 5-10.
/// Likewise a flux-driven column (`line.poiseuille_flux_x`) starts from the pressure gradient
/// that its Poiseuille coefficient in `poiseuille` (nx; NaN or non-positive: none, the
/// line's gradient) gives ([`WARM_FLUX_RESOLVES`]); overwritten with this solution's.
pub fn line_coefficients_from<L: FilmLaws + ?Sized>(
    rule: &Lobatto,
    laws: &L,
    line: &Line,
    t: &[f64],
    opts: &LineOptions,
    thinning: &mut [f64],
    poiseuille: &mut [f64],
) -> Result<(LineCoefficients, Vec<FilmProfile>, usize), FilmError> {
    let nz = rule.len();
    line.check(nz)?;
    let nx = line.nx();
    if t.len() != nx * nz {
        return Err(FilmError::Input(format!(
            "the temperature has {} values, the line {}",
            t.len(),
            nx * nz
        )));
    }
    let mut c = LineCoefficients {
        mass_flux: vec![0.0; nx * nz],
        heating: vec![0.0; nx * nz],
        compression: vec![0.0; nx * nz],
        density: vec![0.0; nx * nz],
        mass_storage: vec![0.0; nx * nz],
        heating_slope: vec![0.0; nx * nz],
        temperature: t.to_vec(),
        profile_solves: 0,
    };
    if thinning.len() != nx * nz || poiseuille.len() != nx {
        return Err(FilmError::Input(format!(
            "the thinning factors have {} values and the Poiseuille coefficients {}, the line {} and {}",
            thinning.len(),
            poiseuille.len(),
            nx * nz,
            nx
        )));
    }
    // the columns are independent, each written into its own slots: solved in parallel where
    // the caller's lines do not keep the threads busy (a line contact has one line, whose
    // columns are then the film's only parallel work), else one after the other
    let slots: Vec<ColumnSlots> = c
        .mass_flux
        .chunks_mut(nz)
        .zip(c.heating.chunks_mut(nz))
        .zip(c.compression.chunks_mut(nz))
        .zip(c.density.chunks_mut(nz))
        .zip(c.mass_storage.chunks_mut(nz))
        .zip(c.heating_slope.chunks_mut(nz))
        .zip(thinning.chunks_mut(nz))
        .zip(poiseuille.iter_mut())
        .map(
            |(
                (
                    (((((mass_flux, heating), compression), density), mass_storage), heating_slope),
                    factors,
                ),
                poiseuille,
            )| ColumnSlots {
                mass_flux,
                heating,
                compression,
                density,
                mass_storage,
                heating_slope,
                factors,
                poiseuille,
            },
        )
        .collect();
    let mut profiles = Vec::with_capacity(nx);
    let (mut unconverged, mut solves) = (0, 0);
    if opts.parallel_columns {
        let solved: Vec<Result<(FilmProfile, bool, usize), FilmError>> = slots
            .into_par_iter()
            .enumerate()
            .with_min_len(COLUMNS_PER_TASK)
            .map(|(i, out)| {
                let mut profile = None;
                column_coefficients(rule, laws, line, t, opts, i, out, |f| profile = Some(f)).map(
                    |(converged, n)| (profile.expect("a column emits its profile"), converged, n),
                )
            })
            .collect();
        // the first error in column order, as one after the other
        for r in solved {
            let (f, converged, n) = r?;
            profiles.push(f);
            unconverged += usize::from(!converged);
            solves += n;
        }
    } else {
        // (the profile goes straight into the list: an extra move of its ~1 KB per column
        // was 2-3 % of a 2D thermal run)
        for (i, out) in slots.into_iter().enumerate() {
            let (converged, n) =
                column_coefficients(rule, laws, line, t, opts, i, out, |f| profiles.push(f))?;
            unconverged += usize::from(!converged);
            solves += n;
        }
    }
    c.profile_solves = solves;
    Ok((c, profiles, unconverged))
}

/// Columns of a line per rayon task in [`line_coefficients_from`] (each two or so profile
/// solves of ~1 us).
const COLUMNS_PER_TASK: usize = 8;

/// Where one column's coefficients go in [`line_coefficients_from`] (nz values each, its
/// warm start in `factors` and `poiseuille`, overwritten).
struct ColumnSlots<'a> {
    mass_flux: &'a mut [f64],
    heating: &'a mut [f64],
    compression: &'a mut [f64],
    density: &'a mut [f64],
    mass_storage: &'a mut [f64],
    heating_slope: &'a mut [f64],
    factors: &'a mut [f64],
    poiseuille: &'a mut f64,
}

/// The limiting shear stress (Bair & Winer 1979; thesis eq. 2.13-2.14) as a cap on the
/// shear-thinning profile `s` of column `col` (its `profile` replaced in place; its `eta_eff`,
/// the shear-thinning iteration's own, kept) at pressure `p` (Pa), mid-film temperature `tmid`
/// (K) and densities `rho` (kg/m^3): where the largest |tau| exceeds tau_L, the effective
/// viscosity is scaled down uniformly by tau_L / max |tau| (twice, the pressure-flow part not
/// scaling), so that the sliding stress sits at the limit and the heating (tau^2 / eta) falls
/// with it, as the heat of a film slipping at its limit, tau_L |u1 - u2|, does. Applied only
/// where the limit exceeds the pressure-flow stress range `range` = h |grad p| (Pa; the sliding
/// part alone can then meet it); in the low-pressure inlet, where tau_L = Lambda p falls below
/// that, the column keeps the law without the cap (its stresses are kPa there). Between the
/// two the cap is phased in, the scaling r taken to the power
/// CAP_BLEND = clamp(tau_L / range - 1, 0, 1): switched on and off abruptly, columns at the
/// threshold flipped between capped and free from one outer iteration to the next and the
/// factors never settled (measured: a ball at 1 m/s, SRR 1, Carreau with Lambda 0.07, 80
/// outer iterations with the flow factor of a few cells cycling by 0.15 in log, the
/// temperatures settled).
///
/// A flux-driven column's `range` is the larger of the pressure's own gradient's and its
/// iterate's. Taken from the iterate alone, the blend fed back on the gradient the flux sets
/// once the flux was matched after the cap (a larger gradient blended the cap out, which
/// raised the gradient the flux needs: the thermal map's SRR 0.05 at L = 22 failed its first
/// Reynolds solve, SRR 0.3 at L = 22 no longer settled); from the pressure's alone, inlet
/// columns whose flux-driven gradient stays up to twice the pressure's (their factors are not
/// part of the fixed point's stop) were capped, and pure rolling at L = 3.2 took 45 outer
/// iterations instead of 15, its friction moved by 3e-3. Where the cap holds the iterate's
/// gradient is the smaller (the capped coefficient is the larger), so the blend is the
/// pressure's and does not feed back; at a settled column the two are the same, and the
/// coupled Newton method, whose columns take the pressure's gradient, blends alike.
#[allow(clippy::too_many_arguments)]
fn capped_profile<L: FilmLaws + ?Sized>(
    rule: &Lobatto,
    laws: &L,
    col: &Column,
    p: f64,
    tmid: f64,
    range: f64,
    s: &mut ShearThinningProfile,
    rho: &[f64],
) -> Result<(), FilmError> {
    let f = &mut s.profile;
    if let Some(cap) = laws.limiting_shear_stress(p, tmid) {
        let blend = if range > 0.0 {
            (cap / range - 1.0).clamp(0.0, 1.0)
        } else {
            1.0
        };
        if blend > 0.0 && cap > 0.0 {
            let mut eta_eff = s.eta_eff.clone();
            for _ in 0..2 {
                let top = f
                    .tau_zx
                    .iter()
                    .zip(&f.tau_zy)
                    .fold(0.0f64, |m, (a, b)| m.max(a.hypot(*b)));
                if top <= cap {
                    break;
                }
                let r = (cap / top).powf(blend);
                eta_eff.iter_mut().for_each(|e| *e *= r);
                *f = super::film::velocity_profile(rule, col, &eta_eff, rho)?;
            }
        }
    }
    Ok(())
}

/// Column `i` of [`line_coefficients_from`]: the laws at its points, its profile (the
/// shear-thinning iteration, the flux-driven gradient, the limiting shear stress's cap) and
/// its coefficients into `out`; gives the profile to `emit` and returns whether its
/// shear-thinning iteration converged and the profile solves it took.
#[allow(clippy::too_many_arguments)]
fn column_coefficients<L: FilmLaws + ?Sized>(
    rule: &Lobatto,
    laws: &L,
    line: &Line,
    t: &[f64],
    opts: &LineOptions,
    i: usize,
    out: ColumnSlots<'_>,
    emit: impl FnOnce(FilmProfile),
) -> Result<(bool, usize), FilmError> {
    let nz = rule.len();
    // the points' scratch on the stack up to 16 points (as the column solve's)
    let (mut stack, mut heap) = ([0.0f64; 4 * 16], Vec::new());
    let work = super::film::scratch(&mut stack, &mut heap, 4 * nz);
    let (start, rest) = work.split_at_mut(nz);
    let (eta, rest) = rest.split_at_mut(nz);
    let (rho, drho) = rest.split_at_mut(nz);
    let p = line.p[i];
    let ti = &t[i * nz..(i + 1) * nz];
    laws.viscosities(p, ti, eta);
    for k in 0..nz {
        let check = |law: &'static str, value: f64| {
            if value > 0.0 && value.is_finite() {
                Ok(value)
            } else {
                Err(FilmError::Law {
                    law,
                    value,
                    p,
                    t: ti[k],
                })
            }
        };
        eta[k] = check("viscosity", eta[k])?;
        rho[k] = check("density", laws.density(p, ti[k]))?;
        drho[k] = laws.density_dt(p, ti[k]);
        if !drho[k].is_finite() {
            return Err(FilmError::Law {
                law: "density derivative",
                value: drho[k],
                p,
                t: ti[k],
            });
        }
    }
    let mut col = line.column(i);
    let factors = &mut *out.factors;
    let warm = factors.iter().all(|f| *f > 0.0 && f.is_finite());
    if warm {
        for k in 0..nz {
            start[k] = eta[k] * factors[k];
        }
    }
    let mut solves = 0usize;
    let mut profile = |col: &Column, from: Option<&[f64]>| {
        solves += 1;
        shear_thinning_profile_from(rule, laws, col, p, ti, &eta, &rho, opts.shear, from)
    };
    // a flux-driven column (below) starts from the pressure gradient its last Poiseuille
    // coefficient gives for the target flux, where it has one
    let mut resolves = FLUX_RESOLVES;
    if let (Some(q), true) = (line.poiseuille_flux_x, *out.poiseuille > 0.0) {
        let g = q[i] / (-*out.poiseuille * col.h.powi(3) / 12.0);
        if g.is_finite() {
            col.dpdx = g;
            resolves = WARM_FLUX_RESOLVES;
        }
    }
    // the limiting shear stress's cap on a profile, phased in by the larger of the pressure's
    // own gradient and the column's flux-driven one (see capped_profile)
    let tmid = ti[nz / 2];
    let range = col.h * line.dpdx[i].hypot(col.dpdy);
    // (the profile is capped in place, not copied: ~1 KB per column and film iteration; see
    // `film::velocity_profile` for what the two saved)
    let cap = |col: &Column, s: &mut ShearThinningProfile| {
        let range = range.max(col.h * col.dpdx.hypot(col.dpdy));
        capped_profile(rule, laws, col, p, tmid, range, s, rho)
    };
    // a Newtonian flux-driven column: its Poiseuille coefficient does not depend on the
    // pressure gradient, so the gradient that carries the target flux (below) is known before
    // the profile, which is then solved once instead of twice a film iteration (the warm
    // start's gradient is the last temperature's); the same arithmetic as the re-solve below,
    // so the same profile (to rounding: the re-solve kept a warm gradient within 1e-12 of it).
    // Not with a limiting shear stress: its cap makes the coefficient depend on the gradient
    // again, and the capped column's warm start is the better one
    if let Some(q) = line.poiseuille_flux_x {
        if (0..nz).all(|k| {
            matches!(
                laws.ln_shear_law(p, ti[k]),
                Some(crate::lubricant::rheology::LnShearLaw::Newtonian)
            ) && laws.limiting_shear_stress(p, ti[k]).is_none()
        }) {
            let (mut stack, mut heap) = ([0.0f64; 2 * 16], Vec::new());
            let work = super::film::scratch(&mut stack, &mut heap, 2 * nz);
            let (i0, i1) = work.split_at_mut(nz);
            let c = column_integrals(rule, col.h, eta, rho, i0, i1);
            let g = q[i] / (-c.rho_over_eta_e * col.h.powi(3) / 12.0);
            if g.is_finite() {
                col.dpdx = g;
            }
        }
    }
    let mut s = profile(&col, warm.then_some(&*start))?;
    cap(&col, &mut s)?;
    // a flux-driven column: the pressure gradient that carries the target pressure-flow
    // flux q_P = -(rho/eta)_e h^3/12 dp/dx with this temperature's viscosity across z
    // (linear in dp/dx for a Newtonian film; a shear-thinning one is re-solved, at most
    // FLUX_RESOLVES times, or WARM_FLUX_RESOLVES when it started warm).
    // Driving the column by its flux rather than its pressure gradient keeps the film's
    // fixed point bounded: at fixed dp/dx the pressure-flow heating (z dp/dx)^2 / eta grows
    // as the viscosity falls and the iteration runs away (measured at the Hertz outlet of
    // the thesis Table 3.7 line at SRR 0.3); at fixed flux dp/dx falls with the viscosity.
    // Only the Poiseuille part is imposed: matching the whole flux would divide a small
    // difference of the Couette fluxes by a vanishing Poiseuille coefficient in the Hertz
    // zone (measured: dp/dx and the temperature ran to -6000 K there).
    // The flux is matched with the capped profile's coefficient, the one the Reynolds factors
    // are taken from: matched before the cap, a capped column's gradient came out a_capped /
    // a_free times the pressure's own at the fixed point (a flux the Reynolds equation did
    // not solve), and the coupled Newton method, whose columns take the pressure's gradient,
    // never agreed with it (measured on the example line at p_h = 2 GPa, U = 1e-11, Lambda
    // 0.04, SRR 0.5: friction 0.03791 against the consistent 0.03833).
    if let Some(q) = line.poiseuille_flux_x {
        // the last gradient tried, as (u, phi) = (ln |g|, ln |a(g) g / q_P|): the plain
        // re-solve is u <- u - phi, whose gain is |1 - slope| with slope = d phi / d u
        let mut last: Option<(f64, f64)> = None;
        let mut unstable = opts.nearest_root;
        let mut n = 0;
        while !unstable {
            let a = -s.profile.rho_over_eta_e * col.h.powi(3) / 12.0;
            let g = q[i] / a;
            if !g.is_finite() || (g - col.dpdx).abs() <= 1e-12 * g.abs().max(1.0) {
                break;
            }
            if col.dpdx * g > 0.0 {
                let (u, phi) = (col.dpdx.abs().ln(), (col.dpdx / g).ln());
                if let Some((ul, pl)) = last {
                    let slope = (phi - pl) / (u - ul);
                    // (over a step at the profile solve's noise the estimate is noise)
                    if (u - ul).abs() > SLOPE_LEAST_STEP
                        && slope.is_finite()
                        && !(UNSTABLE_FLUX_SLOPE.0..=UNSTABLE_FLUX_SLOPE.1).contains(&slope)
                    {
                        unstable = true;
                        break;
                    }
                }
                last = Some((u, phi));
            } else {
                last = None;
            }
            if n >= resolves {
                break;
            }
            col.dpdx = g;
            s = profile(&col, Some(&s.eta_eff))?;
            cap(&col, &mut s)?;
            n += 1;
        }
        let g_line = line.dpdx[i];
        if unstable && g_line * q[i] < 0.0 {
            // the root nearest the pressure's own gradient: bracketed from it by steps in
            // ln |g| to both sides that double, then Illinois false position. Where the search
            // finds no root within its reach, or a profile solve on its way fails, the column
            // keeps the profile it had (its plain re-solves so far; with `nearest_root` its
            // warm start).
            let mut at = |col: &mut Column, u: f64| {
                col.dpdx = g_line.signum() * u.exp();
                let mut s = profile(col, Some(&s.eta_eff)).ok()?;
                cap(col, &mut s).ok()?;
                let a = -s.profile.rho_over_eta_e * col.h.powi(3) / 12.0;
                let phi = (a * col.dpdx / q[i]).ln();
                phi.is_finite().then_some((phi, s))
            };
            let kept = col.dpdx;
            let found = (|| {
                let u_line = g_line.abs().ln();
                let (p_line, sl) = at(&mut col, u_line)?;
                if p_line.abs() <= ROOT_TOLERANCE {
                    return Some((u_line, sl));
                }
                // the last point tried below and above the pressure's gradient
                let mut sides = [(u_line, p_line); 2];
                let mut step = ROOT_FIRST_STEP;
                let mut bracket = None;
                'search: for _ in 0..ROOT_BRACKET_STEPS {
                    for (side, sign) in [(0, -1.0), (1, 1.0)] {
                        let (ua, pa) = sides[side];
                        let ub = u_line + sign * step;
                        let (pb, sb) = at(&mut col, ub)?;
                        if pa * pb <= 0.0 {
                            bracket = Some((ua, pa, ub, pb, sb));
                            break 'search;
                        }
                        sides[side] = (ub, pb);
                    }
                    step *= 2.0;
                }
                let (mut ua, mut pa, mut ub, mut pb, mut sb) = bracket?;
                for _ in 0..ROOT_REFINE_STEPS {
                    if pb.abs() <= ROOT_TOLERANCE || pa == pb {
                        break;
                    }
                    let uc = (ua * pb - ub * pa) / (pb - pa);
                    let (pc, sc) = at(&mut col, uc)?;
                    if pc * pb < 0.0 {
                        (ua, pa) = (ub, pb);
                    } else {
                        pa *= 0.5;
                    }
                    (ub, pb, sb) = (uc, pc, sc);
                }
                Some((ub, sb))
            })();
            match found {
                Some((u, sn)) => {
                    col.dpdx = g_line.signum() * u.exp();
                    s = sn;
                }
                None => col.dpdx = kept,
            }
        }
    }
    // the shear-thinning iteration's warm start is its own fixed point's viscosity (before
    // the cap), the flux's the last capped coefficient (after)
    for k in 0..nz {
        factors[k] = s.eta_eff[k] / eta[k];
    }
    let converged = s.converged;
    let f = s.profile;
    *out.poiseuille = f.rho_over_eta_e;
    for k in 0..nz {
        let at = i * nz + k;
        out.mass_flux[k] = col.h * rho[k] * f.u[k];
        out.heating[k] = if opts.shear_heating {
            f.heating[k]
        } else {
            0.0
        };
        let gx = compression_gradient(col.dpdx, line.dpdx[i], f.u[k]);
        out.compression[k] = drho[k] / rho[k] * (f.u[k] * gx + f.v[k] * col.dpdy);
        out.density[k] = rho[k];
        if opts.linearise_heating && out.heating[k] > 0.0 {
            out.heating_slope[k] =
                laws.viscosity_temperature_coefficient(p, ti[k]) * out.heating[k];
        }
        if let Some(tr) = &line.transient {
            let old = tr.rho_h_old[at];
            if old.is_finite() {
                out.mass_storage[k] = (col.h * rho[k] - old) * tr.inv_dt;
            }
        }
    }
    emit(f);
    Ok((converged, solves))
}

/// The pressure gradient along x (Pa/m) of a column's compression work -(T / rho) (d rho / dT)
/// (u dp/dx + v dp/dy) (W/m^3; the energy equation of thermal EHL, e.g. Yang & Wen, J. Tribol.
/// 112 (1990) 631; Habchi et al. 2008, thermal point contacts;
/// [`LineCoefficients::compression`]) at a point of a column whose oil moves at `u` along x
/// there (m/s; the sign is what counts): the column's
/// flux-driven gradient `flux_driven` or the pressure's own `pressure` (the line's central
/// difference), whichever bounds the feedback of the temperature on the compression work.
///
/// The two are one quantity at the fixed point (the flux-driven gradient carries the flux the
/// Reynolds solve gives), so the choice leaves the fixed point alone. A flux-driven column's
/// gradient is the pressure's times the ratio of the lagged flow factor to the column's current
/// one, so the two share their sign; between outer iterations, with the Reynolds factors
/// lagged, they part, and which one a point takes sets the feedback of the column's
/// temperature on its compression work:
/// * *Compressed oil* (`u` and the gradient of one sign: the oil compressed as it moves): the
///   flux-driven gradient, held to at most [`COMPRESSION_GRADIENT_CAP`] times the pressure's.
///   A hotter column is thinner, so its flux-driven gradient, and the heating, fall: a
///   restoring feedback. In the thick, hot inlet of a high thermal loading it is the steadier
///   one: the pressure's own gradient alone settled 16 of the 20 runs of the thermal map of
///   docs/thermal.md instead of 19. The cap: at a sharp pressure spike the flux-driven one
///   overshoots (measured on a line at p_h = 1 GPa and 5 m/s, 256 cells, the spike one or two
///   cells wide: a Newtonian oil at SRR 0.5 and Carreau at SRR -0.5 ended with a failed
///   temperature solve, the spike's cells heated or cooled by hundreds of kelvin; capped, both
///   settle).
/// * *Expanding oil* (of opposite signs: the oil leaving a pressure spike): the smaller of
///   the two in magnitude. There the flux-driven gradient feeds back the wrong way: a cooler
///   column is more viscous, its flux-driven gradient steeper, its expansion cooling stronger;
///   the smaller of the two bounds that cooling by the pressure's own gradient. Measured
///   (docs/thermal.md, "Fast balls"): a steel ball (p_h 0.77 GPa, Roelands, alpha 20 /GPa,
///   thermal expansion 6.5e-4 /K, Newtonian) has an outlet spike of up to 1.8 p_h at
///   10-20 m/s; at 10 and 15 m/s with SRR 0.3 its film iteration left residuals of 5-100 K at
///   the cells leaving the spike and the fixed point did not settle (at 15 m/s in pure
///   rolling the oil there was 40-80 K below the walls in some outer iterations and not in
///   others); with this choice both settle (15 m/s in pure rolling and 20 m/s settle since
///   2026-12-05 through the coupled polish, docs/thermal.md "Polished until it settles").
///   Without thermal expansion (no compression work) the pure-rolling ball at 15 m/s
///   settled.
///
/// The point's own velocity decides, so the compression work u g is continuous where u changes
/// sign (g jumps there, u g does not). Deciding by the column's mean velocity made it jump
/// where that mean crossed zero, as it can in the side regions of a 2D inlet (the same
/// outcomes otherwise: the robustness scan's 29 cases to the digits printed, the thermal map's
/// 18 of 20 settled in 465 outer iterations against 479).
pub fn compression_gradient(flux_driven: f64, pressure: f64, u: f64) -> f64 {
    let agree = flux_driven * pressure > 0.0;
    if agree && u * pressure < 0.0 {
        if flux_driven.abs() < pressure.abs() {
            flux_driven
        } else {
            pressure
        }
    } else if agree && flux_driven.abs() > COMPRESSION_GRADIENT_CAP * pressure.abs() {
        COMPRESSION_GRADIENT_CAP * pressure
    } else {
        flux_driven
    }
}

/// How far the flux-driven gradient of [`compression_gradient`] may exceed the pressure's own
/// (dimensionless: a factor of two). Measured (docs/thermal.md, "Robustness beyond the
/// examples"): 1 (the smaller of the two, minmod) slowed the pure-rolling thesis roller
/// 256 x 512 from 6 to 8 outer iterations (+30 % time); 1.2 and 2 kept its 6, both fixed the
/// Newtonian and Carreau lines above and lost the same one run of the thermal map (SRR 0.3 at
/// L = 22); 1.2 also settled the Eyring line at SRR 0.5, which 1.5 and 2 did not.
pub const COMPRESSION_GRADIENT_CAP: f64 = 2.0;

/// Per point, what a column loses per unit zeta other than by the x-flow (kg/(m^2 s)): the
/// mass storage d(h rho)/dt of a transient line and the side flow's divergence dm_y/dy. J takes
/// its cumulative integral across the film ([`face_fluxes`]).
fn sinks(line: &Line, coef: &LineCoefficients) -> Vec<f64> {
    let mut s = coef.mass_storage.clone();
    if let Some(sf) = &line.side {
        for (at, v) in s.iter_mut().enumerate() {
            *v += sf.divergence(at);
        }
    }
    s
}

/// Face mass fluxes m_{f} (f = 0..=nx, nz values each, f * nz + k) and the cross-film flux
/// J (nx * nz) of the module documentation; `storage` per point from [`sinks`].
fn face_fluxes(
    rule: &Lobatto,
    nx: usize,
    inv_dx: f64,
    m: &[f64],
    storage: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let nz = rule.len();
    let mut mf = vec![0.0; (nx + 1) * nz];
    for f in 0..=nx {
        for k in 0..nz {
            mf[f * nz + k] = if f == 0 {
                m[k]
            } else if f == nx {
                m[(nx - 1) * nz + k]
            } else {
                0.5 * (m[(f - 1) * nz + k] + m[f * nz + k])
            };
        }
    }
    let mut q = vec![0.0; (nx + 1) * nz];
    for f in 0..=nx {
        rule.apply(
            &rule.cumulative,
            &mf[f * nz..(f + 1) * nz],
            &mut q[f * nz..(f + 1) * nz],
        );
    }
    let mut j = vec![0.0; nx * nz];
    if inv_dx > 0.0 {
        for i in 0..nx {
            for k in 0..nz {
                j[i * nz + k] = -(q[(i + 1) * nz + k] - q[i * nz + k]) * inv_dx;
            }
        }
    }
    // a transient film's mass storage and the side flow's divergence:
    // J -= int_0^zeta (d(h rho)/dt + dm_y/dy)
    if storage.iter().any(|&v| v != 0.0) {
        let mut c = vec![0.0; nz];
        for i in 0..nx {
            rule.apply(&rule.cumulative, &storage[i * nz..(i + 1) * nz], &mut c);
            for k in 0..nz {
                j[i * nz + k] -= c[k];
            }
        }
    }
    (mf, j)
}

/// The largest cross-film Peclet number c |J| h dzeta / k of a collocation point (dzeta the
/// local spacing of the points) that the energy equation keeps where the film is more than
/// [`PECLET_BOUND_FILM_RATIO`] times the line's thinnest (the classical bound of central
/// differences); see [`cell_conductivity`].
pub const MAX_CROSS_FILM_PECLET: f64 = 2.0;

/// The cross-film conduction is raised only where the film is more than this many times the
/// line's thinnest: the thick inlet, where the collocation oscillated.
pub const PECLET_BOUND_FILM_RATIO: f64 = 10.0;

/// The conductivity (W/(m K)) across the film of a cell of film `h` (m) on a line whose thinnest
/// film is `h_min`, with the cross-film mass fluxes `j` at its points (kg/(m^2 s)): the oil's `kf`,
/// raised where the film is more than [`PECLET_BOUND_FILM_RATIO`] times the thinnest to
/// c max_k |J_k| h dzeta_k / [`MAX_CROSS_FILM_PECLET`] when that is larger (c in J/(kg K); dzeta_k
/// the half-distance of point k's neighbours), so that no point's Peclet number exceeds
/// [`MAX_CROSS_FILM_PECLET`]. An artificial conduction, uniform across the column: its flux
/// telescopes with the rule's weights like the oil's, so the energy balance stays exact
/// ([`line_energy`] uses the same conductivity; the heat it carries to the walls is counted as
/// conducted).
pub fn cell_conductivity(rule: &Lobatto, kf: f64, cp: f64, h: f64, h_min: f64, j: &[f64]) -> f64 {
    if !(h > PECLET_BOUND_FILM_RATIO * h_min) {
        return kf;
    }
    let nz = rule.len();
    (1..nz - 1).fold(kf, |k, p| {
        let dz = 0.5 * (rule.points[p + 1] - rule.points[p - 1]);
        k.max(cp * j[p].abs() * h * dz / MAX_CROSS_FILM_PECLET)
    })
}

/// One linear solve of the energy equation of a line with given coefficients: returns T (K) at
/// every point (nx * nz, i-major, the surface temperatures at k = 0 and nz - 1).
pub fn solve_line_linear(
    rule: &Lobatto,
    oil: &OilThermal,
    line: &Line,
    coef: &LineCoefficients,
) -> Result<Vec<f64>, FilmError> {
    let nz = rule.len();
    line.check(nz)?;
    let nx = line.nx();
    if nz < 3 {
        return Err(FilmError::Input(
            "the energy equation needs at least one interior point (nz >= 3)".into(),
        ));
    }
    for f in [&coef.mass_flux, &coef.heating, &coef.compression] {
        if f.len() != nx * nz || f.iter().any(|v| !v.is_finite()) {
            return Err(FilmError::Input(format!(
                "coefficients must hold {} finite values",
                nx * nz
            )));
        }
    }
    let ni = nz - 2;
    let (mf, jflux) = face_fluxes(rule, nx, 1.0 / line.dx, &coef.mass_flux, &sinks(line, coef));
    let h_min = line.h.iter().fold(f64::INFINITY, |m, &v| m.min(v));
    LINE_SYSTEM.with(|cell| {
        let mut a = cell.borrow_mut();
        a.reset(nx * ni, ni, ni);
        assemble_and_solve(rule, oil, line, coef, &mut a, (&mf, &jflux), h_min)
    })
}

thread_local! {
    /// The banded matrix of [`solve_line_linear`], reused from line to line (see
    /// [`Banded::reset`]).
    static LINE_SYSTEM: std::cell::RefCell<Banded> = std::cell::RefCell::new(Banded::new(0, 0, 0));
}

/// The body of [`solve_line_linear`] with its checks done, its face fluxes `(mf, jflux)` and
/// the line's thinnest film `h_min` known, assembled into `a` (zero, of order nx (nz - 2) with
/// nz - 2 sub- and super-diagonals).
fn assemble_and_solve(
    rule: &Lobatto,
    oil: &OilThermal,
    line: &Line,
    coef: &LineCoefficients,
    a: &mut Banded,
    (mf, jflux): (&[f64], &[f64]),
    h_min: f64,
) -> Result<Vec<f64>, FilmError> {
    let nz = rule.len();
    let nx = line.nx();
    let ni = nz - 2;
    let inv_dx = 1.0 / line.dx;
    let cp = oil.heat_capacity;
    let t_in = line.t_in;
    let mut b = vec![0.0; nx * ni];
    for i in 0..nx {
        let h = line.h[i];
        let kf = oil.conductivity_at(line.p[i]);
        let kc = cell_conductivity(rule, kf, cp, h, h_min, &jflux[i * nz..(i + 1) * nz]);
        let th1 = line.t1[i] - t_in;
        let th2 = line.t2[i] - t_in;
        for k in 1..nz - 1 {
            let r = i * ni + k - 1;
            let at = i * nz + k;
            let left = mf[i * nz + k].max(0.0);
            let right = mf[(i + 1) * nz + k].min(0.0);
            a.add(r, r, cp * inv_dx * (left - right));
            if i > 0 {
                a.add(r, r - ni, -cp * inv_dx * left);
            }
            if i + 1 < nx {
                a.add(r, r + ni, cp * inv_dx * right);
            }
            let jk = jflux[at];
            for l in 0..nz {
                let v = cp * jk * rule.d1[k * nz + l] - kc / h * rule.d2[k * nz + l];
                if l == 0 {
                    b[r] -= v * th1;
                } else if l == nz - 1 {
                    b[r] -= v * th2;
                } else {
                    a.add(r, i * ni + l - 1, v);
                }
            }
            let comp = h * coef.compression[at];
            a.add(r, r, own_coefficient(line, coef, cp, at, h));
            b[r] += h * coef.heating[at] - comp * t_in;
            // the heating linearised about the temperature it was taken at (Patankar 1980,
            // sec. 4.2-5: S(T) ~ S(T*) - beta S (T - T*), a source that falls as the point
            // warms kept implicit): the fixed point is the same, but an iterate no longer
            // overshoots where the heating is large and steep in T
            let slope = h * coef.heating_slope[at];
            a.add(r, r, slope);
            b[r] += slope * (coef.temperature[at] - t_in);
            if let Some(sf) = &line.side {
                // c [m_n^- (T_N - T) + m_s^+ (T - T_S)] / dy, the neighbours lagged
                b[r] -= cp * sf.upwind(at, t_in).1;
            }
            if let Some(tr) = line
                .transient
                .as_ref()
                .filter(|tr| tr.t_old[at].is_finite())
            {
                // h rho c (T - T_old) / dt, in theta = T - T_in
                let s = h * coef.density[at] * cp * tr.inv_dt;
                b[r] += s * (tr.t_old[at] - t_in);
            }
        }
    }
    if !a.factor() {
        return Err(FilmError::Singular);
    }
    a.solve(&mut b);
    let mut t = vec![0.0; nx * nz];
    for i in 0..nx {
        t[i * nz] = line.t1[i];
        t[i * nz + nz - 1] = line.t2[i];
        for k in 1..nz - 1 {
            t[i * nz + k] = t_in + b[i * ni + k - 1];
        }
    }
    if t.iter().any(|v| !v.is_finite()) {
        return Err(FilmError::Singular);
    }
    Ok(t)
}

/// The coefficient of a point's own temperature in its equation besides the x-convection and
/// the across-film terms (W/(m^2 K)): the compression h a, the side flow's upwind c m_y / dy
/// of the flow leaving the line, and a transient step's storage h rho c / dt.
fn own_coefficient(line: &Line, coef: &LineCoefficients, cp: f64, at: usize, h: f64) -> f64 {
    let mut own = h * coef.compression[at];
    if let Some(sf) = &line.side {
        own += cp * sf.upwind(at, line.t_in).0;
    }
    if let Some(tr) = line
        .transient
        .as_ref()
        .filter(|tr| tr.t_old[at].is_finite())
    {
        own += h * coef.density[at] * cp * tr.inv_dt;
    }
    own
}

/// How each cell's consistent wall fluxes answer its own surface temperatures, with
/// everything else held: the temperatures of the neighbouring columns (upstream and
/// downstream along x, the side flow's), the coefficients (laws, velocities, heating).
/// Per cell `[dq1/dT1, dq1/dT2, dq2/dT1, dq2/dT2]` (W/(m^2 K)), q_b the flux into body b
/// ([`LineEnergy`]'s `q1`, `q2`), from the column's own block of the linear system: raising
/// T_b by 1 K moves the interior points by -A_ii^-1 c_b (c_b their coupling to that surface),
/// and the fluxes by the gradient and the wall-point residual of that change.
///
/// A film that only conducts gives -k/h and +k/h (a linear profile: raising T1 lowers q1 and
/// raises q2 by k/h). A film that also carries oil in from upstream at another temperature
/// answers more strongly: its thermal layer at the surface is thinner than h (the oil entering
/// the cell is held), so -dq_b/dT_b exceeds k/h, up to the conductance of the first collocation
/// interval. The film-body update of the surfaces ([`super::contact::ThermalContact`]) uses
/// it in place of k/h: at a glass disc at rest under a ball sliding at 2 m/s, k/h
/// underestimated the inlet's answer several times over and the surface temperatures
/// oscillated, growing, to the viscosity law's pole.
pub fn wall_response(
    rule: &Lobatto,
    oil: &OilThermal,
    line: &Line,
    coef: &LineCoefficients,
) -> Vec<[f64; 4]> {
    let nz = rule.len();
    let nx = line.nx();
    let ni = nz - 2;
    let inv_dx = 1.0 / line.dx;
    let cp = oil.heat_capacity;
    let (mf, jflux) = face_fluxes(rule, nx, inv_dx, &coef.mass_flux, &sinks(line, coef));
    let h_min = line.h.iter().fold(f64::INFINITY, |m, &v| m.min(v));
    let w = &rule.weights;
    // per cell: the across-film operator (point k applied to point l, nz x nz), the interior
    // block's LU factors and pivots, and the column's answer to one wall's temperature (scratch
    // reused from cell to cell, and `col` from one wall to the other)
    let mut op = vec![0.0; nz * nz];
    let mut a = vec![0.0; ni * ni];
    let mut piv = vec![0; ni];
    let mut col = vec![0.0; nz];
    let mut out = Vec::with_capacity(nx);
    for i in 0..nx {
        let h = line.h[i];
        let kf = oil.conductivity_at(line.p[i]);
        let kc = cell_conductivity(rule, kf, cp, h, h_min, &jflux[i * nz..(i + 1) * nz]);
        for k in 0..nz {
            let (jk, kh) = (cp * jflux[i * nz + k], kc / h);
            for l in 0..nz {
                op[k * nz + l] = jk * rule.d1[k * nz + l] - kh * rule.d2[k * nz + l];
            }
        }
        // the x-convection's own coefficient at point k: from the left face where the flow
        // enters the cell, the right where it leaves backwards; `ends` counts the faces at the
        // line's ends, which a surface point treats as its own temperature
        let convection = |k: usize, ends: bool| {
            if !(inv_dx > 0.0) {
                return 0.0;
            }
            let left = if i > 0 || ends {
                mf[i * nz + k].max(0.0)
            } else {
                0.0
            };
            let right = if i + 1 < nx || ends {
                mf[(i + 1) * nz + k].min(0.0)
            } else {
                0.0
            };
            cp * inv_dx * (left - right)
        };
        for k in 1..nz - 1 {
            a[(k - 1) * ni..k * ni].copy_from_slice(&op[k * nz + 1..k * nz + nz - 1]);
            a[(k - 1) * ni + k - 1] +=
                convection(k, true) + own_coefficient(line, coef, cp, i * nz + k, h);
        }
        let conduction = [-kf / h, kf / h, kf / h, -kf / h];
        if !crate::linalg::dense::factor_small(&mut a, ni, &mut piv) {
            out.push(conduction);
            continue;
        }
        let mut r4 = [0.0; 4];
        for (b, wall) in [0, nz - 1].into_iter().enumerate() {
            col.fill(0.0);
            col[wall] = 1.0;
            for k in 1..nz - 1 {
                col[k] = -op[k * nz + wall];
            }
            crate::linalg::dense::solve_factored_small(&a, ni, &piv, &mut col[1..nz - 1]);
            for (f, end) in [0, nz - 1].into_iter().enumerate() {
                // the change of the wall point's residual, then of the consistent flux
                let at = i * nz + end;
                let r = (0..nz).map(|l| op[end * nz + l] * col[l]).sum::<f64>()
                    + (convection(end, false) + own_coefficient(line, coef, cp, at, h)) * col[end];
                let grad: f64 = (0..nz).map(|l| rule.d1[end * nz + l] * col[l]).sum();
                let sign = if f == 0 { 1.0 } else { -1.0 };
                r4[2 * f + b] = sign * kc / h * grad - w[end] * r;
            }
        }
        out.push(if r4.iter().all(|v| v.is_finite()) {
            r4
        } else {
            conduction
        });
    }
    out
}

/// The energy accounting ([`LineEnergy`]) of the temperature `t` (K, nx * nz) with the
/// coefficients `coef`.
pub fn line_energy(
    rule: &Lobatto,
    oil: &OilThermal,
    line: &Line,
    coef: &LineCoefficients,
    t: &[f64],
) -> LineEnergy {
    let nz = rule.len();
    let nx = line.nx();
    let sink = sinks(line, coef);
    let (mf, _) = face_fluxes(rule, nx, 0.0, &coef.mass_flux, &sink);
    let w = &rule.weights;
    // the conductivity of each cell, as the linear solve used it (see `cell_conductivity`)
    let (_, jflux) = face_fluxes(rule, nx, 1.0 / line.dx, &coef.mass_flux, &sink);
    let h_min = line.h.iter().fold(f64::INFINITY, |m, &v| m.min(v));
    let kcell: Vec<f64> = (0..nx)
        .map(|i| {
            let j = &jflux[i * nz..(i + 1) * nz];
            let kf = oil.conductivity_at(line.p[i]);
            cell_conductivity(rule, kf, oil.heat_capacity, line.h[i], h_min, j)
        })
        .collect();
    let mut e = LineEnergy {
        generated: vec![0.0; nx],
        q1: vec![0.0; nx],
        q2: vec![0.0; nx],
        q1_gradient: vec![0.0; nx],
        q2_gradient: vec![0.0; nx],
        enthalpy_flux: vec![0.0; nx + 1],
        stored: vec![0.0; nx],
        side_out: vec![0.0; nx],
    };
    for i in 0..nx {
        let h = line.h[i];
        let col = &t[i * nz..(i + 1) * nz];
        if let Some(tr) = &line.transient {
            e.stored[i] = (0..nz)
                .map(|k| {
                    let at = i * nz + k;
                    let heat = if tr.t_old[at].is_finite() {
                        h * coef.density[at] * (col[k] - tr.t_old[at]) * tr.inv_dt
                    } else {
                        0.0
                    };
                    w[k] * oil.heat_capacity * (heat + (col[k] - line.t_in) * coef.mass_storage[at])
                })
                .sum();
        }
        if let Some(sf) = &line.side {
            let th = |v: f64| v - line.t_in;
            e.side_out[i] = oil.heat_capacity
                * sf.inv_dy
                * (0..nz)
                    .map(|k| {
                        let at = i * nz + k;
                        let (n, s) = (sf.north[at], sf.south[at]);
                        let f_n = n.max(0.0) * th(col[k]) + n.min(0.0) * th(sf.t_north[at]);
                        let f_s = s.max(0.0) * th(sf.t_south[at]) + s.min(0.0) * th(col[k]);
                        w[k] * (f_n - f_s)
                    })
                    .sum::<f64>();
        }
        e.generated[i] = h
            * (0..nz)
                .map(|k| w[k] * (coef.heating[i * nz + k] - coef.compression[i * nz + k] * col[k]))
                .sum::<f64>();
        let d0: f64 = (0..nz).map(|l| rule.d1[l] * col[l]).sum();
        let dn: f64 = (0..nz).map(|l| rule.d1[(nz - 1) * nz + l] * col[l]).sum();
        e.q1_gradient[i] = kcell[i] / h * d0;
        e.q2_gradient[i] = -kcell[i] / h * dn;
    }
    let wall = |k: usize| k == 0 || k == nz - 1;
    for f in 0..=nx {
        let mut s = 0.0;
        for k in 0..nz {
            let m = mf[f * nz + k];
            // upstream (left) and downstream (right) temperatures; beyond the ends the flow
            // enters at T_in, except on the surfaces, which keep their own temperature
            let up = if f > 0 {
                t[(f - 1) * nz + k]
            } else if wall(k) {
                t[k]
            } else {
                line.t_in
            };
            let down = if f < nx {
                t[f * nz + k]
            } else if wall(k) {
                t[(nx - 1) * nz + k]
            } else {
                line.t_in
            };
            s += w[k] * (m.max(0.0) * (up - line.t_in) + m.min(0.0) * (down - line.t_in));
        }
        e.enthalpy_flux[f] = oil.heat_capacity * s;
    }
    // the consistent wall fluxes: the equation's residual at the two wall points (which are
    // not collocation points), weighted by the end weights, moved into the wall flux
    let inv_dx = 1.0 / line.dx;
    let cp = oil.heat_capacity;
    for i in 0..nx {
        let h = line.h[i];
        let col = &t[i * nz..(i + 1) * nz];
        for k in [0, nz - 1] {
            let at = i * nz + k;
            let left = mf[i * nz + k].max(0.0);
            let right = mf[(i + 1) * nz + k].min(0.0);
            // beyond the ends a surface keeps its own temperature (as in the enthalpy flux)
            let before = if i > 0 { t[at - nz] } else { t[at] };
            let after = if i + 1 < nx { t[at + nz] } else { t[at] };
            let mut r = if inv_dx > 0.0 {
                cp * inv_dx * (left * (t[at] - before) + right * (after - t[at]))
            } else {
                0.0
            };
            let (mut d1t, mut d2t) = (0.0, 0.0);
            for l in 0..nz {
                d1t += rule.d1[k * nz + l] * col[l];
                d2t += rule.d2[k * nz + l] * col[l];
            }
            r += cp * jflux[at] * d1t - kcell[i] / h * d2t + h * coef.compression[at] * t[at]
                - h * coef.heating[at];
            if let Some(sf) = &line.side {
                let (leave, rest) = sf.upwind(at, line.t_in);
                r += cp * (leave * (t[at] - line.t_in) + rest);
            }
            if let Some(tr) = line
                .transient
                .as_ref()
                .filter(|tr| tr.t_old[at].is_finite())
            {
                r += h * coef.density[at] * cp * (t[at] - tr.t_old[at]) * tr.inv_dt;
            }
            if k == 0 {
                e.q1[i] = e.q1_gradient[i] - w[0] * r;
            } else {
                e.q2[i] = e.q2_gradient[i] - w[nz - 1] * r;
            }
        }
    }
    e
}

/// The temperature of a line for its pressure and film: the fixed point laws(T) -> profile ->
/// heating -> linear solve, relaxed, from `t_start` (nx * nz, K; `None`: linear across the film
/// between the surface temperatures). Not converging within `opts.max_iter` is reported in the
/// result (`converged`), not as an error.
pub fn solve_line<L: FilmLaws + ?Sized>(
    rule: &Lobatto,
    laws: &L,
    oil: &OilThermal,
    line: &Line,
    t_start: Option<&[f64]>,
    opts: &LineOptions,
) -> Result<LineSolution, FilmError> {
    solve_line_from(rule, laws, oil, line, t_start, None, opts)
}

/// [`solve_line`] with the iterations of each column started from `warm` (see
/// [`line_coefficients_from`]; `None`: from the low-shear viscosity and the line's pressure
/// gradient), e.g. the [`LineSolution::thinning`] and [`LineSolution::poiseuille`] of the
/// line's last solve.
pub fn solve_line_from<L: FilmLaws + ?Sized>(
    rule: &Lobatto,
    laws: &L,
    oil: &OilThermal,
    line: &Line,
    t_start: Option<&[f64]>,
    warm: Option<ColumnStart<'_>>,
    opts: &LineOptions,
) -> Result<LineSolution, FilmError> {
    let nz = rule.len();
    line.check(nz)?;
    let nx = line.nx();
    if !(opts.relaxation > 0.0 && opts.relaxation <= 1.0) {
        return Err(FilmError::Input(format!(
            "relaxation must be in (0, 1], got {}",
            opts.relaxation
        )));
    }
    let mut t: Vec<f64> = match t_start {
        Some(s) if s.len() == nx * nz => s.to_vec(),
        Some(s) => {
            return Err(FilmError::Input(format!(
                "t_start has {} values, the line {}",
                s.len(),
                nx * nz
            )))
        }
        None => (0..nx * nz)
            .map(|at| {
                let (i, k) = (at / nz, at % nz);
                let z = rule.points[k];
                line.t1[i] * (1.0 - z) + line.t2[i] * z
            })
            .collect(),
    };
    // the relaxed iterates are kept above a floor, the coldest boundary temperature less
    // FLOOR_MARGIN: an intermediate iterate that undershoots there (the collocation across a thick, fast inlet
    // film oscillates before it settles) would otherwise reach the viscosity law's pole
    // (Roelands: 138 K) and end the run; a physical solution does not go there (the expansion
    // cooling of an oil is ~10 K). A converged solution that touches the floor shows as an
    // energy imbalance.
    let floor = line
        .t1
        .iter()
        .chain(line.t2)
        .fold(line.t_in, |m, &v| m.min(v))
        - floor_margin(laws, oil, line);
    let mut iterations = 0;
    // the relaxation in use and the last change: a change that grows halves the relaxation
    // (a thick inlet film with reverse flow and a temperature-sensitive oil, thesis Table 3.7
    // line in pure rolling at L = 2.2, settled into a limit cycle of +-4 K at 0.4, and converged
    // at 0.2-0.3)
    let (mut omega, mut last) = (opts.relaxation, f64::INFINITY);
    let mut mixing = Anderson::new(opts.anderson);
    let (mut thinning, mut poiseuille) = match warm {
        Some(w) if w.thinning.len() == nx * nz && w.poiseuille.len() == nx => {
            (w.thinning.to_vec(), w.poiseuille.to_vec())
        }
        Some(w) => {
            return Err(FilmError::Input(format!(
                "the thinning factors have {} values and the Poiseuille coefficients {}, the line {} and {}",
                w.thinning.len(),
                w.poiseuille.len(),
                nx * nz,
                nx
            )))
        }
        None => (vec![f64::NAN; nx * nz], vec![f64::NAN; nx]),
    };
    // the heating's linearisation (`LineOptions::linearise_heating`) stands in for a plain
    // step that goes too far: one that changes the temperature by more than 1/beta at the
    // inlet state (a factor e on the viscosity; the step is taken again, linearised, from the
    // same iterate), or one after which the laws fail (taken again from the iterate before).
    // The next step is plain again. Always on, it slowed the lines of the thermal map (up to
    // 3x the outer iterations at L = 3.2) and left a single cold-started line crawling at
    // the relaxation's floor (6x the iterations): -beta S is a column's answer to a uniform
    // warming, not a point's (at a given stress the local heating tau^2 / eta rises as the
    // point warms), so linearised steps stay near 1/beta each.
    let mut linearise = false;
    let mut before = t.clone();
    let beta_in = laws.viscosity_temperature_coefficient(0.0, line.t_in);
    loop {
        iterations += 1;
        let mut o = *opts;
        o.linearise_heating = linearise;
        let (coef, profiles, shear_unconverged) = match line_coefficients_from(
            rule,
            laws,
            line,
            &t,
            &o,
            &mut thinning,
            &mut poiseuille,
        ) {
            Ok(c) => c,
            Err(FilmError::Law { .. })
                if opts.linearise_heating && !linearise && iterations > 1 =>
            {
                linearise = true;
                t.copy_from_slice(&before);
                mixing.clear();
                continue;
            }
            Err(e) => return Err(e),
        };
        let solved = solve_line_linear(rule, oil, line, &coef)?;
        let change = solved
            .iter()
            .zip(&t)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        let converged = change <= opts.tol;
        if opts.linearise_heating && !linearise && beta_in * change > 1.0 {
            linearise = true;
            continue;
        }
        // a linearised step stands in for one plain step; the next is plain again
        let linearised = std::mem::take(&mut linearise);
        if converged || iterations >= opts.max_iter {
            // the residual of the map the iteration runs, the floor included (a point held at
            // the floor by a solve below it has settled there)
            let cell_change = (0..nx)
                .map(|i| {
                    (i * nz..(i + 1) * nz)
                        .fold(0.0f64, |m, at| m.max((solved[at].max(floor) - t[at]).abs()))
                })
                .collect();
            let energy = line_energy(rule, oil, line, &coef, &solved);
            let wall_response = wall_response(rule, oil, line, &coef);
            // the floor on what a caller restarts from, too
            let solved: Vec<f64> = solved.iter().map(|v| v.max(floor)).collect();
            return Ok(LineSolution {
                t: solved,
                profiles,
                coefficients: coef,
                energy,
                wall_response,
                iterations,
                change,
                cell_change,
                converged,
                shear_unconverged,
                thinning,
                poiseuille,
            });
        }
        // the plain steps' changes measure the contraction; a linearised step's is held to
        // about 1/beta and is left out of the comparison
        if !linearised {
            if change > last {
                omega = (0.5 * omega).max(0.25 * opts.relaxation);
                mixing.clear();
            }
            last = change;
        }
        before.copy_from_slice(&t);
        let f: Vec<f64> = solved.iter().zip(&t).map(|(a, b)| a - b).collect();
        let next = mixing.next(&t, &f, omega);
        for (a, b) in t.iter_mut().zip(next) {
            *a = b.max(floor);
        }
    }
}

/// How far below the coldest boundary temperature an iterate of [`solve_line`] may go (K), at
/// least ([`floor_margin`]).
pub const FLOOR_MARGIN: f64 = 30.0;

/// How far below the coldest boundary temperature an iterate of [`solve_line`] may go on
/// `line` (K): [`FLOOR_MARGIN`], or 1.5 times the adiabatic expansion cooling from the line's
/// largest pressure when that is more, dT = alpha T p / (rho c) (the isentropic
/// (dT/dp)_s = alpha T / (rho c_p), taken at that pressure and the hottest boundary temperature
/// T, alpha = -d ln rho / dT; the factor 1.5 is a margin, the floor being a guard, not a
/// model); the floor stays above 150 K unless the
/// fixed margin already puts it lower. The outlet's expansion is fast and nearly adiabatic: on
/// the Table 3.7 line in pure rolling at L = 5 (p 0.7 GPa, dT_ad ~ 75 K) the converged film
/// went 38 K below the surfaces there, and a fixed 30 K floor clamped it and kept the film's
/// iteration cycling.
pub fn floor_margin<L: FilmLaws + ?Sized>(laws: &L, oil: &OilThermal, line: &Line) -> f64 {
    let p = line.p.iter().fold(0.0f64, |m, &v| m.max(v));
    let hot = line
        .t1
        .iter()
        .chain(line.t2)
        .fold(line.t_in, |m, &v| m.max(v));
    let cold = line
        .t1
        .iter()
        .chain(line.t2)
        .fold(line.t_in, |m, &v| m.min(v));
    let rho = laws.density(p, hot);
    let alpha = -laws.density_dt(p, hot) / rho;
    let adiabatic = alpha * hot * p / (rho * oil.heat_capacity);
    let margin = if adiabatic.is_finite() {
        FLOOR_MARGIN.max(1.5 * adiabatic)
    } else {
        FLOOR_MARGIN
    };
    margin.min((cold - 150.0).max(FLOOR_MARGIN.min(cold - 1.0)))
}

/// [`solve_line_from`] on several independent lines in parallel (rayon); `t_start` and
/// `warm` as there, one per line.
pub fn solve_lines<L: FilmLaws + ?Sized>(
    rule: &Lobatto,
    laws: &L,
    oil: &OilThermal,
    lines: &[Line],
    t_start: Option<&[Vec<f64>]>,
    warm: Option<&[ColumnStart<'_>]>,
    opts: &LineOptions,
) -> Vec<Result<LineSolution, FilmError>> {
    // the columns of each line in parallel only while there are fewer lines than threads
    let opts = LineOptions {
        parallel_columns: opts.parallel_columns && lines.len() < rayon::current_num_threads(),
        ..*opts
    };
    lines
        .par_iter()
        .enumerate()
        .map(|(j, line)| {
            let s = t_start.map(|s| s[j].as_slice());
            let f = warm.map(|f| f[j]);
            solve_line_from(rule, laws, oil, line, s, f, &opts)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// eta = eta0 exp(-beta (T - T0)); density rho0 (1 - d (T - T0)) (d = 0: constant).
    struct ExpLaw {
        eta0: f64,
        beta: f64,
        t0: f64,
        rho0: f64,
        d: f64,
    }

    impl ExpLaw {
        /// eta0 (Pa s) falling by beta (1/K), rho0 = 870 kg/m^3 expanding by d (1/K), about T0
        fn new(eta0: f64, beta: f64, d: f64) -> Self {
            ExpLaw {
                eta0,
                beta,
                t0: T0,
                rho0: 870.0,
                d,
            }
        }
    }

    impl FilmLaws for ExpLaw {
        fn viscosity(&self, _: f64, t: f64) -> f64 {
            self.eta0 * (-self.beta * (t - self.t0)).exp()
        }
        fn density(&self, _: f64, t: f64) -> f64 {
            self.rho0 * (1.0 - self.d * (t - self.t0))
        }
        fn density_dt(&self, _: f64, _: f64) -> f64 {
            -self.rho0 * self.d
        }
    }

    const OIL: OilThermal = OilThermal {
        conductivity: 0.13,
        heat_capacity: 2000.0,
        conductivity_pressure: [0.0; 2],
    };
    const T0: f64 = 313.0;

    /// A line of cells `dx` (m) wide at zero pressure with the film `h` and the pressure
    /// gradient `dpdx` given, both walls at T0 (`walls`: nx values of T0; `zeros`: nx zeros)
    /// moving at `u1`, `u2` (m/s).
    fn prescribed<'a>(
        dx: f64,
        h: &'a [f64],
        dpdx: &'a [f64],
        zeros: &'a [f64],
        walls: &'a [f64],
        u1: f64,
        u2: f64,
    ) -> Line<'a> {
        Line {
            dx,
            h,
            p: zeros,
            dpdx,
            dpdy: zeros,
            u1,
            u2,
            t1: walls,
            t2: walls,
            t_in: T0,
            poiseuille_flux_x: None,
            transient: None,
            side: None,
        }
    }

    /// One column without x-variation (dx = +inf, no convection): film `h`, pressure `p`,
    /// surface 1 at rest at T0, surface 2 moving at `u2` (m/s) at the temperature `t2` (K).
    fn column<'a>(h: &'a [f64], p: &'a [f64], u2: f64, t2: &'a [f64]) -> Line<'a> {
        Line {
            dx: f64::INFINITY,
            h,
            p,
            dpdx: &[0.0],
            dpdy: &[0.0],
            u1: 0.0,
            u2,
            t1: &[T0],
            t2,
            t_in: T0,
            poiseuille_flux_x: None,
            transient: None,
            side: None,
        }
    }

    /// The low-shear laws of a test law wrapping an [`ExpLaw`] in its first field.
    macro_rules! exp_law_base {
        () => {
            fn viscosity(&self, p: f64, t: f64) -> f64 {
                self.0.viscosity(p, t)
            }
            fn density(&self, p: f64, t: f64) -> f64 {
                self.0.density(p, t)
            }
            fn density_dt(&self, p: f64, t: f64) -> f64 {
                self.0.density_dt(p, t)
            }
        };
    }

    /// [`ExpLaw`] with Carreau shear thinning (G = 0.2 MPa, n = 0.5), so that a flux-driven
    /// column's pressure gradient is a fixed point (`FLUX_RESOLVES`), and a limiting shear
    /// stress (Pa, the same at every state) where the second field has one.
    struct ThinningLaw(ExpLaw, Option<f64>);

    impl FilmLaws for ThinningLaw {
        exp_law_base!();
        fn ln_effective_viscosity(&self, ln_eta: f64, ln_rate: f64, p: f64, t: f64) -> (f64, f64) {
            self.ln_shear_law(p, t).unwrap().eval(ln_eta, ln_rate)
        }
        fn ln_shear_law(&self, _: f64, _: f64) -> Option<crate::lubricant::rheology::LnShearLaw> {
            Some(crate::lubricant::rheology::LnShearLaw::Carreau {
                e: -0.25,
                ln_g: 2e5f64.ln(),
            })
        }
        fn limiting_shear_stress(&self, _: f64, _: f64) -> Option<f64> {
            self.1
        }
    }

    /// [`ThinningLaw`] without a limit at eta0 = 0.5 Pa s falling by 0.03 1/K (D = 6.5e-4 1/K) and 7 points.
    fn thinning_oil() -> (ThinningLaw, Lobatto) {
        (
            ThinningLaw(ExpLaw::new(0.5, 0.03, 6.5e-4), None),
            Lobatto::new(7),
        )
    }

    /// The Poiseuille flux -rho/eta h^3/12 dp/dx of [`thinning_oil`] without shear thinning
    /// (kg/(m s)) on films `h` under gradients `dpdx`.
    fn newtonian_poiseuille_flux(h: &[f64], dpdx: &[f64]) -> Vec<f64> {
        h.iter()
            .zip(dpdx)
            .map(|(h, g)| -870.0 / 0.5 * h.powi(3) / 12.0 * g)
            .collect()
    }

    /// The flux-driven test lines, 48 cells: film `h` (m), gradient `dpdx` (Pa/m, a sine of
    /// the given amplitude), the imposed Poiseuille flux `q` (kg/(m s),
    /// [`newtonian_poiseuille_flux`]), at zero pressure between walls at T0 sliding at 3 and
    /// 1 m/s ([`FluxDrivenCase::line`]).
    struct FluxDrivenCase {
        h: Vec<f64>,
        dpdx: Vec<f64>,
        q: Vec<f64>,
        zeros: Vec<f64>,
        walls: Vec<f64>,
    }

    impl FluxDrivenCase {
        fn new(amplitude: f64) -> Self {
            let nx = 48;
            let h: Vec<f64> = (0..nx)
                .map(|i| 0.4e-6 * (1.0 + 3.0 * ((i as f64 - 30.0) / 30.0).powi(2)))
                .collect();
            let dpdx: Vec<f64> = (0..nx)
                .map(|i| amplitude * (std::f64::consts::PI * i as f64 / nx as f64).sin())
                .collect();
            let q = newtonian_poiseuille_flux(&h, &dpdx);
            FluxDrivenCase {
                h,
                dpdx,
                q,
                zeros: vec![0.0; nx],
                walls: vec![T0; nx],
            }
        }

        /// The line, 2 um cells, its Poiseuille flux imposed.
        fn line(&self) -> Line<'_> {
            let mut line = prescribed(
                2e-6,
                &self.h,
                &self.dpdx,
                &self.zeros,
                &self.walls,
                3.0,
                1.0,
            );
            line.poiseuille_flux_x = Some(&self.q);
            line
        }
    }

    /// Every column of `sol` carries the imposed Poiseuille flux `q` (kg/(m s)) on film `h`
    /// (m) to 1e-8 (its flux less the Couette part rho* u_e h), and keeps the coefficient
    /// (rho/eta)_e of the profile it ends on as its warm start.
    fn assert_carries_flux(sol: &LineSolution, h: &[f64], q: &[f64]) {
        for (i, pr) in sol.profiles.iter().enumerate() {
            let poiseuille = pr.flux_x - pr.rho_star_ue * h[i];
            assert!(
                (poiseuille - q[i]).abs() <= 1e-8 * q[i].abs().max(1e-12),
                "cell {i}: Poiseuille flux {poiseuille:e} against {:e}",
                q[i]
            );
            assert!((pr.rho_over_eta_e / sol.poiseuille[i] - 1.0).abs() < 1e-12);
        }
    }

    /// An Eyring film (eta = 1e4 Pa s, tau_0 = 5 MPa, rho = 870 kg/m^3, whatever the state).
    struct EyringFilm;

    impl FilmLaws for EyringFilm {
        fn viscosity(&self, _: f64, _: f64) -> f64 {
            1e4
        }
        fn density(&self, _: f64, _: f64) -> f64 {
            870.0
        }
        fn density_dt(&self, _: f64, _: f64) -> f64 {
            0.0
        }
        fn ln_effective_viscosity(&self, ln_eta: f64, ln_rate: f64, p: f64, t: f64) -> (f64, f64) {
            self.ln_shear_law(p, t).unwrap().eval(ln_eta, ln_rate)
        }
        fn ln_shear_law(&self, _: f64, _: f64) -> Option<crate::lubricant::rheology::LnShearLaw> {
            Some(crate::lubricant::rheology::LnShearLaw::Eyring {
                ln_tau0: 5e6f64.ln(),
            })
        }
    }

    /// A flux-driven Eyring column far past tau_0 with sliding (h = 0.64 um, 5.25 and 4.75 m/s,
    /// the Poiseuille stress h |dp/dx| / 2 = 14 MPa at the pressure's gradient, 4.5e13 Pa/m: the
    /// outlet spike of an Eyring line at 1 GPa) has its Poiseuille flux a(g) g falling as the
    /// gradient grows past ~1.1 times 3e13 Pa/m (the secant viscosities' coefficient (rho/eta)_e
    /// falls faster than g grows), so a(g) g = q_P has three roots: 0.8, 1.5 (the pressure's
    /// own) and between 3 and 4.5 times 3e13 Pa/m. The whole flux of the profile grows
    /// monotonically with -g all the same (asserted from 0 to 5 times the pressure's gradient:
    /// a film whose shear rate grows with its stress), so the roots come from the split into
    /// parts, not from the law. With q_P that of the pressure's gradient and the column
    /// started warm from the coefficient at 5 % more gradient, the plain re-solve (gain
    /// |1 - slope| > 1 there) leaves the pressure's root; the column must end on it: its
    /// coefficient (rho/eta)_e that of the profile at the pressure's gradient to 1e-8 (the
    /// root's tolerance is 1e-12 in ln (a g / q_P); the profile solve's own, 1e-10 in ln eta,
    /// sets the margin). Fails with the plain re-solve alone (measured: the coefficient 14 %
    /// off after the one warm re-solve) and with a search that steps one
    /// way only, against the sign of the mismatch at the pressure's gradient (measured: the
    /// mismatch there is at the profile solve's noise, and the search ended on the lower root,
    /// (rho/eta)_e 11.9 against 6.34). Started warm next to the lower root, where the plain
    /// re-solve contracts, the column stays there (its coefficient within 2 % of that root's,
    /// 11.9 against 6.34 at the pressure's; the warm start lies within 1 % in g of the root,
    /// the scan's step, and the coefficient moves by about twice that), unless
    /// [`LineOptions::nearest_root`] is set: then it takes the pressure's root. The
    /// preconditions, that the flux falls at the pressure's gradient and has a root on each
    /// side, are asserted.
    #[test]
    fn an_unstable_flux_driven_column_keeps_the_root_of_its_pressure_gradient() {
        let rule = Lobatto::new(7);
        let nz = rule.len();
        let (h, g_line) = (0.64e-6, -4.5e13);
        let (u1, u2) = (5.25, 4.75);
        // the column's profile at the gradient g, cold
        let profile = |g: f64| {
            let col = crate::thermal::film::Column {
                h,
                dpdx: g,
                dpdy: 0.0,
                u1,
                u2,
            };
            crate::thermal::film::shear_thinning_profile(
                &rule,
                &EyringFilm,
                &col,
                0.0,
                &[T0; 7],
                &[1e4; 7],
                &[870.0; 7],
                ShearOptions::default(),
            )
            .unwrap()
            .profile
        };
        let coefficient = |g: f64| profile(g).rho_over_eta_e;
        let flux = |g: f64| -coefficient(g) * h.powi(3) / 12.0 * g;
        let q = flux(g_line);
        // not the physics going wrong: the whole flux of the profile (Poiseuille and
        // Couette parts) grows monotonically with the pressure-driven push -g, as a film whose
        // shear rate grows with its stress must; only its split into parts by the secant
        // viscosities is not monotone
        let totals: Vec<f64> = (0..=25)
            .map(|k| profile(g_line * 0.2 * k as f64).flux_x)
            .collect();
        assert!(
            totals.windows(2).all(|w| w[1] > w[0]),
            "whole flux against the gradient: {totals:?}"
        );
        // the preconditions: a falling flux at the pressure's gradient, roots on both sides
        assert!(flux(1.05 * g_line) < q && flux(0.95 * g_line) > q);
        assert!(flux(0.5 * g_line) < q && flux(3.0 * g_line) > q && flux(2.0 * g_line) < q);
        let qs = [q];
        let line = Line {
            dx: f64::INFINITY,
            h: &[h],
            p: &[0.0],
            dpdx: &[g_line],
            dpdy: &[0.0],
            u1,
            u2,
            t1: &[T0],
            t2: &[T0],
            t_in: T0,
            poiseuille_flux_x: Some(&qs),
            transient: None,
            side: None,
        };
        let mut thinning = vec![f64::NAN; nz];
        let mut poiseuille = vec![coefficient(1.05 * g_line)];
        let (_, profiles, _) = line_coefficients_from(
            &rule,
            &EyringFilm,
            &line,
            &[T0; 7],
            &LineOptions::default(),
            &mut thinning,
            &mut poiseuille,
        )
        .unwrap();
        let want = coefficient(g_line);
        let got = profiles[0].rho_over_eta_e;
        assert!(
            (got / want - 1.0).abs() < 1e-8,
            "(rho/eta)_e {got:e} against {want:e} at the pressure's gradient"
        );
        let poiseuille_flux = profiles[0].flux_x - profiles[0].rho_star_ue * h;
        assert!((poiseuille_flux / q - 1.0).abs() < 1e-8);

        // started warm next to the lower root instead, a stable one of the plain re-solve (the
        // flux rises there, slope between 0 and 2), the column stays on it; with
        // `nearest_root` (the update that checks a polished solution) it takes the pressure's
        // root all the same
        let lower = (1..45)
            .map(|k| g_line * (0.95 - 0.01 * k as f64))
            .find(|&g| flux(g) < q)
            .expect("a lower root");
        for (nearest, want) in [(false, coefficient(lower)), (true, coefficient(g_line))] {
            let mut thinning = vec![f64::NAN; nz];
            let mut poiseuille = vec![coefficient(lower)];
            let opts = LineOptions {
                nearest_root: nearest,
                ..LineOptions::default()
            };
            let (_, profiles, _) = line_coefficients_from(
                &rule,
                &EyringFilm,
                &line,
                &[T0; 7],
                &opts,
                &mut thinning,
                &mut poiseuille,
            )
            .unwrap();
            let got = profiles[0].rho_over_eta_e;
            assert!(
                (got / want - 1.0).abs() < 0.02,
                "nearest_root {nearest}: (rho/eta)_e {got:e} against {want:e}"
            );
        }
    }

    /// The film iteration of the flux-driven test lines: to 1e-9 K.
    fn flux_driven_options() -> LineOptions {
        LineOptions {
            tol: 1e-9,
            anderson: 4,
            relaxation: 0.4,
            ..LineOptions::default()
        }
    }

    /// A flux-driven shear-thinning line (the Poiseuille flux of a Newtonian film at the line's
    /// gradient imposed, sliding at 2 m/s, the pressure-flow stress at the walls of the order
    /// of the sliding one, so that the column's gradient is a fixed point that takes
    /// re-solves; measured: 1.4 K warmer, eta_eff / eta down to 0.18): solved cold to 1e-9 K,
    /// every column's Poiseuille flux -(rho/eta)_e h^3/12 dp/dx of the final profiles, with
    /// dp/dx recovered from the profile's whole flux, is the imposed one to 1e-8 (measured
    /// 3e-9: the gradient's fixed point goes on across the film iterations, two steps each,
    /// and stops with them; the column solve's own tolerance is 1e-10 in ln eta). Solved again
    /// from that solution's warm start (its temperatures, shear-thinning factors and
    /// Poiseuille coefficients) the line is where it was (1e-9 K) after one iteration, at no
    /// more than 2 profile solves a column ([`WARM_FLUX_RESOLVES`]), where the same
    /// coefficients formed cold take more than 2 (measured 50 and 189 for 48 columns: the
    /// test of the warm branch). Fails if the
    /// warm gradient is formed wrongly (a 0.1 % error in it: the flux is off after one
    /// re-solve) or not used.
    #[test]
    fn a_flux_driven_line_started_warm_is_where_it_was() {
        let (law, rule) = thinning_oil();
        let case = FluxDrivenCase::new(5e12);
        let (h, q, nx) = (&case.h, &case.q, case.h.len());
        let line = case.line();
        let opts = flux_driven_options();
        let cold = solve_line_from(&rule, &law, &OIL, &line, None, None, &opts).unwrap();
        assert!(
            cold.converged && cold.iterations > 3,
            "{} iterations, change {:e} K",
            cold.iterations,
            cold.change
        );
        let hot = cold.t.iter().fold(0.0f64, |m, &v| m.max(v)) - T0;
        assert!(hot > 1.0, "the film heats: {hot} K");
        let thinned = cold.thinning.iter().fold(1.0f64, |m, &v| m.min(v));
        assert!(
            thinned < 0.25,
            "the film thins: eta_eff / eta down to {thinned}"
        );
        assert_carries_flux(&cold, h, q);
        let warm = ColumnStart {
            thinning: &cold.thinning,
            poiseuille: &cold.poiseuille,
        };
        let again =
            solve_line_from(&rule, &law, &OIL, &line, Some(&cold.t), Some(warm), &opts).unwrap();
        assert_eq!(again.iterations, 1);
        let moved = again
            .t
            .iter()
            .zip(&cold.t)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(moved < 1e-9, "moved by {moved:e} K");
        let (mut thin, mut nothing) = (cold.thinning.clone(), vec![f64::NAN; nx]);
        let (unwarmed, _, _) =
            line_coefficients_from(&rule, &law, &line, &cold.t, &opts, &mut thin, &mut nothing)
                .unwrap();
        let (warm_solves, cold_solves) =
            (again.coefficients.profile_solves, unwarmed.profile_solves);
        assert!(
            warm_solves <= 2 * nx && cold_solves > 2 * nx,
            "profile solves: {warm_solves} warm, {cold_solves} cold, {nx} columns"
        );
    }

    /// [`ExpLaw`] that says it is Newtonian (`named`: `LnShearLaw::Newtonian`, as the
    /// program's Newtonian laws do) or not (the general shear-thinning path, which finds
    /// eta_eff = eta all the same).
    struct NewtonianExp(ExpLaw, bool);

    impl FilmLaws for NewtonianExp {
        exp_law_base!();
        fn ln_shear_law(&self, _: f64, _: f64) -> Option<crate::lubricant::rheology::LnShearLaw> {
            self.1
                .then_some(crate::lubricant::rheology::LnShearLaw::Newtonian)
        }
    }

    /// A Newtonian flux-driven column takes the gradient that carries its flux from its
    /// Poiseuille coefficient before its profile (`column_coefficients`): the flux-driven line
    /// of [`a_flux_driven_line_started_warm_is_where_it_was`] with a Newtonian law (eta0 =
    /// 0.5 Pa s falling by 0.03 1/K) solved cold to 1e-9 K through the named law and through
    /// the general path ends at the same temperatures (1e-9 K: both iterations' tolerance;
    /// measured 0) and carries the imposed flux to 1e-8 (the helper's tolerance); the
    /// coefficients at its temperature, formed without a warm start, take one profile solve a
    /// column through the named law and two through the general path (the first at the
    /// line's own gradient), but for the first column, whose gradient and flux are 0 (the
    /// sine's zero), where the line's gradient is already the root. Fails if the gradient
    /// from the coefficient is wrong (the flux check) or not taken (the count).
    #[test]
    fn a_newtonian_flux_driven_column_is_solved_once() {
        let rule = Lobatto::new(7);
        let law = |named| NewtonianExp(ExpLaw::new(0.5, 0.03, 6.5e-4), named);
        let case = FluxDrivenCase::new(5e12);
        let (h, q, nx) = (&case.h, &case.q, case.h.len());
        let line = case.line();
        let opts = flux_driven_options();
        let (named, general) = (law(true), law(false));
        let a = solve_line_from(&rule, &named, &OIL, &line, None, None, &opts).unwrap();
        let b = solve_line_from(&rule, &general, &OIL, &line, None, None, &opts).unwrap();
        assert!(a.converged && b.converged);
        let apart =
            a.t.iter()
                .zip(&b.t)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(apart < 1e-9, "named and general paths {apart:e} K apart");
        assert_carries_flux(&a, h, q);
        let solves = |l: &NewtonianExp| {
            let (mut thin, mut nothing) = (vec![f64::NAN; nx * 7], vec![f64::NAN; nx]);
            let (c, _, _) =
                line_coefficients_from(&rule, l, &line, &a.t, &opts, &mut thin, &mut nothing)
                    .unwrap();
            c.profile_solves
        };
        let (once, twice) = (solves(&named), solves(&general));
        assert!(
            once == nx && twice == 2 * nx - 1,
            "profile solves: {once} named, {twice} general, {nx} columns"
        );
    }

    /// A flux-driven line whose columns reach the limiting shear stress carries the imposed
    /// Poiseuille flux with the profiles it ends on, the capped ones, whose coefficients are
    /// the Reynolds factors: the line of [`a_flux_driven_line_started_warm_is_where_it_was`]
    /// at a tenth of its gradients (the sliding stress then dominates, and the cap is applied
    /// in full where tau_L >= 2 h |dp/dx|), capped at 0.7 of its largest stress without the
    /// cap. Checked on every column to 1e-8 of the flux (measured 1.1e-12; the tolerance of
    /// that test, whose gradient iteration this is), on at least a third of the columns
    /// stressed below 0.9 of their free stress (measured: 29 of 48). Fails with the flux
    /// matched before the cap (measured: off by up to 45 %), where the column's gradient at the
    /// fixed point is a_capped / a_free times the one the Reynolds equation solved with.
    #[test]
    fn a_capped_flux_driven_line_carries_its_flux_with_the_capped_profiles() {
        let (law, rule) = thinning_oil();
        let case = FluxDrivenCase::new(5e11);
        let (h, q, nx) = (&case.h, &case.q, case.h.len());
        let line = case.line();
        let opts = flux_driven_options();
        let top = |pr: &FilmProfile| {
            pr.tau_zx
                .iter()
                .zip(&pr.tau_zy)
                .fold(0.0f64, |m, (a, b)| m.max(a.hypot(*b)))
        };
        let free = solve_line_from(&rule, &law, &OIL, &line, None, None, &opts).unwrap();
        let cap = 0.7 * free.profiles.iter().map(top).fold(0.0, f64::max);
        let capped_law = ThinningLaw(law.0, Some(cap));
        let capped = solve_line_from(&rule, &capped_law, &OIL, &line, None, None, &opts).unwrap();
        assert!(capped.converged, "change {:e} K", capped.change);
        let mut held = 0;
        assert_carries_flux(&capped, h, q);
        for (i, pr) in capped.profiles.iter().enumerate() {
            if top(pr) < 0.9 * top(&free.profiles[i]) {
                held += 1;
            }
        }
        assert!(3 * held >= nx, "{held} of {nx} columns held by the cap");
    }

    /// The columns of a line solved in parallel or one after the other give the same
    /// coefficients, profiles and warm starts to the bit (each column writes only its own
    /// slots), and the same error: the first in column order (two columns made to fail by
    /// temperatures at which the viscosity underflows).
    #[test]
    fn columns_in_parallel_are_the_columns_one_after_the_other() {
        let (law, rule) = thinning_oil();
        let nx = 96;
        let h: Vec<f64> = (0..nx)
            .map(|i| 0.4e-6 * (1.0 + (i as f64 / 40.0).powi(2)))
            .collect();
        let dpdx: Vec<f64> = (0..nx).map(|i| 3e12 * (0.1 * i as f64).sin()).collect();
        let q = newtonian_poiseuille_flux(&h, &dpdx);
        let (zeros, walls) = (vec![0.0; nx], vec![T0; nx]);
        let mut line = prescribed(2e-6, &h, &dpdx, &zeros, &walls, 3.0, 1.0);
        line.poiseuille_flux_x = Some(&q);
        let nz = rule.len();
        let t: Vec<f64> = (0..nx * nz)
            .map(|at| T0 + 0.01 * (at % 13) as f64)
            .collect();
        let run = |parallel: bool, t: &[f64]| {
            let opts = LineOptions {
                parallel_columns: parallel,
                ..LineOptions::default()
            };
            let (mut thin, mut pois) = (vec![f64::NAN; nx * nz], vec![f64::NAN; nx]);
            line_coefficients_from(&rule, &law, &line, t, &opts, &mut thin, &mut pois)
                .map(|(c, profiles, unconverged)| (c, profiles, unconverged, thin, pois))
        };
        let (a, b) = (run(true, &t).unwrap(), run(false, &t).unwrap());
        assert_eq!(a.0.mass_flux, b.0.mass_flux);
        assert_eq!(a.0.heating, b.0.heating);
        assert_eq!(a.0.compression, b.0.compression);
        assert_eq!(a.0.heating_slope, b.0.heating_slope);
        assert_eq!(a.0.profile_solves, b.0.profile_solves);
        assert!(a.0.profile_solves > nx, "{}", a.0.profile_solves);
        assert_eq!(a.1, b.1);
        assert_eq!((a.2, &a.3, &a.4), (b.2, &b.3, &b.4));
        // absurd temperatures at two columns: the viscosity underflows to 0 there, and the
        // error names the first column's
        let mut bad = t.clone();
        bad[70 * nz + 3] = 2e5;
        bad[20 * nz + 2] = 1e5;
        let (ea, eb) = (run(true, &bad).unwrap_err(), run(false, &bad).unwrap_err());
        assert_eq!(ea, eb);
        assert!(matches!(ea, FilmError::Law { t, .. } if t == 1e5), "{ea:?}");
    }

    /// The compression's gradient where the oil is compressed (u dp/dx > 0) is the flux-driven
    /// one, held to at most twice the pressure's own where they agree in sign: unchanged where
    /// they agree (the fixed point), below the cap or of opposite signs; the cap where the
    /// flux-driven one overshoots. Where the oil expands (u dp/dx < 0) the smaller of the two
    /// where they agree in sign. Odd in the gradients and u together.
    #[test]
    fn the_compression_gradient_is_the_flux_driven_one_capped() {
        let u = 1.0;
        assert_eq!(compression_gradient(3e12, 3e12, u), 3e12);
        assert_eq!(compression_gradient(1e12, 4e12, u), 1e12);
        assert_eq!(compression_gradient(7e12, 4e12, u), 7e12);
        assert_eq!(compression_gradient(9e12, 4e12, u), 8e12);
        assert_eq!(compression_gradient(-9e12, -4e12, -u), -8e12);
        assert_eq!(compression_gradient(-5e12, 2e12, u), -5e12);
        assert_eq!(compression_gradient(2e12, 0.0, u), 2e12);
        // expanding oil: the smaller of the two
        assert_eq!(compression_gradient(-3e12, -3e12, u), -3e12);
        assert_eq!(compression_gradient(-9e12, -4e12, u), -4e12);
        assert_eq!(compression_gradient(-1e12, -4e12, u), -1e12);
        assert_eq!(compression_gradient(9e12, 4e12, -u), 4e12);
        assert_eq!(compression_gradient(-5e12, 2e12, -u), -5e12);
        for (a, b, u) in [
            (2.0, 7.0, 1.0),
            (-3.0, -0.5, 1.0),
            (1.0, -1.0, -2.0),
            (10.0, 1.0, -1.0),
        ] {
            assert_eq!(
                compression_gradient(-a, -b, -u),
                -compression_gradient(a, b, u)
            );
        }
    }

    /// The floor's margin: 30 K on an unloaded line and an incompressible oil; 1.5 times the
    /// adiabatic cooling alpha T p / (rho c), computed here by hand, at 0.7 GPa with D =
    /// 6.5e-4 1/K and the hottest boundary at 320 K (1.5 x 84.4 K = 126.7 K); held so that the
    /// floor stays at 150 K on a line whose coldest boundary is 250 K.
    #[test]
    fn the_floor_leaves_room_for_adiabatic_expansion_cooling() {
        let law = |d: f64| ExpLaw {
            eta0: 0.04,
            beta: 0.03,
            t0: T0,
            rho0: 870.0,
            d,
        };
        fn line<'a>(p: &'a [f64], t: &'a [f64]) -> Line<'a> {
            Line {
                dx: 1e-6,
                h: &[1e-6, 1e-6],
                p,
                dpdx: &[0.0, 0.0],
                dpdy: &[0.0, 0.0],
                u1: 1.0,
                u2: 1.0,
                t1: t,
                t2: t,
                t_in: T0,
                poiseuille_flux_x: None,
                transient: None,
                side: None,
            }
        }
        let warm: &[f64] = &[T0, 320.0];
        assert_eq!(
            floor_margin(&law(6.5e-4), &OIL, &line(&[0.0, 0.0], warm)),
            FLOOR_MARGIN
        );
        assert_eq!(
            floor_margin(&law(0.0), &OIL, &line(&[7e8, 0.0], warm)),
            FLOOR_MARGIN
        );
        let (hot, p, d) = (320.0, 7e8, 6.5e-4);
        let rho = 870.0 * (1.0 - d * (hot - T0));
        let alpha = 870.0 * d / rho;
        let expected = 1.5 * alpha * hot * p / (rho * OIL.heat_capacity);
        let loaded = [p, 0.0];
        let m = floor_margin(&law(d), &OIL, &line(&loaded, warm));
        assert!(
            (m / expected - 1.0).abs() < 1e-12 && m > 100.0,
            "{m} {expected}"
        );
        // a cold line: the floor stops at 150 K
        let cold: &[f64] = &[250.0, 250.0];
        let m = floor_margin(&law(d), &OIL, &line(&loaded, cold));
        assert!((m - 100.0).abs() < 1e-12, "{m}");
    }

    /// Plane Couette flow between walls at T0 (thermal.md): one column, dx = inf.
    /// Returns (tau/tau_iso, mid-film rise) from the solver.
    fn couette(nz: usize, lambda: f64) -> (f64, f64) {
        let rule = Lobatto::new(nz);
        let laws = ExpLaw {
            eta0: 0.01,
            beta: 0.03,
            t0: T0,
            rho0: 870.0,
            d: 0.0,
        };
        let us = (lambda * OIL.conductivity / (laws.beta * laws.eta0)).sqrt();
        let h = 1e-6;
        let hs = [h];
        let line = column(&hs, &[0.0], us, &[T0]);
        let opts = LineOptions {
            tol: 1e-11,
            max_iter: 2000,
            relaxation: 0.5,
            ..Default::default()
        };
        let s = solve_line(&rule, &laws, &OIL, &line, None, &opts).unwrap();
        assert!(s.converged, "nz {nz} Lambda {lambda}: {}", s.change);
        let tau_iso = laws.eta0 * us / h;
        let ratio = -s.profiles[0].traction2[0] / tau_iso;
        let mid = rule.interpolate(&s.t, 0.5) - T0;
        // the column's energy balance: all the heat goes into the walls
        // the column's energy balance with the consistent fluxes: all the heat goes into the
        // walls, to rounding of the O(1e5) W/m^2 terms (1e-9 relative)
        let (net, _) = s.energy.balance(line.dx);
        assert!(net.abs() < 1e-9 * s.energy.generated[0], "{net}");
        (ratio, mid)
    }

    /// A conductivity that grows with pressure (`OilThermal::conductivity_at`) enters wherever
    /// the conductivity does: a sheared column at 1 GPa with k0 (1 + a p / (1 + b p)) gives the
    /// temperatures, traction and wall fluxes of the same column with the constant k(1 GPa), to
    /// rounding (1e-12 relative); and that differs from k0's by far more (k doubles here).
    #[test]
    fn a_pressure_dependent_conductivity_acts_as_its_local_value() {
        let rule = Lobatto::new(9);
        let laws = ExpLaw {
            eta0: 0.01,
            beta: 0.03,
            t0: T0,
            rho0: 870.0,
            d: 0.0,
        };
        let p = 1e9;
        let growing = OilThermal {
            conductivity_pressure: [1.7e-9, 0.5e-9],
            ..OIL
        };
        let k = growing.conductivity_at(p);
        assert!((k / OIL.conductivity - (1.0 + 1.7 / 1.5)).abs() < 1e-12);
        let fixed = OilThermal {
            conductivity: k,
            ..OIL
        };
        let ps = [p];
        let solve = |oil: &OilThermal| {
            let line = column(&[1e-6], &ps, 20.0, &[T0 + 5.0]);
            let opts = LineOptions {
                tol: 1e-12,
                max_iter: 2000,
                relaxation: 0.5,
                ..Default::default()
            };
            solve_line(&rule, &laws, oil, &line, None, &opts).unwrap()
        };
        let (a, b, c) = (solve(&growing), solve(&fixed), solve(&OIL));
        let rel = |x: f64, y: f64| (x - y).abs() / y.abs().max(1e-300);
        for (x, y) in a.t.iter().zip(&b.t) {
            assert!(
                rel(x - T0, y - T0) < 1e-12 || (x - y).abs() < 1e-12,
                "{x} {y}"
            );
        }
        let (ta, tb) = (a.profiles[0].traction2[0], b.profiles[0].traction2[0]);
        assert!(rel(ta, tb) < 1e-12, "traction {ta} against {tb}");
        assert!(rel(a.energy.q1[0], b.energy.q1[0]) < 1e-12);
        assert!(rel(a.energy.q2[0], b.energy.q2[0]) < 1e-12);
        // the mid-film rise above the walls' mean, T0 + 2.5 K: the shear heating's
        let mid = |s: &LineSolution| rule.interpolate(&s.t, 0.5) - T0 - 2.5;
        assert!(
            mid(&c) > 1.5 * mid(&a),
            "k0: {} K, k(p): {} K",
            mid(&c),
            mid(&a)
        );
    }

    /// The exact plane Couette solution of thermal.md: tau/tau_iso = 2 s / sinh(2 s), mid-film
    /// rise (2/beta) ln cosh s, s = asinh(sqrt(Lambda/8)). The solution is analytic in zeta,
    /// so the collocation error must fall spectrally: by at least 10x for each step in nz
    /// below the floor, below 1e-7 at nz = 13 and 1e-9 at nz = 17 (relative traction; rise
    /// relative to the rise; measured at Lambda = 1: 5e-5, 2e-7, 2e-9, 1e-13 at nz = 5, 7, 9,
    /// 13; at Lambda = 10: 3e-3, 1e-4, 4e-6, 1e-8) - the floor is the fixed point's 1e-11 K
    /// tolerance and rounding.
    #[test]
    fn plane_couette_exact() {
        let beta = 0.03;
        for lambda in [1.0f64, 10.0] {
            let s = (lambda / 8.0).sqrt().asinh();
            let ratio = 2.0 * s / (2.0 * s).sinh();
            let rise = 2.0 / beta * s.cosh().ln();
            let mut previous = f64::INFINITY;
            for nz in [5usize, 7, 9, 13, 17] {
                let (r, m) = couette(nz, lambda);
                let err = ((r - ratio) / ratio).abs().max(((m - rise) / rise).abs());
                eprintln!(
                    "Couette Lambda {lambda} nz {nz}: tau/tau_iso {r:.12} (exact {ratio:.12}), \
                     rise {m:.9} K (exact {rise:.9}), max rel. error {err:.2e}"
                );
                if previous > 1e-9 {
                    assert!(err < previous / 10.0, "nz {nz}: {err} after {previous}");
                }
                if nz == 13 {
                    assert!(err < 1e-7, "nz {nz}: {err}");
                }
                if nz == 17 {
                    assert!(err < 1e-9, "nz {nz}: {err}");
                }
                previous = err;
            }
        }
    }

    /// A converging-diverging line, h = h0 + x^2 / (2 R), Poiseuille + Couette flow with dp/dx
    /// set (by a few passes of the generalized Reynolds relation per cell) so that the mass
    /// flux is the same in every cell: dp/dx = 12 (rho*_x u_e h - q) / ((rho/eta)_e h^3).
    fn converging_diverging(
        u1: f64,
        u2: f64,
        d: f64,
        nz: usize,
        nx: usize,
    ) -> (LineSolution, Vec<f64>, f64, Lobatto) {
        let (s, h, dx, rule, _) = converging_diverging_dpdx(u1, u2, d, nz, nx);
        (s, h, dx, rule)
    }

    /// [`converging_diverging`] and the pressure gradient it converged to.
    fn converging_diverging_dpdx(
        u1: f64,
        u2: f64,
        d: f64,
        nz: usize,
        nx: usize,
    ) -> (LineSolution, Vec<f64>, f64, Lobatto, Vec<f64>) {
        let rule = Lobatto::new(nz);
        let laws = ExpLaw {
            eta0: 0.05,
            beta: 0.03,
            t0: T0,
            rho0: 870.0,
            d,
        };
        // from x = -2 mm (h = 5 h0) to the point where h = 1.3 h0 (the flux's film, where
        // dp/dx = 0 like a Reynolds exit): the pressure-flow reverses mid-film in the inlet,
        // not at the outlet
        let (h0, radius, start): (f64, f64, f64) = (1e-5, 0.05, 2e-3);
        let end = (2.0 * radius * 0.3 * h0).sqrt();
        let dx = (start + end) / nx as f64;
        let x: Vec<f64> = (0..nx).map(|i| -start + (i as f64 + 0.5) * dx).collect();
        let h: Vec<f64> = x.iter().map(|x| h0 + x * x / (2.0 * radius)).collect();
        let ue = 0.5 * (u1 + u2);
        let q = laws.rho0 * ue * 1.3 * h0;
        let mut dpdx: Vec<f64> = h
            .iter()
            .map(|h| 12.0 * laws.eta0 * (ue * h - q / laws.rho0) / h.powi(3))
            .collect();
        let zeros = vec![0.0; nx];
        let walls = vec![T0; nx];
        let opts = LineOptions {
            tol: 1e-9,
            ..Default::default()
        };
        let mut t_start: Option<Vec<f64>> = None;
        let mut sol = None;
        for _ in 0..40 {
            let line = prescribed(dx, &h, &dpdx, &zeros, &walls, u1, u2);
            let s = solve_line(&rule, &laws, &OIL, &line, t_start.as_deref(), &opts).unwrap();
            assert!(
                s.converged,
                "{} {} max T {}",
                s.change,
                s.iterations,
                s.t.iter().fold(0.0f64, |m, t| m.max(*t))
            );
            let worst = s
                .profiles
                .iter()
                .fold(0.0f64, |m, f| m.max((f.flux_x - q).abs() / q));
            for (i, f) in s.profiles.iter().enumerate() {
                dpdx[i] = 12.0 * (f.rho_star_ue * h[i] - q) / (f.rho_over_eta_e * h[i].powi(3));
            }
            t_start = Some(s.t.clone());
            sol = Some(s);
            if worst < 1e-9 {
                break;
            }
        }
        let s = sol.unwrap();
        (s, h, dx, rule, dpdx)
    }

    /// One transient step of the converging-diverging line (Barus-type oil, thermal expansion,
    /// slip) against its steady solution:
    /// * from the steady state itself (T_old and h rho at the steady solution) the step returns
    ///   the steady temperature (to the iteration tolerance): the time terms vanish there;
    /// * from a cold start (T_old = T0) with a film that was 2 % thicker a step earlier (mass
    ///   storage d(h rho)/dt != 0) the film heats less than steady, between T0 and the steady
    ///   temperature, and the energy balance generated = walls + convected + stored still
    ///   telescopes (asserted < 1e-3 as the steady balance test; the rule's error);
    /// * dt -> infinity (1/dt = 0) is the steady solve.
    #[test]
    fn transient_step_keeps_steady_state_and_balances_storage() {
        let (u1, u2, d, nz, nx) = (15.0, 5.0, 6.5e-4, 7, 200);
        let (steady, h, dx, rule, dpdx) = converging_diverging_dpdx(u1, u2, d, nz, nx);
        let laws = ExpLaw {
            eta0: 0.05,
            beta: 0.03,
            t0: T0,
            rho0: 870.0,
            d,
        };
        let zeros = vec![0.0; nx];
        let walls = vec![T0; nx];
        let opts = LineOptions {
            tol: 1e-9,
            ..Default::default()
        };
        let rho_h = |t: &[f64], scale: f64| -> Vec<f64> {
            (0..nx * nz)
                .map(|at| scale * h[at / nz] * laws.density(0.0, t[at]))
                .collect()
        };
        let step = |t_old: &[f64], rho_h_old: &[f64], inv_dt: f64| {
            let line = Line {
                transient: Some(LineTransient {
                    inv_dt,
                    t_old,
                    rho_h_old,
                }),
                ..prescribed(dx, &h, &dpdx, &zeros, &walls, u1, u2)
            };
            solve_line(&rule, &laws, &OIL, &line, Some(&steady.t), &opts).unwrap()
        };
        let rise = steady.t.iter().fold(0.0f64, |m, t| m.max(t - T0));
        // a step of the order of the transit time of a cell
        let inv_dt = 0.5 * (u1 + u2) / dx;
        let same = step(&steady.t, &rho_h(&steady.t, 1.0), inv_dt);
        let gap = same
            .t
            .iter()
            .zip(&steady.t)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(gap < 1e-6 * rise, "steady state moved by {gap} K");
        let cold = vec![T0; nx * nz];
        let s = step(&cold, &rho_h(&cold, 1.02), inv_dt);
        let top = s.t.iter().fold(0.0f64, |m, t| m.max(t - T0));
        assert!(top > 0.0 && top < rise, "rise {top} vs steady {rise}");
        let e = &s.energy;
        let stored: f64 = e.stored.iter().sum::<f64>() * dx;
        let generated: f64 = e.generated.iter().sum::<f64>() * dx;
        let (net, convected) = e.balance(dx);
        assert!(
            stored > 0.1 * generated,
            "storage must matter: {stored} of {generated}"
        );
        let err = (net - convected).abs() / generated;
        assert!(err < 1e-3, "balance with storage {err}");
        let inf = step(&cold, &rho_h(&cold, 1.02), 0.0);
        let gap = inf
            .t
            .iter()
            .zip(&steady.t)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(gap < 1e-6 * rise, "1/dt = 0 differs from steady by {gap} K");
    }

    /// Energy balance on a converging-diverging line (Pe = rho c u h^2 / (k L) ~ 6: convection
    /// matters), pure rolling and with slip, with and without thermal expansion (then the
    /// compression source works too): generated = into both walls + convected out of the
    /// ends. With the consistent wall fluxes the discrete balance closes up to the rule's error
    /// in the J terms (see LineEnergy): measured <= 2e-4 at nz = 5, 6e-5 at nz = 7, 1e-6 at
    /// nz = 13; asserted < 1e-3 (10x under the 1 % asked). The gradient fluxes k dT/dz of the
    /// polynomial are an independent check: their balance error (measured 11 %, 4-7 %, 0.3 %
    /// at nz = 5, 7, 13, from the thermal boundary layers of the thick inlet) must fall with nz
    /// and be under 1 % at nz = 13.
    #[test]
    fn energy_balance_with_convection() {
        for (u1, u2, d) in [(10.0, 10.0, 0.0), (15.0, 5.0, 0.0), (15.0, 5.0, 6.5e-4)] {
            let mut gradient_errors = vec![];
            for nz in [5usize, 7, 13] {
                let (s, _, dx, _) = converging_diverging(u1, u2, d, nz, 200);
                let e = &s.energy;
                let (net, convected) = e.balance(dx);
                let generated: f64 = e.generated.iter().sum::<f64>() * dx;
                let walls: f64 = e.q1.iter().chain(&e.q2).sum::<f64>() * dx;
                let gradient: f64 = e.q1_gradient.iter().chain(&e.q2_gradient).sum::<f64>() * dx;
                let err = (net - convected).abs() / generated;
                let gradient_err = (generated - gradient - convected).abs() / generated;
                eprintln!(
                    "balance u1 {u1} u2 {u2} d {d} nz {nz}: generated {generated:.6e} W/m, \
                     walls {walls:.6e}, convected {convected:.6e}, error {err:.2e} \
                     (gradient fluxes {gradient_err:.2e}), max rise {:.3} K",
                    s.t.iter().fold(0.0f64, |m, t| m.max(t - T0))
                );
                assert!(convected.abs() > 0.2 * generated, "convection must matter");
                assert!(err < 1e-3, "nz {nz}: {err}");
                gradient_errors.push(gradient_err);
            }
            assert!(
                gradient_errors[2] < gradient_errors[0] / 5.0,
                "{gradient_errors:?}"
            );
            assert!(gradient_errors[2] < 0.01, "{gradient_errors:?}");
        }
    }

    /// One column (no x-flow, no heating, walls at T0) crossed by a side flow of uniform
    /// m = h rho v per unit zeta that enters from the south at T_S = T0 + 10 K and leaves
    /// through the north face (and the mirror: from the north, m < 0). The lagged neighbour
    /// is given, so the column solves c (m/dy) (T - T_S) = (k/h) d2T/dzeta2 with T = T0 at the
    /// walls: theta = theta_S [1 - cosh(lambda (zeta - 1/2)) / cosh(lambda / 2)],
    /// lambda^2 = c m h / (k dy). The solution is analytic, so the collocation error must fall
    /// spectrally (below 1e-3, 1e-6 and 1e-9 of theta_S at nz = 7, 11 and 17; lambda = 6, a
    /// boundary layer of a sixth of the film). With the consistent wall fluxes the column's
    /// balance closes to rounding: the walls take what the side flow brings in,
    /// q1 + q2 = -side_out (1e-10 relative).
    #[test]
    fn side_flow_through_a_column_is_exact() {
        let laws = ExpLaw {
            eta0: 0.01,
            beta: 0.0,
            t0: T0,
            rho0: 870.0,
            d: 0.0,
        };
        let (h, dy, lambda, rise) = (1e-6, 1e-4, 6.0f64, 10.0);
        let m = lambda * lambda * OIL.conductivity * dy / (OIL.heat_capacity * h);
        for (nz, bound) in [(7usize, 1e-3), (11, 1e-6), (17, 1e-9)] {
            let rule = Lobatto::new(nz);
            for from_south in [true, false] {
                let flux = if from_south { m } else { -m };
                let mut f = vec![flux; nz];
                f[0] = 0.0;
                f[nz - 1] = 0.0;
                let hot = vec![T0 + rise; nz];
                let cold = vec![T0 - 50.0; nz];
                let (t_north, t_south) = if from_south {
                    (&cold, &hot)
                } else {
                    (&hot, &cold)
                };
                let hs = [h];
                let line = Line {
                    side: Some(SideFlow {
                        inv_dy: 1.0 / dy,
                        north: &f,
                        south: &f,
                        t_north,
                        t_south,
                    }),
                    ..column(&hs, &[0.0], 0.0, &[T0])
                };
                let opts = LineOptions {
                    tol: 1e-12,
                    shear_heating: false,
                    ..Default::default()
                };
                let s = solve_line(&rule, &laws, &OIL, &line, None, &opts).unwrap();
                let err = (0..nz).fold(0.0f64, |e, k| {
                    let z = rule.points[k];
                    let exact = rise * (1.0 - (lambda * (z - 0.5)).cosh() / (0.5 * lambda).cosh());
                    e.max((s.t[k] - T0 - exact).abs() / rise)
                });
                let e = &s.energy;
                let (net, _) = e.balance(line.dx);
                eprintln!(
                    "side flow nz {nz} from south {from_south}: error {err:.2e}, walls {:.6e} \
                     W/m^2, side_out {:.6e}, net {net:.2e}",
                    e.q1[0] + e.q2[0],
                    e.side_out[0]
                );
                assert!(err < bound, "nz {nz}: {err}");
                assert!(e.side_out[0] < 0.0, "the side flow brings heat in");
                assert!(net.abs() < 1e-10 * e.side_out[0].abs(), "{net}");
            }
        }
    }

    /// A side flow that diverges across the film but conserves mass over the column (the
    /// north face carries m0 6 zeta (1 - zeta), the south face that plus an odd part that
    /// integrates to zero): J takes the divergence, J(1) = 0 to the rule's accuracy, and on a
    /// heated line with x-flow the line's energy balance, side flow included, closes as well
    /// as without it (1e-3 of the heat generated, the tolerance of
    /// `energy_balance_with_convection`; measured 3e-5).
    #[test]
    fn a_diverging_side_flow_keeps_the_balance() {
        let nz = 9;
        let (s0, h, dx, rule, dpdx) = converging_diverging_dpdx(15.0, 5.0, 0.0, nz, 100);
        let nx = h.len();
        let m0 = 0.2
            * s0.coefficients
                .mass_flux
                .iter()
                .fold(0.0f64, |a, v| a.max(v.abs()));
        let mut north = vec![0.0; nx * nz];
        let mut south = vec![0.0; nx * nz];
        for i in 0..nx {
            for k in 0..nz {
                let z = rule.points[k];
                north[i * nz + k] = m0 * 6.0 * z * (1.0 - z);
                south[i * nz + k] = north[i * nz + k] + 20.0 * m0 * (z - 0.5) * z * (1.0 - z);
            }
        }
        let t_north: Vec<f64> = s0.t.iter().map(|t| t + 3.0).collect();
        let t_south: Vec<f64> = s0.t.iter().map(|t| t - 2.0).collect();
        let zeros = vec![0.0; nx];
        let walls = vec![T0; nx];
        let line = Line {
            side: Some(SideFlow {
                inv_dy: 1.0 / 2e-5,
                north: &north,
                south: &south,
                t_north: &t_north,
                t_south: &t_south,
            }),
            ..prescribed(dx, &h, &dpdx, &zeros, &walls, 15.0, 5.0)
        };
        let laws = ExpLaw {
            eta0: 0.05,
            beta: 0.03,
            t0: T0,
            rho0: 870.0,
            d: 0.0,
        };
        let opts = LineOptions {
            tol: 1e-9,
            ..Default::default()
        };
        let s = solve_line(&rule, &laws, &OIL, &line, Some(&s0.t), &opts).unwrap();
        assert!(s.converged, "{}", s.change);
        let e = &s.energy;
        let (net, convected) = e.balance(dx);
        let generated: f64 = e.generated.iter().sum::<f64>() * dx;
        let side_in: f64 = -e.side_out.iter().sum::<f64>() * dx;
        let err = (net - convected).abs() / generated;
        eprintln!(
            "diverging side flow: generated {generated:.6e} W/m, side flow in {side_in:.6e}, \
             error {err:.2e}"
        );
        assert!(
            side_in.abs() > 0.05 * generated,
            "the side flow must matter"
        );
        assert!(err < 1e-3, "{err}");
    }

    /// Reverse flow: the prescribed film of the balance test has u < 0 mid-film in the first
    /// cell (checked) in pure rolling; the solve converges, stays finite, and the temperature
    /// keeps above the walls' T0 up to the collocation's small undershoot (the heating is
    /// positive and the walls and inlet are at T0; 1e-3 of the rise allowed).
    #[test]
    fn reverse_flow_inlet() {
        let (s, _, _, rule) = converging_diverging(10.0, 10.0, 0.0, 7, 100);
        let nz = rule.len();
        let u_mid = s.profiles[0].u[nz / 2];
        assert!(u_mid < 0.0, "no reverse flow: {u_mid}");
        let rise = s.t.iter().fold(0.0f64, |m, t| m.max(t - T0));
        assert!(rise > 1.0 && s.t.iter().all(|t| t.is_finite()));
        let low = s.t.iter().fold(f64::INFINITY, |m, t| m.min(*t - T0));
        assert!(low > -1e-3 * rise, "undershoot {low} of {rise}");
    }

    /// The isoviscous limit: beta = 0, constant density, no heating (shear heating switched
    /// off) on a converging film with Poiseuille + Couette flow, walls and inlet at T0: the
    /// unknowns are T - T_in with a zero right-hand side, so T = T0 exactly (assert_eq). Then
    /// plug flow (u1 = u2, no pressure gradient: no shear, so no heating even with it on) gives
    /// the same.
    #[test]
    fn isoviscous_no_heating_stays_at_t0() {
        let rule = Lobatto::new(7);
        let laws = ExpLaw {
            eta0: 0.05,
            beta: 0.0,
            t0: T0,
            rho0: 870.0,
            d: 0.0,
        };
        let nx = 50;
        let h: Vec<f64> = (0..nx).map(|i| 1e-5 * (3.0 - 0.04 * i as f64)).collect();
        let dpdx = vec![5e9; nx];
        let zeros = vec![0.0; nx];
        let walls = vec![T0; nx];
        for (u2, dp, heating) in [(3.0, &dpdx, false), (1.0, &zeros, true)] {
            let line = Line {
                dx: 1e-5,
                h: &h,
                p: &zeros,
                dpdx: dp,
                dpdy: &zeros,
                u1: 1.0,
                u2,
                t1: &walls,
                t2: &walls,
                t_in: T0,
                poiseuille_flux_x: None,
                transient: None,
                side: None,
            };
            let opts = LineOptions {
                shear_heating: heating,
                ..Default::default()
            };
            let s = solve_line(&rule, &laws, &OIL, &line, None, &opts).unwrap();
            assert!(s.converged);
            for t in &s.t {
                assert_eq!(*t, T0);
            }
        }
    }

    /// A film that only conducts (one column, no x-flow, no heating) answers its surfaces as
    /// a linear profile does: dq1/dT1 = dq2/dT2 = -k/h and dq1/dT2 = dq2/dT1 = +k/h, exactly
    /// (the collocation holds a linear profile to rounding: 1e-12 relative).
    #[test]
    fn a_conducting_film_answers_its_surfaces_by_k_over_h() {
        let laws = ExpLaw::new(0.05, 0.03, 0.0);
        for nz in [5usize, 7, 11] {
            let rule = Lobatto::new(nz);
            let (h, p, t2) = ([2e-6], [0.0], [T0 + 20.0]);
            let line = column(&h, &p, 0.0, &t2);
            let t: Vec<f64> = (0..nz).map(|k| T0 + 20.0 * rule.points[k]).collect();
            let (coef, _, _) =
                line_coefficients(&rule, &laws, &line, &t, &LineOptions::default()).unwrap();
            let g = wall_response(&rule, &OIL, &line, &coef)[0];
            let c = OIL.conductivity / h[0];
            for (got, want) in g.iter().zip([-c, c, c, -c]) {
                assert!(
                    (got - want).abs() < 1e-12 * c,
                    "nz {nz}: {g:?} against -+{c}"
                );
            }
        }
    }

    /// The response of a cell's wall fluxes to its own surface temperatures is what the whole
    /// line's linear solve gives when only that surface temperature moves: on a line where
    /// the oil flows downstream everywhere (both surfaces moving along +x, no pressure
    /// gradient, a converging film so that J is not zero) a cell depends on its upstream
    /// neighbours only, so raising T_b of cell i by 1 K changes cell i's fluxes by exactly
    /// `wall_response` (the solve is linear: 1e-8 of k/h, the banded solve's rounding). And
    /// because the oil entering the cell is held, each surface's own answer is stronger than
    /// the conduction's k/h.
    #[test]
    fn the_wall_response_is_the_cells_own_answer_in_the_line_solve() {
        let laws = ExpLaw::new(0.05, 0.03, 6.5e-4);
        let rule = Lobatto::new(7);
        let nx = 24;
        let h: Vec<f64> = (0..nx).map(|i| 4e-6 - 1e-7 * i as f64).collect();
        let zeros = vec![0.0; nx];
        let walls = vec![T0; nx];
        let line = prescribed(2e-5, &h, &zeros, &zeros, &walls, 3.0, 1.0);
        let opts = LineOptions {
            shear_heating: false,
            ..Default::default()
        };
        let t = vec![T0 + 5.0; nx * rule.len()];
        let (coef, _, _) = line_coefficients(&rule, &laws, &line, &t, &opts).unwrap();
        let base_t = solve_line_linear(&rule, &OIL, &line, &coef).unwrap();
        let base = line_energy(&rule, &OIL, &line, &coef, &base_t);
        let g = wall_response(&rule, &OIL, &line, &coef);
        for i in [0, 5, 23] {
            let c = OIL.conductivity / h[i];
            for b in 0..2 {
                let mut moved = walls.clone();
                moved[i] += 1.0;
                let mut l = line;
                if b == 0 {
                    l.t1 = &moved;
                } else {
                    l.t2 = &moved;
                }
                let t = solve_line_linear(&rule, &OIL, &l, &coef).unwrap();
                let e = line_energy(&rule, &OIL, &l, &coef, &t);
                let dq = [e.q1[i] - base.q1[i], e.q2[i] - base.q2[i]];
                for f in 0..2 {
                    let want = dq[f];
                    let got = g[i][2 * f + b];
                    assert!(
                        (got - want).abs() < 1e-8 * c,
                        "cell {i}, dq{}/dT{}: {got} against the solve's {want}",
                        f + 1,
                        b + 1
                    );
                }
            }
            assert!(
                -g[i][0] > c && -g[i][3] > c,
                "cell {i}: {:?}, k/h {c}",
                g[i]
            );
        }
    }

    /// The heating linearised in the linear solve (`LineCoefficients::heating_slope`) leaves
    /// the fixed point where it was, and steadies a stiff film. A Couette line (surfaces at 4
    /// and 1 m/s, 1 um film) of an oil whose viscosity falls by 5 % a kelvin:
    /// * at eta0 = 2 Pa s (a 12 K rise) the iteration linearised at every step (the loop run
    ///   here by hand) ends where `solve_line`'s plain one does (each to its 1e-9 K; 1e-6 K
    ///   allowed);
    /// * with thermal expansion (the density turns negative 1540 K above T0), at eta0 = 50
    ///   Pa s (63 K rise) `solve_line` with and without the linearisation when needed ends at
    ///   the same temperatures (1e-6 K); at eta0 = 1000 Pa s the plain iteration's first steps
    ///   overshoot by thousands of kelvin, past the density's zero (measured 1930 K), while
    ///   the linearised steps, held to about 1/beta each, settle on the 120 K rise.
    #[test]
    fn the_linearised_heating_keeps_the_fixed_point_and_steadies_a_stiff_film() {
        let rule = Lobatto::new(7);
        let nx = 16;
        let h = vec![1e-6; nx];
        let zeros = vec![0.0; nx];
        let walls = vec![T0; nx];
        let line = prescribed(2e-5, &h, &zeros, &zeros, &walls, 4.0, 1.0);
        let laws = |eta0: f64| ExpLaw::new(eta0, 0.05, 0.0);
        let opts = |linearise_heating: bool| LineOptions {
            tol: 1e-9,
            linearise_heating,
            ..Default::default()
        };
        let apart = |a: &[f64], b: &[f64]| {
            a.iter()
                .zip(b)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        };
        let plain = solve_line(&rule, &laws(2.0), &OIL, &line, None, &opts(false)).unwrap();
        assert!(plain.converged);
        let rise = plain.t.iter().fold(0.0f64, |m, v| m.max(v - T0));
        assert!(rise > 10.0, "the heating must matter: {rise} K");
        let mut t = vec![T0; nx * rule.len()];
        let mut done = false;
        for _ in 0..200 {
            let (coef, _, _) =
                line_coefficients(&rule, &laws(2.0), &line, &t, &opts(true)).unwrap();
            assert!(coef.heating_slope.iter().any(|&v| v > 0.0));
            let next = solve_line_linear(&rule, &OIL, &line, &coef).unwrap();
            let change = apart(&next, &t);
            t.iter_mut()
                .zip(&next)
                .for_each(|(a, b)| *a += 0.7 * (b - *a));
            if change <= 1e-9 {
                done = true;
                break;
            }
        }
        let diff = apart(&t, &plain.t);
        assert!(
            done && diff < 1e-6,
            "linearised throughout: {diff} K from the plain fixed point"
        );
        // an oil that expands with temperature (its density turns negative 1540 K above T0)
        let expanding = |eta0: f64| ExpLaw::new(eta0, 0.05, 6.5e-4);
        let a = solve_line(&rule, &expanding(50.0), &OIL, &line, None, &opts(true)).unwrap();
        let b = solve_line(&rule, &expanding(50.0), &OIL, &line, None, &opts(false)).unwrap();
        assert!(a.converged && b.converged);
        let diff = apart(&a.t, &b.t);
        assert!(diff < 1e-6, "eta0 50: {diff} K apart");
        let stiff = solve_line(&rule, &expanding(1000.0), &OIL, &line, None, &opts(true)).unwrap();
        let rise = stiff.t.iter().fold(0.0f64, |m, v| m.max(v - T0));
        eprintln!(
            "eta0 1000: rise {rise:.1} K in {} iterations",
            stiff.iterations
        );
        assert!(stiff.converged && rise > 100.0, "{} K", rise);
        match solve_line(&rule, &expanding(1000.0), &OIL, &line, None, &opts(false)) {
            Err(FilmError::Law { law, t, .. }) => {
                eprintln!("eta0 1000, plain: the {law} failed at {t:.0} K")
            }
            other => panic!("the plain iteration was expected to overshoot: {other:?}"),
        }
    }
}
