//! `ehl sweep`: a case over the grid of all combinations of the `--vary` values, solved in
//! parallel, one sub-folder per point and `sweep.csv` rebuilt from every finished point.

use crate::io;
use crate::progress::Bar;
use crate::{default_out, SweepArgs, EXIT_NOT_CONVERGED};
use anyhow::{Context, Result};
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The most points a sweep may have: per `--vary` (N of a range, or the values of a list) and in
/// all (the product over every `--vary`). Generous for studies, and checked before anything is
/// allocated per point.
pub const MAX_POINTS: usize = 100_000;

/// The summary figures written to sweep.csv after the varied keys (empty where absent).
pub const FIGURES: &[&str] = &[
    "converged",
    "iterations",
    "residual",
    "wall_time_s",
    "load_n",
    "load_error",
    "max_pressure_pa",
    "hertz_pressure_pa",
    "hertz_half_width_m",
    "approach_m",
    "contact_area_m2",
    "central_film_m",
    "min_film_m",
    "centerline_min_film_m",
    "friction_coefficient",
    "friction_force_n",
    // transient runs: the extremes and the mean over the travel
    "max_pressure_over_travel_pa",
    "min_film_over_travel_m",
    "friction_coefficient_mean_over_travel",
    // thermal runs
    "max_film_temperature_k",
    "mean_film_temperature_k",
    "flash_temperature_k",
    "heat_generated_w",
    // [stress] and [fatigue]
    "max_von_mises_pa",
    "max_shear_pa",
    "max_orthogonal_shear_pa",
    "fatigue_integral",
    "smooth_fatigue_integral",
    "life_ratio",
];

/// One `--vary KEY=SPEC`.
#[derive(Debug, Clone)]
pub struct Vary {
    /// dotted key, as the case file writes it
    pub key: String,
    /// each value as TOML text (given to `--set`)
    pub values: Vec<String>,
}

/// Splits at commas that are not inside quotes, braces or brackets.
fn split_top_level(s: &str) -> Vec<String> {
    let (mut out, mut cur, mut depth, mut quote) = (Vec::new(), String::new(), 0i32, None);
    for c in s.chars() {
        match (quote, c) {
            (Some(q), _) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '{' | '[') => depth += 1,
            (None, '}' | ']') => depth -= 1,
            (None, ',') if depth == 0 => {
                out.push(std::mem::take(&mut cur));
                continue;
            }
            _ => {}
        }
        cur.push(c);
    }
    out.push(cur);
    out.into_iter().map(|v| v.trim().to_string()).collect()
}

/// A number as TOML text, rounded to 12 significant digits to drop linspace round-off.
fn number_text(v: f64) -> String {
    let rounded: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    format!("{rounded:?}")
}

