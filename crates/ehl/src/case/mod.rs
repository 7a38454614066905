//! Case files: TOML text -> `--set` overrides -> unknown-key check -> validation into [`Case`].
//!
//! Every error is an [`Error::Case`] naming the file, the full dotted key (`body1.radius`,
//! `features[0].x`) and what is wrong; an unknown or misspelt key names the closest valid key
//! ("did you mean `load.force`?"). An unreadable or malformed file is an [`Error::CaseFile`] with
//! the TOML parser's line and column. Parts of the format that are not built yet (a ball against
//! a roller, the Hertz-pressure load of an elliptical contact) are parsed and checked, then
//! refused with [`Error::Unsupported`]. Nothing here panics on user input.
//!
//! # Defaults
//!
//! | key | default |
//! | --- | --- |
//! | `title` | `""` |
//! | `body.radius_y` (ball) | `radius` (a sphere) |
//! | `radius`, `radius_y`, `length` of a flat | `inf` (a plane); a ball's `length` and a roller's `radius_y` are `inf` too |
//! | `body.profile` (roller) | `{ kind = "straight" }` |
//! | `body2.axial_offset` | 0 m |
//! | `[alignment]` `tilt`, `skew` | 0 rad |
//! | `motion.slide_to_roll` | 0 (pure rolling) |
//! | `lubricant.viscosity_model` | `"roelands"` |
//! | `lubricant.density_model` | `"dowson-higginson"` |
//! | `lubricant.rheology` | `{ model = "newtonian" }` |
//! | `grid.nx`, `grid.ny` | 128 (`ny` = 1 for an infinite line contact) |
//! | `grid.x_min`, `grid.x_max` | -1.5, 1.5 b (dry); -4.0, 1.5 b (ehl: room for the inlet meniscus) |
//! | `grid.y_min`, `grid.y_max` | rollers: the union of both rollers' axial extents (body2 shifted by `axial_offset`), in b, i.e. the contact length plus any overhang; balls: -3, 3 (in a); infinite line: -0.5/b, 0.5/b, the 1 m reference strip of the library convention (ny = 1, dy = 1 m) |
//! | `solver.tolerance` | 1e-6 |
//! | `solver.max_iterations` | 500 for dry (constrained conjugate gradient: O(100) iterations on fine grids, more for misaligned cases), 200 for ehl |
//! | `solver.mirror_levels` | 1 |
//! | `solver.free_end_correction` | true |
//! | `solver.wedge_upwind_order` | 2 (second-order upwind wedge term; 1: first order, as EHL-FBNS) |
//! | `motion.travel` | absent: a steady run |
//! | `output.frames_every` | absent (`None`): every step, unless the frames exceed the memory limit |
//! | `output.snapshots` | `[]` |
//! | `output.animation` | true |
//!
//! `[motion]` and `[lubricant]` are required for `kind = "ehl"` and ignored for `kind = "dry"`
//! (they are still checked for unknown keys; the resolved case holds `None`), except
//! `motion.travel`, which a dry case refuses (a dry contact has no time).
//!
//! # Transient runs
//!
//! `motion.travel` makes an ehl run transient ([`Travel`]), in one of two forms:
//!
//! * `{ from, to, steps }`: the path of x_p, the centre of `features[0]` (m), in `steps` equal
//!   steps of its body's surface speed u (u1 = u_e (1 + SRR/2) on body 1, u2 = u_e (1 - SRR/2)
//!   on body 2): dt = (to - from) / steps / u. At t = 0 every body's surface is shifted so that
//!   `features[0]`'s centre sits at `from` (the features keep their relative positions). Needs a
//!   feature, on a body with u > 0, and `to > from` (both surfaces move in +x since |SRR| <= 2).
//! * `{ duration, steps }`: `duration` s (> 0) in `steps` equal steps, dt = duration / steps;
//!   the features start where the case puts them, x_p = `features[0].x` + u t. The form for
//!   smooth surfaces and for `features[0]` on a body standing still.
//!
//! `steps` is a whole number from 1 to [`MAX_TRAVEL_STEPS`] (100 000). With a travel,
//! features may lie on a moving body and outside the grid along x (they travel through it);
//! without one, a feature on a moving body is refused (its film is transient). `[output]`
//! ([`OutputSpec`]) sets the per-step outputs; its keys are accepted without a travel and used
//! only by transient runs. Each `output.snapshots` value must lie within the x_p range of the
//! travel, half a step either side allowed (the path form: `from .. to`; the duration form with
//! a feature: `features[0].x .. features[0].x + u duration`; without a feature it is not
//! checked).
//!
//! # Load and dimensionless forms
//!
//! Exactly one of `load.force` (N), `load.max_hertz_pressure` (Pa), `load.force_per_length`
//! (N/m) or `load.dimensionless_load` (W). With E' = 2/((1-nu1^2)/E1 + (1-nu2^2)/E2) and
//! 1/R = 1/R1 + 1/R2 (radii in the rolling plane; thesis eq. 2.5-2.8):
//!
//! * line contact (roller on roller or on a flat), contact length L = the axial overlap of the
//!   rollers (or the roller length on a flat; L = 1 m reference for `length = inf`):
//!   w' = F / L; from the Hertz pressure w' = 2 pi R p_h^2 / E' ([`crate::units::line_load_for_pressure`]);
//!   from W: w' = W E' R. Then [`Load::force`] = w' L and [`Load::force_per_length`] = w'.
//!   An infinite line contact (`length = inf`) must not use `force`.
//! * point contact (ball on flat or ball): F directly; from the Hertz pressure of a circular
//!   contact F = (2 pi/3) p0 a^2 with a = pi p0 R/E' ([`crate::units::point_load_for_pressure`];
//!   refused for an elliptical ball); from W: F = W E' R^2. `force_per_length` is refused;
//!   [`Load::force_per_length`] is set to F/(2a), the mean load per unit length across the
//!   Hertz contact diameter, so that it is finite.
//! * `motion.dimensionless_speed` U: u_e = U E' R / eta0; `lubricant.dimensionless_material` G:
//!   alpha = G / E'.
//!
//! The grid's unit length is the Hertz half-width: b = sqrt(8 w' R/(pi E')) for line contacts
//! ([`crate::units::hertz_line_half_width`]), the contact radius a = (3 F R/(2 E'))^(1/3) for
//! balls ([`crate::units::hertz_point`], with R the reduced radius in x also for an ellipsoid).
//!
//! # Overrides
//!
//! `--set KEY=VALUE` strings are applied to the TOML tree before validation; see
//! [`overrides`].

