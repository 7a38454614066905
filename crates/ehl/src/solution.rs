//! What a solve produces: the fields on the grid and the summary figures. Writers in
//! [`crate::output`] read only this.

use crate::grid::Grid;
use serde::Serialize;

/// Fields on the cell grid, row-major `ny * nx` (see the crate conventions).
#[derive(Debug, Clone, Default)]
pub struct Fields {
    /// pressure (Pa)
    pub pressure: Vec<f64>,
    /// combined elastic deflection of both surfaces (m)
    pub deformation: Vec<f64>,
    /// film thickness h (m); dry contact: the gap after deformation
    pub film: Option<Vec<f64>>,
    /// viscosity (Pa s), ehl only
    pub viscosity: Option<Vec<f64>>,
    /// density (kg/m^3), ehl only
    pub density: Option<Vec<f64>>,
}

/// The figures of `summary.json` (SI). Optional figures are omitted when they do not apply.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Summary {
    pub converged: bool,
    /// why the solver stopped, in words (e.g. "residual 3e-11 < tolerance")
    pub termination: String,
    pub iterations: usize,
    /// final relative residual of the solver; absent when the solver could not evaluate it
    /// (a solve that broke down)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual: Option<f64>,
    pub wall_time_s: f64,
    /// integrated load (N); for an infinite line contact, per unit length (N/m)
    pub load_n: f64,
    /// relative load error |integrated - applied| / applied
    pub load_error: f64,
    pub max_pressure_pa: f64,
    pub max_pressure_at_m: [f64; 2],
    pub hertz_pressure_pa: f64,
    pub hertz_half_width_m: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub approach_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_area_m2: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub central_film_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film_at_m: Option<[f64; 2]>,
    /// ehl: the minimum film along the axial centre line (the row nearest y = 0) (m). For a
    /// straight finite roller the overall minimum sits at the free ends, where it depends on the
    /// axial grid; this figure is the converged mid-length one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub centerline_min_film_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_coefficient: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_force_n: Option<f64>,
    /// ehl: lubricant mass flow into the pressurised zone through the inlet (kg/s; line: per m)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass_inflow_kg_s: Option<f64>,
    /// ehl: mass flow out through the outlet (cavitation boundary) (kg/s)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass_outflow_kg_s: Option<f64>,
    /// ehl: mass flow out through the sides (roller ends) (kg/s); inflow = outflow + side leakage
    #[serde(skip_serializing_if = "Option::is_none")]
    pub side_leakage_kg_s: Option<f64>,
    /// transient runs: the largest pressure over the converged steps (step 0 included; all
    /// steps when none converged) (Pa)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_pressure_over_travel_pa: Option<f64>,
    /// transient runs: x_p (m) and step of that largest pressure
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_pressure_over_travel_at_xp_m: Option<f64>,
    /// transient runs: the smallest film over the converged steps (m)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film_over_travel_m: Option<f64>,
    /// transient runs: x_p (m) of that smallest film
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_film_over_travel_at_xp_m: Option<f64>,
    /// transient runs: friction coefficient extremes over the steps where it was computed
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_coefficient_over_travel: Option<[f64; 2]>,
    /// transient runs: the mean friction coefficient over the steps where it was computed
    /// (equal time steps: the time average over the travel)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_coefficient_mean_over_travel: Option<f64>,
    /// transient runs: number of time steps solved (step 0, the steady start, not counted)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steps: Option<usize>,
    /// transient runs: the steps that did not converge (the run goes on from their best state)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failed_steps: Option<Vec<usize>>,
    /// transient runs: the largest |mass balance| over the steps, relative to the inflow
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_mass_balance_error: Option<f64>,
    /// `[stress]`: the largest von Mises stress over the chosen bodies (Pa) and where ([x, y, z],
    /// m; z the depth in that body)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_von_mises_pa: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_von_mises_at_m: Option<[f64; 3]>,
    /// `[stress]`: the largest maximum shear (sigma_1 - sigma_3)/2 (Pa) and where
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_shear_pa: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_shear_at_m: Option<[f64; 3]>,
    /// `[stress]`: the largest |tau_xz| (Pa) and where
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_orthogonal_shear_pa: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_orthogonal_shear_at_m: Option<[f64; 3]>,
    /// `[fatigue]`: the Ioannides-Harris integral summed over the chosen bodies
    /// (m^3, the stress over 1 GPa and the depth over 1 mm, `stress::fatigue`; a line contact
    /// m^2 per metre)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fatigue_integral: Option<f64>,
    /// `[fatigue]` with features: the same integral for smooth surfaces at the same conditions
    #[serde(skip_serializing_if = "Option::is_none")]
    pub smooth_fatigue_integral: Option<f64>,
    /// `[fatigue]` with features: life against the smooth surfaces, (I_smooth / I)^(1/e)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub life_ratio: Option<f64>,
    /// transient runs with `[stress]`: x_p (m) of the step whose stress is reported (the kept
    /// frame with the highest pressure; with `[fatigue]`, the kept frame of largest fatigue
    /// integral)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress_at_xp_m: Option<f64>,
    /// `[stress]`: the figures of each chosen body
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress: Option<Vec<StressFigures>>,
    /// `[thermal]`: the largest film temperature (K) and where ([x, y], m)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_film_temperature_k: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_film_temperature_at_m: Option<[f64; 2]>,
    /// `[thermal]`: the largest surface temperature of [body1, body2] (K)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_surface_temperature_k: Option<[f64; 2]>,
    /// `[thermal]`: the mean film temperature over the pressurised zone (p > 0), weighted by
    /// area and across the film (K)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_film_temperature_k: Option<f64>,
    /// `[thermal]`: the heat generated in the film by shear and compression (W; a line contact
    /// per metre)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub heat_generated_w: Option<f64>,
    /// `[thermal]`: the heat conducted into [body1, body2] (W)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub heat_to_body_w: Option<[f64; 2]>,
    /// `[thermal]`: the heat carried out of the domain by the oil (W)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub heat_convected_w: Option<f64>,
    /// `[thermal]`: (generated - to bodies - convected) / generated
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_balance_error: Option<f64>,
    /// `[thermal]`: the flash temperature, the largest surface temperature rise above the inlet
    /// over both bodies (K), which a gear engineer compares with a scuffing limit
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flash_temperature_k: Option<f64>,
    /// `[thermal]`: Blok's estimate of the same from the friction coefficient (K), for comparison
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flash_temperature_blok_k: Option<f64>,
    /// `[thermal]`: outer (Reynolds - temperature) fixed-point iterations (a transient run: of
    /// its steady start)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thermal_iterations: Option<usize>,
    /// `[thermal]`, steady contacts: Newton steps of the coupled method
    /// (`thermal.coupled_newton`) that ended in a solution (0: the fixed point settled on its
    /// own)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thermal_newton_steps: Option<usize>,
    /// `[thermal]`: where the run's wall time went (s), phase by phase
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thermal_time: Option<ThermalTimeSplit>,
    /// `[thermal]`, transient runs: the largest film temperature over the travel (K) and the
    /// x_p (m) of its step
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_film_temperature_over_travel_k: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_film_temperature_over_travel_at_xp_m: Option<f64>,
    /// `[thermal]`, transient runs: the largest surface temperature over the travel, body 1 and
    /// body 2 (K)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_surface_temperature_over_travel_k: Option<[f64; 2]>,
    /// `[thermal]`, transient runs: the largest |energy balance error| over the steps
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_energy_balance_error: Option<f64>,
    /// transient runs with `[stress]`: the maxima of each chosen body's passage maps
    /// (`stress_passage.npz`), positions in that body's material frame
    #[serde(skip_serializing_if = "Option::is_none")]
    pub passage: Option<Vec<PassageFigures>>,
    /// true when the EHL pressure and film were solved but the friction integral failed (the
    /// friction keys are then absent and `warnings` says why); written only when true
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub friction_failed: bool,
    /// whether the case asks for friction ([`crate::run::friction_requested`]); not written
    #[serde(skip)]
    pub friction_requested: bool,
    /// findings about the solution, one sentence each (docs/case-file.md lists them); always
    /// written, possibly empty
    pub warnings: Vec<String>,
}

