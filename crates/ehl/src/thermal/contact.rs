//! The thermal model of a contact: the film across z ([`super::film_energy`]) between two
//! bodies whose surfaces are heated as they move through it ([`super::solid`]), for a given
//! pressure and film; the generalized Reynolds factors the EHL solver needs back; the heat
//! balance and the temperatures for the outputs. A physics object: no case file, no I/O.
//!
//! # Coupling of film and bodies
//!
//! For a pressure and film, [`ThermalContact::update`] iterates
//!
//! 1. each grid line's film temperature for the current surface temperatures
//!    ([`super::film_energy::solve_lines`], the laws at (p, T) inside);
//! 2. the heat flux into each body from the film (the consistent wall fluxes);
//! 3. each surface temperature towards T0 + the moving-heat-source response to that flux
//!    (Jaeger), each film column's own answer to its surface temperatures taken into
//!    account (`ThermalContact::update_surfaces`, `film_energy::wall_response`),
//!
//! until the surface temperatures change by less than [`ContactOptions::surface_tol`]. The grid
//! lines exchange heat through the side flow (v dT/dy, [`ContactOptions::side_flow`]): each
//! film iteration takes the y mass fluxes of the last one, and sweeps the lines along y in
//! blocks, each line the temperatures of the line solved just before it
//! ([`ContactOptions::sweep_lines`], `film_energy::SideFlow`). The plain update of step 3
//! (T0 + the response) converges while the film's conductance k_f / h (~1e5 W/(m^2 K) for
//! 1 um) is below the body's k sqrt(U / (kappa x)) (~1e6 for steel at 1 m/s over 0.1 mm:
//! loop gain ~0.1); a slow body under a thin film turns that gain above 1 (a ball at
//! 0.09 m/s under 0.2 um: ~70), hence the linearised update.
//!
//! # Neglected (said in docs/thermal.md)
//!
//! * In-plane conduction in the film (negligible: film Peclet ~1e3).
//! * The cavitated zone is treated as a full film at ambient pressure; no temperature is
//!   solved downstream of a row's film, whose Reynolds factors are those of its last cell.

use super::collocation::Lobatto;
use super::film::{FilmError, FilmLaws, FilmProfile, OilThermal};
use super::film_energy::{
    solve_line_from, solve_lines, ColumnStart, Line, LineOptions, LineSolution, LineTransient,
    SideFlow,
};
use super::solid::{MovingHalfSpace, SolidThermal};
use crate::grid::Grid;
use crate::lubricant::rheology::{
    effective_viscosity, limiting_shear_stress, ln_effective_viscosity, LnShearLaw,
};
use crate::lubricant::temperature::ThermalLaws;
use crate::lubricant::Rheology;
use crate::{Error, Result};

mod coupled;
pub(crate) use coupled::CoupledFrame;

impl FilmLaws for ThermalLaws {
    fn viscosity(&self, p: f64, t: f64) -> f64 {
        ThermalLaws::viscosity(self, p, t)
    }
    fn viscosities(&self, p: f64, t: &[f64], eta: &mut [f64]) {
        ThermalLaws::viscosities(self, p, t, eta)
    }
    fn density(&self, p: f64, t: f64) -> f64 {
        ThermalLaws::density(self, p, t)
    }
    fn density_dt(&self, p: f64, t: f64) -> f64 {
        ThermalLaws::density_dt(self, p, t)
    }
    /// The shear-thinning law at temperature `t` WITHOUT its limiting shear stress: a film whose
    /// stress is capped pointwise at tau_L = Lambda p has no profile where the pressure-flow
    /// stress alone exceeds the cap (the low-pressure inlet), and a hard cap leaves the slip
    /// undetermined. The cap acts per column instead ([`FilmLaws::limiting_shear_stress`],
    /// `film_energy::line_coefficients`).
    fn effective_viscosity(&self, eta: f64, shear_rate: f64, p: f64, t: f64) -> f64 {
        effective_viscosity(&unlimited(self.rheology(t)), eta, shear_rate, p)
    }
    /// The closed form of the same law (no limit), [`ln_effective_viscosity`].
    fn ln_effective_viscosity(
        &self,
        ln_eta: f64,
        ln_shear_rate: f64,
        _p: f64,
        t: f64,
    ) -> (f64, f64) {
        ln_effective_viscosity(&self.rheology(t), ln_eta, ln_shear_rate)
    }
    fn ln_shear_law(&self, _p: f64, t: f64) -> Option<LnShearLaw> {
        Some(LnShearLaw::of(&self.rheology(t)))
    }
    fn limiting_shear_stress(&self, p: f64, t: f64) -> Option<f64> {
        limiting_shear_stress(&self.rheology(t), p)
    }
}

/// `r` without its limiting shear stress.
fn unlimited(r: Rheology) -> Rheology {
    match r {
        Rheology::Carreau {
            shear_modulus,
            power_law_index,
            ..
        } => Rheology::Carreau {
            shear_modulus,
            power_law_index,
            limiting_shear_coefficient: None,
        },
        Rheology::Eyring { eyring_stress, .. } => Rheology::Eyring {
            eyring_stress,
            limiting_shear_coefficient: None,
        },
        Rheology::Newtonian => Rheology::Newtonian,
    }
}

/// A grid line's film starts at its first cell whose film is at most this many times the
/// line's thinnest (upstream the oil is taken at the inlet temperature; see `update`).
pub const INLET_FILM_RATIO: f64 = 20.0;

/// With [`ContactOptions::inlet_hysteresis`], a grid line's film start moves downstream only
/// when the film at its last start has grown past [`INLET_FILM_RATIO`] by more than this
/// fraction (upstream it moves freely). Without it the start of the Table 3.7 line at SRR 1
/// and L = 9.5 flipped between two cells from one outer iteration to the next once Newton's
/// method on the coupled problem (which freezes the film's extent) had taken over: the film
/// at the first cell just below the ratio with the film started at the second, just above
/// it with the film started there, and the coupled solution of each start gave the other.
pub const INLET_FILM_HYSTERESIS: f64 = 0.005;

/// [`ThermalContact::inner_residual`] takes the film's own residual over the cells whose film
/// is at most this many times its row's thinnest: the inlet that sets the film thickness, but
/// not the film's first cells at up to [`INLET_FILM_RATIO`], where a turning reverse flow kept
/// a limit cycle of ~0.5 K (Table 3.7 line at 1024 cells) that the films and friction did not
/// feel.
pub const RESIDUAL_FILM_RATIO: f64 = 10.0;

/// A grid line's film ends one cell past its last pressurised cell (see `update`); past the
/// cells the last update counted as pressurised, a cell counts only where its pressure exceeds
/// this fraction of the contact's highest pressure (the contact's first update, and the cells
/// the last one counted: above zero, as before). A cavitated cell's pressure is zero only to
/// the Reynolds solve's tolerance: at the outlet of the glass-disc ball example at 5 m/s and
/// SRR 2 (disc at rest, L = 2.3), one cell of the grid's edge row held 0 and 8-19 Pa (3-6e-8
/// of the peak) on alternate outer iterations, its row's film ended one cell later on every
/// other one, and the fixed point's factors' residual cycled at 8-13e-4 there (against a 1e-4
/// stop) through 80 outer iterations while the film had settled to 7.6e-9. Two variants were
/// dropped: the floor for every cell gave the same contact a cycle at the floor (a cell of the
/// next row climbed from 247 to 314 Pa over six outer iterations, crossed 304 Pa, and the
/// longer film put it back at 247 Pa); a band, the floor to join and half of it to stay, moved
/// the film ends of rows whose pressures did not cycle (the thesis roller + `[thermal]` at
/// 256 x 512 took 6 outer iterations instead of 5). Held from below by zero, a counted cell
/// stays until the pressure there vanishes: the thermal map's lines, the scan's lines and
/// finite rollers, the thesis roller and the thermal pit at 128^2 came out as before to the
/// last digit, the scan's balls within 7.4e-8 of their films (docs/thermal.md, "A film end
/// held against the pressure's noise").
pub const PRESSURISED_FRACTION: f64 = 1e-6;

/// [`ThermalContact::update`] reports the film-temperature change over the cells whose film is
/// at most this many times its row's thinnest (see there).
pub const CONVERGED_FILM_RATIO: f64 = 5.0;

/// The linear solve of [`ThermalContact::update_surfaces`]: relative residual, Krylov
/// dimension before a restart and most iterations. The linearisation is itself approximate
/// (each film column's own answer and the heating's slope only), so a loose tolerance
/// suffices: the next film-body iteration corrects the rest.
const SURFACE_GMRES_RTOL: f64 = 1e-3;
const SURFACE_GMRES_RESTART: usize = 30;
const SURFACE_GMRES_MAX_ITER: usize = 90;

