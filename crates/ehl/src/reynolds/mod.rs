//! The discrete Reynolds equation (thesis eq. 2.1, 3.1) and its solvers.
//!
//! * [`residual`]: the finite-volume Reynolds operator in the dimensionless Venner-Lubrecht
//!   form, its residual and the mass-flow diagnostics;
//! * [`multigrid`]: the EHL solver: Venner-Lubrecht relaxation (Gauss-Seidel lines along x where
//!   the Poiseuille term dominates, Jacobi distributive where it is small) inside FAS multigrid
//!   with the film recomputed by the elastic operator on every level and h0 fixed by the load
//!   balance on the coarsest level.

pub mod multigrid;
pub mod residual;
