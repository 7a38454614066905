//! `fields.npz`: the fields as NumPy arrays (uncompressed npz, float64, C order).
//!
//! Arrays: `x` (nx) and `y` (ny), the cell-centre coordinates (m); `pressure` (Pa) and
//! `deformation` (m), shape (ny, nx); `film` (m), `viscosity` (Pa s), `density` (kg/m^3) with the
//! same shape when the solution has them. `field[j, i]` is the value at `(x[i], y[j])`. Read with
//! `numpy.load("fields.npz")`.

use crate::grid::Grid;
use crate::solution::Solution;
use crate::{Error, Result};
use ndarray::{Array1, Array2};
use ndarray_npy::{NpzWriter, WriteNpyExt};
use std::io::BufWriter;
use std::path::Path;

/// Writes `fields.npz` to `path`.
pub fn write(path: &Path, solution: &Solution) -> Result<()> {
    let g = &solution.grid;
    let mut npz = Npz::create(path)?;
    npz.add_grid(g)?;
    for (name, field) in super::named_fields(solution) {
        let a = Array2::from_shape_vec((g.ny, g.nx), field.to_vec())
            .map_err(|e| npz.err(format!("field `{name}`: {e}")))?;
        npz.add(name, &a)?;
    }
    npz.finish()
}

/// Bytes of array data from which an npz entry is written with the zip64 extension: 4 GiB less
/// a margin for the `.npy` header.
pub(super) const ZIP64_FROM: u64 = u32::MAX as u64 - (1 << 20);

/// An uncompressed npz file being written (`fields.npz`, `frames.npz`); every error names the
/// file.
pub(super) struct Npz<'p> {
    path: &'p Path,
    writer: NpzWriter<BufWriter<std::fs::File>>,
}

impl<'p> Npz<'p> {
    /// Creates (or truncates) the file at `path`.
    pub(super) fn create(path: &'p Path) -> Result<Self> {
        let file = std::fs::File::create(path).map_err(|e| super::io_err(path, e))?;
        Ok(Npz {
            path,
            writer: NpzWriter::new(BufWriter::new(file)),
        })
    }

    /// The error of this file with `message`.
    pub(super) fn err(&self, message: impl std::fmt::Display) -> Error {
        super::io_err(self.path, message)
    }

    /// Adds the array `name`.
    pub(super) fn add<T: WriteNpyExt + ?Sized>(&mut self, name: &str, array: &T) -> Result<()> {
        self.writer
            .add_array(name, array)
            .map_err(|e| super::io_err(self.path, e))
    }

    /// Adds the array `name` of `bytes` bytes of data: past [`ZIP64_FROM`] its entry carries the
    /// zip64 extension (a plain zip entry stops at 4 GiB: `frames.npz` of a long run on a fine
    /// grid, e.g. 8192 frames of 256 x 256, would fail at the end of the run).
    pub(super) fn add_sized<T: WriteNpyExt + ?Sized>(
        &mut self,
        name: &str,
        array: &T,
        bytes: u64,
    ) -> Result<()> {
        self.add_with(name, array, bytes >= ZIP64_FROM)
    }

    fn add_with<T: WriteNpyExt + ?Sized>(
        &mut self,
        name: &str,
        array: &T,
        large: bool,
    ) -> Result<()> {
        if !large {
            return self.add(name, array);
        }
        let options = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Stored)
            .large_file(true);
        self.writer
            .add_array_with_options(name, array, options)
            .map_err(|e| super::io_err(self.path, e))
    }

    /// Adds `x` (nx) and `y` (ny), the cell-centre coordinates of `g` (m).
    pub(super) fn add_grid(&mut self, g: &Grid) -> Result<()> {
        self.add("x", &Array1::from(g.xs()))?;
        self.add("y", &Array1::from(g.ys()))
    }

    /// Finishes the archive, flushes and syncs the file.
    pub(super) fn finish(self) -> Result<()> {
        let path = self.path;
        let w = self.writer.finish().map_err(|e| super::io_err(path, e))?;
        w.into_inner()
            .map_err(|e| super::io_err(path, e.error()))?
            .sync_all()
            .map_err(|e| super::io_err(path, e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::Array3;
    use ndarray_npy::NpzReader;

    /// An entry written with the zip64 extension (what an array past 4 GiB gets) reads back
    /// as any other.
    #[test]
    fn a_zip64_entry_reads_back() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.npz");
        let a = Array3::from_shape_fn((3, 2, 4), |(k, j, i)| (100 * k + 10 * j + i) as f64);
        let mut npz = Npz::create(&path).unwrap();
        npz.add_with("big", &a, true).unwrap();
        npz.add_with("small", &a, false).unwrap();
        npz.finish().unwrap();
        let mut r = NpzReader::new(std::fs::File::open(&path).unwrap()).unwrap();
        let big: Array3<f64> = r.by_name("big").unwrap();
        let small: Array3<f64> = r.by_name("small").unwrap();
        assert_eq!(big, a);
        assert_eq!(small, a);
    }
}
