//! The discrete Reynolds equation (thesis eq. 2.1, 3.1) and the linear algebra of its solver.
//!
//! * [`residual`]: the finite-volume Reynolds operator in the dimensionless Venner-Lubrecht
//!   form, its residual and the mass-flow diagnostics;
//! * [`banded`]: banded LU with partial pivoting (the line solves of the Newton preconditioner);
//! * [`dense`]: dense blocked LU with partial pivoting (the preconditioner of a transient
//!   infinite line contact, reused over time steps);
//! * [`multigrid`]: line-relaxation aggregation multigrid for the local part of the linearised
//!   operator (the Newton preconditioner on 2D grids);
//! * [`gmres`]: restarted, flexible, right-preconditioned GMRES (the Newton steps).
//!
//! The EHL Newton-Krylov solver that couples them to the elastic operator is [`crate::ehl`].

pub mod banded;
pub mod dense;
pub mod gmres;
pub mod multigrid;
pub mod residual;