impl Summary {
    /// True when the case asked for friction and the friction integral failed: the CLI then
    /// exits with a non-zero status although the pressure and film were written.
    pub fn requested_friction_failed(&self) -> bool {
        self.friction_failed && self.friction_requested
    }
}

/// Where a thermal run's wall time went (`summary.json`: `thermal_time`, seconds). The phases
/// of the thermal fixed point are those of [`crate::ehl::thermal::ThermalTimes`], summed over a
/// transient run's steady start and time steps (and over both runs of a solve started again
/// with more points across the film). The dry contact solve before the isothermal start, the
/// summary figures after the fixed point and a transient run's output are in `wall_time_s`
/// only.
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct ThermalTimeSplit {
    /// the isothermal EHL solve from the dry contact's pressure (to
    /// `thermal::START_TOLERANCE`), with the bodies' moving-heat-source tables built beside it
    /// (a steady run), or the transient run's steady isothermal start
    pub isothermal_start_s: f64,
    /// the film's energy equation across z (the grid lines' temperature solves)
    pub film_energy_s: f64,
    /// the bodies' surface temperatures (moving heat source matched to the film)
    pub body_temperature_s: f64,
    /// the generalized Reynolds factors from the temperatures
    pub reynolds_factors_s: f64,
    /// the Newton solves of the Reynolds equation with the factors (a transient run: every
    /// Newton solve of its thermal steps)
    pub reynolds_s: f64,
    /// Newton's method on the coupled problem (`thermal.coupled_newton`)
    pub coupled_newton_s: f64,
    /// the rest of the fixed point (a transient run: of its steps): setting up the Reynolds
    /// system and its elastic operator, evaluating it between solves, the mixing, the residuals
    /// and the final fields. Never negative: the phases are disjoint spans of the whole
    pub other_s: f64,
}