impl Vary {
    /// Parses `KEY=START:STOP:N` or `KEY=v1,v2,...`; the key must be a valid case key.
    pub fn parse(s: &str) -> std::result::Result<Vary, String> {
        let (key, spec) = ehl::case::split_assignment(s).ok_or_else(|| {
            "expected KEY=START:STOP:N or KEY=v1,v2,... (e.g. motion.slide_to_roll=0:0.1:11)"
                .to_string()
        })?;
        let key = ehl::case::check_key(key).map_err(|m| format!("`{key}`: {m}"))?;
        if spec.is_empty() {
            return Err(format!("no values given for `{key}`"));
        }
        let parts: Vec<&str> = spec.split(':').collect();
        let values = if parts.len() == 3 && !spec.contains(['"', '{', '[']) {
            let num = |t: &str, what: &str| -> std::result::Result<f64, String> {
                let v = t
                    .trim()
                    .parse::<f64>()
                    .map_err(|_| format!("{what} `{t}` in `{key}={spec}` is not a number"))?;
                if !v.is_finite() {
                    return Err(format!(
                        "{what} `{t}` in `{key}={spec}` is not a finite number"
                    ));
                }
                Ok(v)
            };
            let (a, b) = (num(parts[0], "START")?, num(parts[1], "STOP")?);
            let n: usize = parts[2].trim().parse().map_err(|_| {
                format!(
                    "N `{}` in `{key}={spec}` is not a whole number of points",
                    parts[2]
                )
            })?;
            if n == 0 {
                return Err(format!("N in `{key}={spec}` must be at least 1"));
            }
            if n > MAX_POINTS {
                return Err(format!(
                    "N = {n} in `{key}={spec}` is more than the {MAX_POINTS} points a sweep may have"
                ));
            }
            if n == 1 && a != b {
                return Err(format!(
                    "`{key}={spec}` asks for 1 point between two different values; give N >= 2 or one value"
                ));
            }
            let values: Vec<f64> = (0..n)
                .map(|i| {
                    if i + 1 == n {
                        b
                    } else {
                        // a + (b - a) t, written so that the difference cannot overflow
                        let t = i as f64 / (n - 1).max(1) as f64;
                        a * (1.0 - t) + b * t
                    }
                })
                .collect();
            if values.iter().any(|v| !v.is_finite()) {
                return Err(format!(
                    "`{key}={spec}` gives a value that is not a finite number"
                ));
            }
            values.into_iter().map(number_text).collect()
        } else if parts.len() > 1 && !spec.contains(['"', '{', '[']) {
            return Err(format!(
                "`{key}={spec}`: a range is written START:STOP:N (three parts), e.g. 0:0.1:11"
            ));
        } else {
            let vals = split_top_level(spec);
            if vals.iter().any(|v| v.is_empty()) {
                return Err(format!("`{key}={spec}` has an empty value in its list"));
            }
            if vals.len() > MAX_POINTS {
                return Err(format!(
                    "`{key}=...` lists {} values, more than the {MAX_POINTS} points a sweep may have",
                    vals.len()
                ));
            }
            vals
        };
        Ok(Vary { key, values })
    }
}

/// `--shard K/N`.
#[derive(Debug, Clone, Copy)]
pub struct Shard {
    pub k: usize,
    pub n: usize,
}

