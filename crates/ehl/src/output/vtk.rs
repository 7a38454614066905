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

/// A value type of VTK XML point data: its `type` attribute and its little-endian bytes.
pub trait VtkValue: Copy {
    /// the `DataArray` type name (`Float64`, `Float32`)
    const TYPE: &'static str;
    /// bytes per value
    const SIZE: usize;
    fn put(self, out: &mut Vec<u8>);
}

impl VtkValue for f64 {
    const TYPE: &'static str = "Float64";
    const SIZE: usize = 8;
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl VtkValue for f32 {
    const TYPE: &'static str = "Float32";
    const SIZE: usize = 4;
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

/// A VTK XML RectilinearGrid (`.vtr`) over the points `xs` x `ys` x `zs` (x varying fastest,
/// then y, then z): `fields` are `(name, values)` with `xs.len() * ys.len() * zs.len()` values
/// each, written as point data of their own type (`Float64` or `Float32`: the stress volume,
/// computed in single precision, is written as such at half the size), the coordinates as
/// `Float64`; `time_s` as in [`rectilinear_xml`].
pub fn rectilinear_volume_xml<T: VtkValue>(
    xs: &[f64],
    ys: &[f64],
    zs: &[f64],
    fields: &[(&str, &[T])],
    time_s: Option<f64>,
) -> Vec<u8> {
    let (nx, ny, nz) = (xs.len(), ys.len(), zs.len());
    let extent = format!("0 {} 0 {} 0 {}", nx - 1, ny - 1, nz - 1);
    // appended blocks in the order of their offsets: the fields, then x, y, z; each block is
    // its byte count (UInt64) and the values
    let mut offsets = Vec::with_capacity(fields.len() + 3);
    let mut at = 0usize;
    for (_, v) in fields {
        offsets.push(at);
        at += 8 + T::SIZE * v.len();
    }
    for c in [xs, ys, zs] {
        offsets.push(at);
        at += 8 + 8 * c.len();
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
            "        <DataArray type=\"{}\" Name=\"{name}\" format=\"appended\" offset=\"{}\"/>",
            T::TYPE,
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
    for (_, v) in fields {
        out.extend_from_slice(&((T::SIZE * v.len()) as u64).to_le_bytes());
        for &x in *v {
            x.put(&mut out);
        }
    }
    for c in [xs, ys, zs] {
        out.extend_from_slice(&((8 * c.len()) as u64).to_le_bytes());
        for v in c {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out.extend_from_slice(b"\n  </AppendedData>\n</VTKFile>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every `DataArray` of the appended `.vtr` as (type, name, bytes of its values), read
    /// back through its `offset` and its UInt64 byte count, as a VTK reader does.
    fn arrays(bytes: &[u8]) -> Vec<(String, String, Vec<u8>)> {
        let marker = b"<AppendedData encoding=\"raw\">\n   _";
        let start = bytes
            .windows(marker.len())
            .position(|w| w == marker)
            .expect("appended data")
            + marker.len();
        let xml = std::str::from_utf8(&bytes[..start]).expect("xml head");
        let attr = |line: &str, key: &str| -> String {
            let i = line.find(&format!("{key}=\"")).unwrap() + key.len() + 2;
            line[i..].split('"').next().unwrap().to_string()
        };
        xml.lines()
            .filter(|l| l.contains("format=\"appended\""))
            .map(|l| {
                let at = start + attr(l, "offset").parse::<usize>().unwrap();
                let len = u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap()) as usize;
                (
                    attr(l, "type"),
                    attr(l, "Name"),
                    bytes[at + 8..at + 8 + len].to_vec(),
                )
            })
            .collect()
    }

    /// Point data in single and in double precision, and the coordinates, read back exactly
    /// through the offsets and byte counts; the tail closes the file.
    #[test]
    fn volume_arrays_round_trip_in_either_precision() {
        let (xs, ys, zs) = ([0.0, 1.0, 2.0], [5.0, 6.0], [-0.5, -1.5]);
        let a32: Vec<f32> = (0..12).map(|k| k as f32 * 0.25 - 1.0).collect();
        let b32: Vec<f32> = (0..12).map(|k| 1e6 / (k as f32 + 1.0)).collect();
        let out = rectilinear_volume_xml(&xs, &ys, &zs, &[("a", &a32), ("b", &b32)], None);
        assert!(out.ends_with(b"</AppendedData>\n</VTKFile>\n"));
        let arr = arrays(&out);
        let f32s = |b: &[u8]| -> Vec<f32> {
            b.chunks(4)
                .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
                .collect()
        };
        let f64s = |b: &[u8]| -> Vec<f64> {
            b.chunks(8)
                .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
                .collect()
        };
        assert_eq!(arr.len(), 5);
        assert_eq!((arr[0].0.as_str(), arr[0].1.as_str()), ("Float32", "a"));
        assert_eq!(f32s(&arr[0].2), a32);
        assert_eq!(f32s(&arr[1].2), b32);
        assert_eq!((arr[2].0.as_str(), arr[2].1.as_str()), ("Float64", "x"));
        assert_eq!(f64s(&arr[2].2), xs);
        assert_eq!(f64s(&arr[3].2), ys);
        assert_eq!(f64s(&arr[4].2), zs);
        let a64: Vec<f64> = a32.iter().map(|&v| v as f64 + 1e-12).collect();
        let out = rectilinear_volume_xml(&xs, &ys, &zs, &[("a", &a64)], Some(0.5));
        let arr = arrays(&out);
        assert_eq!(arr[0].0, "Float64");
        assert_eq!(f64s(&arr[0].2), a64);
        assert_eq!(f64s(&arr[3].2), zs);
        // the double-precision file is the larger by the 4 bytes per value saved in single
        // (and the few digits the coordinates' larger offsets take in the XML)
        let single = rectilinear_volume_xml(&xs, &ys, &zs, &[("a", &a32)], Some(0.5));
        let extra = out.len() - single.len() - 4 * a32.len();
        assert!(extra <= 6, "{extra}");
    }
}