/// The stress figures of one body (`summary.json`: `stress`).
#[derive(Debug, Clone, Default, Serialize)]
pub struct StressFigures {
    pub body: u8,
    pub max_von_mises_pa: f64,
    pub max_von_mises_at_m: [f64; 3],
    pub max_shear_pa: f64,
    pub max_shear_at_m: [f64; 3],
    pub max_orthogonal_shear_pa: f64,
    pub max_orthogonal_shear_at_m: [f64; 3],
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fatigue_integral: Option<f64>,
}

/// The passage figures of one body (`summary.json`: `passage`): maxima over its material
/// points of the max-over-passage maps, positions [x_body, y, z] (m) in the body's material frame
/// (x_body = x - u_body t; `features[0]`'s centre at x_body = x_p(0) when on this body).
#[derive(Debug, Clone, Default, Serialize)]
pub struct PassageFigures {
    pub body: u8,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_von_mises_pa: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_von_mises_at_m: Option<[f64; 3]>,
    /// the largest range (max - min over the passage) of tau_xz
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_tau_xz_range_pa: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_tau_xz_range_at_m: Option<[f64; 3]>,
    /// `fatigue.dang_van`: the largest Dang Van indicator (> 1: the fatigue limit is crossed)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_dang_van: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_dang_van_at_m: Option<[f64; 3]>,
    /// steps whose stress was accumulated
    pub evaluations: usize,
    /// every k-th step evaluated (and the last)
    pub every_steps: usize,
    /// deepest layer of the window (m) and the number of layers
    pub window_m: f64,
    pub layers: usize,
    /// bytes of the accumulators
    pub memory_bytes: f64,
}

/// A solved case.
#[derive(Debug, Clone)]
pub struct Solution {
    pub grid: Grid,
    pub fields: Fields,
    pub summary: Summary,
    /// transient runs: the timeline, frames and snapshots (`fields` and `summary` are the last step)
    pub transient: Option<TransientRecord>,
    /// `[stress]`: the stress below the surface
    pub stress: Option<crate::run::stress::StressAnalysis>,
    /// `[thermal]`: the temperatures of the film and the bodies
    pub temperature: Option<TemperatureFields>,
}

/// The temperatures of a thermal run (K) on the cell grid (row-major `ny * nx`), and the film
/// temperature across z along one grid line.
#[derive(Debug, Clone, Default)]
pub struct TemperatureFields {
    /// the film temperature at mid-film (z = h/2)
    pub mid_film: Vec<f64>,
    /// the largest film temperature across z
    pub max_film: Vec<f64>,
    /// the surface temperature of body 1 (z = 0) and body 2 (z = h)
    pub surface_1: Vec<f64>,
    pub surface_2: Vec<f64>,
    /// the film temperature at the collocation points along the grid line `section_row`,
    /// row-major (nz, nx): `film_section[k * nx + i]` at z = `section_z[k * nx + i]` (m)
    pub film_section: Vec<f64>,
    pub section_z: Vec<f64>,
    pub section_row: usize,
    /// collocation points across the film
    pub nz: usize,
    /// the inlet temperature T0
    pub inlet: f64,
}

