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
use std::fmt::Write as _;
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

/// The bytes of a VTK XML rectilinear grid (`.vtr`, `VTKFile` version 1.0, little-endian,
/// `UInt64` block headers, the arrays appended raw after the XML): the frames of a transient
/// run (`frames/frame_NNNNN.vtr`, listed by `passage.pvd`). ParaView's collection reader
/// (`.pvd`) opens only the XML formats (`.vtr`, `.vti`, ...), not the legacy `.vtk` of
/// [`to_bytes`]; the grid and the point layout are the same as in `fields.vtk` (cell centres,
/// `z = 0`, x varying fastest). `fields` are `(name, values)` with `grid.len()` values each,
/// written as `Float64` point data (`+inf` film cells as `inf`); `time_s`, when given, is the
/// field-data array `TimeValue` that ParaView shows as the data's time.
pub fn rectilinear_xml(
    grid: &crate::grid::Grid,
    fields: &[(&str, &[f64])],
    time_s: Option<f64>,
) -> Vec<u8> {
    rectilinear_volume_xml(&grid.xs(), &grid.ys(), &[0.0], fields, time_s)
}

/// A VTK XML RectilinearGrid (`.vtr`) over the points `xs` x `ys` x `zs` (x varying fastest,
/// then y, then z): `fields` are `(name, values)` with `xs.len() * ys.len() * zs.len()` values
/// each, written as `Float64` point data; `time_s` as in [`rectilinear_xml`].
pub fn rectilinear_volume_xml(
    xs: &[f64],
    ys: &[f64],
    zs: &[f64],
    fields: &[(&str, &[f64])],
    time_s: Option<f64>,
) -> Vec<u8> {
    let (nx, ny, nz) = (xs.len(), ys.len(), zs.len());
    let extent = format!("0 {} 0 {} 0 {}", nx - 1, ny - 1, nz - 1);
    // appended blocks in the order of their offsets: the fields, then x, y, z
    let mut blocks: Vec<&[f64]> = fields.iter().map(|(_, v)| *v).collect();
    blocks.extend([xs, ys, zs]);
    let mut offsets = Vec::with_capacity(blocks.len());
    let mut at = 0usize;
    for b in &blocks {
        offsets.push(at);
        at += 8 + 8 * b.len();
    }
    let mut xml = String::with_capacity(1024);
    xml.push_str(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"RectilinearGrid\" version=\"1.0\" \
         byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
    );
    let _ = writeln!(xml, "  <RectilinearGrid WholeExtent=\"{extent}\">");
    if let Some(t) = time_s {
        let _ = writeln!(
            xml,
            "    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TimeValue\" \
             NumberOfTuples=\"1\" format=\"ascii\">{t:e}</DataArray>\n    </FieldData>"
        );
    }
    let _ = writeln!(xml, "    <Piece Extent=\"{extent}\">");
    let first = fields.first().map_or("", |(n, _)| *n);
    let _ = writeln!(xml, "      <PointData Scalars=\"{first}\">");
    for (k, (name, _)) in fields.iter().enumerate() {
        let _ = writeln!(
            xml,
            "        <DataArray type=\"Float64\" Name=\"{name}\" format=\"appended\" offset=\"{}\"/>",
            offsets[k]
        );
    }
    xml.push_str("      </PointData>\n      <CellData/>\n      <Coordinates>\n");
    for (k, name) in ["x", "y", "z"].iter().enumerate() {
        let _ = writeln!(
            xml,
            "        <DataArray type=\"Float64\" Name=\"{name}\" format=\"appended\" offset=\"{}\"/>",
            offsets[fields.len() + k]
        );
    }
    xml.push_str(
        "      </Coordinates>\n    </Piece>\n  </RectilinearGrid>\n  <AppendedData encoding=\"raw\">\n   _",
    );
    let mut out = Vec::with_capacity(xml.len() + at + 64);
    out.extend_from_slice(xml.as_bytes());
    for b in &blocks {
        out.extend_from_slice(&((8 * b.len()) as u64).to_le_bytes());
        for v in *b {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out.extend_from_slice(b"\n  </AppendedData>\n</VTKFile>\n");
    out
}
