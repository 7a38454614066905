//! Case files: raw TOML structures, validation into [`Case`], `--set` overrides.
//!
//! Errors name the file, the dotted key and what is wrong; an unknown key names the closest
//! valid key.

pub mod model;

pub use model::*;