/// The preconditioner of [`ThermalContact::update_surfaces`]'s linear solve: per cell, the
/// inverse of its equations with each body's operator R_b cut to its own cell's coefficient
/// `own[b]` (K m^2/W), the 2 x 2 block
///
/// [1 + r_1 (S - G_11), r_1 (S - G_12); r_2 (S - G_21), 1 + r_2 (S - G_22)]
///
/// (`response` G per cell `[G_11, G_12, G_21, G_22]` and `softening` S, both W/(m^2 K)), row
/// by row `[m_11, m_12, m_21, m_22]`; the identity where the block is singular or not finite.
fn local_surface_blocks(response: &[[f64; 4]], softening: &[f64], own: [f64; 2]) -> Vec<[f64; 4]> {
    response
        .iter()
        .zip(softening)
        .map(|(g, &s)| {
            let a = 1.0 + own[0] * (s - g[0]);
            let b = own[0] * (s - g[1]);
            let c = own[1] * (s - g[2]);
            let d = 1.0 + own[1] * (s - g[3]);
            let det = a * d - b * c;
            let inv = [d / det, -b / det, -c / det, a / det];
            if det != 0.0 && inv.iter().all(|v| v.is_finite()) {
                inv
            } else {
                [1.0, 0.0, 0.0, 1.0]
            }
        })
        .collect()
}

/// How far above the highest temperature of the film's iterate and of the surfaces an update
/// may take a surface (K; [`ThermalContact::update_surfaces`]): half the viscosity's
/// temperature scale 1 / beta at the inlet (beta = -d ln eta / dT, 1/K; 12 K for the
/// robustness scan's mineral oil, beta = 0.042 1/K), at least 1 K (an oil whose viscosity does
/// not depend on temperature). The surfaces lead the film they heat: with the bound at the
/// film's highest temperature itself the glass-disc ball example (`ehl_thermal_ball.toml`),
/// whose surfaces rise up to 0.8 K above the film's iterate an update, took 13 outer
/// iterations instead of 4 (4 with this margin). Measured on the scan's Newtonian lines at
/// 1.5-3 GPa and SRR 0.1-1 and its finite roller at SRR 0.5 and 1 (14 runs): with 0.5 / beta
/// and 0.25 / beta all settle; with 1 / beta the line at 1.5 GPa and SRR 1 ended with a failed
/// Reynolds solve at its 12th outer iteration, its film 590 K hot.
pub fn surface_overshoot(beta: f64) -> f64 {
    if beta > 0.0 {
        (0.5 / beta).max(1.0)
    } else {
        1.0
    }
}

/// Controls of [`ThermalContact::update`].
#[derive(Debug, Clone, Copy)]
pub struct ContactOptions {
    /// stop the film-body iteration when the surface temperatures change by less (K)
    pub surface_tol: f64,
    /// most film-body iterations per update
    pub max_surface_iterations: usize,
    /// the film's own fixed point (laws at T) per line
    pub line: LineOptions,
    /// convect the film's heat along y with the side flow, v dT/dy, between the grid lines
    /// (the mass fluxes lagged by one film-body iteration, the temperatures swept along y,
    /// `sweep_lines`; see `film_energy::SideFlow`); false: independent
    /// lines, as before 2026-11-26
    pub side_flow: bool,
    /// the grid lines of a block that the film iteration sweeps along y, each line taking
    /// the side flow's temperatures of the line solved just before it (see
    /// `ThermalContact::solve_swept`); the blocks are solved in parallel. 1: every line takes
    /// its neighbours' temperatures of the last film-body iteration (a Jacobi iteration, as
    /// before 2026-12-02). On the thesis roller 256 x 512 with `[thermal]` the film-body
    /// iteration's last steps contracted by ~0.8 a step with 1 and ~0.07 with 4 to 64 (the
    /// surface temperatures' change 2.7e-4 -> 1.6e-5 -> 1.1e-6 K with 8 against 2.8e-4 ->
    /// 8.2e-5 -> 6.6e-5 -> 5.4e-5 -> 4.4e-5 K with 1); 8 keeps 16 or more blocks (parallel
    /// tasks) where 129 or more lines have a film
    pub sweep_lines: usize,
    /// hold a grid line's film start against small moves downstream
    /// ([`INLET_FILM_HYSTERESIS`]); off by default (the results of a run are then those of
    /// the rule alone), on once the steady driver has handed the contact to Newton's method
    /// on the coupled problem (`crate::ehl::thermal`)
    pub inlet_hysteresis: bool,
}

impl Default for ContactOptions {
    /// A few film and body iterations per update, not a converged film: with the pressure held,
    /// the film's own fixed point can run away where the pressure-flow heating (z dp/dx)^2 / eta
    /// grows as the viscosity falls (the Bratu problem driven by the stress has no solution past
    /// a limit; measured on the thesis Table 3.7 line at SRR 0.3: the film alone diverged from
    /// the second body update on, at the Hertz outlet). The pressure must move with the
    /// temperature, so the driver alternates short updates with Reynolds solves.
    ///
    /// The film iterations are Anderson-mixed (depth 4): 5 of them do what 10 plain relaxed
    /// ones did. Measured against a tight inner solve (5 body x 50 film iterations) on the
    /// Table 3.7 line (256 and 512 cells, SRR 0, 0.01, 0.3, 1) and the thesis roller
    /// (256 x 128, SRR 0 and 0.3): films and friction within 1e-5 of it, 1.5-1.9x faster than
    /// 3 x 10 plain. Fewer body iterations (1 or 2) stopped the outer fixed point early in pure
    /// rolling (central film 1.6e-4 to 4.7e-4 off): the inlet's body temperatures set the film.
    fn default() -> Self {
        ContactOptions {
            surface_tol: 1e-3,
            max_surface_iterations: 3,
            line: LineOptions {
                tol: 1e-4,
                max_iter: 5,
                anderson: 4,
                relaxation: 0.4,
                ..LineOptions::default()
            },
            side_flow: true,
            sweep_lines: 8,
            inlet_hysteresis: false,
        }
    }
}

/// The heat balance of the film (W; a line contact per metre of length).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct HeatBalance {
    /// shear and compression heating integrated over the film
    pub generated: f64,
    /// conducted into body 1 and body 2
    pub to_body: [f64; 2],
    /// enthalpy carried out of the domain by the oil, c int rho u (T - T0) dz through the ends
    /// of the grid lines and, with the side flow, c int rho v (T - T0) dz through the film's
    /// edges along y
    pub convected: f64,
    /// the rate of change of the enthalpy the film holds (a time step of a transient run; 0
    /// when steady)
    pub stored: f64,
    /// mean film temperature over the pressurised cells (K)
    pub mean_film_temperature: f64,
}

impl HeatBalance {
    /// (generated - to bodies - convected - stored) / generated (0 without heat).
    pub fn balance_error(&self) -> f64 {
        let r = self.generated - self.to_body[0] - self.to_body[1] - self.convected - self.stored;
        if self.generated != 0.0 {
            r / self.generated
        } else {
            0.0
        }
    }
}

/// Film and bodies of one contact on one grid (see the module docs).
pub struct ThermalContact {
    grid: Grid,
    laws: ThermalLaws,
    oil: OilThermal,
    rule: Lobatto,
    u1: f64,
    u2: f64,
    solids: [MovingHalfSpace; 2],
    pub options: ContactOptions,
    /// per grid line, the film temperature (nx * nz, i-major) of the last update
    film: Vec<Vec<f64>>,
    /// per grid line, the shear-thinning factors eta_eff / eta of the last update (nx * nz;
    /// NaN: none yet), where the next update's column iterations start
    thinning: Vec<Vec<f64>>,
    /// per grid line, the Poiseuille coefficients (rho/eta)_e of the last update's columns (nx;
    /// NaN: none yet), where the next update's flux-driven columns start
    /// (`film_energy::ColumnStart`)
    poiseuille: Vec<Vec<f64>>,
    /// surface temperatures of body 1 and 2 (K), per cell
    surface: [Vec<f64>; 2],
    /// per grid line, the last solution (None before the first update)
    lines: Vec<Option<LineSolution>>,
    /// per grid line, the first cell of its film (see [`INLET_FILM_RATIO`])
    start: Vec<usize>,
    /// per grid line, one past the last cell of its film (see [`PRESSURISED_FRACTION`])
    end: Vec<usize>,
    /// cells taking part in the last update
    active: Vec<bool>,
    /// cells with material on both sides (a finite film) in the last update
    material: Vec<bool>,
    /// the pressure and film of the last update
    p: Vec<f64>,
    h: Vec<f64>,
    dpdx: Vec<f64>,
    /// a time step in progress (see [`ThermalContact::begin_step`])
    step: Option<TimeLevel>,
    /// the residuals the last update left (K): the film's own fixed point (the last film
    /// iteration's change, where the film is at most RESIDUAL_FILM_RATIO times its row's
    /// thinnest) and the bodies' (the last surface-temperature update's change)
    residual: [f64; 2],
    /// why the solve was started again with more points across the film, if it was
    /// ([`ThermalContact::retry_with_points_across_film`])
    retry_reason: Option<String>,
    /// wall time (s) the updates spent on the bodies' surface temperatures, all updates
    /// together ([`ThermalContact::body_time_s`])
    body_time_s: f64,
}

