//! The validated case: every key resolved, every default filled, every value checked.
//! Solvers and writers read only this; [`super::load_file`] builds it from a TOML file.
//!
//! All quantities SI (m, Pa, N, m/s, Pa s, kg/m^3, rad). Serialised into `summary.json` as the
//! resolved case, with the same key names as the case file.

use serde::Serialize;

/// `kind = "dry" | "ehl"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    Dry,
    Ehl,
}

/// `body.shape`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Shape {
    Roller,
    Ball,
    Flat,
}

/// Axial profile of a roller (drop of the surface below the nominal cylinder, as a function of y).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Profile {
    Straight,
    /// circular crown of radius `crown_radius` (m) along y, centred at mid-length
    Crowned {
        crown_radius: f64,
    },
    /// Lundberg logarithmic profile designed for load `load` (N) (ISO/TS 16281 form)
    Logarithmic {
        load: f64,
    },
    /// straight centre, circular-arc ends of radius `edge_radius` over `edge_length` at each end
    RoundedEdge {
        edge_length: f64,
        edge_radius: f64,
    },
    /// straight centre, straight chamfer of angle `angle` (rad) over `edge_length` at each end
    Chamfer {
        edge_length: f64,
        angle: f64,
    },
}

/// One body (`[body1]`, `[body2]`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Body {
    pub shape: Shape,
    /// radius in the rolling plane x-z (m); infinite for a flat
    pub radius: f64,
    /// radius in the axial plane y-z (m): ball only (ellipsoid); infinite for rollers and flats
    pub radius_y: f64,
    /// axial length (m); infinite for an infinite line contact, a ball or a flat
    pub length: f64,
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    pub profile: Profile,
    /// shift of this body's mid-length along y (m); body1 is always 0
    pub axial_offset: f64,
}

/// `[alignment]` (rad).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Alignment {
    /// misalignment perpendicular to the contact plane: gap varies linearly along y
    pub tilt: f64,
    /// misalignment in the contact plane: axes crossed in the x-y view
    pub skew: f64,
}

/// `[load]`, resolved to a force. For an infinite line contact, `force_per_length` is the
/// load per unit length (N/m) and `force` is NaN-free but meaningless (set to `force_per_length`
/// times the 1 m reference length).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Load {
    /// total normal load (N)
    pub force: f64,
    /// load per unit length (N/m): given for infinite line contacts, else force / contact length
    pub force_per_length: f64,
}

/// `[motion]` (ehl only).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Motion {
    /// u_e = (u1 + u2)/2 (m/s)
    pub entrainment_speed: f64,
    /// SRR = (u1 - u2)/u_e
    pub slide_to_roll: f64,
    /// `motion.travel`: present for a transient run
    #[serde(skip_serializing_if = "Option::is_none")]
    pub travel: Option<Travel>,
}

/// `motion.travel`: the time span of a transient run, in equal time steps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Travel {
    /// The centre of `features[0]` (x_p, m) moves from `from` to `to` with its body's surface
    /// speed: time step = (to - from) / steps / u_body. Every body's surface is placed at t = 0
    /// so that `features[0]`'s centre sits at `from` (all features keep their relative positions).
    Path { from: f64, to: f64, steps: usize },
    /// `duration` seconds in `steps` equal steps; features start where the case puts them.
    Duration { duration: f64, steps: usize },
}

impl Travel {
    /// Number of time steps.
    pub fn steps(&self) -> usize {
        match *self {
            Travel::Path { steps, .. } | Travel::Duration { steps, .. } => steps,
        }
    }
}

/// `[output]` (optional; transient runs).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OutputSpec {
    /// keep the fields of every k-th step in frames.npz; None: every step unless the frames
    /// would exceed the memory limit (then the least k that fits)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub frames_every: Option<usize>,
    /// x_p values (m) at which to also write the maps and profiles (snapshots/)
    pub snapshots: Vec<f64>,
    /// write passage.gif
    pub animation: bool,
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            frames_every: None,
            snapshots: Vec::new(),
            animation: true,
        }
    }
}

