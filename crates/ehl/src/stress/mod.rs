//! Stress below the surface of each body from the surface pressure and shear traction.

pub mod kernel;
pub mod derived;
pub mod field;