/// The side flow of one grid line (see `film_energy::SideFlow`), owned.
#[derive(Debug, Clone)]
struct SideArrays {
    north: Vec<f64>,
    south: Vec<f64>,
    t_north: Vec<f64>,
    t_south: Vec<f64>,
}

/// The film at the previous time level of a transient run, per grid line (nx * nz, i-major):
/// its temperature and h rho, NaN where it had no film.
#[derive(Debug, Clone)]
struct TimeLevel {
    inv_dt: f64,
    t_old: Vec<Vec<f64>>,
    rho_h_old: Vec<Vec<f64>>,
}

impl ThermalContact {
    /// The model of a contact on `grid` whose surfaces move at `u1`, `u2` (m/s), with the
    /// lubricant laws `laws` (their `points_across_film` collocation points) and the bodies'
    /// properties.
    pub fn new(
        grid: Grid,
        laws: ThermalLaws,
        bodies: [SolidThermal; 2],
        u1: f64,
        u2: f64,
    ) -> Result<Self> {
        let solid = |k: usize, u: f64| {
            MovingHalfSpace::new(&grid, bodies[k], u).map_err(|e| {
                Error::Solver(format!("the surface temperature of body {}: {e}", k + 1))
            })
        };
        // two bodies alike in material and speed (pure rolling of like rollers) share one
        // table: its quadratures are most of the set-up (0.48 s a body at 256 x 512 cells)
        let first = solid(0, u1)?;
        let second = if bodies[1] == bodies[0] && u2 == u1 {
            first.clone()
        } else {
            solid(1, u2)?
        };
        let solids = [first, second];
        let nz = laws.thermal.points_across_film.max(3);
        let oil = OilThermal {
            conductivity: laws.thermal.conductivity,
            heat_capacity: laws.thermal.heat_capacity,
            conductivity_pressure: laws.thermal.conductivity_pressure,
        };
        let t0 = laws.thermal.inlet_temperature;
        let n = grid.len();
        Ok(ThermalContact {
            grid,
            oil,
            rule: Lobatto::new(nz),
            u1,
            u2,
            solids,
            options: ContactOptions::default(),
            film: vec![vec![t0; grid.nx * nz]; grid.ny],
            thinning: vec![vec![f64::NAN; grid.nx * nz]; grid.ny],
            poiseuille: vec![vec![f64::NAN; grid.nx]; grid.ny],
            surface: [vec![t0; n], vec![t0; n]],
            lines: vec![None; grid.ny],
            start: vec![0; grid.ny],
            end: vec![0; grid.ny],
            active: vec![false; n],
            material: vec![false; n],
            p: vec![0.0; n],
            h: vec![0.0; n],
            dpdx: vec![0.0; n],
            step: None,
            residual: [f64::INFINITY; 2],
            retry_reason: None,
            body_time_s: 0.0,
            laws,
        })
    }

    /// Resolves the film with `nz` collocation points across it from now on (at least 3), and
    /// starts the temperatures again at the inlet's, as a new contact would: the bodies'
    /// moving-heat-source tables are kept.
    pub fn set_points_across_film(&mut self, nz: usize) {
        let nz = nz.max(3);
        let (g, t0) = (self.grid, self.t0());
        self.laws.thermal.points_across_film = nz;
        self.rule = Lobatto::new(nz);
        self.film = vec![vec![t0; g.nx * nz]; g.ny];
        self.thinning = vec![vec![f64::NAN; g.nx * nz]; g.ny];
        self.poiseuille = vec![vec![f64::NAN; g.nx]; g.ny];
        self.surface = [vec![t0; g.len()], vec![t0; g.len()]];
        self.lines = vec![None; g.ny];
        self.start = vec![0; g.ny];
        self.end = vec![0; g.ny];
        self.active = vec![false; g.len()];
        self.material = vec![false; g.len()];
        self.step = None;
        self.residual = [f64::INFINITY; 2];
    }

    /// [`ThermalContact::set_points_across_film`] for a solve started again after a failed
    /// temperature solve, `why` the failure (kept for the run's warning:
    /// [`ThermalContact::retry_reason`]).
    pub fn retry_with_points_across_film(&mut self, nz: usize, why: String) {
        self.set_points_across_film(nz);
        self.retry_reason = Some(why);
    }

    /// Wall time (s) all updates so far spent on the bodies' surface temperatures (the
    /// moving-heat-source responses matched to the film); the rest of an update is the film's
    /// energy equation.
    pub fn body_time_s(&self) -> f64 {
        self.body_time_s
    }

    /// Why the solve was started again with more points across the film (None: it was not).
    pub fn retry_reason(&self) -> Option<&str> {
        self.retry_reason.as_deref()
    }

    /// Starts a time step of `dt` seconds from the present temperatures (a transient run):
    /// until [`ThermalContact::end_steps`], every [`ThermalContact::update`] solves the film's
    /// energy equation with its time derivatives against this level (backward Euler; see
    /// `film_energy::LineTransient`). The bodies stay quasi-steady: each surface takes the
    /// moving-heat-source response to the present flux, as if it had acted for long (see
    /// docs/thermal.md, "Transient runs").
    pub fn begin_step(&mut self, dt: f64) {
        let (nx, nz) = (self.grid.nx, self.nz());
        let mut t_old = self.film.clone();
        let mut rho_h_old = vec![vec![f64::NAN; nx * nz]; self.grid.ny];
        for (j, (t, rh)) in t_old.iter_mut().zip(rho_h_old.iter_mut()).enumerate() {
            for i in 0..nx {
                let k = j * nx + i;
                let wet = self.active.get(k).copied().unwrap_or(false);
                for z in 0..nz {
                    let at = i * nz + z;
                    if wet {
                        rh[at] = self.h[k] * self.laws.density(self.p[k], t[at]);
                    } else {
                        t[at] = f64::NAN;
                    }
                }
            }
        }
        self.step = Some(TimeLevel {
            inv_dt: 1.0 / dt,
            t_old,
            rho_h_old,
        });
    }

    /// Ends the transient mode of [`ThermalContact::begin_step`]: updates are steady again.
    pub fn end_steps(&mut self) {
        self.step = None;
    }

    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The largest residual the last update left (K): of the film's own fixed point (where the
    /// film is at most [`RESIDUAL_FILM_RATIO`] times its row's thinnest) and of the surface
    /// temperatures. An update does a few film and body iterations, not a converged solve
    /// ([`ContactOptions`]), so a small change between updates can be slow progress; a fixed
    /// point is settled only when this is small too. Infinite before the first update.
    pub fn inner_residual(&self) -> f64 {
        self.residual[0].max(self.residual[1])
    }

    /// The cells the last update solved a film for (false everywhere before the first).
    pub fn film_cells(&self) -> &[bool] {
        &self.active
    }

    /// Whether an update has solved the film on some cell (else there are no temperatures).
    pub fn solved(&self) -> bool {
        self.active.iter().any(|&a| a)
    }

    /// collocation points across the film
    pub fn nz(&self) -> usize {
        self.rule.len()
    }

    fn t0(&self) -> f64 {
        self.laws.thermal.inlet_temperature
    }

