//! Test and bench support for the dry solver: operator factories over the lead's DC-FFT
//! operator (`elastic::operator::FftDeflection`).
#![allow(dead_code)]

use ehl::elastic::operator::{BodyCompliance, EndImages, FftDeflection};
use ehl::elastic::Deflection;
use ehl::grid::Grid;

/// Half-space FFT operator factory for reduced modulus `e_red`.
pub fn half_space(e_red: f64) -> impl Fn(Grid) -> Box<dyn Deflection> + Sync {
    move |g: Grid| Box::new(FftDeflection::half_space(g, e_red)) as Box<dyn Deflection>
}

/// Plane-strain line-contact FFT operator factory (grids with ny == 1).
pub fn line(e_red: f64) -> impl Fn(Grid) -> Box<dyn Deflection> + Sync {
    move |g: Grid| Box::new(FftDeflection::line(g, e_red)) as Box<dyn Deflection>
}

/// Roller (modulus `e`, ratio `nu`, free ends at `ends`, `levels` mirror levels with factor
/// `psi`) on a second body of the same material: a flat without images (`two_rollers` false)
/// or an equal roller with the same ends and images.
pub fn rollers(
    e: f64,
    nu: f64,
    ends: (f64, f64),
    levels: usize,
    psi: f64,
    two_rollers: bool,
) -> impl Fn(Grid) -> Box<dyn Deflection> + Sync {
    move |g: Grid| {
        let mut roller = BodyCompliance::new(e, nu);
        if levels > 0 {
            roller.images = Some(EndImages { ends, levels, psi });
        }
        let flat = if two_rollers {
            roller
        } else {
            BodyCompliance::new(e, nu)
        };
        Box::new(FftDeflection::with_images(g, &[roller, flat])) as Box<dyn Deflection>
    }
}