impl Shard {
    pub fn parse(s: &str) -> std::result::Result<Shard, String> {
        let bad = || format!("expected K/N with 0 <= K < N (e.g. 0/4), found `{s}`");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let k: usize = k.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        if n == 0 || k >= n {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }
}

/// One point of the sweep.
struct Point {
    /// one value text per --vary
    values: Vec<String>,
    folder: String,
}

/// A value for a folder name or a csv cell: TOML text without quotes, `1.0` -> `1`.
fn label(v: &str) -> String {
    let v = v.trim();
    let v = v
        .strip_prefix('"')
        .and_then(|s| s.strip_suffix('"'))
        .unwrap_or(v);
    match v.strip_suffix(".0") {
        Some(int) if int.parse::<i64>().is_ok() => int.to_string(),
        _ => v.to_string(),
    }
}

fn sanitize(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "._+-=".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect()
}

fn points(varies: &[Vary]) -> Vec<Point> {
    let total: usize = varies.iter().map(|v| v.values.len()).product();
    let width = total.saturating_sub(1).to_string().len().max(3);
    // short names: the last key segment, unless two varied keys share it
    let leaves: Vec<&str> = varies
        .iter()
        .map(|v| v.key.rsplit('.').next().unwrap_or(&v.key))
        .collect();
    let names: Vec<&str> = varies
        .iter()
        .zip(&leaves)
        .map(|(v, l)| {
            if leaves.iter().filter(|m| *m == l).count() > 1 {
                v.key.as_str()
            } else {
                l
            }
        })
        .collect();
    (0..total)
        .map(|index| {
            // first --vary outermost
            let mut rest = index;
            let mut values = vec![String::new(); varies.len()];
            for (d, v) in varies.iter().enumerate().rev() {
                values[d] = v.values[rest % v.values.len()].clone();
                rest /= v.values.len();
            }
            let mut folder = format!("p{index:0width$}");
            for (n, v) in names.iter().zip(&values) {
                folder.push('_');
                folder.push_str(&sanitize(&format!("{n}={}", label(v))));
            }
            Point { values, folder }
        })
        .collect()
}

fn csv_cell(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// A summary figure read back from summary.json (top level, or under "summary").
fn figure(json: &serde_json::Value, key: &str) -> String {
    let v = json
        .get(key)
        .or_else(|| json.get("summary").and_then(|s| s.get(key)));
    match v {
        Some(serde_json::Value::Bool(b)) => b.to_string(),
        Some(serde_json::Value::Number(n)) => n.to_string(),
        Some(serde_json::Value::String(s)) => s.clone(),
        _ => String::new(),
    }
}

/// Rebuilds sweep.csv from every point whose folder holds a summary.json. Returns the number
/// of rows. Written to a temporary file, then renamed, so readers never see half a file.
fn write_csv(dir: &Path, varies: &[Vary], pts: &[Point]) -> Result<usize> {
    let mut text = String::new();
    let header: Vec<String> = varies
        .iter()
        .map(|v| v.key.clone())
        .chain(FIGURES.iter().map(|s| s.to_string()))
        .chain(["folder".to_string()])
        .collect();
    text.push_str(&header.join(","));
    text.push('\n');
    let mut rows = 0;
    for p in pts {
        let path = dir.join(&p.folder).join("summary.json");
        let Ok(raw) = std::fs::read_to_string(&path) else {
            continue;
        };
        let json: serde_json::Value =
            serde_json::from_str(&raw).with_context(|| format!("reading {}", path.display()))?;
        let cells: Vec<String> = p
            .values
            .iter()
            .map(|v| label(v))
            .chain(FIGURES.iter().map(|k| figure(&json, k)))
            .chain([p.folder.clone()])
            .map(|c| csv_cell(&c))
            .collect();
        text.push_str(&cells.join(","));
        text.push('\n');
        rows += 1;
    }
    let out = dir.join("sweep.csv");
    write_atomic(&out, |tmp| {
        std::fs::write(tmp, &text).with_context(|| format!("writing {}", out.display()))
    })?;
    Ok(rows)
}

/// The figure a study is usually about, with its axis label and scale to display units.
const PLOT_FIGURES: [(&str, &str, f64); 7] = [
    // a study with [fatigue] and features is about the life they cost
    ("life_ratio", "life against smooth surfaces (-)", 1.0),
    // a transient run's friction is read over the whole travel, not at its last step
    (
        "friction_coefficient_mean_over_travel",
        "friction coefficient, mean over the travel (-)",
        1.0,
    ),
    ("friction_coefficient", "friction coefficient (-)", 1.0),
    ("central_film_m", "central film thickness (µm)", 1e6),
    ("max_pressure_pa", "maximum pressure (GPa)", 1e-9),
    ("approach_m", "approach (µm)", 1e6),
    ("load_n", "load (N)", 1.0),
];

/// Draws `sweep.png`: the first summary figure of [`PLOT_FIGURES`] that the points report,
/// against the first varied key, one curve per value of the second varied key (if any). Only
/// converged points are drawn; a study over non-numeric values draws nothing.
fn write_plot(dir: &Path, title: &str, varies: &[Vary], pts: &[Point]) -> Result<()> {
    let Some(first) = varies.first() else {
        return Ok(());
    };
    let mut rows = Vec::new();
    for p in pts {
        let Ok(raw) = std::fs::read_to_string(dir.join(&p.folder).join("summary.json")) else {
            continue;
        };
        let Ok(json) = serde_json::from_str::<serde_json::Value>(&raw) else {
            continue;
        };
        if figure(&json, "converged") != "true" {
            continue;
        }
        let Ok(x) = label(&p.values[0]).parse::<f64>() else {
            return Ok(());
        };
        let group = p.values.get(1).map(|v| label(v)).unwrap_or_default();
        rows.push((x, group, json));
    }
    let Some(&(key, axis, scale)) = PLOT_FIGURES.iter().find(|(k, _, _)| {
        rows.iter()
            .any(|(_, _, j)| figure(j, k).parse::<f64>().is_ok())
    }) else {
        return Ok(());
    };
    let mut series: Vec<ehl::output::plot::Series> = Vec::new();
    for (x, group, json) in &rows {
        let Ok(y) = figure(json, key).parse::<f64>() else {
            continue;
        };
        let name = match varies.get(1) {
            Some(v) => format!("{} = {group}", v.key),
            None => key.to_string(),
        };
        match series.iter_mut().find(|s| s.label == name) {
            Some(s) => s.points.push((*x, y * scale)),
            None => series.push(ehl::output::plot::Series {
                label: name,
                points: vec![(*x, y * scale)],
            }),
        }
    }
    if series.is_empty() {
        return Ok(());
    }
    let out = dir.join("sweep.png");
    // the unit of the varied key: the [stress] depths are in b, the features' sizes in m,
    // the rest from the key's last segment (the case file is otherwise all SI)
    let last = first.key.rsplit('.').next().unwrap_or("");
    let feature = first.key.starts_with("features[");
    let unit = match last {
        "depth" | "window" if first.key.starts_with("stress.") => " (b)",
        "width" | "depth" | "amplitude" | "wavelength" | "x" | "y" | "dx" | "dy" | "row_pitch"
        | "column_pitch"
            if feature =>
        {
            " (m)"
        }
        "force" | "load" => " (N)",
        "force_per_length" => " (N/m)",
        "max_hertz_pressure" | "youngs_modulus" | "shear_modulus" | "eyring_stress" => " (Pa)",
        "entrainment_speed" => " (m/s)",
        "radius" | "radius_y" | "length" | "crown_radius" | "edge_length" | "edge_radius"
        | "axial_offset" | "depth_m" => " (m)",
        "tilt" | "skew" | "angle" => " (rad)",
        "viscosity" => " (Pa s)",
        "pressure_viscosity_coefficient" => " (1/Pa)",
        "density" => " (kg/m³)",
        _ => " (-)",
    };
    // lengths drawn in um or mm where metres would print as 0.0000002
    let largest = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0.abs()))
        .fold(0.0f64, f64::max);
    let (unit, scale) = match unit {
        " (m)" if largest < 1e-3 => (" (µm)", 1e6),
        " (m)" if largest < 1.0 => (" (mm)", 1e3),
        u => (u, 1.0),
    };
    for s in series.iter_mut() {
        s.points.iter_mut().for_each(|p| p.0 *= scale);
    }
    write_atomic(&out, |path| {
        Ok(ehl::output::plot::write_xy(
            path,
            title,
            &format!(
                "{} converged points; the numbers are in sweep.csv",
                rows.len()
            ),
            &format!("{}{unit}", first.key),
            axis,
            &series,
        )?)
    })
}