    /// Solves the temperatures for the pressure `p` (Pa) and film `h` (m; infinite or any value
    /// on cells with `active == false`), from the last ones. Returns the largest change of the
    /// film temperature since the last update (K) where the film is at most
    /// [`CONVERGED_FILM_RATIO`] times its row's thinnest.
    ///
    /// `factors` are the generalized Reynolds factors (flow, couette) the pressure was solved
    /// with (None: 1, the isothermal Newtonian film); with them each column carries the
    /// pressure-flow flux of that Reynolds equation, q_P = -flow (rho/eta)(p, T0) h^3/12 dp/dx,
    /// and its pressure gradient follows its temperature
    /// (`film_energy::Line::poiseuille_flux_x`).
    pub fn update(
        &mut self,
        p: &[f64],
        h: &[f64],
        active: &[bool],
        factors: Option<(&[f64], &[f64])>,
    ) -> Result<f64> {
        let g = self.grid;
        let (nx, ny, n) = (g.nx, g.ny, g.len());
        let nz = self.nz();
        let t0 = self.t0();
        let (hh, pp) = film_fields(&g, p, h, active);
        let (dpdx, dpdy) = gradients(&g, &pp);
        // each row's film ends one cell past its last pressurised cell: downstream the film is
        // cavitated (ruptured into streamers, which the Reynolds solution does not fill), and a
        // full film there would have to draw oil through the surfaces to fill the diverging gap
        // The pressurised zone is the one holding the row's largest pressure: a feature in the
        // cavitated outlet (a groove passing out of the contact) can hold a pressurised pocket
        // downstream, but the film between is ruptured, and continuing a full film through it
        // drew oil through the surfaces (measured: energy balance off by 3 % while a groove
        // crossed the outlet of the thesis line at SRR 0.3).
        // (a cell past the ones the last update counted, up to its end - 2, joins above
        // PRESSURISED_FRACTION of the peak; a row whose film reached the grid's last column
        // holds all of its cells)
        let p_floor = PRESSURISED_FRACTION * pp.iter().cloned().fold(0.0f64, f64::max);
        let first = !self.solved();
        let len: Vec<usize> = (0..ny)
            .map(|j| {
                let end = self.end[j];
                let wet = |i: usize| {
                    let k = j * nx + i;
                    let held = first || i + 2 <= end || end == nx;
                    active[k] && h[k].is_finite() && pp[k] > if held { 0.0 } else { p_floor }
                };
                let top = (0..nx)
                    .filter(|&i| wet(i))
                    .max_by(|&a, &b| pp[j * nx + a].total_cmp(&pp[j * nx + b]));
                top.map_or(0, |t| {
                    let last = (t..nx).take_while(|&i| wet(i)).last().unwrap_or(t);
                    (last + 2).min(nx)
                })
            })
            .collect();
        // and starts where the film is at most INLET_FILM_RATIO times the row's thinnest: the
        // far inlet, a thick film with a reverse flow that 7 points across cannot resolve, took
        // the film iteration to 3.6e6 K there (thesis Table 3.7 line at SRR 0.5, h 45 um, 56
        // times the minimum); its heating is small (it scales with 1/h)
        let start: Vec<usize> = (0..ny)
            .map(|j| {
                let row = j * nx..j * nx + len[j];
                let thin = row
                    .clone()
                    .filter(|&k| active[k] && h[k].is_finite())
                    .map(|k| hh[k])
                    .fold(f64::INFINITY, f64::min);
                let rule = row
                    .clone()
                    .find(|&k| hh[k] <= INLET_FILM_RATIO * thin)
                    .map_or(len[j], |k| k - j * nx);
                // the last start, while the film there is within the hysteresis
                let last = self.start[j];
                let keep = self.options.inlet_hysteresis
                    && self.lines[j].is_some()
                    && last < rule
                    && last < len[j]
                    && active[j * nx + last]
                    && hh[j * nx + last] <= INLET_FILM_RATIO * (1.0 + INLET_FILM_HYSTERESIS) * thin;
                (if keep { last } else { rule }).min(len[j].saturating_sub(1))
            })
            .collect();
        let wet: Vec<bool> = (0..n)
            .map(|k| {
                let (i, j) = (k % nx, k / nx);
                active[k] && h[k].is_finite() && i >= start[j] && i < len[j]
            })
            .collect();
        let previous = self.film.clone();
        let flux: Vec<f64> = (0..n)
            .map(|k| {
                let fl = factors.map_or(1.0, |(f, _)| f[k]);
                let rho = self.laws.density(pp[k], t0);
                let eta = self.laws.viscosity(pp[k], t0);
                -fl * rho / eta * hh[k].powi(3) / 12.0 * dpdx[k]
            })
            .collect();
        let mut rise = vec![0.0; n];
        let mut q = [vec![0.0; n], vec![0.0; n]];
        let mut sols: Vec<Option<LineSolution>> = Vec::new();
        let opts = self.options;
        let mut surface_change = f64::INFINITY;
        for _ in 0..opts.max_surface_iterations.max(1) {
            if crate::run::cancel::requested() {
                return Err(Error::Cancelled);
            }
            let rows: Vec<usize> = (0..ny).filter(|&j| len[j] > 0).collect();
            // the y mass fluxes of the last iterate: this update's lines once solved, the last
            // update's before
            let my: Option<Vec<f64>> = (opts.side_flow && ny > 1).then(|| {
                if sols.is_empty() {
                    self.side_mass_flux(&self.lines, &self.start, &self.h)
                } else {
                    self.side_mass_flux(&sols, &start, &hh)
                }
            });
            let lines: Vec<Line> = rows
                .iter()
                .map(|&j| {
                    let r = j * nx + start[j]..j * nx + len[j];
                    Line {
                        dx: g.dx,
                        h: &hh[r.clone()],
                        p: &pp[r.clone()],
                        dpdx: &dpdx[r.clone()],
                        dpdy: &dpdy[r.clone()],
                        u1: self.u1,
                        u2: self.u2,
                        t1: &self.surface[0][r.clone()],
                        t2: &self.surface[1][r.clone()],
                        t_in: t0,
                        poiseuille_flux_x: Some(&flux[r.clone()]),
                        transient: self.step.as_ref().map(|s| {
                            let at = start[j] * nz..len[j] * nz;
                            LineTransient {
                                inv_dt: s.inv_dt,
                                t_old: &s.t_old[j][at.clone()],
                                rho_h_old: &s.rho_h_old[j][at],
                            }
                        }),
                        side: None,
                    }
                })
                .collect();
            let from: Vec<Vec<f64>> = rows
                .iter()
                .map(|&j| self.film[j][start[j] * nz..len[j] * nz].to_vec())
                .collect();
            let warm: Vec<ColumnStart> = rows
                .iter()
                .map(|&j| ColumnStart {
                    thinning: &self.thinning[j][start[j] * nz..len[j] * nz],
                    poiseuille: &self.poiseuille[j][start[j]..len[j]],
                })
                .collect();
            let out = match &my {
                Some(my) => self.solve_swept(
                    &rows,
                    &lines,
                    my,
                    (&start, &len, &wet),
                    (&from, &warm),
                    opts.sweep_lines.max(1),
                    &opts.line,
                ),
                None => solve_lines(
                    &self.rule,
                    &self.laws,
                    &self.oil,
                    &lines,
                    Some(&from),
                    Some(&warm),
                    &opts.line,
                ),
            };
            let solved = out
                .into_iter()
                .collect::<std::result::Result<Vec<_>, _>>()
                .map_err(|e| Error::Solver(format!("film temperature: {e}")))?;
            sols = vec![None; ny];
            for (&j, s) in rows.iter().zip(solved) {
                sols[j] = Some(s);
            }
            // per row, in parallel (serially the softening's viscosities took 11 ms over the 7
            // surface iterations of `ehl_thermal_ball.toml`): the film's wall fluxes, how they
            // answer the surface temperatures where it was solved (`film_energy::wall_response`; a
            // film that only conducts: -+ k_f / h), and how fast its heating falls as it warms: a
            // film whose mean temperature rises by dT generates beta G dT less (G its heat per
            // area, beta = -d ln eta / dT of the low-shear law at its mid-film temperature, an
            // upper bound for a shear-thinning oil), half of it less into each surface
            let mut response = vec![[0.0; 4]; n];
            let mut softening = vec![0.0; n];
            {
                use rayon::prelude::*;
                let [q1, q2] = &mut q;
                let (rule, laws) = (&self.rule, &self.laws);
                q1.par_chunks_mut(nx)
                    .zip(q2.par_chunks_mut(nx))
                    .zip(response.par_chunks_mut(nx))
                    .zip(softening.par_chunks_mut(nx))
                    .zip(sols.par_iter())
                    .enumerate()
                    .for_each(|(j, ((((q1, q2), response), softening), s))| {
                        let row = j * nx;
                        q1.fill(0.0);
                        q2.fill(0.0);
                        let Some(s) = s else { return };
                        let at = start[j];
                        for i in at..len[j] {
                            if wet[row + i] {
                                q1[i] = s.energy.q1[i - at];
                                q2[i] = s.energy.q2[i - at];
                            }
                        }
                        for (i, g) in s.wall_response.iter().enumerate() {
                            if wet[row + at + i] {
                                response[at + i] = *g;
                            }
                        }
                        for (i, gen) in s.energy.generated.iter().enumerate() {
                            let k = row + at + i;
                            if !wet[k] || !(*gen > 0.0) {
                                continue;
                            }
                            let tm = rule.interpolate(&s.t[i * nz..(i + 1) * nz], 0.5);
                            let beta = laws.viscosity_temperature_coefficient(pp[k], tm);
                            softening[at + i] = 0.25 * beta * gen;
                        }
                    });
            }
            // the range the surfaces may take (see update_surfaces): the film's iterate (its
            // surface points included), the surfaces before this update and the inlet's, the
            // top raised by half the viscosity's temperature scale at the inlet
            let range = sols
                .iter()
                .flatten()
                .flat_map(|s| s.t.iter())
                .chain(self.surface.iter().flatten())
                .fold((t0, t0), |(lo, hi), &v| (lo.min(v), hi.max(v)));
            let beta = self.laws.viscosity_temperature_coefficient(0.0, t0);
            let range = (range.0, range.1 + surface_overshoot(beta));
            let clock = std::time::Instant::now();
            let change = self.update_surfaces(&q, &response, &softening, range, &mut rise);
            self.body_time_s += clock.elapsed().as_secs_f64();
            for (j, s) in sols.iter().enumerate() {
                if let Some(s) = s {
                    let at = start[j] * nz;
                    self.film[j][at..at + s.t.len()].copy_from_slice(&s.t);
                    self.thinning[j][at..at + s.t.len()].copy_from_slice(&s.thinning);
                    self.poiseuille[j][start[j]..start[j] + s.poiseuille.len()]
                        .copy_from_slice(&s.poiseuille);
                }
            }
            surface_change = change;
            if change <= opts.surface_tol {
                break;
            }
        }
        // the film solved last went with the surface temperatures before the last body update:
        // one more film solve would chase a change below surface_tol
        //
        // The change is taken where the film is at most CONVERGED_FILM_RATIO times the row's
        // thinnest: in the thick inlet beyond it (a reverse flow whose thermal layers 7 points
        // across resolve poorly) single points near a wall kept moving by ~1 K from update to
        // update while the films and the friction had settled (the groove of
        // ehl_thermal_transient_groove.toml in the inlet at SRR 1.0: the fixed point ran its 80
        // iterations with the films fixed to 1e-5).
        // the film's own residual where the film is at most RESIDUAL_FILM_RATIO times its row's
        // thinnest: the inlet, where the film is thick, sets the film thickness through its
        // viscosity (measured: stopping with 0.85 K left there, all else settled, put the
        // minimum film of the Table 3.7 line 1.1e-3 off)
        let mut film_residual = 0.0f64;
        for (j, s) in sols.iter().enumerate() {
            if let Some(s) = s {
                let thin = (j * nx..(j + 1) * nx)
                    .filter(|&k| wet[k])
                    .map(|k| hh[k])
                    .fold(f64::INFINITY, f64::min);
                for (i, c) in s.cell_change.iter().enumerate() {
                    let k = j * nx + start[j] + i;
                    if wet[k] && hh[k] <= RESIDUAL_FILM_RATIO * thin {
                        film_residual = film_residual.max(*c);
                    }
                }
            }
        }
        let mut change = 0.0f64;
        for j in 0..ny {
            let thin = (j * nx..(j + 1) * nx)
                .filter(|&k| wet[k])
                .map(|k| hh[k])
                .fold(f64::INFINITY, f64::min);
            for i in 0..nx {
                if !wet[j * nx + i] || hh[j * nx + i] > CONVERGED_FILM_RATIO * thin {
                    continue;
                }

                if !self.active[j * nx + i] {
                    // a cell the last update did not solve
                    change = f64::INFINITY;
                    continue;
                }
                let (now, before) = (
                    &self.film[j][i * nz..(i + 1) * nz],
                    &previous[j][i * nz..(i + 1) * nz],
                );
                for (a, b) in now.iter().zip(before) {
                    change = change.max((a - b).abs());
                }
            }
        }
        self.residual = [film_residual, surface_change];
        self.lines = sols;
        self.start = start;
        self.end = len;
        self.active = wet;
        self.material = (0..n).map(|k| active[k] && h[k].is_finite()).collect();
        self.p = pp;
        self.h = hh;
        self.dpdx = dpdx;
        Ok(change)
    }

