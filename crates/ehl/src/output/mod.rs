//! Writers: `summary.json`, `fields.npz`, `fields.vtk`, `centerline.csv`, `axial.csv`,
//! `pressure.png`, `film.png`, `centerline.png` (see the "Outputs in DIR" table of the interface).
//!
//! [`write_all`] is atomic: every file goes into a temporary sibling folder
//! (`.<DIR name>.tmp-<pid>-<n>`), which replaces `DIR` only when every file is written. On any
//! failure the temporary folder is removed and an old `DIR` is left untouched, so a half-written
//! output folder never exists under the final name.
//!
//! Before anything is written the solution is checked: every field must have `nx * ny` values and
//! every value must be finite, and so must every summary figure. A NaN or infinity is refused with
//! an error naming the field (and the cell) or the summary key: the program never writes a NaN
//! silently. The one exception is `film`, which may be `+inf` in cells where there is no material
//! (beyond the end of the shorter roller, per the gap convention of the crate); those cells are
//! written as `inf` in `fields.npz`, `fields.vtk` and the csv files, drawn grey on `film.png` and
//! left out of every range and extreme.
//!
//! | file | writer |
//! | --- | --- |
//! | `summary.json` | [`summary`] |
//! | `fields.npz` | [`npz`] |
//! | `fields.vtk` | [`vtk`] |
//! | `centerline.csv`, `axial.csv` | [`csv`] |
//! | `pressure.png`, `film.png`, `centerline.png` | [`plot`] |

pub mod colormap;
pub mod csv;
pub mod npz;
pub mod plot;
pub mod summary;
pub mod synthetic;
pub mod vtk;

use crate::case::Case;
use crate::solution::Solution;
use crate::{Error, Result};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Names of the files [`write_all`] writes (film.png only when the solution has a film).
pub const SUMMARY_JSON: &str = "summary.json";
pub const FIELDS_NPZ: &str = "fields.npz";
pub const FIELDS_VTK: &str = "fields.vtk";
pub const CENTERLINE_CSV: &str = "centerline.csv";
pub const AXIAL_CSV: &str = "axial.csv";
pub const PRESSURE_PNG: &str = "pressure.png";
pub const FILM_PNG: &str = "film.png";
pub const CENTERLINE_PNG: &str = "centerline.png";

/// Writes every output of a solved case into `dir`, atomically: all files go to a temporary
/// sibling folder which replaces `dir` only when every file is written. An existing `dir` is
/// replaced (it must be a folder); missing parent folders are created.
///
/// Errors ([`Error::Output`], naming the path): a field of the wrong length, a NaN or infinite
/// value (naming the field or summary key), any I/O or drawing failure. After an error neither
/// `dir` nor the temporary folder has changed or remains.
pub fn write_all(dir: &Path, case: &Case, solution: &Solution) -> Result<()> {
    write_with(
        dir,
        |tmp| write_files(tmp, case, solution),
        || validate(dir, solution),
    )
}

