//! `fields.npz`: the fields as NumPy arrays (uncompressed npz, float64, C order).
//!
//! Arrays: `x` (nx) and `y` (ny), the cell-centre coordinates (m); `pressure` (Pa) and
//! `deformation` (m), shape (ny, nx); `film` (m), `viscosity` (Pa s), `density` (kg/m^3) with the
//! same shape when the solution has them. `field[j, i]` is the value at `(x[i], y[j])`. Read with
//! `numpy.load("fields.npz")`.

use crate::solution::Solution;
use crate::Result;
use ndarray::{Array1, Array2};
use ndarray_npy::NpzWriter;
use std::path::Path;

/// Writes `fields.npz` to `path`.
pub fn write(path: &Path, solution: &Solution) -> Result<()> {
    let err = |e: &dyn std::fmt::Display| super::io_err(path, e);
    let g = &solution.grid;
    let file = std::fs::File::create(path).map_err(|e| err(&e))?;
    let mut npz = NpzWriter::new(std::io::BufWriter::new(file));
    npz.add_array("x", &Array1::from(g.xs()))
        .map_err(|e| err(&e))?;
    npz.add_array("y", &Array1::from(g.ys()))
        .map_err(|e| err(&e))?;
    for (name, field) in super::named_fields(solution) {
        let a = Array2::from_shape_vec((g.ny, g.nx), field.to_vec())
            .map_err(|e| err(&format!("field `{name}`: {e}")))?;
        npz.add_array(name, &a).map_err(|e| err(&e))?;
    }
    let w = npz.finish().map_err(|e| err(&e))?;
    w.into_inner()
        .map_err(|e| err(&e.error().to_string()))?
        .sync_all()
        .map_err(|e| err(&e))
}