    /// Moves the surface temperatures towards the bodies' response to the film's heat fluxes
    /// `q` (W/m^2 into body 1 and 2, per cell) and returns the largest change (K); `rise` is
    /// scratch (n values).
    ///
    /// The plain update, T_b <- T0 + R_b q_b (R_b body b's moving-heat-source operator), is a
    /// Dirichlet-Neumann iteration whose gain is the film's conductance k_f / h over the
    /// body's, k / sqrt(kappa x / U) for a body at speed U: ~0.1 on a steel roller at 1 m/s and
    /// 1 um, but ~70 for a ball at 0.09 m/s on a 0.17 um film (measured: the surface
    /// temperatures of the EHL-FBNS ball at SRR 0.05 oscillated with growing amplitude to
    /// -150 degC and the run failed). So the update takes the film's response to its own
    /// change into account: with the surfaces moved by d_b, the film changes its fluxes by
    /// G_b1 d_1 + G_b2 d_2, G = `response` (W/(m^2 K), per cell `[dq1/dT1, dq1/dT2, dq2/dT1,
    /// dq2/dT2]`, [`super::film_energy::wall_response`]: each column's own answer, its
    /// neighbours held; -+ k_f / h for a film that only conducts, stronger where oil arrives
    /// from upstream at another temperature), and a film that warms with them generates less:
    /// each flux falls by S (d_1 + d_2) more, S = `softening` = beta G / 4 (W/(m^2 K); G the
    /// film's heat per area, W/m^2, beta = -d ln eta / dT, 1/K, of the low-shear law; its mean
    /// temperature moves by (d_1 + d_2) / 2 and half the lost heat is each surface's; our own
    /// linearisation, not from the literature). The changes d (K) solve
    ///
    /// d_b - R_b [G_bb d_b + G_bo d_other - S (d_b + d_other)] = b_b,  b_b = T0 + R_b q_b - T_b,
    ///
    /// by GMRES (each product two convolutions), preconditioned by the same equations with
    /// each R_b cut to its own cell's coefficient (a 2 x 2 block a cell: the film's local
    /// tie between the two surfaces and each body's self-heating; measured on
    /// `ehl_thermal_ball.toml`: 88 -> 57 GMRES iterations over its 7 surface solves, before
    /// its first update's looser stop, the results unchanged within the solve's own
    /// tolerance). Only each column's own answer and the
    /// heating's temperature slope are linearised: what a surface change does downstream
    /// follows in the next film iteration. With k_f / h in place of the column's answer, a
    /// glass disc at rest under a ball sliding at 2 m/s went 66 K cold in the first update
    /// and oscillated, growing, to the viscosity law's pole: in the inlet the oil arrives at
    /// T0 and the glass's heat enters a thermal layer much thinner than the film (several
    /// times k_f / h). Without the slope, a ball at 3 m/s and SRR 1 with a shear-thinning oil
    /// oscillated (beta 0.052 1/K: the heat falls by up to 5 % a kelvin) and failed. Where
    /// G R is small (a fast body, a thick film) d is the plain update, in one or two
    /// iterations.
    ///
    /// The new surface temperatures are kept within `range` (K): from the lowest of the film's
    /// iterate (its surface points included), of the surfaces before the update and of the
    /// inlet temperature, to the highest of them plus [`surface_overshoot`]. The bodies are
    /// heated and cooled only through the film and enter at the inlet temperature (in a
    /// transient step too: their temperature answers the step's own flux), so at a solution
    /// their surfaces lie between the film's extremes (the maximum principle of their
    /// conduction) and the bound holds no solution back. Far from a solution, where the heating
    /// is many orders above its solution's, it bounds the linearisation's steps: the
    /// isothermal pressure of a Newtonian line at 1.5 GPa and SRR 0.5 heats its surfaces by
    /// 6e12 W/m^2 at the first update (the viscosity's fall over the hundreds of kelvins that
    /// would bring is far from linear), and the linear step took one surface 128 K below the
    /// inlet and the other 131 K up; the next film solve, between a 185 K wall and the 1.5 GPa
    /// pressure, overflowed the viscosity law, and the run failed (lines at 1.5-3 GPa with
    /// SRR 0.1-1 and the thesis ch. 2 finite rollers at 1.7 GPa with SRR 0.5 and 1 did so;
    /// with the bound they settle in 13-21 outer iterations; with the lower bound alone they
    /// still fail, their surfaces at 2000-3000 K). The returned change is that of the step
    /// before the bound, so that a surface held at it is never taken as settled.
    fn update_surfaces(
        &mut self,
        q: &[Vec<f64>; 2],
        response: &[[f64; 4]],
        softening: &[f64],
        range: (f64, f64),
        rise: &mut [f64],
    ) -> f64 {
        let n = self.grid.len();
        let t0 = self.t0();
        let mut b = vec![0.0; 2 * n];
        for (body, (solid, qb)) in self.solids.iter_mut().zip(q).enumerate() {
            solid.temperature_rise(qb, rise);
            for k in 0..n {
                b[body * n + k] = t0 + rise[k] - self.surface[body][k];
            }
        }
        let mut d = vec![0.0; 2 * n];
        if response.iter().any(|g| g.iter().any(|&v| v != 0.0)) {
            let own = [
                self.solids[0].coefficient(0, 0),
                self.solids[1].coefficient(0, 0),
            ];
            let blocks = local_surface_blocks(response, softening, own);
            let solids = &mut self.solids;
            let mut flux = vec![0.0; n];
            let mut out = vec![0.0; n];
            let mut matvec = |x: &[f64], y: &mut [f64]| {
                for (body, solid) in solids.iter_mut().enumerate() {
                    let (own, other) = (body * n, (1 - body) * n);
                    for k in 0..n {
                        let g = &response[k];
                        flux[k] = -(g[3 * body] * x[own + k] + g[body + 1] * x[other + k])
                            + softening[k] * (x[own + k] + x[other + k]);
                    }
                    solid.temperature_rise(&flux, &mut out);
                    for k in 0..n {
                        y[own + k] = x[own + k] + out[k];
                    }
                }
            };
            let mut local = |x: &[f64], y: &mut [f64]| {
                for (k, m) in blocks.iter().enumerate() {
                    let (a, b) = (x[k], x[n + k]);
                    y[k] = m[0] * a + m[1] * b;
                    y[n + k] = m[2] * a + m[3] * b;
                }
            };
            let mut work = crate::linalg::gmres::GmresWork::default();
            crate::linalg::gmres::gmres(
                &mut work,
                &b,
                &mut d,
                SURFACE_GMRES_RESTART,
                SURFACE_GMRES_MAX_ITER,
                SURFACE_GMRES_RTOL,
                &mut matvec,
                &mut local,
            );
            if d.iter().any(|v| !v.is_finite()) {
                d.copy_from_slice(&b);
            }
        } else {
            d.copy_from_slice(&b);
        }
        let mut change = 0.0f64;
        for (body, surface) in self.surface.iter_mut().enumerate() {
            for (k, s) in surface.iter_mut().enumerate() {
                change = change.max(d[body * n + k].abs());
                *s = (*s + d[body * n + k]).clamp(range.0, range.1);
            }
        }
        change
    }

