//! `fields.vtk`: the fields for ParaView / VisIt, legacy VTK format (version 3.0),
//! `DATASET RECTILINEAR_GRID`, `BINARY` (big-endian IEEE float64).
//!
//! The points are the cell centres of the solver grid (the same `x`, `y` as `fields.npz`, in
//! metres, `z = 0`), so `DIMENSIONS nx ny 1` and each field is `POINT_DATA` (`SCALARS <name>
//! double 1`), x varying fastest, exactly the crate's row-major order. Field names and units:
//! `pressure` (Pa), `deformation` (m), and when present `film` (m), `viscosity` (Pa s),
//! `density` (kg/m^3); the units are also in the header line. An infinite line contact
//! (`ny == 1`) is a single row of points at `y = 0`.

use crate::case::Case;
use crate::solution::Solution;
use crate::Result;
use std::io::Write;
use std::path::Path;

/// Unit of each field name, for the header line.
fn unit(name: &str) -> &'static str {
    match name {
        "pressure" => "Pa",
        "deformation" | "film" => "m",
        "viscosity" => "Pa s",
        "density" => "kg/m^3",
        _ => "SI",
    }
}

/// The bytes of `fields.vtk`.
pub fn to_bytes(case: &Case, solution: &Solution) -> Vec<u8> {
    let g = &solution.grid;
    let fields = super::named_fields(solution);
    let mut out = Vec::with_capacity(8 * g.len() * (fields.len() + 1) + 4096);
    let units: Vec<String> = fields
        .iter()
        .map(|(n, _)| format!("{n} {}", unit(n)))
        .collect();
    // header line: at most 256 characters, one line
    let title: String = case
        .title
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    let mut header = format!(
        "ehl {} | {} | x y in m; {}",
        crate::VERSION,
        title,
        units.join(", ")
    );
    if header.len() > 255 {
        let mut cut = 255;
        while !header.is_char_boundary(cut) {
            cut -= 1;
        }
        header.truncate(cut);
    }
    let _ = writeln!(
        out,
        "# vtk DataFile Version 3.0\n{header}\nBINARY\nDATASET RECTILINEAR_GRID"
    );
    let _ = writeln!(out, "DIMENSIONS {} {} 1", g.nx, g.ny);
    let put = |out: &mut Vec<u8>, v: &[f64]| {
        for x in v {
            out.extend_from_slice(&x.to_be_bytes());
        }
        out.push(b'\n');
    };
    let _ = writeln!(out, "X_COORDINATES {} double", g.nx);
    put(&mut out, &g.xs());
    let _ = writeln!(out, "Y_COORDINATES {} double", g.ny);
    put(&mut out, &g.ys());
    let _ = writeln!(out, "Z_COORDINATES 1 double");
    put(&mut out, &[0.0]);
    let _ = writeln!(out, "POINT_DATA {}", g.len());
    for (name, field) in fields {
        let _ = writeln!(out, "SCALARS {name} double 1\nLOOKUP_TABLE default");
        put(&mut out, field);
    }
    out
}

/// Writes `fields.vtk` to `path`.
pub fn write(path: &Path, case: &Case, solution: &Solution) -> Result<()> {
    let bytes = to_bytes(case, solution);
    let mut f = std::fs::File::create(path).map_err(|e| super::io_err(path, e))?;
    f.write_all(&bytes).map_err(|e| super::io_err(path, e))?;
    f.sync_all().map_err(|e| super::io_err(path, e))
}
