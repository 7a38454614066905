//! `centerline.csv` and `axial.csv`: profiles through the solution, comma-separated, one header
//! line whose names carry the unit (`x_m`, `pressure_pa`, ...), numbers in Rust's shortest
//! round-trip exponent form (`1.05e9`), which numpy, pandas and spreadsheets read.
//!
//! * `centerline.csv`: along x at the axial centre (the grid row nearest y = 0; the only row of an
//!   infinite line contact): `x_m, pressure_pa, deformation_m` and, when the solution has them,
//!   `film_m, viscosity_pa_s, density_kg_m3`. Columns of fields the solution does not have are
//!   left out (not left blank), so a dry contact without a film has three columns.
//! * `axial.csv`: along y through the grid column nearest the x of the pressure maximum
//!   (`summary.max_pressure_at_m[0]`): `y_m, pressure_pa, deformation_m` and `film_m` when present.
//!
//! A film cell with no material (`+inf`) is written `inf`.

use crate::solution::Solution;
use crate::Result;
use std::fmt::Write as _;
use std::path::Path;

/// Column name of each field.
fn column(name: &str) -> &'static str {
    match name {
        "pressure" => "pressure_pa",
        "deformation" => "deformation_m",
        "film" => "film_m",
        "viscosity" => "viscosity_pa_s",
        "density" => "density_kg_m3",
        _ => "value",
    }
}

fn table(first: &str, coords: &[f64], cols: &[(&str, Vec<f64>)]) -> String {
    let mut s = String::with_capacity(24 * coords.len() * (cols.len() + 1) + 64);
    s.push_str(first);
    for (name, _) in cols {
        s.push(',');
        s.push_str(column(name));
    }
    s.push('\n');
    for (k, c) in coords.iter().enumerate() {
        let _ = write!(s, "{c:e}");
        for (_, v) in cols {
            let _ = write!(s, ",{:e}", v[k]);
        }
        s.push('\n');
    }
    s
}

/// The text of `centerline.csv`.
pub fn centerline(solution: &Solution) -> String {
    let g = &solution.grid;
    let j = super::centre_row(solution);
    let cols: Vec<(&str, Vec<f64>)> = super::named_fields(solution)
        .into_iter()
        .map(|(n, f)| (n, f[j * g.nx..(j + 1) * g.nx].to_vec()))
        .collect();
    table("x_m", &g.xs(), &cols)
}

/// The text of `axial.csv`.
pub fn axial(solution: &Solution) -> String {
    let g = &solution.grid;
    let i = super::max_pressure_column(solution);
    let cols: Vec<(&str, Vec<f64>)> = super::named_fields(solution)
        .into_iter()
        .filter(|(n, _)| matches!(*n, "pressure" | "deformation" | "film"))
        .map(|(n, f)| (n, (0..g.ny).map(|j| f[g.idx(i, j)]).collect()))
        .collect();
    table("y_m", &g.ys(), &cols)
}

fn write_text(path: &Path, text: &str) -> Result<()> {
    std::fs::write(path, text).map_err(|e| super::io_err(path, e))
}

/// Writes `centerline.csv` to `path`.
pub fn write_centerline(path: &Path, solution: &Solution) -> Result<()> {
    write_text(path, &centerline(solution))
}

/// Writes `axial.csv` to `path`.
pub fn write_axial(path: &Path, solution: &Solution) -> Result<()> {
    write_text(path, &axial(solution))
}