/// Writes `out` through a temporary sibling `.<name>.<pid>.tmp.<ext>` (the picture writer
/// needs the extension), renamed over `out` when complete, so that a reader never sees half a
/// file. A Ctrl-C removes the temporary file; a killed process's is removed by the next
/// [`SummaryLock`].
fn write_atomic(out: &Path, fill: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let name = out.file_name().unwrap_or_default().to_string_lossy();
    let ext = out.extension().unwrap_or_default().to_string_lossy();
    let tmp = out.with_file_name(format!(".{name}.{}.tmp.{ext}", std::process::id()));
    ehl::output::register_temp(&tmp);
    let r = fill(&tmp).and_then(|()| {
        std::fs::rename(&tmp, out).with_context(|| format!("writing {}", out.display()))
    });
    if r.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    ehl::output::unregister_temp(&tmp);
    r
}

/// The lock on a sweep folder's summary files (sweep.csv, sweep.png): `.sweep.lock` in the
/// folder, waited for (a rebuild takes a moment), so that concurrent shards rebuild one after
/// the other. The file stays (it is ehl's own folder).
struct SummaryLock {
    _file: std::fs::File,
}

impl SummaryLock {
    fn acquire(dir: &Path) -> Result<SummaryLock> {
        let path = dir.join(".sweep.lock");
        let file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .with_context(|| format!("writing {}", path.display()))?;
        match file.lock() {
            Ok(()) => {}
            // a file system without locks: go on unlocked
            Err(e) if e.kind() == std::io::ErrorKind::Unsupported => {}
            Err(e) => {
                return Err(anyhow::Error::new(e).context(format!("locking {}", path.display())))
            }
        }
        // temporary files of shards that were killed
        if let Ok(entries) = std::fs::read_dir(dir) {
            for e in entries.flatten() {
                let name = e.file_name().to_string_lossy().into_owned();
                let pid = [".sweep.csv.", ".sweep.png."]
                    .iter()
                    .find_map(|p| name.strip_prefix(p))
                    .and_then(|r| r.split_once(".tmp."))
                    .and_then(|(pid, _)| pid.parse::<u32>().ok());
                if pid.is_some_and(|p| !ehl::output::pid_is_running(p)) {
                    let _ = std::fs::remove_file(e.path());
                }
            }
        }
        Ok(SummaryLock { _file: file })
    }
}