    /// The film of the rows `rows` (their lines `lines` without side flow; each row's film
    /// from `start` to `len`, the cells with a film `wet`; `t_start` and `warm` as in
    /// [`solve_lines`]) with the side flow of the y mass fluxes `my`
    /// ([`ThermalContact::side_mass_flux`]), swept along y: the rows go in blocks of `block`,
    /// the blocks in parallel, each block's rows one after the other in the direction of its
    /// net side flow, every row taking the temperatures of the row solved just before it
    /// (upstream, where the flow goes that way) and the last iterate's elsewhere: a block
    /// Gauss-Seidel iteration on the upwinded v dT/dy ([`ContactOptions::sweep_lines`]; 1: a
    /// Jacobi iteration, every row on the last iterate). The blocks are fixed by the grid,
    /// not by the number of threads, so a run's result does not depend on it.
    #[allow(clippy::too_many_arguments)]
    fn solve_swept(
        &self,
        rows: &[usize],
        lines: &[Line],
        my: &[f64],
        (start, len, wet): (&[usize], &[usize], &[bool]),
        (t_start, warm): (&[Vec<f64>], &[ColumnStart]),
        block: usize,
        opts: &LineOptions,
    ) -> Vec<std::result::Result<LineSolution, FilmError>> {
        use rayon::prelude::*;
        let (nx, nz) = (self.grid.nx, self.nz());
        let blocks: Vec<std::ops::Range<usize>> = (0..rows.len())
            .step_by(block)
            .map(|a| a..(a + block).min(rows.len()))
            .collect();
        // the columns of each line in parallel too while there are fewer than two blocks a
        // thread: a block's lines go one after the other, so with 17 blocks (a ball whose 129
        // lines all have a film) on 16 threads the last block would run alone (not measured
        // on 16 cores: the device machine was not lent; on 2 threads the ball's 17 blocks
        // keep the columns serial)
        let opts = LineOptions {
            parallel_columns: opts.parallel_columns
                && blocks.len() < 2 * rayon::current_num_threads(),
            ..*opts
        };
        let solved: Vec<Vec<std::result::Result<LineSolution, FilmError>>> = blocks
            .into_par_iter()
            .map(|block| {
                // the block's net y mass flux: the sweep goes with it
                let net: f64 = block
                    .clone()
                    .flat_map(|at| {
                        let j = rows[at];
                        (j * nx + start[j]) * nz..(j * nx + len[j]) * nz
                    })
                    .map(|q| my[q])
                    .filter(|v| v.is_finite())
                    .sum();
                let ahead = net >= 0.0;
                let order: Vec<usize> = if ahead {
                    block.collect()
                } else {
                    block.rev().collect()
                };
                let mut out = Vec::with_capacity(order.len());
                // the row solved last in this sweep and its temperatures over the whole row
                let mut last: Option<(usize, Vec<f64>)> = None;
                for at in order {
                    let j = rows[at];
                    let a = self.side_arrays(
                        j,
                        start[j],
                        len[j],
                        wet,
                        my,
                        &self.film,
                        last.as_ref().map(|(r, t)| (*r, t.as_slice())),
                    );
                    let mut line = lines[at];
                    line.side = Some(SideFlow {
                        inv_dy: 1.0 / self.grid.dy,
                        north: &a.north,
                        south: &a.south,
                        t_north: &a.t_north,
                        t_south: &a.t_south,
                    });
                    let s = solve_line_from(
                        &self.rule,
                        &self.laws,
                        &self.oil,
                        &line,
                        Some(&t_start[at]),
                        Some(warm[at]),
                        &opts,
                    );
                    last = match &s {
                        Ok(s) => {
                            let mut row = self.film[j].clone();
                            row[start[j] * nz..start[j] * nz + s.t.len()].copy_from_slice(&s.t);
                            Some((j, row))
                        }
                        Err(_) => None,
                    };
                    out.push(s);
                }
                // back in the rows' order
                if !ahead {
                    out.reverse();
                }
                out
            })
            .collect();
        solved.into_iter().flatten().collect()
    }

    /// The y mass flux per unit zeta, h rho v (kg/(m s)), at every point (cell-major, nz per
    /// cell) of the lines `lines` (film starting at `start[j]`, films `h` per cell); NaN where
    /// no line was solved.
    fn side_mass_flux(
        &self,
        lines: &[Option<LineSolution>],
        start: &[usize],
        h: &[f64],
    ) -> Vec<f64> {
        use rayon::prelude::*;
        let (nx, nz) = (self.grid.nx, self.nz());
        let mut my = vec![f64::NAN; self.grid.len() * nz];
        my.par_chunks_mut(nx * nz)
            .zip(lines.par_iter())
            .enumerate()
            .for_each(|(j, (my, s))| {
                if let Some(s) = s {
                    let h = &h[j * nx..(j + 1) * nx];
                    row_side_mass_flux(my, nz, start[j], h, &s.coefficients.density, &s.profiles);
                }
            });
        my
    }

    /// The side flow of row `j`'s film (cells `start..end`) from the y mass fluxes `my` (see
    /// [`ThermalContact::side_mass_flux`]) and the film temperatures `film`: face
    /// fluxes the mean of the two cells' where both have a film (`wet`) and a flux, else the
    /// cell's own (a flux with nothing beyond: the side leakage at a roller's end); the
    /// temperature beyond a face the neighbour's in `film` (per row, nx * nz, i-major: the
    /// last iterate), or the inlet's where it has no film.
    ///
    /// `fresh`: a neighbouring row solved since (its index and its film temperatures, nx * nz
    /// i-major over the whole row), taken in place of the last iterate's.
    #[allow(clippy::too_many_arguments)]
    fn side_arrays(
        &self,
        j: usize,
        start: usize,
        end: usize,
        wet: &[bool],
        my: &[f64],
        film: &[Vec<f64>],
        fresh: Option<(usize, &[f64])>,
    ) -> SideArrays {
        let (nx, ny, nz) = (self.grid.nx, self.grid.ny, self.nz());
        let t0 = self.t0();
        let m = (end - start) * nz;
        let mut a = SideArrays {
            north: vec![0.0; m],
            south: vec![0.0; m],
            t_north: vec![t0; m],
            t_south: vec![t0; m],
        };
        let flux = |at: usize| if my[at].is_finite() { my[at] } else { 0.0 };
        for i in start..end {
            let k = j * nx + i;
            let neighbours = [
                (j + 1 < ny).then(|| k + nx),
                j.checked_sub(1).map(|_| k - nx),
            ];
            for z in 0..nz {
                let at = (i - start) * nz + z;
                let own = flux(k * nz + z);
                for (side, nb) in neighbours.iter().enumerate() {
                    let (face, t) = match nb {
                        Some(kn) if wet[*kn] && my[kn * nz + z].is_finite() => (
                            0.5 * (own + my[kn * nz + z]),
                            match fresh {
                                Some((row, t)) if row == kn / nx => t[(kn % nx) * nz + z],
                                _ => film[kn / nx][(kn % nx) * nz + z],
                            },
                        ),
                        _ => (own, t0),
                    };
                    if side == 0 {
                        a.north[at] = face;
                        a.t_north[at] = t;
                    } else {
                        a.south[at] = face;
                        a.t_south[at] = t;
                    }
                }
            }
        }
        a
    }

    /// The last solution of cell `k`'s grid line and the cell's index along it (None where
    /// the film was not solved).
    fn local(&self, k: usize) -> Option<(&LineSolution, usize)> {
        if !self.active.get(k).copied().unwrap_or(false) {
            return None;
        }
        let (i, j) = (k % self.grid.nx, k / self.grid.nx);
        self.lines[j].as_ref().map(|s| (s, i - self.start[j]))
    }

    fn profile(&self, k: usize) -> Option<&FilmProfile> {
        self.local(k).map(|(s, i)| &s.profiles[i])
    }

    /// The film temperature at the collocation points of cell `k` (K).
    fn column_t(&self, k: usize) -> Option<&[f64]> {
        let nz = self.nz();
        self.local(k).map(|(s, i)| &s.t[i * nz..(i + 1) * nz])
    }

