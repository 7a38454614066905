//! Generic linear algebra of the solvers, free of physics: nothing here knows the Reynolds
//! equation, the elastic kernel or the case file.
//!
//! * [`anderson`]: Anderson acceleration of a fixed-point iteration (the film temperature);
//! * [`banded`]: banded LU with partial pivoting (the line solves of the Newton preconditioner);
//! * [`dense`]: dense blocked LU with partial pivoting (the fallback preconditioner of a
//!   transient infinite line contact), and small double-precision LU factors (`SmallLu`: the
//!   HODLR leaves and coupling systems, Anderson mixing);
//! * [`multigrid`]: line-relaxation aggregation multigrid for a local line operator (the Newton
//!   preconditioner on 2D grids);
//! * [`hodlr`]: hierarchical off-diagonal low-rank approximate inverse (the preconditioner of
//!   a transient infinite line contact: O(n k log n) solves in place of dense LU's O(n^2));
//! * [`gmres`]: restarted, flexible, right-preconditioned GMRES (the Newton steps).
//!
//! The discrete Reynolds operator that these solve is [`crate::reynolds`]; the EHL
//! Newton-Krylov solver that couples them to the elastic operator is [`crate::ehl`].

pub mod anderson;
pub mod banded;
pub mod dense;
pub mod gmres;
pub mod hodlr;
pub mod multigrid;