enum Outcome {
    Solved { converged: bool },
    Skipped,
    Failed(String),
}

pub fn sweep(args: SweepArgs) -> Result<ExitCode> {
    let case_path = &args.case.case;
    let file = case_path.display().to_string();
    let text = ehl::case::read_case_text(case_path)?;
    for (i, v) in args.vary.iter().enumerate() {
        if args.vary[..i].iter().any(|w| w.key == v.key) {
            return Err(crate::Usage(format!(
                "--vary {} is given twice; give each varied key once",
                v.key
            ))
            .into());
        }
    }
    // the size first: nothing per point is made before the total is known to be bounded
    let total = args
        .vary
        .iter()
        .try_fold(1usize, |acc, v| acc.checked_mul(v.values.len()))
        .filter(|&n| n <= MAX_POINTS);
    if total.is_none() {
        let sizes: Vec<String> = args
            .vary
            .iter()
            .map(|v| format!("{} ({})", v.values.len(), v.key))
            .collect();
        return Err(crate::Usage(format!(
            "--vary: the sweep would have {} points, more than the {MAX_POINTS} a sweep may \
             have; vary fewer values, or split the study into several sweeps",
            sizes.join(" x ")
        ))
        .into());
    }
    let pts = points(&args.vary);

    // validate every point before solving anything (and before creating any folder)
    let mut cases = Vec::with_capacity(pts.len());
    for p in &pts {
        let mut sets = args.case.set.clone();
        sets.extend(
            args.vary
                .iter()
                .zip(&p.values)
                .map(|(v, val)| format!("{}={val}", v.key)),
        );
        let case = ehl::case::parse_str(&text, &file, &sets)
            .with_context(|| format!("sweep point {}", p.folder))?;
        cases.push(case);
    }

    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| default_out(case_path, "-sweep"));
    let shard = args.shard.unwrap_or(Shard { k: 0, n: 1 });
    let mine: Vec<usize> = (0..pts.len()).filter(|i| i % shard.n == shard.k).collect();
    // before solving: every point folder to write must be ehl's to replace
    for &i in &mine {
        let folder = dir.join(&pts[i].folder);
        if !folder.join("summary.json").is_file() {
            ehl::output::check_replaceable(&folder)?;
        }
    }
    ehl::output::create_folder(&dir)?;

    let jobs = args.jobs.map(|j| j as usize).unwrap_or_else(|| {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
    });
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .context("starting the worker threads")?;
    let bar = Bar::new(args.quiet, mine.len() as u64);
    let outcomes: Vec<Outcome> = pool.install(|| {
        mine.par_iter()
            .map(|&i| {
                let p = &pts[i];
                let folder: PathBuf = dir.join(&p.folder);
                let outcome = if folder.join("summary.json").is_file() {
                    Outcome::Skipped
                } else {
                    // one writer per point folder (shards of one sweep may run at once)
                    let solved = ehl::output::OutputLock::acquire(&folder)
                        .map_err(anyhow::Error::from)
                        .and_then(|lock| {
                            let s = crate::solve_and_write(
                                &lock,
                                &cases[i],
                                &ehl::run::Silent,
                                &|| {},
                            )?;
                            Ok(s.summary.converged)
                        });
                    match solved {
                        Ok(converged) => Outcome::Solved { converged },
                        Err(e) => Outcome::Failed(format!("sweep point {}: {e}", p.folder)),
                    }
                };
                bar.inc(&p.folder);
                outcome
            })
            .collect()
    });
    bar.finish();

    let title = cases.first().map(|c| c.title.clone()).unwrap_or_default();
    let rows = {
        // shards rebuild sweep.csv and sweep.png one at a time, each from every point finished
        // before it, so that the last rebuild holds every point
        let _lock = SummaryLock::acquire(&dir)?;
        let rows = write_csv(&dir, &args.vary, &pts)?;
        write_plot(&dir, &title, &args.vary, &pts)?;
        rows
    };
    let solved = outcomes
        .iter()
        .filter(|o| matches!(o, Outcome::Solved { .. }))
        .count();
    let not_converged = outcomes
        .iter()
        .filter(|o| matches!(o, Outcome::Solved { converged: false }))
        .count();
    let skipped = outcomes
        .iter()
        .filter(|o| matches!(o, Outcome::Skipped))
        .count();
    let failed: Vec<&String> = outcomes
        .iter()
        .filter_map(|o| match o {
            Outcome::Failed(m) => Some(m),
            _ => None,
        })
        .collect();
    for m in &failed {
        io::err(&format!("error: {m}"));
    }
    let shard_note = if shard.n > 1 {
        format!(" (shard {}/{})", shard.k, shard.n)
    } else {
        String::new()
    };
    io::out(&format!(
        "sweep{shard_note}: {} points here: {solved} solved ({not_converged} not converged), {skipped} already done, {} failed; sweep.csv holds {rows} of {} points -> {}",
        mine.len(),
        failed.len(),
        pts.len(),
        dir.join("sweep.csv").display()
    ))?;
    if !failed.is_empty() {
        anyhow::bail!("{} sweep point(s) failed", failed.len());
    }
    if not_converged > 0 {
        io::err(&format!(
            "warning: {not_converged} point(s) did not converge (converged = false in sweep.csv)"
        ));
        return Ok(ExitCode::from(EXIT_NOT_CONVERGED));
    }
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_and_lists() {
        let v = Vary::parse("motion.slide_to_roll=0:0.1:11").unwrap();
        assert_eq!(v.values.len(), 11);
        assert_eq!(v.values[3], "0.03");
        assert_eq!(v.values[10], "0.1");
        let v = Vary::parse("load.force=4000,5000, 6000").unwrap();
        assert_eq!(v.values, ["4000", "5000", "6000"]);
        let v = Vary::parse("body1.profile={kind=\"crowned\", crown_radius=1},{kind=\"straight\"}")
            .unwrap();
        assert_eq!(v.values.len(), 2);
        assert!(Vary::parse("load.forse=1,2")
            .unwrap_err()
            .contains("load.force"));
        assert!(Vary::parse("load.force=1:2").is_err());
        assert!(Vary::parse("load.force=1:2:0").is_err());
        assert!(Shard::parse("2/2").is_err());
        assert!(Shard::parse("1/3").is_ok());
    }

    #[test]
    fn folder_names() {
        let a = Vary::parse("motion.slide_to_roll=0,0.05").unwrap();
        let b = Vary::parse("load.force=5000.0,6000").unwrap();
        let p = points(&[a, b]);
        assert_eq!(p.len(), 4);
        assert_eq!(p[3].folder, "p003_slide_to_roll=0.05_force=6000");
        assert_eq!(p[1].values, ["0", "6000"]);
        let c = Vary::parse("body1.radius=0.01,0.02").unwrap();
        let d = Vary::parse("body2.radius=0.01").unwrap();
        assert_eq!(
            points(&[c, d])[1].folder,
            "p001_body1.radius=0.02_body2.radius=0.01"
        );
    }
}