impl Motion {
    /// Surface speed of body 1: u1 = u_e (1 + SRR/2)  (m/s).
    pub fn u1(&self) -> f64 {
        self.entrainment_speed * (1.0 + 0.5 * self.slide_to_roll)
    }
    /// Surface speed of body 2: u2 = u_e (1 - SRR/2)  (m/s).
    pub fn u2(&self) -> f64 {
        self.entrainment_speed * (1.0 - 0.5 * self.slide_to_roll)
    }
}

// The lubricant's parameters are physics types of plain numbers, defined with their laws in
// `crate::lubricant` (which knows nothing of the case file); the case re-exports them.
pub use crate::lubricant::{DensityModel, Lubricant, Rheology, ViscosityModel};

/// `[grid]`: cell counts and extents in Hertz half-widths b.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GridSpec {
    pub nx: usize,
    pub ny: usize,
    pub x_min: f64,
    pub x_max: f64,
    pub y_min: f64,
    pub y_max: f64,
}

/// `[solver]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SolverSpec {
    pub tolerance: f64,
    pub max_iterations: usize,
    pub mirror_levels: usize,
    pub free_end_correction: bool,
    /// order of the upwind rule of the wedge term d(rho h)/dx (ehl): 2 or 1
    pub wedge_upwind_order: u8,
}

/// A validated case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Case {
    pub title: String,
    pub kind: Kind,
    pub body1: Body,
    pub body2: Body,
    pub alignment: Alignment,
    pub load: Load,
    pub motion: Option<Motion>,
    pub lubricant: Option<Lubricant>,
    pub grid: GridSpec,
    pub solver: SolverSpec,
    /// `[[features]]`: surface features, each on its body (empty: smooth surfaces)
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub features: Vec<FeatureSpec>,
    /// `[output]`: per-step outputs of a transient run
    pub output: OutputSpec,
    /// `[stress]`: stress below the surface (absent: not computed)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress: Option<StressSpec>,
    /// `[fatigue]`: fatigue indicator (needs `[stress]`)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fatigue: Option<FatigueSpec>,
    /// `[thermal]`: thermal EHL (None: isothermal)
    pub thermal: Option<ThermalSpec>,
}

/// One resolved `[[features]]` table: the feature as the solver samples it, on its body.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FeatureSpec {
    /// the table as the case file gives it, with `body` filled in (for the resolved case)
    #[serde(flatten)]
    pub table: toml::Table,
    /// the body whose surface carries the feature: 1 or 2
    #[serde(skip)]
    pub body: u8,
    /// the feature's shape, centre and pattern (SI), with a height map's data loaded
    #[serde(skip)]
    pub feature: crate::surface::Feature,
}

impl Case {
    /// E' (Pa).
    pub fn reduced_modulus(&self) -> f64 {
        crate::units::reduced_modulus(
            self.body1.youngs_modulus,
            self.body1.poisson_ratio,
            self.body2.youngs_modulus,
            self.body2.poisson_ratio,
        )
    }

    /// Reduced radius in the rolling plane, 1/R = 1/R1 + 1/R2 (m).
    pub fn reduced_radius(&self) -> f64 {
        crate::units::reduced_radius(self.body1.radius, self.body2.radius)
    }

    /// True for a line contact between rollers (or roller on flat) of infinite length (1D).
    pub fn is_infinite_line(&self) -> bool {
        self.body1.shape != Shape::Ball
            && self.body2.shape != Shape::Ball
            && self.body1.length.is_infinite()
            && self.body2.length.is_infinite()
    }

    /// True for a point (ball) contact.
    pub fn is_point(&self) -> bool {
        self.body1.shape == Shape::Ball || self.body2.shape == Shape::Ball
    }
}

/// How the depth layers of `[stress]` are spaced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DepthSpacing {
    /// fine near the surface: z_1 = half the smallest cell size (at most depth / layers), then a
    /// constant ratio up to the deepest layer
    Geometric,
    /// z_k = depth k / layers
    Uniform,
}

