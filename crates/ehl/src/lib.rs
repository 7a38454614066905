//! # ehl — elastohydrodynamic lubrication of finite rollers and balls
//!
//! The library behind the `ehl` program. Data flows one way:
//!
//! ```text
//! case file --case--> validated Case --geometry, elastic--> operators
//!           --dry / ehl solvers--> Solution --output--> summary.json, npz, vtk, csv, png
//! ```
//!
//! Where to find the physics:
//!
//! | physics | module |
//! | --- | --- |
//! | E', R, Hertz, W U G, Moes M L (the scales) | [`units`] |
//! | cell grid | [`grid`] |
//! | gap of the undeformed bodies: profiles, misalignment, ball | [`geometry`] |
//! | elastic kernel (Love 1929 rectangle coefficients), DC-FFT operator, mirror images + psi | [`elastic`] |
//! | dry contact solver (constrained conjugate gradient) | [`dry`] |
//! | density, viscosity and rheology laws | [`lubricant`] |
//! | discrete Reynolds equation: Poiseuille, wedge and squeeze terms, cavitation, mass flows | [`reynolds`] |
//! | generic linear algebra: GMRES, banded and dense LU, line multigrid | [`linalg`] |
//! | EHL coupling: film, load balance, steady and transient (time loop, BDF2) drivers | [`ehl`] |
//! | shear stress and friction integral | [`friction`] |
//! | surface features (pits, dents, waviness, height maps) as cell averages | [`surface`] |
//! | analytic and classical reference results | [`reference`](mod@reference) |
//! | from a case to a solution (steady or transient), no I/O | [`run`] |
//! | writers | [`output`] |
//!
//! Conventions (written once here): SI units everywhere in the public API (m, Pa, N, s, Pa s,
//! kg/m^3, rad). `x` is the rolling direction with the inlet at negative `x`, `y` the roller axis,
//! origin at the centre of the nominal contact line. Fields on the cell grid are row-major
//! `Vec<f64>` of length `ny * nx`, index `j * nx + i` (`j` along `y`, `i` along `x`). Pressure is
//! positive in compression; the gap and the film are positive when the surfaces are apart;
//! the elastic deflection is the sum of both bodies' normal surface displacements, positive
//! when it opens the gap.

pub mod case;
pub mod dry;
pub mod ehl;
pub mod elastic;
pub mod error;
pub mod friction;
pub mod geometry;
pub mod grid;
pub mod linalg;
pub mod lubricant;
pub mod output;
pub mod reference;
pub mod reynolds;
pub mod run;
pub mod solution;
pub mod stress;
pub mod surface;
pub mod thermal;
pub mod units;

pub use error::{Error, Result};

/// The program version written into every `summary.json`.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
