//! Stress below the surface of each body from the surface pressure and shear traction, and the
//! fatigue indicator built on it.
//!
//! # Model
//!
//! Each body is an elastic half-space of its own Poisson ratio (the stress from given surface
//! tractions does not depend on E). Its surface carries the contact pressure p (the same on both
//! bodies) and a tangential traction q along x, both piecewise constant on the solution's cells.
//! The stress at depth is their convolution with the closed-form influence coefficients of a
//! uniformly loaded rectangle ([`kernel`]; plane strain for an infinite line contact), evaluated
//! by zero-padded FFT ([`field`]), exact for the piecewise-constant loads and free of periodic
//! images. The free ends of a finite roller are not modelled in depth (the mirror images of the
//! film solution are not applied to the stress): within about b of a roller end the stress is
//! that of a half-space.
//!
//! # Sign convention (stated once; docs/stress.md repeats it)
//!
//! * Each body has its own frame: x the rolling direction (as the solution's grid), y the axis,
//!   z the depth into that body (> 0). Stresses are positive in tension; sigma_zz = -p at the
//!   surface.
//! * q is the force per unit area along +x that the lubricant exerts on that body's surface:
//!   it pulls the slower surface forward and holds the faster one back
//!   ([`crate::friction::surface_tractions`]); at the surface tau_xz = -q. In a dry run with
//!   `stress.friction = mu`, body 1 carries q = mu p and body 2 q = -mu p (full sliding, body 1
//!   moving towards -x relative to body 2).
//! * The shear traction across the rolling direction (side flow) is neglected.
//!
//! # Modules
//!
//! * [`kernel`]: influence coefficients (Love 1929; Johnson 1985 sec. 3.2; Flamant strips).
//! * [`field`]: the DC-FFT field on a depth grid.
//! * [`derived`]: von Mises, principal stresses, maximum shear (Tresca), hydrostatic.
//! * [`fatigue`]: Ioannides-Harris integral and life ratio.
//! * [`passage`]: the history of a transient run in a moving body's material frame: max-over-
//!   passage von Mises, range of tau_xz, Dang Van.

pub mod derived;
pub mod fatigue;
pub mod field;
pub mod kernel;
pub mod passage;

use crate::grid::Grid;
use field::StressField;
use rayon::prelude::*;

/// The largest value of a stress measure and where it is.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Peak {
    /// Pa
    pub value: f64,
    /// [x, y, z] (m): cell centre and layer depth
    pub at: [f64; 3],
    /// index of the layer (0 is the shallowest)
    pub layer: usize,
    /// flat index in the field, `(layer * ny + j) * nx + i`
    pub index: usize,
}

/// The stress in one body and its derived measures.
#[derive(Debug, Clone)]
pub struct BodyStress {
    /// 1 or 2
    pub body: u8,
    pub poisson_ratio: f64,
    pub field: StressField,
    /// von Mises equivalent stress at every point (Pa)
    pub von_mises: Vec<f32>,
    /// maximum shear (sigma_1 - sigma_3)/2, the Tresca measure, at every point (Pa)
    pub max_shear: Vec<f32>,
    pub peak_von_mises: Peak,
    pub peak_max_shear: Peak,
    /// largest |tau_xz| (the orthogonal shear of Lundberg & Palmgren)
    pub peak_orthogonal_shear: Peak,
}

impl BodyStress {
    /// Computes the field and its measures for one body: `pressure` (Pa) and `traction` (Pa,
    /// along +x on this body; None: frictionless) on `grid`, Poisson ratio `nu`, depths `z` (m).
    pub fn new(
        body: u8,
        grid: &Grid,
        pressure: &[f64],
        traction: Option<&[f64]>,
        nu: f64,
        z: &[f64],
        plane_strain: bool,
    ) -> Self {
        let field = field::stress_field(grid, pressure, traction, nu, z, plane_strain);
        Self::from_field(body, grid, nu, field)
    }

    /// The measures of a computed `field` (on `grid`, its layers) of body `body`, Poisson
    /// ratio `nu`.
    pub fn from_field(body: u8, grid: &Grid, nu: f64, field: StressField) -> Self {
        let z = field.z.clone();
        let n = field.len();
        let (von_mises, max_shear): (Vec<f32>, Vec<f32>) = (0..n)
            .into_par_iter()
            .with_min_len(4096)
            .map(|k| {
                let s = field.tensor(k);
                (derived::von_mises(&s) as f32, derived::max_shear(&s) as f32)
            })
            .unzip();
        let peak = |v: &dyn Fn(usize) -> f64| {
            let mut best = Peak {
                value: f64::NEG_INFINITY,
                ..Peak::default()
            };
            for k in 0..n {
                let x = v(k);
                if x > best.value {
                    best.value = x;
                    best.index = k;
                }
            }
            let plane = grid.nx * grid.ny;
            let (layer, rem) = (best.index / plane, best.index % plane);
            best.layer = layer;
            best.at = [grid.x(rem % grid.nx), grid.y(rem / grid.nx), z[layer]];
            best
        };
        let peak_von_mises = peak(&|k| von_mises[k] as f64);
        let peak_max_shear = peak(&|k| max_shear[k] as f64);
        let peak_orthogonal_shear = peak(&|k| (field.components[4][k] as f64).abs());
        BodyStress {
            body,
            poisson_ratio: nu,
            field,
            von_mises,
            max_shear,
            peak_von_mises,
            peak_max_shear,
            peak_orthogonal_shear,
        }
    }

    /// The equivalent stress of a fatigue criterion at every point (Pa).
    pub fn equivalent(&self, criterion: fatigue::Criterion) -> Vec<f32> {
        match criterion {
            fatigue::Criterion::VonMises => self.von_mises.clone(),
            fatigue::Criterion::MaxShear => self.max_shear.clone(),
            fatigue::Criterion::OrthogonalShear => {
                self.field.components[4].iter().map(|v| v.abs()).collect()
            }
        }
    }

    /// The Ioannides-Harris integral of this body's field ([`fatigue::integral`]); `cell_area`
    /// in m^2 (a line contact: dx times 1 m).
    pub fn fatigue_integral(&self, cell_area: f64, params: &fatigue::Params) -> f64 {
        fatigue::integral(
            &self.equivalent(params.criterion),
            &self.field.z,
            cell_area,
            params,
        )
    }
}
