//! Writers: summary.json, fields.npz, fields.vtk, csv profiles, png pictures (atomic folder writes).

use crate::case::Case;
use crate::solution::Solution;
use crate::{Error, Result};
use std::path::Path;

/// Writes every output of a solved case into `dir`, atomically: all files go to a temporary
/// sibling folder which replaces `dir` only when every file is written.
pub fn write_all(dir: &Path, case: &Case, solution: &Solution) -> Result<()> {
    let _ = (case, solution);
    Err(Error::Output {
        path: dir.to_path_buf(),
        message: "not built yet".into(),
    })
}
