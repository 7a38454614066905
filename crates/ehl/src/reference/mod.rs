//! Analytic and classical reference results used by `ehl check` and the tests (Hertz, Moes,
//! Pan-Hamrock, Dowson-Higginson, Hamrock-Dowson, Palmgren).
//!
//! * [`hertz`]: complete elliptic integrals, exact elliptical Hertz contact, Hamrock-Brewe
//!   approximations (line and circular Hertz are in [`crate::units`]).
//! * [`film`]: classical EHL film-thickness fits, each with its groups and the lubricant laws
//!   of the solutions it was fitted to.
//! * [`palmgren`]: the empirical roller approach.
//! * [`subsurface`]: closed-form stress fields below Hertz line (McEwen, Smith & Liu) and circular
//!   (Huber) contacts.
//! * [`waviness`]: amplitude reduction of waviness in transient EHL (Venner et al. 1997).
//! * [`check`]: the `ehl check` report.

pub mod check;
pub mod film;
pub mod hertz;
pub mod palmgren;
pub mod subsurface;
pub mod thermal;
pub mod waviness;

pub use check::{check_report, CheckReport};
