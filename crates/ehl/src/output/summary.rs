//! `summary.json`: the summary figures, the resolved case and the program version.
//!
//! Layout (one JSON object, keys in this order):
//!
//! * `"title"`: the case title; `"version"`: [`crate::VERSION`];
//! * every [`Summary`] field under its own name (`converged`, `iterations`, `load_n`,
//!   `max_pressure_pa`, ... see the interface), options that do not apply are left out;
//! * `"grid_m"`: the solved grid in metres: `nx`, `ny`, `x_min`, `x_max`, `y_min`, `y_max` (cell
//!   edges), `dx`, `dy` (for an infinite line contact `ny = 1` and the y extent is the 1 m
//!   reference length);
//! * `"case"`: the resolved case (every default filled in), with the case file's key names.
//!
//! JSON has no infinity: an infinite length or radius in the resolved case (an infinite line
//! contact, a flat, a ball's axial length) is written as the string `"inf"` (`"-inf"` for a
//! negative one), the spelling a case file accepts, so the resolved case reads back into a case.
//! The summary figures themselves are always finite (see [`check_finite`]); keys inside `"case"`
//! are sorted alphabetically.

use crate::case::Case;
use crate::solution::{Solution, Summary};
use crate::{Error, Result};
use serde::Serialize;
use std::io::Write;
use std::path::Path;

#[derive(Serialize)]
struct GridOut {
    nx: usize,
    ny: usize,
    x_min: f64,
    x_max: f64,
    y_min: f64,
    y_max: f64,
    dx: f64,
    dy: f64,
}

#[derive(Serialize)]
struct SummaryFile<'a> {
    title: &'a str,
    version: &'static str,
    #[serde(flatten)]
    summary: &'a Summary,
    grid_m: GridOut,
    case: serde_json::Value,
}

/// The JSON document written to `summary.json`.
pub fn to_json(case: &Case, solution: &Solution) -> Result<String> {
    let g = &solution.grid;
    let err = |message: String| Error::Output {
        path: super::SUMMARY_JSON.into(),
        message,
    };
    let file = SummaryFile {
        title: &case.title,
        version: crate::VERSION,
        summary: &solution.summary,
        grid_m: GridOut {
            nx: g.nx,
            ny: g.ny,
            x_min: g.x_min,
            x_max: g.x_max(),
            y_min: g.y_min,
            y_max: g.y_max(),
            dx: g.dx,
            dy: g.dy,
        },
        case: case_json(case).map_err(|e| err(format!("resolved case: {e}")))?,
    };
    let mut s = serde_json::to_string_pretty(&file).map_err(|e| err(e.to_string()))?;
    s.push('\n');
    Ok(s)
}

/// Writes `summary.json` to `path`.
pub fn write(path: &Path, case: &Case, solution: &Solution) -> Result<()> {
    let text = to_json(case, solution).map_err(|e| match e {
        Error::Output { message, .. } => Error::Output {
            path: path.to_path_buf(),
            message,
        },
        other => other,
    })?;
    let mut f = std::fs::File::create(path).map_err(|e| super::io_err(path, e))?;
    f.write_all(text.as_bytes())
        .map_err(|e| super::io_err(path, e))
}

/// The resolved case as JSON, non-finite numbers written as the strings `"inf"`, `"-inf"`,
/// `"nan"` (see the module documentation).
pub fn case_json(case: &Case) -> std::result::Result<serde_json::Value, String> {
    // TOML keeps infinities (serde_json would turn them into null), so go through it.
    let v = toml::Value::try_from(case).map_err(|e| e.to_string())?;
    Ok(toml_to_json(v))
}

fn toml_to_json(v: toml::Value) -> serde_json::Value {
    use serde_json::Value as J;
    match v {
        toml::Value::String(s) => J::String(s),
        toml::Value::Integer(i) => J::from(i),
        toml::Value::Float(f) if f.is_finite() => J::from(f),
        toml::Value::Float(f) => J::String(
            if f.is_nan() {
                "nan"
            } else if f > 0.0 {
                "inf"
            } else {
                "-inf"
            }
            .into(),
        ),
        toml::Value::Boolean(b) => J::Bool(b),
        toml::Value::Datetime(d) => J::String(d.to_string()),
        toml::Value::Array(a) => J::Array(a.into_iter().map(toml_to_json).collect()),
        toml::Value::Table(t) => {
            J::Object(t.into_iter().map(|(k, v)| (k, toml_to_json(v))).collect())
        }
    }
}

/// `Ok` when every number in the summary is finite, else `Err(key)` naming the first figure that
/// is not (a dotted path, e.g. `max_pressure_at_m.1`).
pub fn check_finite(summary: &Summary) -> std::result::Result<(), String> {
    let v = toml::Value::try_from(summary).map_err(|e| format!("(unserialisable: {e})"))?;
    match first_non_finite(&v, "") {
        Some(key) => Err(key),
        None => Ok(()),
    }
}

fn first_non_finite(v: &toml::Value, path: &str) -> Option<String> {
    let join = |k: &str| {
        if path.is_empty() {
            k.to_string()
        } else {
            format!("{path}.{k}")
        }
    };
    match v {
        toml::Value::Float(f) if !f.is_finite() => Some(path.to_string()),
        toml::Value::Array(a) => a
            .iter()
            .enumerate()
            .find_map(|(i, x)| first_non_finite(x, &join(&i.to_string()))),
        toml::Value::Table(t) => t.iter().find_map(|(k, x)| first_non_finite(x, &join(k))),
        _ => None,
    }
}