    /// The generalized Reynolds factors of every cell against the isothermal Newtonian laws at
    /// the inlet temperature and the pressure `p` (Pa): `flow` = (rho/eta)_e / (rho/eta)(p, T0),
    /// `couette` = rho* / rho(p, T0) (see `crate::ehl::system::ThermalFactors`); 1 on cells
    /// without material or before the first update, and upstream of each row's film (the oil
    /// arrives at T0). Downstream of a row's film (the cavitated outlet, where no temperature
    /// is solved) the cells take the factors of the row's last solved cell: the oil leaves
    /// with the state it had there. With 1 there instead the Couette flux jumped by the oil's
    /// thermal expansion at the film's end, the cavitation boundary moved by a cell, and the
    /// film's extent flickered between outer iterations (a ball sliding at 2 m/s on a glass
    /// disc at rest: the factors' residual stuck at 0.1).
    pub fn reynolds_factors(
        &self,
        p: &[f64],
        active: &[bool],
        flow: &mut [f64],
        couette: &mut [f64],
    ) {
        self.factors_of(
            p,
            active,
            |k| {
                if self.active.get(k).copied().unwrap_or(false) {
                    self.profile(k)
                } else {
                    None
                }
            },
            flow,
            couette,
        );
    }

    /// [`ThermalContact::reynolds_factors`] of the profiles `profile_of` gives per cell (None:
    /// no film solved there).
    fn factors_of<'a>(
        &self,
        p: &[f64],
        active: &[bool],
        profile_of: impl Fn(usize) -> Option<&'a FilmProfile>,
        flow: &mut [f64],
        couette: &mut [f64],
    ) {
        let t0 = self.t0();
        let ue = 0.5 * (self.u1 + self.u2);
        for k in 0..self.grid.len() {
            flow[k] = 1.0;
            couette[k] = 1.0;
            if !active[k] {
                continue;
            }
            let Some(pr) = profile_of(k) else { continue };
            let pk = p[k].max(0.0);
            let rho = self.laws.density(pk, t0);
            let eta = self.laws.viscosity(pk, t0);
            let f = pr.rho_over_eta_e / (rho / eta);
            if f.is_finite() && f > 0.0 {
                flow[k] = f;
            }
            if ue != 0.0 {
                let c = pr.rho_star_ue / ue / rho;
                if c.is_finite() && c > 0.0 {
                    couette[k] = c;
                }
            }
        }
        let film: Vec<bool> = (0..self.grid.len())
            .map(|k| active[k] && profile_of(k).is_some())
            .collect();
        copy_past_film(self.grid, flow, couette, &film, active);
    }

    /// Viscosity (Pa s, low-shear, at the mid-film temperature) and density (kg/m^3, mean
    /// across the film) at the pressure `p` into the output fields; cells without material keep
    /// their values.
    pub fn fill_laws(
        &self,
        p: &[f64],
        active: &[bool],
        viscosity: &mut [f64],
        density: &mut [f64],
    ) {
        let nz = self.nz();
        for k in 0..self.grid.len() {
            if !active[k] {
                continue;
            }
            let Some(col) = self.column_t(k) else {
                continue;
            };
            let tm = self.rule.interpolate(col, 0.5);
            let pk = p[k].max(0.0);
            let v = self.laws.viscosity(pk, tm);
            viscosity[k] = if v.is_finite() { v } else { f64::MAX };
            let rho: f64 = (0..nz)
                .map(|z| self.rule.weights[z] * self.laws.density(pk, col[z]))
                .sum();
            density[k] = rho;
        }
    }

    /// The largest film temperature and the largest temperature of each surface over the
    /// cells of the last update (K; the inlet temperature before any).
    pub fn extremes(&self) -> (f64, [f64; 2]) {
        let nz = self.nz();
        let t0 = self.t0();
        let (mut film, mut surf) = (t0, [t0; 2]);
        for k in 0..self.grid.len() {
            if !self.active.get(k).copied().unwrap_or(false) {
                continue;
            }
            if let Some(col) = self.column_t(k) {
                film = col.iter().take(nz).cloned().fold(film, f64::max);
            }
            for (b, s) in surf.iter_mut().enumerate() {
                *s = s.max(self.surface[b][k]);
            }
        }
        (film, surf)
    }

    /// The temperatures for the outputs; `film` (m) gives the section's z.
    pub fn fields(&self, film: &[f64]) -> crate::solution::TemperatureFields {
        let g = self.grid;
        let (nx, n, nz) = (g.nx, g.len(), self.nz());
        let t0 = self.t0();
        let mut mid = vec![t0; n];
        let mut max = vec![t0; n];
        for k in 0..n {
            if !self.active.get(k).copied().unwrap_or(false) {
                mid[k] = f64::NAN;
                max[k] = f64::NAN;
                continue;
            }
            if let Some(col) = self.column_t(k) {
                mid[k] = self.rule.interpolate(col, 0.5);
                max[k] = col.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            }
        }
        // the centre line: the row nearest y = 0
        let row = (0..g.ny)
            .min_by(|&a, &b| g.y(a).abs().total_cmp(&g.y(b).abs()))
            .unwrap_or(0);
        let mut section = vec![f64::NAN; nz * nx];
        let mut z = vec![0.0; nz * nx];
        for i in 0..nx {
            let k = row * nx + i;
            let col = self.column_t(k);
            let hk = if film[k].is_finite() {
                film[k].max(0.0)
            } else {
                0.0
            };
            for zk in 0..nz {
                section[zk * nx + i] = col.map_or(f64::NAN, |c| c[zk]);
                z[zk * nx + i] = self.rule.points[zk] * hk;
            }
        }
        let surf = |b: usize| -> Vec<f64> {
            (0..n)
                .map(|k| {
                    if self.active.get(k).copied().unwrap_or(false) {
                        self.surface[b][k]
                    } else {
                        f64::NAN
                    }
                })
                .collect()
        };
        crate::solution::TemperatureFields {
            mid_film: mid,
            max_film: max,
            surface_1: surf(0),
            surface_2: surf(1),
            film_section: section,
            section_z: z,
            section_row: row,
            nz,
            inlet: t0,
        }
    }

    /// The heat balance of the last update.
    pub fn heat(&self) -> HeatBalance {
        let g = self.grid;
        let nx = g.nx;
        let nz = self.nz();
        let area = g.cell_area();
        let mut hb = HeatBalance::default();
        let (mut tsum, mut count) = (0.0, 0usize);
        for (j, s) in self.lines.iter().enumerate() {
            let Some(s) = s else { continue };
            let e = &s.energy;
            // the row's film ends where its cavitated outlet begins (see `update`)
            let m = e.q1.len();
            for i in 0..m {
                let k = j * nx + self.start[j] + i;
                if !self.active[k] {
                    continue;
                }
                hb.generated += e.generated[i] * area;
                hb.to_body[0] += e.q1[i] * area;
                hb.to_body[1] += e.q2[i] * area;
                hb.stored += e.stored[i] * area;
                // the side flow's exchanges cancel between lines (up to the lag of one film
                // iteration); what is left leaves through the film's y-edges (the roller ends)
                hb.convected += e.side_out[i] * area;
                if self.p[k] > 0.0 {
                    let col = &s.t[i * nz..(i + 1) * nz];
                    tsum += (0..nz).map(|z| self.rule.weights[z] * col[z]).sum::<f64>();
                    count += 1;
                }
            }
            hb.convected += (e.enthalpy_flux[m] - e.enthalpy_flux[0]) * g.dy;
        }
        hb.mean_film_temperature = if count > 0 {
            tsum / count as f64
        } else {
            self.t0()
        };
        hb
    }

    /// The x-force of the film on body 2 (N; a line contact per metre), positive along +x (the
    /// convention of [`crate::friction`]): on pressurised cells the whole shear stress of the
    /// thermal velocity profile (capped by the limiting shear stress where the rheology has one,
    /// see `film_energy::line_coefficients`), on every other cell with a film (the far inlet
    /// upstream of the thermal film, the cavitated outlet) its pressure-flow part -(h/2) dp/dx
    /// plus, where pressurised, the Couette stress at the inlet temperature (the summation rule
    /// of `crate::friction`). The far inlet's share is not small where the
    /// friction is: 5 % of f = 0.0019 on the thesis Table 3.6 line (Newtonian, SRR 0.3), whose
    /// rolling (pressure-flow) traction is most of it.
    pub fn friction_force(&self) -> f64 {
        let g = self.grid;
        let mut f = 0.0;
        for k in 0..g.len() {
            if !self.material[k] {
                continue;
            }
            if self.active[k] && self.p[k] > 0.0 {
                if let Some(pr) = self.profile(k) {
                    f += pr.traction2[0];
                }
            } else {
                f += -0.5 * self.h[k] * self.dpdx[k];
                // a pressurised cell outside the thermal film (the far inlet): the isothermal
                // Couette stress at the inlet temperature, as `crate::friction` has it
                let (slide, t0) = (self.u1 - self.u2, self.t0());
                if self.p[k] > 0.0 && slide != 0.0 && self.h[k] > 0.0 {
                    let eta = self.laws.viscosity(self.p[k], t0);
                    let tau = crate::lubricant::rheology::shear_stress(
                        &self.laws.rheology(t0),
                        eta,
                        slide / self.h[k],
                        self.p[k],
                    );
                    if tau.is_finite() {
                        f += tau;
                    }
                }
            }
        }
        f * g.cell_area()
    }
}