/// One time step of a transient run (SI): a row of `timeline.csv`.
#[derive(Debug, Clone, Default, Serialize)]
pub struct StepRecord {
    /// 0 is the steady start
    pub step: usize,
    pub time_s: f64,
    /// centre of `features[0]` along x (m); NaN-free: the body's travel when there is no feature
    pub x_p_m: f64,
    pub max_pressure_pa: f64,
    pub min_film_m: f64,
    /// film at x = 0, y = 0 (m)
    pub central_film_m: f64,
    /// None when the friction integral failed at this step
    pub friction_coefficient: Option<f64>,
    /// relative load error (sum p dA - load) / load
    pub load_error: f64,
    pub converged: bool,
    /// minimum film along the axial centre row (the row nearest y = 0) (m): on a finite roller
    /// the overall minimum sits at the free ends; this one shows what a pit does mid-length
    pub centerline_min_film_m: f64,
    /// rigid-body film constant h0 (m): varies so that the load stays constant
    pub h0_m: f64,
    /// Newton steps of this time step
    pub newton_iterations: usize,
    /// GMRES iterations of this time step
    pub linear_iterations: usize,
    /// elastic operator applications of this time step
    pub operator_applications: usize,
    /// discrete mass balance of the pressurised zone, relative to the inflow:
    /// (inflow - outflow - side leakage - d(mass)/dt) / inflow
    pub mass_balance: f64,
    /// lubricant mass flows (kg/s; line contact: per metre)
    pub mass_inflow_kg_s: f64,
    pub mass_outflow_kg_s: f64,
    pub side_leakage_kg_s: f64,
    /// rate of change of the lubricant mass in the pressurised zone (kg/s)
    pub mass_storage_kg_s: f64,
    /// wall time of this step (s)
    pub wall_time_s: f64,
    /// a thermal run's figures of this step (extra `timeline.csv` columns)
    #[serde(flatten)]
    pub thermal: Option<StepThermalRecord>,
}

/// The thermal columns of a `timeline.csv` row ([`crate::output::transient::THERMAL_COLUMNS`]).
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct StepThermalRecord {
    /// largest film temperature (K)
    pub max_film_temperature_k: f64,
    /// largest surface temperature of body 1 and body 2 (K)
    pub max_surface_temperature_1_k: f64,
    pub max_surface_temperature_2_k: f64,
    /// heat generated in the film (W; per metre on a line)
    pub heat_generated_w: f64,
    /// rate of change of the film's enthalpy (W; per metre on a line)
    pub heat_stored_w: f64,
    /// (generated - to bodies - convected - stored) / generated
    pub energy_balance_error: f64,
    /// Reynolds - temperature passes of the step
    pub thermal_passes: usize,
}

/// The fields of one kept time step (row-major `ny * nx`, SI).
#[derive(Debug, Clone, Default)]
pub struct Frame {
    pub step: usize,
    pub time_s: f64,
    pub x_p_m: f64,
    /// Pa
    pub pressure: Vec<f64>,
    /// m (f64::INFINITY where a body has no material)
    pub film: Vec<f64>,
}

/// What a transient run adds to a [`Solution`]: the timeline of every step, the frames kept
/// (every `output.frames_every`-th step) and the full fields at the requested snapshots.
/// `Solution::fields` and `Solution::summary` hold the last step.
#[derive(Debug, Clone, Default)]
pub struct TransientRecord {
    pub timeline: Vec<StepRecord>,
    /// the kept frames held in memory: all of them from [`crate::run::solve`]; none from a
    /// run whose [`crate::run::StepSink`] streamed them to disk (`ehl run`), unless the case
    /// has `[stress]`
    pub frames: Vec<Frame>,
    /// (requested x_p (m), the step nearest to it, its fields)
    pub snapshots: Vec<(f64, usize, Fields)>,
    /// time step (s)
    pub dt_s: f64,
    /// every k-th step kept in `frames`
    pub frames_every: usize,
    /// `[stress]`: the stress history in the material frame of each chosen body
    pub passage: Option<crate::run::stress::PassageRun>,
}