/// Checks that a solution can be written: field lengths, finite values, finite summary figures.
/// [`write_all`] calls it first; it is public so that callers can check before a long write.
pub fn validate(dir: &Path, solution: &Solution) -> Result<()> {
    let g = &solution.grid;
    let err = |message: String| Error::Output {
        path: dir.to_path_buf(),
        message,
    };
    if g.nx == 0 || g.ny == 0 {
        return Err(err(format!("empty grid ({} x {} cells)", g.nx, g.ny)));
    }
    for (name, v) in [
        ("dx", g.dx),
        ("dy", g.dy),
        ("x_min", g.x_min),
        ("y_min", g.y_min),
    ] {
        if !v.is_finite() || ((name == "dx" || name == "dy") && v <= 0.0) {
            return Err(err(format!(
                "grid.{name} = {v} is not a finite positive size"
            )));
        }
    }
    for (name, field) in named_fields(solution) {
        if field.len() != g.len() {
            return Err(err(format!(
                "field `{name}` has {} values, the {} x {} grid needs {}",
                field.len(),
                g.nx,
                g.ny,
                g.len()
            )));
        }
        let allow_pos_inf = name == "film";
        if let Some(k) = field
            .iter()
            .position(|v| v.is_nan() || (v.is_infinite() && !(allow_pos_inf && *v > 0.0)))
        {
            let (i, j) = (k % g.nx, k / g.nx);
            return Err(err(format!(
                "field `{name}` is {} at cell (i = {i}, j = {j}), x = {:.6e} m, y = {:.6e} m; \
                 refusing to write a non-finite value",
                field[k],
                g.x(i),
                g.y(j)
            )));
        }
    }
    if solution
        .fields
        .film
        .as_ref()
        .is_some_and(|f| f.iter().all(|v| !v.is_finite()))
    {
        return Err(err("field `film` has no finite value".into()));
    }
    summary::check_finite(&solution.summary).map_err(|key| {
        err(format!(
            "summary figure `{key}` is not finite; refusing to write a non-finite value"
        ))
    })
}

/// The fields present in a solution, by their output name, in output order.
pub(crate) fn named_fields(solution: &Solution) -> Vec<(&'static str, &[f64])> {
    let f = &solution.fields;
    let mut v: Vec<(&'static str, &[f64])> = vec![
        ("pressure", &f.pressure[..]),
        ("deformation", &f.deformation[..]),
    ];
    if let Some(h) = &f.film {
        v.push(("film", &h[..]));
    }
    if let Some(e) = &f.viscosity {
        v.push(("viscosity", &e[..]));
    }
    if let Some(r) = &f.density {
        v.push(("density", &r[..]));
    }
    v
}

fn write_files(tmp: &Path, case: &Case, solution: &Solution) -> Result<()> {
    summary::write(&tmp.join(SUMMARY_JSON), case, solution)?;
    npz::write(&tmp.join(FIELDS_NPZ), solution)?;
    vtk::write(&tmp.join(FIELDS_VTK), case, solution)?;
    csv::write_centerline(&tmp.join(CENTERLINE_CSV), solution)?;
    csv::write_axial(&tmp.join(AXIAL_CSV), solution)?;
    plot::write_pressure(&tmp.join(PRESSURE_PNG), case, solution)?;
    if solution.fields.film.is_some() {
        plot::write_film(&tmp.join(FILM_PNG), case, solution)?;
    }
    plot::write_centerline(&tmp.join(CENTERLINE_PNG), case, solution)?;
    Ok(())
}

static SEQ: AtomicUsize = AtomicUsize::new(0);