/// `[stress]`: the stress below the surface of each chosen body.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StressSpec {
    /// the bodies whose stress is computed: `[1]`, `[2]` or `[1, 2]`
    pub bodies: Vec<u8>,
    /// deepest layer (m)
    pub depth_m: f64,
    pub layers: usize,
    pub spacing: DepthSpacing,
    /// dry runs: Coulomb coefficient of full sliding (traction mu p along +x on body 1)
    pub friction: f64,
    /// transient runs: the depth (m) down to which the passage maps are kept
    /// (`stress.window`, given in b); None: every layer of the depth grid
    pub window_m: Option<f64>,
}

impl StressSpec {
    /// The layer depths (m, increasing, > 0) for cells of `dx` x `dy` (`dy` infinite for a line).
    pub fn depths(&self, dx: f64, dy: f64) -> Vec<f64> {
        let n = self.layers;
        match self.spacing {
            DepthSpacing::Uniform => (1..=n)
                .map(|k| self.depth_m * k as f64 / n as f64)
                .collect(),
            DepthSpacing::Geometric => {
                let z1 = (0.5 * dx.min(dy)).min(self.depth_m / n as f64);
                if n == 1 {
                    return vec![self.depth_m];
                }
                let r = (self.depth_m / z1).powf(1.0 / (n - 1) as f64);
                (0..n)
                    .map(|k| {
                        if k + 1 == n {
                            self.depth_m
                        } else {
                            z1 * r.powi(k as i32)
                        }
                    })
                    .collect()
            }
        }
    }

    /// The layers of the passage maps of a transient run: those of [`Self::depths`] within the
    /// window (all of them without a window; at least the first).
    pub fn window_depths(&self, dx: f64, dy: f64) -> Vec<f64> {
        let z = self.depths(dx, dy);
        let Some(w) = self.window_m else {
            return z;
        };
        // a relative margin so that window = depth keeps the deepest layer despite round-off
        let n = z.iter().filter(|&&v| v <= w * (1.0 + 1e-9)).count().max(1);
        z[..n].to_vec()
    }
}

/// `[fatigue]`: the parameters of the Ioannides-Harris integral (defined with the physics).
pub use crate::stress::fatigue::Params as FatigueSpec;

pub use crate::lubricant::temperature::{
    RheologyTables, TemperatureTable, ThermalLubricant, ViscosityTemperature,
};

/// The thermal properties of a body (`[body1]`, `[body2]`: conductivity, heat_capacity,
/// density), used when `[thermal]` is present; steel by default
/// ([`crate::thermal::solid::SolidThermal::steel`]).
pub use crate::thermal::solid::SolidThermal as BodyThermal;

/// `[thermal]` with both bodies' properties.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ThermalSpec {
    pub lubricant: ThermalLubricant,
    pub bodies: [BodyThermal; 2],
    /// `[thermal]`'s `tolerance` (K): the film temperature's distance to the fixed point
    /// ([`crate::ehl::thermal::ThermalParams::tolerance_k`])
    pub tolerance_k: f64,
    /// `film_tolerance`: the film's, relative to its thinnest, and the Reynolds factors'
    /// residual ([`crate::ehl::thermal::ThermalParams::film_tolerance`], `factor_tolerance`)
    pub film_tolerance: f64,
    /// `max_iterations`: most outer (Reynolds-temperature) iterations of a steady solve
    pub max_iterations: usize,
    /// `side_flow` (default true): the film's heat convected along y by the side flow,
    /// v dT/dy ([`crate::thermal::ContactOptions::side_flow`]); false keeps the grid lines
    /// independent
    pub side_flow: bool,
    /// `coupled_newton` (default true): a steady contact whose fixed point has not settled
    /// after a few outer iterations (a line) or 20 (a ball, a finite roller), and a transient
    /// time step not settled after its passes, is handed to Newton's method on the coupled
    /// problem ([`crate::ehl::thermal::ThermalParams::coupled_newton`]); false: the fixed
    /// point alone
    pub coupled_newton: bool,
}
