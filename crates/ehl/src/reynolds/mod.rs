//! The discrete Reynolds equation (thesis eq. 2.1, 3.1).
//!
//! * [`residual`]: the finite-volume Reynolds operator in the dimensionless Venner-Lubrecht
//!   form (Poiseuille, wedge and squeeze terms, cavitation as P >= 0), its residual and the
//!   mass-flow diagnostics; the Poiseuille face rule and the Couette upwind rule are stated
//!   once there.
//! * [`jacobian`]: the rows of its Jacobian dF/dP written from those same rules (the Newton
//!   solver's preconditioners and diagonal scaling).
//!
//! The linear algebra that solves its linearisation (GMRES, banded and dense LU, line
//! multigrid) is [`crate::linalg`]; the EHL Newton-Krylov solver that couples it to the elastic
//! operator is [`crate::ehl`].

pub(crate) mod jacobian;
pub mod residual;