pub mod model;
pub mod overrides;
pub(crate) mod read;
mod resolve;
pub mod schema;

pub use model::*;
pub use overrides::{check_key, parse_value, split_assignment};
pub use resolve::{
    DEFAULT_CELLS, DEFAULT_DRY_ITERATIONS, DEFAULT_EHL_ITERATIONS, MAX_CELLS,
    MAX_PRESSURE_OVER_MODULUS, MAX_TRAVEL_STEPS, MIN_CELLS_ACROSS_CONTACT,
};

use crate::{Error, Result};
use std::path::Path;
use toml::Table;

/// Reads, overrides and validates a case file. `overrides` are `"dotted.key=value"` strings
/// (the CLI's `--set`). Errors name the file as given in `path`. The file is read with
/// [`read_case_text`].
pub fn load_file(path: &Path, overrides: &[String]) -> Result<Case> {
    let text = read_case_text(path)?;
    parse_str(&text, &path.display().to_string(), overrides)
}

/// The largest case file read: 16 MiB (a case file is a few hundred bytes; this only keeps a
/// wrong path, e.g. a disk image, from filling the memory).
pub const MAX_CASE_FILE_BYTES: u64 = 16 * 1024 * 1024;

/// Reads the text of a case file: a regular file (or a link to one) of at most
/// [`MAX_CASE_FILE_BYTES`], in UTF-8. A folder, FIFO, device or socket is refused from its
/// metadata before it is opened, so that reading never blocks (a FIFO would wait for a writer
/// forever). Errors are [`Error::CaseFile`] naming the file as given: "cannot read the case
/// file: ...".
pub fn read_case_text(path: &Path) -> Result<String> {
    use std::io::Read;
    let file = path.display().to_string();
    let err = |message: String| Error::CaseFile {
        file: file.clone(),
        message: format!("cannot read the case file: {message}"),
    };
    let kind = |m: &std::fs::Metadata| -> Option<&'static str> {
        let t = m.file_type();
        if t.is_file() {
            return None;
        }
        if t.is_dir() {
            return Some("it is a folder, not a file");
        }
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileTypeExt;
            if t.is_fifo() {
                return Some("it is a FIFO (named pipe), not a regular file");
            }
            if t.is_block_device() || t.is_char_device() {
                return Some("it is a device, not a regular file");
            }
            if t.is_socket() {
                return Some("it is a socket, not a regular file");
            }
        }
        Some("it is not a regular file")
    };
    let too_big = |n: u64| {
        err(format!(
            "it is {n} bytes, more than the {} MiB a case file may have",
            MAX_CASE_FILE_BYTES / (1024 * 1024)
        ))
    };
    let meta = std::fs::metadata(path).map_err(|e| err(e.to_string()))?;
    if let Some(why) = kind(&meta) {
        return Err(err(why.into()));
    }
    if meta.len() > MAX_CASE_FILE_BYTES {
        return Err(too_big(meta.len()));
    }
    let f = std::fs::File::open(path).map_err(|e| err(e.to_string()))?;
    // the path may have been replaced between the two looks: check what was opened
    let meta = f.metadata().map_err(|e| err(e.to_string()))?;
    if let Some(why) = kind(&meta) {
        return Err(err(why.into()));
    }
    let mut bytes = Vec::new();
    f.take(MAX_CASE_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| err(e.to_string()))?;
    if bytes.len() as u64 > MAX_CASE_FILE_BYTES {
        return Err(too_big(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|e| {
        err(format!(
            "it is not UTF-8 text (invalid byte at offset {})",
            e.utf8_error().valid_up_to()
        ))
    })
}

/// Parses case text (`file` names it in errors), applies `overrides`, validates.
pub fn parse_str(text: &str, file: &str, overrides: &[String]) -> Result<Case> {
    let mut root: Table = text.parse().map_err(|e: toml::de::Error| Error::CaseFile {
        file: file.to_string(),
        message: format!("not valid TOML: {}", e.to_string().trim_end()),
    })?;
    for o in overrides {
        overrides::apply(&mut root, o, file)?;
    }
    if let Some(key) = schema::first_unknown(&root) {
        // a blank key name would vanish from "file: key: message": quote it
        let shown = if key.split('.').any(|s| s.trim().is_empty()) {
            format!("`{key}`")
        } else {
            key.clone()
        };
        return Err(Error::Case {
            file: file.to_string(),
            message: schema::unknown_key_message(&key),
            key: shown,
        });
    }
    resolve::resolve(&root, file)
}

#[cfg(test)]
mod tests;
