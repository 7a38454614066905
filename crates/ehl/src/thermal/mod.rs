//! Thermal EHL (issue 13): the temperature across the film and in both bodies.
//!
//! * [`solid`]: the surface temperature of a body moving under a heat flux (Jaeger's moving heat
//!   source on a half-space, Carslaw & Jaeger 1959), by zero-padded FFT convolution;
//! * [`collocation`]: Legendre-Gauss-Lobatto points, quadrature, differentiation and
//!   cumulative-integration matrices across the film;
//! * [`film`]: the energy equation across the film (collocation across z), the velocity profile
//!   of a film whose viscosity varies across z and the generalized Reynolds coefficients
//!   (Yang & Wen 1990).
//!
//! SI units throughout; temperatures in K.

pub mod collocation;
pub mod film;
pub mod solid;
