//! Thermal EHL (issue 13): the temperature across the film and in both bodies.
//!
//! * [`solid`]: the surface temperature of a body moving under a heat flux (Jaeger's moving heat
//!   source on a half-space, Carslaw & Jaeger 1959), by zero-padded FFT convolution;
//! * [`collocation`]: Legendre-Gauss-Lobatto points, quadrature, differentiation and
//!   cumulative-integration matrices across the film;
//! * [`film`]: the lubricant laws' trait, the velocity profile of a film whose viscosity varies
//!   across z (with a shear-thinning iteration) and the generalized Reynolds coefficients
//!   (Yang & Wen 1990);
//! * [`film_energy`]: the energy equation of the film along a grid line (collocation across z,
//!   upwind along x), its fixed point with the temperature-dependent laws, and the energy
//!   accounting (heat into each surface, generated, convected).
//!
//! * [`contact`]: film and both bodies together for a given pressure and film: the
//!   temperatures, the generalized Reynolds factors, the heat balance (the physics object the
//!   thermal driver `crate::ehl::thermal` iterates with).
//!
//! SI units throughout; temperatures in K.

pub mod collocation;
pub mod contact;
pub mod film;
pub mod film_energy;
pub mod solid;

pub use contact::{ContactOptions, HeatBalance, ThermalContact};
