//! Normal elastic deflection of the contacting bodies under the contact pressure.
//!
//! * [`kernel`]: the influence coefficient of one uniformly loaded rectangle on a half-space
//!   (Love 1929; thesis eq. 1.11-1.12) and of one uniformly loaded strip (plane strain, for the
//!   infinite line contact).
//! * [`operator`]: the DC-FFT operator (O(N log N)) with mirror images and Guilbault's psi at the
//!   free roller ends: what the solvers use;
//! * [`dense`]: the O(N^2) direct sum, kept as the reference the fast operators are tested against.
//!
//! Conventions: pressure in Pa, positive in compression; deflection in m, the *sum* of both
//! bodies' surface displacements, positive into the bodies (so it opens the gap:
//! h = h0 + g + deflection, thesis eq. 2.3). With the reduced modulus E' (see
//! [`crate::units::reduced_modulus`]) the half-space compliance is 2/(pi E') (eq. 1.6, 1.12).

pub mod dense;
pub mod kernel;
pub mod operator;

pub use operator::{guilbault_psi, BodyCompliance, EndImages, FftDeflection, InverseHalfSpace};

use crate::grid::Grid;

/// A linear map from cell pressures to cell-centre deflections: the operator the dry and EHL
/// solvers share. Implementations plan their scratch space once at construction; `apply`
/// writes into a caller-owned buffer and allocates nothing.
pub trait Deflection: Send {
    /// The grid the operator acts on.
    fn grid(&self) -> &Grid;

    /// `out[k] = sum_l K[k, l] p[l]`: deflection (m) at each cell centre for cell pressures `p` (Pa).
    fn apply(&mut self, p: &[f64], out: &mut [f64]);

    /// Deflection (m/Pa) at the centre of a cell `(di, dj)` cells away from a cell carrying unit
    /// pressure, for the plain half-space kernel (no images). `(0, 0)` is the diagonal, used by
    /// relaxation solvers.
    fn coefficient(&self, di: isize, dj: isize) -> f64;
}