fn io_err(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Output {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// The atomic folder write: `check` runs first (nothing touched if it fails), then `fill` writes
/// into a fresh temporary sibling folder, which then replaces `dir`.
fn write_with(
    dir: &Path,
    fill: impl FnOnce(&Path) -> Result<()>,
    check: impl FnOnce() -> Result<()>,
) -> Result<()> {
    check()?;
    let name = dir
        .file_name()
        .ok_or_else(|| io_err(dir, "the output folder needs a name (not `..` or `/`)"))?
        .to_string_lossy()
        .into_owned();
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if dir.exists() && !dir.is_dir() {
        return Err(io_err(dir, "exists and is not a folder; not replacing it"));
    }
    std::fs::create_dir_all(&parent).map_err(|e| io_err(&parent, e))?;
    let tag = format!(
        "{}-{}",
        std::process::id(),
        SEQ.fetch_add(1, Ordering::Relaxed)
    );
    let tmp = parent.join(format!(".{name}.tmp-{tag}"));
    if tmp.exists() {
        // a leftover of a crashed process with the same pid: it is ours to clear
        std::fs::remove_dir_all(&tmp).map_err(|e| io_err(&tmp, e))?;
    }
    std::fs::create_dir(&tmp).map_err(|e| io_err(&tmp, e))?;
    let result = fill(&tmp).and_then(|()| replace_dir(&tmp, dir, &parent, &name, &tag));
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    result
}

/// Moves `tmp` to `dir`; an existing `dir` is first moved aside and removed only once the new
/// folder is in place (it is restored if the move fails).
fn replace_dir(tmp: &Path, dir: &Path, parent: &Path, name: &str, tag: &str) -> Result<()> {
    if dir.is_dir() {
        let old = parent.join(format!(".{name}.old-{tag}"));
        std::fs::rename(dir, &old).map_err(|e| io_err(dir, e))?;
        if let Err(e) = std::fs::rename(tmp, dir) {
            let _ = std::fs::rename(&old, dir);
            return Err(io_err(dir, e));
        }
        std::fs::remove_dir_all(&old).map_err(|e| io_err(&old, e))?;
        Ok(())
    } else {
        std::fs::rename(tmp, dir).map_err(|e| io_err(dir, e))
    }
}

/// Index of the row nearest y = 0 (the axial centre); for a tie the lower row.
pub(crate) fn centre_row(solution: &Solution) -> usize {
    let g = &solution.grid;
    nearest(g.ny, |j| g.y(j), 0.0)
}

/// Index of the column nearest the x of the pressure maximum (`summary.max_pressure_at_m[0]`).
pub(crate) fn max_pressure_column(solution: &Solution) -> usize {
    let g = &solution.grid;
    nearest(g.nx, |i| g.x(i), solution.summary.max_pressure_at_m[0])
}

fn nearest(n: usize, coord: impl Fn(usize) -> f64, target: f64) -> usize {
    (0..n)
        .min_by(|&a, &b| {
            (coord(a) - target)
                .abs()
                .total_cmp(&(coord(b) - target).abs())
        })
        .unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failing_fill_leaves_no_dir_and_no_temp() {
        let root = tempfile::tempdir().unwrap();
        let dir = root.path().join("out");
        let r = write_with(
            &dir,
            |tmp| {
                std::fs::write(tmp.join("summary.json"), "{}").unwrap();
                Err(io_err(&tmp.join("fields.npz"), "disk full (injected)"))
            },
            || Ok(()),
        );
        let e = r.unwrap_err().to_string();
        assert!(e.contains("fields.npz") && e.contains("injected"), "{e}");
        assert!(!dir.exists());
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 0);
    }

    #[test]
    fn failing_fill_keeps_old_dir() {
        let root = tempfile::tempdir().unwrap();
        let dir = root.path().join("out");
        std::fs::create_dir(&dir).unwrap();
        std::fs::write(dir.join("old.txt"), "old").unwrap();
        let r = write_with(&dir, |_| Err(io_err(&dir, "injected")), || Ok(()));
        assert!(r.is_err());
        assert_eq!(std::fs::read_to_string(dir.join("old.txt")).unwrap(), "old");
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 1);
    }

    #[test]
    fn success_replaces_old_dir() {
        let root = tempfile::tempdir().unwrap();
        let dir = root.path().join("out");
        std::fs::create_dir(&dir).unwrap();
        std::fs::write(dir.join("stale.txt"), "old").unwrap();
        write_with(
            &dir,
            |tmp| std::fs::write(tmp.join("new.txt"), "new").map_err(|e| io_err(tmp, e)),
            || Ok(()),
        )
        .unwrap();
        assert!(!dir.join("stale.txt").exists());
        assert_eq!(std::fs::read_to_string(dir.join("new.txt")).unwrap(), "new");
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 1);
    }

    #[test]
    fn nearest_index() {
        let xs = [-1.0, -0.2, 0.3, 1.0];
        assert_eq!(nearest(4, |i| xs[i], 0.0), 1);
        assert_eq!(nearest(4, |i| xs[i], 0.9), 3);
    }
}