/// The film h (m) and pressure p (Pa) the temperature model takes on each cell: where the
/// cell has material (`active` and a finite film) its own, a film that closed (h <= 0) held
/// at 1 nm (a column needs h > 0) and a negative pressure at 0; elsewhere the row's thickest
/// film at ambient pressure (those cells' temperatures are not used).
fn film_fields(g: &Grid, p: &[f64], h: &[f64], active: &[bool]) -> (Vec<f64>, Vec<f64>) {
    let (nx, n) = (g.nx, g.len());
    let mut hh = vec![0.0; n];
    let mut pp = vec![0.0; n];
    for j in 0..g.ny {
        let row = j * nx..(j + 1) * nx;
        let thick = row
            .clone()
            .filter(|&k| active[k] && h[k].is_finite())
            .map(|k| h[k])
            .fold(0.0f64, f64::max)
            .max(1e-6);
        for k in row {
            let ok = active[k] && h[k].is_finite();
            hh[k] = if ok { h[k].max(1e-9) } else { thick };
            pp[k] = if ok { p[k].max(0.0) } else { 0.0 };
        }
    }
    (hh, pp)
}

/// The y mass flux per unit zeta, h rho v (kg/(m s)), of one row's film into `my` (nz values
/// per cell, cell-major, indexed as `h`): its first cell `first` (an index into `h`), films `h`
/// per cell (a grid row, or the whole grid), the density at its points (cells * nz) and its
/// velocity profiles.
fn row_side_mass_flux(
    my: &mut [f64],
    nz: usize,
    first: usize,
    h: &[f64],
    density: &[f64],
    profiles: &[FilmProfile],
) {
    for (i, pr) in profiles.iter().enumerate() {
        let k = first + i;
        for z in 0..nz {
            my[k * nz + z] = h[k] * density[i * nz + z] * pr.v[z];
        }
    }
}

/// Past each grid row's last cell with a film (`film`), the cells with material (`material`)
/// take that cell's Reynolds factors (`flow`, `couette`): downstream of the film's end the film
/// is cavitated and not solved (see [`ThermalContact::update`]), so the cells there carry the
/// factors of the oil leaving it. The fresh factors of an update are copied so
/// ([`ThermalContact::reynolds_factors`]), and the steady driver copies its mixed ones the same
/// way (`crate::ehl::thermal`).
pub fn copy_past_film(
    grid: Grid,
    flow: &mut [f64],
    couette: &mut [f64],
    film: &[bool],
    material: &[bool],
) {
    for j in 0..grid.ny {
        let row = j * grid.nx..(j + 1) * grid.nx;
        let Some(last) = row.clone().rev().find(|&k| film[k]) else {
            continue;
        };
        let (f_last, c_last) = (flow[last], couette[last]);
        let past = last + 1..row.end;
        let cells = flow[past.clone()]
            .iter_mut()
            .zip(&mut couette[past.clone()])
            .zip(&material[past]);
        for ((f, c), _) in cells.filter(|(_, &m)| m) {
            *f = f_last;
            *c = c_last;
        }
    }
}

/// dp/dx and dp/dy (Pa/m) at the cell centres: central differences, one-sided at the edges,
/// zero along a direction with one cell.
fn gradients(g: &Grid, p: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let (nx, ny) = (g.nx, g.ny);
    let mut dx = vec![0.0; p.len()];
    let mut dy = vec![0.0; p.len()];
    for j in 0..ny {
        for i in 0..nx {
            let k = j * nx + i;
            if nx > 1 {
                let (a, b) = (i.saturating_sub(1), (i + 1).min(nx - 1));
                dx[k] = (p[j * nx + b] - p[j * nx + a]) / ((b - a) as f64 * g.dx);
            }
            if ny > 1 {
                let (a, b) = (j.saturating_sub(1), (j + 1).min(ny - 1));
                dy[k] = (p[b * nx + i] - p[a * nx + i]) / ((b - a) as f64 * g.dy);
            }
        }
    }
    (dx, dy)
}

#[cfg(test)]
mod tests {
    use crate::case::parse_str;
    use crate::grid::Grid;
    use crate::run::thermal::contact_for;

    /// A prescribed pressure (Pa) and film (m) on `grid` for the contact's tests: p_h (1 -
    /// r^2/a^2) inside the circle of radius `a` (m), zero outside, and a film `hc` at the
    /// centre opening as r^2 / (2 R).
    pub(super) fn hertzian_fields(
        grid: Grid,
        a: f64,
        ph: f64,
        hc: f64,
        radius: f64,
    ) -> (Vec<f64>, Vec<f64>) {
        let n = grid.len();
        let (mut p, mut h) = (vec![0.0; n], vec![0.0; n]);
        for k in 0..n {
            let (x, y) = (grid.x(k % grid.nx), grid.y(k / grid.nx));
            let s = 1.0 - (x * x + y * y) / (a * a);
            p[k] = ph * s.max(0.0);
            h[k] = hc + (x * x + y * y) / (2.0 * radius);
        }
        (p, h)
    }

    /// Past a row's last cell with a film, the cells with material take its factors, also
    /// beyond a cell without material (as the fresh factors do); cells without material and
    /// rows without a film keep theirs.
    #[test]
    fn the_cells_past_a_film_copy_its_last_cell() {
        let grid = Grid::new(5, 3, 0.0, 1.0, 0.0, 1.0);
        let mut flow = vec![
            1.1, 1.2, 1.3, 1.4, 1.5, 2.1, 2.2, 2.3, 2.4, 2.5, 3.1, 3.2, 3.3, 3.4, 3.5,
        ];
        let mut couette = vec![
            0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.5,
        ];
        let t = true;
        let o = false;
        // row 0: film on cells 1-2; row 1: film on cells 0-1, cell 2 without material; row 2:
        // no film
        let film = [o, t, t, o, o, t, t, o, o, o, o, o, o, o, o];
        let mut material = [true; 15];
        material[7] = false;
        super::copy_past_film(grid, &mut flow, &mut couette, &film, &material);
        assert_eq!(&flow[..5], &[1.1, 1.2, 1.3, 1.3, 1.3]);
        assert_eq!(&couette[..5], &[0.1, 0.2, 0.3, 0.3, 0.3]);
        assert_eq!(&flow[5..10], &[2.1, 2.2, 2.3, 2.2, 2.2]);
        assert_eq!(&couette[5..10], &[0.6, 0.7, 0.8, 0.7, 0.7]);
        assert_eq!(&flow[10..], &[3.1, 3.2, 3.3, 3.4, 3.5]);
        assert_eq!(&couette[10..], &[1.1, 1.2, 1.3, 1.4, 1.5]);
    }

    /// A row's film ends one cell past its last pressurised cell; past the cells the last
    /// update counted as pressurised, a cell counts above [`super::PRESSURISED_FRACTION`] of
    /// the peak pressure. On a prescribed pressure (p_h (1 - r^2/a^2), 0.3 GPa, the robustness
    /// scan's ball under a Newtonian oil, 36 x 24 cells, the film ending well inside the grid)
    /// the first cell past the central row's last pressurised cell is given a pressure: 1e-8 of
    /// the peak (a Reynolds solve's noise) leaves the film's end where it was; 2e-6 moves it
    /// one cell on; 1e-8 then keeps it there (the cell was counted); zero takes it back. With a
    /// floor at zero for every cell (before) the noise moved it; with the floor for every cell,
    /// or half of it to stay, 1e-8 would take it back.
    #[test]
    fn the_film_end_ignores_pressure_noise_and_holds_where_it_reached() {
        const BALL: &str = include_str!("../../tests/data/thermal_scan_ball.toml");
        let sets = ["lubricant.rheology=\"newtonian\"".to_string()];
        let case = parse_str(BALL, "thermal_scan_ball.toml", &sets).unwrap();
        let (a, hc, ph, r) = (2.0e-4, 5.0e-7, 0.3e9, 0.0127);
        let grid = Grid::new(36, 24, -2.0 * a, 1.6 * a, -1.2 * a, 1.2 * a);
        let mut contact = contact_for(&case, grid).unwrap();
        let n = grid.len();
        let (mut p, h) = hertzian_fields(grid, a, ph, hc, r);
        let peak = p.iter().cloned().fold(0.0f64, f64::max);
        let active = vec![true; n];
        let j = grid.ny / 2;
        contact.update(&p, &h, &active, None).unwrap();
        let end = contact.end[j];
        assert!(end > 2 && end + 1 < grid.nx, "the row's film ends at {end}");
        // the first cell past the last pressurised one
        let k = j * grid.nx + end - 1;
        assert_eq!(p[k], 0.0);
        let mut end_with = |fraction: f64| {
            p[k] = fraction * peak;
            contact.update(&p, &h, &active, None).unwrap();
            contact.end[j]
        };
        assert_eq!(end_with(1e-8), end, "noise moved the film's end");
        assert_eq!(end_with(2e-6), end + 1, "a pressure above the floor");
        assert_eq!(
            end_with(1e-8),
            end + 1,
            "a reached cell holds while pressurised"
        );
        assert_eq!(end_with(0.0), end, "at zero pressure the end goes back");
    }
}
