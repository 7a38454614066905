//! The outputs of a transient run (`Solution::transient` is `Some`); a steady solution writes
//! none of them. [`write()`] puts them into the output folder beside the steady files (which hold
//! the last step), inside the atomic write of [`super::write_all`].
//!
//! | file | content |
//! | --- | --- |
//! | `timeline.csv` | one row per step (step 0 is the steady start): the columns of [`TIMELINE_COLUMNS`], numbers in the shortest round-trip form of the other csv files, `converged` as `true` / `false`, an empty `friction_coefficient` cell where the friction integral failed |
//! | `frames.npz` | `time_s` (k), `x_p_m` (k), `step` (k, int64), `x` (nx), `y` (ny), `pressure` (k, ny, nx) in Pa, `film` (k, ny, nx) in m, for the k frames kept (every `output.frames_every`-th step); `pressure[f, j, i]` is at `(x[i], y[j])` |
//! | `timeline.png` | stacked panels over a shared x axis (x_p in mm, or time when x_p does not move): maximum pressure (GPa), minimum and central film, friction coefficient (when any step has one); steps that did not converge are shaded red and marked |
//! | `passage.gif` | with `output.animation` and at least two frames: the pressure map (fixed colour scale over all frames) above the centre-line pressure and film, x_p marked, x_p and time in the title; an infinite line contact (`ny == 1`) has the profile only |
//! | `passage.png` | the kept frame with the highest pressure, drawn as a frame of `passage.gif` (always written) |
//! | (zoom) | on a 2D grid where `features[0]` is small along y (a pit on a roller), `passage.gif` and `passage.png` show the strip of [`zoom_window`] around it, titled "zoom on `features[0]`"; the frames and the files for ParaView keep the whole grid |
//! | `frames/frame_NNNNN.vtr`, `passage.pvd` | the frames for ParaView: one VTK XML rectilinear grid per frame (`pressure`, `film`; NNNNN the step), and the collection `passage.pvd` that opens them as one time series (`timestep` = time in s) |
//! | `snapshots/xp_<x_p in mm>mm/` | for each `output.snapshots` x_p, the step nearest to it: `fields.npz`, `centerline.csv`, `axial.csv`, `pressure.png`, `film.png`, `centerline.png` as for a steady run, and `pressure_zoom.png`, `film_zoom.png` on a strip of three times `features[0]`'s y extent when that is less than half the map ([`zoom_window`]) |
//!
//! Film cells with no material (`+inf`, beyond the end of the shorter roller) are written as
//! `inf` in `frames.npz` and the `.vtr` frames, exactly as `fields.npz` and `fields.vtk` write
//! them (NumPy reads them as `inf`; mask with `numpy.isfinite`); the pictures draw them grey
//! or leave them out of every range.
//!
//! `passage.gif` stays a few MB: at most [`GIF_MAX_FRAMES`] frames (evenly subsampled over the
//! kept frames, the first and the last always in), [`GIF_WIDTH`] x [`GIF_HEIGHT`] px, played in
//! about 8 s (40 to 200 ms a frame) and looping.
//!
//! Memory: `frames.npz` gathers one field of all frames at a time (the pressure, then the film),
//! so writing it needs at most one more copy of half the frames.

use super::colormap::ColorMap;
use super::npz::Npz;
use super::plot::{
    arg_max, arg_min, clip, draw_colorbar_on, draw_err, draw_legend, draw_map_axes,
    draw_right_axis, drawable, drawable_range, ensure_font, film_unit, film_word, fit, fmt_fixed,
    fmt_sig, fmt_tick, legend_corner, line_chart_mesh, map_ranges, paint_map, render_sized,
    say_in_middle, text_style, titled, y_axis_label, Fonts, LegendLook, FILM_COLOR, GREY, LEGEND,
    PRESSURE_COLOR, SERIES_COLORS,
};
use crate::case::Case;
use crate::grid::Grid;
use crate::solution::{Fields, Frame, Solution, StepRecord, Summary, TransientRecord};
use crate::Result;
use ndarray::{Array1, Array3};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::ops::Range;
use std::path::Path;

pub const TIMELINE_CSV: &str = "timeline.csv";
pub const FRAMES_NPZ: &str = "frames.npz";
pub const TIMELINE_PNG: &str = "timeline.png";
pub const PASSAGE_GIF: &str = "passage.gif";
/// The frame of `passage.gif` with the highest pressure, as a still picture.
pub const PASSAGE_PNG: &str = "passage.png";
pub const PASSAGE_PVD: &str = "passage.pvd";
/// The folder of the `.vtr` frames that `passage.pvd` lists.
pub const FRAMES_DIR: &str = "frames";
/// Zoomed maps of a snapshot around `features[0]` (see [`zoom_window`]).
pub const PRESSURE_ZOOM_PNG: &str = "pressure_zoom.png";
pub const FILM_ZOOM_PNG: &str = "film_zoom.png";
/// The folder of the snapshot sub-folders.
pub const SNAPSHOTS_DIR: &str = "snapshots";

/// Most frames in `passage.gif`: more kept frames are subsampled evenly.
pub const GIF_MAX_FRAMES: usize = 120;
/// Size of `passage.gif` (px).
pub const GIF_WIDTH: u32 = 800;
pub const GIF_HEIGHT: u32 = 600;
/// Frames of `passage.gif` its one palette is learnt from (evenly spaced, the first and the
/// last included).
const GIF_PALETTE_FRAMES: usize = 5;

/// The columns of `timeline.csv`, in order: the interface's nine, then the solver's figures.
pub const TIMELINE_COLUMNS: [&str; 20] = [
    "step",
    "time_s",
    "x_p_m",
    "max_pressure_pa",
    "min_film_m",
    "central_film_m",
    "friction_coefficient",
    "load_error",
    "converged",
    "centerline_min_film_m",
    "h0_m",
    "newton_iterations",
    "linear_iterations",
    "operator_applications",
    "mass_balance",
    "mass_inflow_kg_s",
    "mass_outflow_kg_s",
    "side_leakage_kg_s",
    "mass_storage_kg_s",
    "wall_time_s",
];

/// The columns a thermal run adds to `timeline.csv`, after [`TIMELINE_COLUMNS`] (interface.md:
/// "transient timelines add `max_film_temperature_k`").
pub const THERMAL_COLUMNS: [&str; 7] = [
    "max_film_temperature_k",
    "max_surface_temperature_1_k",
    "max_surface_temperature_2_k",
    "heat_generated_w",
    "heat_stored_w",
    "energy_balance_error",
    "thermal_passes",
];

type DrawResult<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// Writes every transient output of `solution` into `dir` (an existing folder: the temporary
/// folder of the atomic write); nothing when `solution.transient` is `None`. Errors name the
/// file.
pub fn write(dir: &Path, case: &Case, solution: &Solution) -> Result<()> {
    let Some(t) = &solution.transient else {
        return Ok(());
    };
    let g = &solution.grid;
    write_timeline_csv(&dir.join(TIMELINE_CSV), t)?;
    write_frames_npz(&dir.join(FRAMES_NPZ), g, t)?;
    write_timeline_png(&dir.join(TIMELINE_PNG), case, t)?;
    // the animation and its still zoom onto features[0] where the whole map would show it as
    // a speck (a pit on a roller; see `zoom_window`)
    let zoomed = zoom_window(case, g).and_then(|(y0, y1)| crop_record(g, t, y0, y1));
    let zcase;
    let (case_a, g_a, t_a) = match &zoomed {
        Some((zg, zt)) => {
            let mut c = case.clone();
            c.title = format!("zoom on features[0] — {}", case.title);
            zcase = c;
            (&zcase, zg, zt)
        }
        None => (case, g, t),
    };
    if case.output.animation && t_a.frames.len() >= 2 {
        write_passage_gif(&dir.join(PASSAGE_GIF), case_a, g_a, t_a)?;
    }
    // the still of the passage: the kept frame with the highest pressure
    if let Some(k) = highest_frame(t_a.frames.iter().map(frame_peak)) {
        write_passage_frame_png(&dir.join(PASSAGE_PNG), case_a, g_a, t_a, k)?;
    }
    write_vtk_series(dir, g, t)?;
    write_snapshots(&dir.join(SNAPSHOTS_DIR), case, solution)?;
    Ok(())
}

/// The largest pressure of a frame (0 when none is positive): what `passage.png` picks by.
pub fn frame_peak(f: &Frame) -> f64 {
    f.pressure.iter().cloned().fold(0.0f64, f64::max)
}

/// The index of the frame `passage.png` shows among frames of these peaks: the highest, the
/// last of equals.
pub fn highest_frame(peaks: impl IntoIterator<Item = f64>) -> Option<usize> {
    peaks
        .into_iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(k, _)| k)
}

/// Checks the transient record before anything is written (called by [`super::validate`]):
/// every timeline figure finite (a friction coefficient may be absent, not NaN), every frame
/// and snapshot field of `grid.len()` values, finite (the film may be `+inf`, no material),
/// finite frame times and x_p. The message names the step or the snapshot, the field and the
/// cell.
pub fn validate(grid: &Grid, t: &TransientRecord) -> std::result::Result<(), String> {
    for r in &t.timeline {
        let mut figures = vec![
            ("time_s", r.time_s),
            ("x_p_m", r.x_p_m),
            ("max_pressure_pa", r.max_pressure_pa),
            ("min_film_m", r.min_film_m),
            ("central_film_m", r.central_film_m),
            ("centerline_min_film_m", r.centerline_min_film_m),
            ("load_error", r.load_error),
            ("h0_m", r.h0_m),
            ("mass_balance", r.mass_balance),
            ("mass_inflow_kg_s", r.mass_inflow_kg_s),
            ("mass_outflow_kg_s", r.mass_outflow_kg_s),
            ("side_leakage_kg_s", r.side_leakage_kg_s),
            ("mass_storage_kg_s", r.mass_storage_kg_s),
            ("wall_time_s", r.wall_time_s),
        ];
        if let Some(f) = r.friction_coefficient {
            figures.push(("friction_coefficient", f));
        }
        if let Some(th) = &r.thermal {
            figures.extend([
                ("max_film_temperature_k", th.max_film_temperature_k),
                (
                    "max_surface_temperature_1_k",
                    th.max_surface_temperature_1_k,
                ),
                (
                    "max_surface_temperature_2_k",
                    th.max_surface_temperature_2_k,
                ),
                ("heat_generated_w", th.heat_generated_w),
                ("heat_stored_w", th.heat_stored_w),
                ("energy_balance_error", th.energy_balance_error),
            ]);
        }
        if let Some((name, v)) = figures.into_iter().find(|(_, v)| !v.is_finite()) {
            return Err(format!(
                "{TIMELINE_CSV}: step {}: `{name}` is {v}; refusing to write a non-finite value",
                r.step
            ));
        }
    }
    for f in &t.frames {
        validate_frame(grid, f)?;
    }
    for (x_p, step, fields) in &t.snapshots {
        let at = format!("snapshot at x_p = {x_p:e} m (step {step})");
        if !x_p.is_finite() {
            return Err(format!("{at}: x_p is not finite"));
        }
        for (name, field) in super::named(fields) {
            super::check_field(grid, &at, name, field)?;
        }
        if fields
            .film
            .as_ref()
            .is_some_and(|f| f.iter().all(|v| !v.is_finite()))
        {
            return Err(format!("{at}: field `film` has no finite value"));
        }
    }
    Ok(())
}

/// The checks of [`validate`] on one frame: finite time and x_p, fields of `grid.len()` finite
/// values (the film may be `+inf`).
pub fn validate_frame(grid: &Grid, f: &Frame) -> std::result::Result<(), String> {
    let at = format!("frame of step {}", f.step);
    for (name, v) in [("time_s", f.time_s), ("x_p_m", f.x_p_m)] {
        if !v.is_finite() {
            return Err(format!(
                "{at}: `{name}` is {v}; refusing to write a non-finite value"
            ));
        }
    }
    super::check_field(grid, &at, "pressure", &f.pressure)?;
    super::check_field(grid, &at, "film", &f.film)
}

// ---------------------------------------------------------------- timeline.csv

/// The header line of `timeline.csv` (with its newline): [`TIMELINE_COLUMNS`], then
/// [`THERMAL_COLUMNS`] for a thermal run.
pub fn timeline_header(thermal: bool) -> String {
    let mut s = TIMELINE_COLUMNS.join(",");
    if thermal {
        s.push(',');
        s.push_str(&THERMAL_COLUMNS.join(","));
    }
    s.push('\n');
    s
}

/// Appends the line of `r` (with its newline) to `s`; `thermal`: the run's header has the
/// thermal columns (empty cells on a step without temperatures).
pub fn timeline_row(s: &mut String, r: &StepRecord, thermal: bool) {
    let friction = r
        .friction_coefficient
        .map(|f| format!("{f:e}"))
        .unwrap_or_default();
    let _ = writeln!(
        s,
        "{},{:e},{:e},{:e},{:e},{:e},{friction},{:e},{},{:e},{:e},{},{},{},{:e},{:e},{:e},{:e},{:e},{:e}",
        r.step,
        r.time_s,
        r.x_p_m,
        r.max_pressure_pa,
        r.min_film_m,
        r.central_film_m,
        r.load_error,
        r.converged,
        r.centerline_min_film_m,
        r.h0_m,
        r.newton_iterations,
        r.linear_iterations,
        r.operator_applications,
        r.mass_balance,
        r.mass_inflow_kg_s,
        r.mass_outflow_kg_s,
        r.side_leakage_kg_s,
        r.mass_storage_kg_s,
        r.wall_time_s,
    );
    if thermal {
        s.pop();
        match &r.thermal {
            Some(th) => {
                let _ = writeln!(
                    s,
                    ",{:e},{:e},{:e},{:e},{:e},{:e},{}",
                    th.max_film_temperature_k,
                    th.max_surface_temperature_1_k,
                    th.max_surface_temperature_2_k,
                    th.heat_generated_w,
                    th.heat_stored_w,
                    th.energy_balance_error,
                    th.thermal_passes
                );
            }
            None => s.push_str(&",".repeat(THERMAL_COLUMNS.len())),
        }
        if !s.ends_with('\n') {
            s.push('\n');
        }
    }
}

/// Whether `timeline.csv` has the thermal columns: some step of `t` has temperatures.
pub fn timeline_is_thermal(t: &TransientRecord) -> bool {
    t.timeline.iter().any(|r| r.thermal.is_some())
}

/// The text of `timeline.csv`.
pub fn timeline_csv(t: &TransientRecord) -> String {
    // a thermal run: its columns on every row (empty on a step without temperatures)
    let thermal = timeline_is_thermal(t);
    let mut s = String::with_capacity(256 * (t.timeline.len() + 1));
    s.push_str(&timeline_header(thermal));
    for r in &t.timeline {
        timeline_row(&mut s, r, thermal);
    }
    s
}

/// Writes `timeline.csv` to `path`.
pub fn write_timeline_csv(path: &Path, t: &TransientRecord) -> Result<()> {
    std::fs::write(path, timeline_csv(t)).map_err(|e| super::io_err(path, e))
}

// ---------------------------------------------------------------- frames.npz

/// Writes `frames.npz` to `path` (see the module documentation).
pub fn write_frames_npz(path: &Path, grid: &Grid, t: &TransientRecord) -> Result<()> {
    let frames = &t.frames;
    let (k, n) = (frames.len(), grid.len());
    let mut npz = Npz::create(path)?;
    let per_frame = |f: fn(&Frame) -> f64| Array1::from_iter(frames.iter().map(f));
    npz.add("time_s", &per_frame(|f| f.time_s))?;
    npz.add("x_p_m", &per_frame(|f| f.x_p_m))?;
    npz.add(
        "step",
        &Array1::from_iter(frames.iter().map(|f| f.step as i64)),
    )?;
    npz.add_grid(grid)?;
    type FieldOf = fn(&Frame) -> &[f64];
    let fields: [(&str, FieldOf); 2] = [("pressure", |f| &f.pressure), ("film", |f| &f.film)];
    for (name, get) in fields {
        let mut v = Vec::with_capacity(k * n);
        for f in frames {
            let a = get(f);
            if a.len() != n {
                return Err(npz.err(format!(
                    "frame of step {}: field `{name}` has {} values, the grid needs {n}",
                    f.step,
                    a.len()
                )));
            }
            v.extend_from_slice(a);
        }
        let a = Array3::from_shape_vec((k, grid.ny, grid.nx), v)
            .map_err(|e| npz.err(format!("field `{name}`: {e}")))?;
        npz.add_sized(name, &a, (8 * k * n) as u64)?;
    }
    npz.finish()
}

// ---------------------------------------------------------------- VTK series

/// The name of a frame's `.vtr` file inside [`FRAMES_DIR`].
pub fn frame_file_name(step: usize) -> String {
    format!("frame_{step:05}.vtr")
}

/// The text of `passage.pvd`: a ParaView collection of the frames, `timestep` = time (s).
pub fn pvd(t: &TransientRecord) -> String {
    pvd_of(t.frames.iter().map(|f| (f.step, f.time_s)))
}

/// [`pvd`] of frames given as (step, time in s).
pub fn pvd_of(frames: impl IntoIterator<Item = (usize, f64)>) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" \
         byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for (step, time_s) in frames {
        let _ = writeln!(
            s,
            "    <DataSet timestep=\"{:e}\" group=\"\" part=\"0\" file=\"{FRAMES_DIR}/{}\"/>",
            time_s,
            frame_file_name(step)
        );
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    s
}

/// Writes the `.vtr` file of frame `f` into `folder` (the [`FRAMES_DIR`] folder).
pub fn write_vtr_frame(folder: &Path, grid: &Grid, f: &Frame) -> Result<()> {
    let path = folder.join(frame_file_name(f.step));
    let bytes = super::vtk::rectilinear_xml(
        grid,
        &[("pressure", &f.pressure), ("film", &f.film)],
        Some(f.time_s),
    );
    std::fs::write(&path, bytes).map_err(|e| super::io_err(&path, e))
}

/// Writes `frames/frame_NNNNN.vtr` for every frame and `passage.pvd` into `dir`; nothing when
/// there is no frame.
pub fn write_vtk_series(dir: &Path, grid: &Grid, t: &TransientRecord) -> Result<()> {
    if t.frames.is_empty() {
        return Ok(());
    }
    let folder = dir.join(FRAMES_DIR);
    std::fs::create_dir_all(&folder).map_err(|e| super::io_err(&folder, e))?;
    for f in &t.frames {
        write_vtr_frame(&folder, grid, f)?;
    }
    let path = dir.join(PASSAGE_PVD);
    std::fs::write(&path, pvd(t)).map_err(|e| super::io_err(&path, e))
}

// ---------------------------------------------------------------- snapshots

/// The sub-folder name of a snapshot at `x_p_m` (m): `xp_<x_p in mm, 3 decimals>mm`, e.g.
/// `xp_-0.780mm`, `xp_0.000mm`, `xp_0.560mm`.
pub fn snapshot_folder_name(x_p_m: f64) -> String {
    format!("xp_{}mm", fmt_fixed(x_p_m * 1e3, 3))
}

/// The timeline row of `step`, if any.
fn row_of(t: &TransientRecord, step: usize) -> Option<&StepRecord> {
    t.timeline
        .iter()
        .find(|r| r.step == step)
        .or_else(|| t.timeline.get(step).filter(|r| r.step == step))
}

/// A steady-looking (case, solution) for the snapshot `(x_p, step, fields)` of a transient
/// solution, for the steady writers: the fields of that step, the summary figures of that step
/// (maximum pressure, films and their places from the fields; convergence, load error, friction
/// and mass flows from its timeline row; the Hertz figures of the run), and the case title
/// prefixed with the snapshot's x_p, step and time.
pub fn snapshot_solution(
    case: &Case,
    solution: &Solution,
    x_p: f64,
    step: usize,
    fields: &Fields,
) -> (Case, Solution) {
    let g = solution.grid;
    let row = solution.transient.as_ref().and_then(|t| row_of(t, step));
    let last = &solution.summary;
    let (pm, kp) = arg_max(&fields.pressure);
    let mut summary = Summary {
        converged: row.map_or(last.converged, |r| r.converged),
        termination: format!("snapshot of the transient run at step {step}"),
        iterations: row.map_or(0, |r| r.newton_iterations),
        residual: None,
        wall_time_s: row.map_or(0.0, |r| r.wall_time_s),
        load_n: fields.pressure.iter().sum::<f64>() * g.cell_area(),
        load_error: row.map_or(last.load_error, |r| r.load_error),
        max_pressure_pa: if pm.is_finite() { pm } else { 0.0 },
        max_pressure_at_m: [g.x(kp % g.nx), g.y(kp / g.nx)],
        hertz_pressure_pa: last.hertz_pressure_pa,
        hertz_half_width_m: last.hertz_half_width_m,
        friction_coefficient: row.and_then(|r| r.friction_coefficient),
        friction_requested: last.friction_requested,
        ..Summary::default()
    };
    if let Some(r) = row {
        summary.mass_inflow_kg_s = Some(r.mass_inflow_kg_s);
        summary.mass_outflow_kg_s = Some(r.mass_outflow_kg_s);
        summary.side_leakage_kg_s = Some(r.side_leakage_kg_s);
    }
    if let Some(film) = &fields.film {
        let (hmin, k) = arg_min(film);
        if hmin.is_finite() {
            summary.min_film_m = Some(hmin);
            summary.min_film_at_m = Some([g.x(k % g.nx), g.y(k / g.nx)]);
        }
        let centre = g.idx(
            super::nearest(g.nx, |i| g.x(i), 0.0),
            super::nearest(g.ny, |j| g.y(j), 0.0),
        );
        summary.central_film_m = row
            .map(|r| r.central_film_m)
            .or(Some(film[centre]))
            .filter(|h| h.is_finite());
        let j = super::centre_row(solution);
        let (hc, _) = arg_min(&film[j * g.nx..(j + 1) * g.nx]);
        summary.centerline_min_film_m = Some(hc).filter(|h| h.is_finite());
    }
    let at_x = row.map_or(x_p, |r| r.x_p_m);
    let mut label = format!("x_p = {} mm", fmt_sig_or_zero(at_x * 1e3, 3));
    if (at_x - x_p).abs() > 5e-7 {
        label += &format!(" (asked {} mm)", fmt_sig_or_zero(x_p * 1e3, 3));
    }
    label += &format!(", step {step}");
    if let Some(r) = row {
        let (unit, scale) = time_unit(r.time_s);
        label += &format!(", t = {} {unit}", fmt_sig_or_zero(r.time_s * scale, 4));
    }
    let mut c = case.clone();
    c.title = format!("{label} — {}", case.title.trim());
    (
        c,
        Solution {
            stress: None,
            temperature: None,
            grid: g,
            fields: fields.clone(),
            summary,
            transient: None,
        },
    )
}

/// Writes `snapshots/<xp folder>/` for every snapshot of the record into `dir` (the
/// `snapshots` folder, created when there is at least one). Two snapshots whose names round to
/// the same folder get the step appended to the second (`xp_0.000mm_step00040`).
pub fn write_snapshots(dir: &Path, case: &Case, solution: &Solution) -> Result<()> {
    let Some(t) = &solution.transient else {
        return Ok(());
    };
    if t.snapshots.is_empty() {
        return Ok(());
    }
    std::fs::create_dir_all(dir).map_err(|e| super::io_err(dir, e))?;
    let mut used: Vec<String> = Vec::new();
    for (x_p, step, fields) in &t.snapshots {
        let base = snapshot_folder_name(*x_p);
        let mut name = base.clone();
        let mut n = 1;
        while used.contains(&name) {
            name = if n == 1 {
                format!("{base}_step{step:05}")
            } else {
                format!("{base}_step{step:05}_{n}")
            };
            n += 1;
        }
        used.push(name.clone());
        let sub = dir.join(&name);
        std::fs::create_dir(&sub).map_err(|e| super::io_err(&sub, e))?;
        let (c, s) = snapshot_solution(case, solution, *x_p, *step, fields);
        super::npz::write(&sub.join(super::FIELDS_NPZ), &s)?;
        super::csv::write_centerline(&sub.join(super::CENTERLINE_CSV), &s)?;
        super::csv::write_axial(&sub.join(super::AXIAL_CSV), &s)?;
        super::plot::write_pressure(&sub.join(super::PRESSURE_PNG), &c, &s)?;
        if s.fields.film.is_some() {
            super::plot::write_film(&sub.join(super::FILM_PNG), &c, &s)?;
        }
        super::plot::write_centerline(&sub.join(super::CENTERLINE_PNG), &c, &s)?;
        if let Some((y0, y1)) = zoom_window(case, &s.grid) {
            if let Some(z) = crop_y(&s, y0, y1) {
                let mut cz = c.clone();
                cz.title = format!("zoom on features[0] — {}", c.title);
                super::plot::write_pressure(&sub.join(PRESSURE_ZOOM_PNG), &cz, &z)?;
                if z.fields.film.is_some() {
                    super::plot::write_film(&sub.join(FILM_ZOOM_PNG), &cz, &z)?;
                }
            }
        }
    }
    Ok(())
}

/// The y range (m) of the zoomed maps of a snapshot: three times the y extent of `features[0]`
/// (all copies of a pattern), centred on it, when that is less than half the grid's y extent
/// (a pit on a roller: the whole-roller map shows it as a speck); `None` for an infinite line,
/// a feature unbounded along y, or one that already fills the map.
pub fn zoom_window(case: &Case, grid: &Grid) -> Option<(f64, f64)> {
    if grid.ny < 2 {
        return None;
    }
    let (lo, hi) = case.features.first()?.feature.y_span()?;
    let span = hi - lo;
    let (ylo, yhi) = (grid.y_min, grid.y_max());
    if !(span > 0.0) || 3.0 * span > 0.5 * (yhi - ylo) {
        return None;
    }
    let w = (lo - span).max(ylo)..(hi + span).min(yhi);
    (w.end - w.start >= 8.0 * grid.dy).then_some((w.start, w.end))
}

/// The strip of `g` whose cell centres lie in `y0 ..= y1` and its first and last row; `None`
/// when fewer than 4 rows fall inside.
pub(super) fn crop_grid(g: &Grid, y0: f64, y1: f64) -> Option<(Grid, usize, usize)> {
    let rows: Vec<usize> = (0..g.ny)
        .filter(|&j| g.y(j) >= y0 && g.y(j) <= y1)
        .collect();
    if rows.len() < 4 {
        return None;
    }
    let (j0, j1) = (rows[0], rows[rows.len() - 1]);
    let sub = Grid::new(
        g.nx,
        j1 - j0 + 1,
        g.x_min,
        g.x_max(),
        g.y_min + j0 as f64 * g.dy,
        g.y_min + (j1 + 1) as f64 * g.dy,
    );
    Some((sub, j0, j1))
}

/// The record with every frame cut to the strip `y0 ..= y1` (see [`crop_grid`]), for the
/// zoomed animation; the timeline is kept whole, the snapshots are dropped.
/// The record the pictures draw: `t`'s timeline with `frames` (a crop, or the frames shown);
/// no snapshots, and no passage maps (they are written from the full solution).
pub(super) fn picture_record(t: &TransientRecord, frames: Vec<Frame>) -> TransientRecord {
    TransientRecord {
        timeline: t.timeline.clone(),
        frames,
        snapshots: Vec::new(),
        dt_s: t.dt_s,
        frames_every: t.frames_every,
        passage: None,
    }
}

pub(super) fn crop_record(
    g: &Grid,
    t: &TransientRecord,
    y0: f64,
    y1: f64,
) -> Option<(Grid, TransientRecord)> {
    let (sub, j0, j1) = crop_grid(g, y0, y1)?;
    let cut = |v: &[f64]| v[j0 * g.nx..(j1 + 1) * g.nx].to_vec();
    let frames = t
        .frames
        .iter()
        .map(|f| Frame {
            step: f.step,
            time_s: f.time_s,
            x_p_m: f.x_p_m,
            pressure: cut(&f.pressure),
            film: cut(&f.film),
        })
        .collect();
    Some((sub, picture_record(t, frames)))
}

/// The rows of `solution` whose cell centres lie in `y0 ..= y1`, as a solution on that strip of
/// the grid (same x cells); `None` when fewer than 4 rows fall inside.
pub fn crop_y(solution: &Solution, y0: f64, y1: f64) -> Option<Solution> {
    let g = solution.grid;
    let (sub, j0, j1) = crop_grid(&g, y0, y1)?;
    let cut = |v: &[f64]| v[j0 * g.nx..(j1 + 1) * g.nx].to_vec();
    let f = &solution.fields;
    let fields = Fields {
        pressure: cut(&f.pressure),
        deformation: cut(&f.deformation),
        film: f.film.as_deref().map(cut),
        viscosity: f.viscosity.as_deref().map(cut),
        density: f.density.as_deref().map(cut),
    };
    let mut summary = solution.summary.clone();
    let (pm, k) = arg_max(&fields.pressure);
    summary.max_pressure_pa = pm;
    summary.max_pressure_at_m = [sub.x(k % sub.nx), sub.y(k / sub.nx)];
    Some(Solution {
        stress: None,
        temperature: None,
        grid: sub,
        fields,
        summary,
        transient: None,
    })
}

// ---------------------------------------------------------------- shared helpers

/// [`fmt_sig`], with 0 written `0`.
fn fmt_sig_or_zero(v: f64, sig: usize) -> String {
    // a position reached by summing steps is zero only to round-off (x_p = -1.6 mm + 120 x
    // 3.2/240 mm is ~1e-16 mm): 1e-9 of the display unit is zero
    if v.abs() < 1e-9 {
        "0".into()
    } else {
        fmt_sig(v, sig)
    }
}

/// Display unit for times up to `t` (s): µs, ms or s.
fn time_unit(t: f64) -> (&'static str, f64) {
    let t = t.abs();
    if t < 1e-3 {
        ("µs", 1e6)
    } else if t < 1.0 {
        ("ms", 1e3)
    } else {
        ("s", 1.0)
    }
}

/// The x axis of the timeline: x_p (mm) when it moves over the run, otherwise time.
struct TimeAxis {
    use_xp: bool,
    scale: f64,
    label: String,
}

impl TimeAxis {
    fn new(case: &Case, rows: &[StepRecord]) -> TimeAxis {
        let (lo, hi) = rows
            .iter()
            .map(|r| r.x_p_m)
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
        if hi - lo > 1e-12 {
            let what = if case.features.is_empty() {
                "travel of the surface"
            } else {
                "centre of the first feature"
            };
            TimeAxis {
                use_xp: true,
                scale: 1e3,
                label: format!("x_p, {what} (mm)"),
            }
        } else {
            let t_end = rows.iter().map(|r| r.time_s.abs()).fold(0.0, f64::max);
            let (unit, scale) = time_unit(t_end);
            TimeAxis {
                use_xp: false,
                scale,
                label: format!("time ({unit})"),
            }
        }
    }

    fn x(&self, r: &StepRecord) -> f64 {
        if self.use_xp {
            r.x_p_m * self.scale
        } else {
            r.time_s * self.scale
        }
    }
}

// ---------------------------------------------------------------- timeline.png

const TIMELINE_WIDTH: u32 = 1000;
const NOT_CONVERGED: RGBColor = RGBColor(220, 20, 20);
const MIN_FILM_COLOR: RGBColor = SERIES_COLORS[2];
const FRICTION_COLOR: RGBColor = SERIES_COLORS[3];
const CENTRE_MIN_FILM_COLOR: RGBColor = RGBColor(230, 140, 20);

/// One curve of a timeline panel (NaN where a step has no value).
struct Line {
    label: String,
    color: RGBColor,
    pts: Vec<(f64, f64)>,
}

struct Panel {
    y_label: String,
    range: Range<f64>,
    lines: Vec<Line>,
}

/// Splits a polyline at its non-finite points.
fn pieces(pts: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut out = vec![];
    let mut cur = vec![];
    for &(x, y) in pts {
        if x.is_finite() && y.is_finite() {
            cur.push((x, y));
        } else if !cur.is_empty() {
            out.push(std::mem::take(&mut cur));
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

/// Top of a magnitude axis: 12 % above the largest finite value (0..1.12 when there is none).
fn top_of(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((0.0f64, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    let hi = if hi.is_finite() { hi } else { 1.0 };
    let lo = if lo < 0.0 { lo * 1.12 } else { 0.0 };
    drawable_range(lo, hi + 0.12 * (hi - lo))
}

/// An axis fitted to a series whose change over the travel is the point (the friction
/// coefficient: a pit moves it by a few per cent, thesis ch. 3): its finite values with 12 %
/// of their span above and below, and at least 2 % of their magnitude, so that a flat series
/// sits mid-panel in a band of +-2 % (0..1 when there is none). Either sign: the friction of
/// the thesis examples is negative where the rolling Poiseuille traction outweighs the
/// sliding one (docs/pits.md). Before, the panel took the magnitude axis: from zero for a
/// positive series, which flattened a 5 % change to a line, and to the largest value for a
/// negative one, where a flat series ran along the panel's top edge.
fn fitted(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo > hi {
        return drawable_range(0.0, 1.0);
    }
    let pad = (0.12 * (hi - lo)).max(0.02 * lo.abs().max(hi.abs()));
    drawable_range(lo - pad, hi + pad)
}

/// Writes `timeline.png`: see the module documentation.
pub fn write_timeline_png(path: &Path, case: &Case, t: &TransientRecord) -> Result<()> {
    let rows = &t.timeline;
    let axis = TimeAxis::new(case, rows);
    let xs: Vec<f64> = rows.iter().map(|r| axis.x(r)).collect();
    let (x0, x1) = xs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let x_range = drawable_range(x0, x1);
    // pressure
    let mut panels = vec![Panel {
        y_label: "maximum pressure (GPa)".into(),
        range: top_of(rows.iter().map(|r| r.max_pressure_pa * 1e-9)),
        lines: vec![Line {
            label: "maximum pressure".into(),
            color: PRESSURE_COLOR,
            pts: xs
                .iter()
                .zip(rows)
                .map(|(&x, r)| (x, r.max_pressure_pa * 1e-9))
                .collect(),
        }],
    }];
    // films
    let h_top = rows
        .iter()
        .flat_map(|r| [r.min_film_m, r.central_film_m])
        .filter(|h| h.is_finite())
        .fold(0.0, f64::max);
    let (unit, scale) = film_unit(if h_top > 0.0 { h_top } else { 1e-6 });
    let word = film_word(case);
    panels.push(Panel {
        y_label: format!("{word} ({unit})"),
        range: top_of(
            rows.iter()
                .flat_map(|r| [r.min_film_m * scale, r.central_film_m * scale]),
        ),
        lines: vec![
            Line {
                label: "central film (x = 0, y = 0)".into(),
                color: FILM_COLOR,
                pts: xs
                    .iter()
                    .zip(rows)
                    .map(|(&x, r)| (x, r.central_film_m * scale))
                    .collect(),
            },
            Line {
                label: "minimum film".into(),
                color: MIN_FILM_COLOR,
                pts: xs
                    .iter()
                    .zip(rows)
                    .map(|(&x, r)| (x, r.min_film_m * scale))
                    .collect(),
            },
        ],
    });
    // on a finite roller the overall minimum sits at the free ends: the centre row's too
    if rows
        .iter()
        .any(|r| (r.centerline_min_film_m - r.min_film_m).abs() > 1e-3 * r.min_film_m.abs())
    {
        if let Some(p) = panels.last_mut() {
            p.lines.push(Line {
                label: "minimum film on the centre row (y = 0)".into(),
                color: CENTRE_MIN_FILM_COLOR,
                pts: xs
                    .iter()
                    .zip(rows)
                    .map(|(&x, r)| (x, r.centerline_min_film_m * scale))
                    .collect(),
            });
        }
    }
    // friction
    if rows.iter().any(|r| r.friction_coefficient.is_some()) {
        let mu: Vec<f64> = rows
            .iter()
            .map(|r| r.friction_coefficient.unwrap_or(f64::NAN))
            .collect();
        panels.push(Panel {
            y_label: "friction coefficient".into(),
            range: fitted(mu.iter().copied()),
            lines: vec![Line {
                label: if mu.iter().all(|m| m.is_finite()) {
                    "friction coefficient".into()
                } else {
                    "friction coefficient (gaps: not computed)".into()
                },
                color: FRICTION_COLOR,
                pts: xs.iter().copied().zip(mu).collect(),
            }],
        });
    }
    // a thermal run: the temperature rises above the inlet
    if let (Some(spec), true) = (&case.thermal, rows.iter().any(|r| r.thermal.is_some())) {
        let t0 = spec.lubricant.inlet_temperature;
        type Of = fn(&crate::solution::StepThermalRecord) -> f64;
        let series: [(&str, RGBColor, Of); 3] = [
            ("film, maximum across z", PRESSURE_COLOR, |t| {
                t.max_film_temperature_k
            }),
            ("surface of body 1", FILM_COLOR, |t| {
                t.max_surface_temperature_1_k
            }),
            ("surface of body 2", MIN_FILM_COLOR, |t| {
                t.max_surface_temperature_2_k
            }),
        ];
        let lines: Vec<Line> = series
            .iter()
            .map(|&(label, color, of)| Line {
                label: format!("{label} (largest over the contact)"),
                color,
                pts: xs
                    .iter()
                    .zip(rows)
                    .map(|(&x, r)| (x, r.thermal.as_ref().map_or(f64::NAN, |t| of(t) - t0)))
                    .collect(),
            })
            .collect();
        // room above the film's line for the legend (the surfaces' lines run along the bottom)
        let top = lines
            .iter()
            .flat_map(|l| l.pts.iter().map(|p| p.1))
            .filter(|v| v.is_finite())
            .fold(0.0f64, f64::max);
        panels.push(Panel {
            y_label: format!("temperature rise above {} K (K)", fmt_sig_or_zero(t0, 4)),
            range: drawable_range(0.0, 1.8 * top),
            lines,
        });
    }
    let bad: Vec<(f64, usize)> = rows
        .iter()
        .enumerate()
        .filter(|(_, r)| !r.converged)
        .map(|(k, r)| (axis.x(r), k))
        .collect();
    // the half-width of a non-converged band: half the mean step along the axis
    let half = if xs.len() > 1 {
        0.5 * (x_range.end - x_range.start) / (xs.len() - 1) as f64
    } else {
        0.01 * (x_range.end - x_range.start)
    };
    let lines = timeline_lines(case, t, &axis, &bad);
    let height = 120 + 24 * lines.len() as u32 + 270 * panels.len() as u32;
    render_sized(path, (TIMELINE_WIDTH, height), |root| {
        let area = titled(root, &case.title, &lines)?;
        let (_, h) = area.dim_in_pixel();
        let n = panels.len();
        // every panel gets the same plot height; the bottom one also holds the x labels
        let bottom_extra = 54u32;
        let each = (h - bottom_extra) / n as u32;
        let mut rest = area;
        for (k, panel) in panels.iter().enumerate() {
            let last = k + 1 == n;
            let (this, below) = if last {
                (rest.clone(), rest.clone())
            } else {
                rest.split_vertically(each)
            };
            draw_panel(
                &this,
                panel,
                x_range.clone(),
                last.then_some(axis.label.as_str()),
                &bad,
                half,
                k == 0,
            )?;
            rest = below;
        }
        Ok(())
    })
}

/// The two lines under the title of `timeline.png`.
fn timeline_lines(
    case: &Case,
    t: &TransientRecord,
    axis: &TimeAxis,
    bad: &[(f64, usize)],
) -> Vec<String> {
    let rows = &t.timeline;
    let kind = if case.is_infinite_line() {
        "transient EHL, infinite line contact"
    } else {
        "transient EHL"
    };
    let steps = rows.iter().map(|r| r.step).max().unwrap_or(0);
    let (tu, ts) = time_unit(t.dt_s * steps.max(1) as f64);
    let mut l1 = format!(
        "{kind}: {steps} time steps of {} {tu}",
        fmt_sig_or_zero(t.dt_s * ts, 3)
    );
    if let (Some(a), Some(b)) = (rows.first(), rows.last()) {
        if axis.use_xp {
            l1 += &format!(
                ", x_p from {} to {} mm",
                fmt_sig_or_zero(a.x_p_m * 1e3, 3),
                fmt_sig_or_zero(b.x_p_m * 1e3, 3)
            );
        } else {
            l1 += &format!(
                ", t from {} to {} {tu}",
                fmt_sig_or_zero(a.time_s * ts, 3),
                fmt_sig_or_zero(b.time_s * ts, 3)
            );
        }
    }
    let mut l2 = String::new();
    let pk = rows
        .iter()
        .filter(|r| r.max_pressure_pa.is_finite())
        .max_by(|a, b| a.max_pressure_pa.total_cmp(&b.max_pressure_pa));
    let hk = rows
        .iter()
        .filter(|r| r.min_film_m.is_finite())
        .min_by(|a, b| a.min_film_m.total_cmp(&b.min_film_m));
    let at = |r: &StepRecord| {
        if axis.use_xp {
            format!("x_p = {} mm", fmt_sig_or_zero(r.x_p_m * 1e3, 3))
        } else {
            format!("t = {} {tu}", fmt_sig_or_zero(r.time_s * ts, 3))
        }
    };
    if let Some(r) = pk {
        l2 += &format!(
            "highest pressure {} GPa at {}",
            fmt_sig(r.max_pressure_pa * 1e-9, 4),
            at(r)
        );
    }
    if let Some(r) = hk {
        let (u, s) = film_unit(r.min_film_m);
        l2 += &format!(
            ";  thinnest film {} {u} at {}",
            fmt_sig(r.min_film_m * s, 3),
            at(r)
        );
    }
    l2 += &if bad.is_empty() {
        ";  every step converged".to_string()
    } else {
        format!(";  {} step(s) NOT CONVERGED (red)", bad.len())
    };
    vec![l1, l2.trim_start_matches(";  ").to_string()]
}

fn draw_panel(
    area: &DrawingArea<BitMapBackend, Shift>,
    panel: &Panel,
    x_range: Range<f64>,
    x_desc: Option<&str>,
    bad: &[(f64, usize)],
    half: f64,
    first: bool,
) -> DrawResult<()> {
    let xr = drawable(x_range);
    let yr = drawable(panel.range.clone());
    let (xspan, yspan) = (xr.end - xr.start, yr.end - yr.start);
    let x_fmt = move |v: &f64| fmt_tick(*v, xspan);
    let no_label = |_: &f64| String::new();
    let y_fmt = move |v: &f64| fmt_tick(*v, yspan);
    let bottom = x_desc.is_some();
    let mut chart = ChartBuilder::on(area)
        .margin_left(10)
        .margin_right(30)
        .margin_top(10)
        .margin_bottom(if bottom { 10 } else { 4 })
        .x_label_area_size(if bottom { 62 } else { 10 })
        .y_label_area_size(96)
        .build_cartesian_2d(xr.clone(), yr.clone())?;
    {
        let mut mesh = chart.configure_mesh();
        line_chart_mesh(&mut mesh)
            .y_label_formatter(&y_fmt)
            .y_desc(panel.y_label.as_str());
        if let Some(d) = x_desc {
            mesh.x_label_formatter(&x_fmt).x_desc(d);
        } else {
            mesh.x_label_formatter(&no_label);
        }
        mesh.draw()?;
    }
    // non-converged steps: a red band over the panel height and a marker on every curve
    let band = ShapeStyle::from(&NOT_CONVERGED.mix(0.16)).filled();
    for &(x, _) in bad {
        let a = (x - half).max(xr.start);
        let b = (x + half).min(xr.end);
        if a < b {
            chart.draw_series(std::iter::once(Rectangle::new(
                [(a, yr.start), (b, yr.end)],
                band,
            )))?;
        }
    }
    let mut all = vec![];
    for line in &panel.lines {
        let style = ShapeStyle::from(&line.color).stroke_width(3);
        let mut labelled = false;
        for piece in pieces(&line.pts) {
            all.extend(piece.iter().copied());
            for part in clip(&piece, &yr) {
                let anno = if part.len() == 1 {
                    chart.draw_series(std::iter::once(Circle::new(
                        part[0],
                        3,
                        ShapeStyle::from(&line.color).filled(),
                    )))?
                } else {
                    chart.draw_series(LineSeries::new(part, style))?
                };
                if !labelled {
                    anno.label(line.label.as_str())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 21, y)], style));
                    labelled = true;
                }
            }
        }
        for &(_, k) in bad {
            if let Some(&(x, y)) = line.pts.get(k) {
                if x.is_finite() && y.is_finite() && y >= yr.start && y <= yr.end {
                    chart.draw_series([
                        Circle::new((x, y), 6, ShapeStyle::from(&NOT_CONVERGED).filled()),
                        Circle::new((x, y), 6, ShapeStyle::from(&BLACK).stroke_width(1)),
                    ])?;
                }
            }
        }
    }
    if first && !bad.is_empty() {
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
            .label("step not converged")
            .legend(|(x, y)| {
                EmptyElement::at((x, y))
                    + Rectangle::new(
                        [(0, -7), (21, 7)],
                        ShapeStyle::from(&NOT_CONVERGED.mix(0.16)).filled(),
                    )
                    + Circle::new((10, 0), 5, ShapeStyle::from(&NOT_CONVERGED).filled())
            });
    }
    if all.is_empty() {
        say_in_middle(&chart, "no value to draw", 18.0)?;
    }
    draw_legend(
        chart.configure_series_labels(),
        legend_corner(&all, (xr.start, xr.end), (yr.start, yr.end)),
        LegendLook {
            margin: 10,
            ..LEGEND
        },
    )
}

// ---------------------------------------------------------------- passage.gif

/// The frames `passage.gif` shows out of `n` kept frames: all of them up to `cap`, otherwise
/// `cap` evenly spaced ones, the first and the last included.
pub fn gif_frame_indices(n: usize, cap: usize) -> Vec<usize> {
    if n <= cap {
        return (0..n).collect();
    }
    if cap < 2 {
        return (0..cap).collect();
    }
    let mut v: Vec<usize> = (0..cap)
        .map(|k| ((k as f64) * (n - 1) as f64 / (cap - 1) as f64).round() as usize)
        .collect();
    v.dedup();
    v
}

/// What every frame of the animation shares: fixed axes and colour scale.
struct Passage<'a> {
    case: &'a Case,
    grid: &'a Grid,
    t: &'a TransientRecord,
    /// centre row
    j: usize,
    /// colour scale and profile axis top (GPa)
    p_top: f64,
    /// film axis top (display units), unit and scale
    h_top: f64,
    h_unit: &'static str,
    h_scale: f64,
    time_unit: (&'static str, f64),
    last_step: usize,
}

impl<'a> Passage<'a> {
    fn new(case: &'a Case, grid: &'a Grid, t: &'a TransientRecord, shown: &[usize]) -> Self {
        let g = grid;
        let j = super::nearest(g.ny, |j| g.y(j), 0.0);
        let mut p_top: f64 = 0.0;
        let mut loaded: f64 = f64::NEG_INFINITY;
        let mut finite = vec![];
        for &k in shown {
            let f = &t.frames[k];
            let (pm, _) = arg_max(&f.pressure);
            if pm.is_finite() {
                p_top = p_top.max(pm);
            }
            let row_p = &f.pressure[j * g.nx..(j + 1) * g.nx];
            let row_h = &f.film[j * g.nx..(j + 1) * g.nx];
            for (p, h) in row_p.iter().zip(row_h) {
                if h.is_finite() {
                    finite.push(*h);
                    if *p > 0.05 * pm {
                        loaded = loaded.max(*h);
                    }
                }
            }
        }
        // the film axis: 2.5 x the film over the loaded zone (as centerline.png), or the
        // median film along the centre line when nothing is loaded
        let h_top = if loaded.is_finite() && loaded > 0.0 {
            2.5 * loaded
        } else {
            finite.sort_by(f64::total_cmp);
            finite.get(finite.len() / 2).copied().unwrap_or(1e-6)
        };
        let (h_unit, h_scale) = film_unit(h_top);
        let t_end = t.frames.iter().map(|f| f.time_s.abs()).fold(0.0, f64::max);
        Passage {
            case,
            grid,
            t,
            j,
            p_top: p_top * 1e-9,
            h_top: h_top * h_scale,
            h_unit,
            h_scale,
            time_unit: time_unit(t_end),
            last_step: t.timeline.iter().map(|r| r.step).max().unwrap_or(0),
        }
    }

    /// Draws frame `k` onto `root` (already white).
    fn draw(&self, root: &DrawingArea<BitMapBackend, Shift>, k: usize) -> DrawResult<()> {
        let f = &self.t.frames[k];
        let g = self.grid;
        let row = row_of(self.t, f.step);
        let converged = row.is_none_or(|r| r.converged);
        // header: the case title, then where and when
        let (w, _) = root.dim_in_pixel();
        let (band, body) = root.split_vertically(62);
        band.draw_text(
            &fit(&band, self.case.title.trim(), 18.0)?,
            &text_style(18.0, BLACK),
            (12, 8),
        )?;
        let (tu, ts) = self.time_unit;
        let mut line = format!(
            "x_p = {} mm    t = {} {tu}    step {} of {}",
            fmt_fixed(f.x_p_m * 1e3, 3),
            fmt_sig_or_zero(f.time_s * ts, 4),
            f.step,
            self.last_step
        );
        if !converged {
            line += "    NOT CONVERGED";
        }
        band.draw_text(
            &line,
            &text_style(17.0, if converged { GREY } else { NOT_CONVERGED }),
            (12, 34),
        )?;
        let _ = w;
        if g.ny > 1 {
            let (_, h) = body.dim_in_pixel();
            let (top, bottom) = body.split_vertically((h as f64 * 0.52) as u32);
            self.draw_map(&top, f)?;
            self.draw_profile(&bottom, f)?;
        } else {
            self.draw_profile(&body, f)?;
        }
        Ok(())
    }

    fn draw_map(&self, area: &DrawingArea<BitMapBackend, Shift>, f: &Frame) -> DrawResult<()> {
        let g = self.grid;
        let (aw, _) = area.dim_in_pixel();
        let (main, bar) = area.split_horizontally(aw - GIF_RIGHT);
        let mm = 1e3;
        let (xr, yr) = map_ranges(g);
        let mut chart = ChartBuilder::on(&main)
            .margin_left(GIF_LEFT_MARGIN)
            .margin_right(10)
            .margin_top(4)
            .margin_bottom(4)
            .x_label_area_size(30)
            .y_label_area_size(GIF_Y_LABELS)
            .build_cartesian_2d(xr.clone(), yr.clone())?;
        draw_map_axes(&mut chart, 5, GIF_FONTS, None, y_axis_label(self.case))?;
        let hi = drawable(0.0..self.p_top).end;
        paint_map(&chart, g, &f.pressure, 1e-9, 0.0..hi, ColorMap::Inferno)?;
        // x_p: a dashed white line across the map
        let xp = f.x_p_m * mm;
        if xp >= xr.start && xp <= xr.end {
            chart.draw_series(DashedLineSeries::new(
                [(xp, yr.start), (xp, yr.end)],
                8,
                6,
                ShapeStyle::from(&WHITE).stroke_width(2),
            ))?;
        }
        // the colour bar, aligned with the map
        let mut cb = ChartBuilder::on(&bar)
            .margin_top(4)
            .margin_bottom(4)
            .margin_left(10)
            .margin_right(4)
            .x_label_area_size(30)
            .right_y_label_area_size(GIF_RIGHT as i32 - 10 - 4 - 26)
            .build_cartesian_2d(0.0..1.0, 0.0..hi)?;
        draw_colorbar_on(
            &mut cb,
            ColorMap::Inferno,
            6,
            GIF_FONTS,
            None,
            "pressure (GPa)",
        )
    }

    fn draw_profile(&self, area: &DrawingArea<BitMapBackend, Shift>, f: &Frame) -> DrawResult<()> {
        let g = self.grid;
        let j = self.j;
        let xr = drawable(g.x_min * 1e3..g.x_max() * 1e3);
        let pr = drawable(0.0..self.p_top * 1.12);
        let hr = drawable(0.0..self.h_top);
        let (xspan, pspan) = (xr.end - xr.start, pr.end - pr.start);
        let x_fmt = move |v: &f64| fmt_tick(*v, xspan);
        let p_fmt = move |v: &f64| fmt_tick(*v, pspan);
        let mut chart = ChartBuilder::on(area)
            .margin_left(GIF_LEFT_MARGIN)
            .margin_right(10)
            .margin_top(8)
            .margin_bottom(6)
            .x_label_area_size(50)
            .y_label_area_size(GIF_Y_LABELS)
            .right_y_label_area_size(GIF_RIGHT as i32)
            .build_cartesian_2d(xr.clone(), pr.clone())?
            .set_secondary_coord(xr.clone(), hr.clone());
        chart
            .configure_mesh()
            .x_labels(9)
            .y_labels(6)
            .max_light_lines(0)
            .bold_line_style(ShapeStyle::from(&RGBColor(225, 225, 225)).stroke_width(1))
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&p_fmt)
            .label_style(text_style(14.0, BLACK))
            .axis_desc_style(text_style(15.0, BLACK))
            .x_desc(if g.ny > 1 {
                "x, rolling direction (mm), along the axial centre line"
            } else {
                "x, rolling direction (mm)   —   inlet ← → outlet"
            })
            .y_desc("pressure (GPa)")
            .draw()?;
        let word = film_word(self.case);
        let h_desc = format!("{word} ({})", self.h_unit);
        draw_right_axis(&mut chart, &hr, 6, GIF_FONTS, h_desc.as_str())?;
        let xs = g.xs();
        let row = j * g.nx..(j + 1) * g.nx;
        let p: Vec<(f64, f64)> = xs
            .iter()
            .zip(&f.pressure[row.clone()])
            .map(|(x, p)| (x * 1e3, p * 1e-9))
            .collect();
        let h: Vec<(f64, f64)> = xs
            .iter()
            .zip(&f.film[row])
            .map(|(x, h)| (x * 1e3, h * self.h_scale))
            .collect();
        // x_p: a dashed vertical line with its name
        let xp = f.x_p_m * 1e3;
        if xp >= xr.start && xp <= xr.end {
            let style = ShapeStyle::from(&GREY).stroke_width(2);
            chart
                .draw_series(DashedLineSeries::new(
                    [(xp, pr.start), (xp, pr.end)],
                    8,
                    6,
                    style,
                ))?
                .label("x_p")
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 21, y)], style));
        }
        let pstyle = ShapeStyle::from(&PRESSURE_COLOR).stroke_width(3);
        let mut first = true;
        for piece in clip(&p, &pr) {
            let a = chart.draw_series(LineSeries::new(piece, pstyle))?;
            if first {
                a.label("pressure (left)")
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 21, y)], pstyle));
                first = false;
            }
        }
        let hstyle = ShapeStyle::from(&FILM_COLOR).stroke_width(3);
        let mut first = true;
        for piece in clip(&h, &hr) {
            let a = chart.draw_secondary_series(LineSeries::new(piece, hstyle))?;
            if first {
                a.label(format!("{word} (right)"))
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 21, y)], hstyle));
                first = false;
            }
        }
        draw_legend(
            chart.configure_series_labels(),
            SeriesLabelPosition::UpperRight,
            GIF_LEGEND,
        )
    }
}

/// Left margin, y-label width and right column (colour bar / film axis) of the animation, the
/// same for the map and the profile so that their x axes line up.
const GIF_LEFT_MARGIN: i32 = 6;
const GIF_Y_LABELS: i32 = 70;
const GIF_RIGHT: u32 = 110;
/// The legend of the animation's profile.
const GIF_LEGEND: LegendLook = LegendLook {
    font: 14.0,
    sample: 30,
    margin: 8,
    opacity: 0.85,
};
/// The fonts of the animation.
const GIF_FONTS: Fonts = Fonts {
    label: 14.0,
    desc: 15.0,
};

/// Milliseconds a frame of `passage.gif` with `n` frames is shown: about 8 s in all, 40 to 200
/// ms each.
fn gif_delay_ms(n: usize) -> u32 {
    (8000 / n.max(1)).clamp(40, 200) as u32
}

/// Writes `passage.gif` (see the module documentation); at least two frames are needed.
pub fn write_passage_gif(path: &Path, case: &Case, grid: &Grid, t: &TransientRecord) -> Result<()> {
    if t.frames.len() < 2 {
        return Err(draw_err(path, "an animation needs at least two frames"));
    }
    let shown = gif_frame_indices(t.frames.len(), GIF_MAX_FRAMES);
    write_passage_gif_of(path, case, grid, t, &shown)
}

/// [`write_passage_gif`] of the frames `shown` of `t` (indices into `t.frames`, at least two):
/// the streaming writer holds only these.
pub(super) fn write_passage_gif_of(
    path: &Path,
    case: &Case,
    grid: &Grid,
    t: &TransientRecord,
    shown: &[usize],
) -> Result<()> {
    if shown.len() < 2 {
        return Err(draw_err(path, "an animation needs at least two frames"));
    }
    ensure_font().map_err(|e| draw_err(path, e))?;
    let shown = shown.to_vec();
    let passage = Passage::new(case, grid, t, &shown);
    // One palette for the whole animation (a global colour table: no flicker between frames),
    // learnt by NeuQuant from a few frames spread over the passage; every frame, drawn into its
    // own RGB buffer in parallel, is then mapped onto it. NeuQuant on every frame (a local
    // table each) was ~30 % of a 2000-step line run; sequentially through plotters' gif
    // backend, 120 frames took ~4 s.
    use rayon::prelude::*;
    let (w, h) = (GIF_WIDTH, GIF_HEIGHT);
    let delay = gif_delay_ms(shown.len());
    let draw = |k: usize| -> std::result::Result<Vec<u8>, String> {
        let mut buf = vec![255u8; (w * h * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
            passage.draw(&root, k).map_err(|e| e.to_string())?;
            root.present().map_err(|e| e.to_string())?;
        }
        Ok(buf)
    };
    let sample: Vec<usize> = gif_frame_indices(shown.len(), GIF_PALETTE_FRAMES)
        .into_iter()
        .map(|i| shown[i])
        .collect();
    let sample = sample
        .par_iter()
        .map(|&k| draw(k))
        .collect::<std::result::Result<Vec<_>, _>>()
        .map_err(|e| draw_err(path, e))?;
    let rgba: Vec<u8> = sample
        .iter()
        .flat_map(|b| b.chunks_exact(3).flat_map(|c| [c[0], c[1], c[2], 255]))
        .collect();
    let quant = color_quant::NeuQuant::new(10, 256, &rgba);
    drop((sample, rgba));
    let palette = quant.color_map_rgb();
    let frames: Vec<std::result::Result<gif::Frame<'static>, String>> = shown
        .par_iter()
        .map(|&k| {
            let buf = draw(k)?;
            // a direct-mapped cache of the palette search: a frame has few distinct colours
            let mut seen = vec![(u32::MAX, 0u8); 1 << 12];
            let idx: Vec<u8> = buf
                .chunks_exact(3)
                .map(|c| {
                    let key = u32::from_be_bytes([0, c[0], c[1], c[2]]);
                    let slot = &mut seen[(key.wrapping_mul(0x9E37_79B1) >> 20) as usize];
                    if slot.0 != key {
                        *slot = (key, quant.index_of(&[c[0], c[1], c[2], 255]) as u8);
                    }
                    slot.1
                })
                .collect();
            let mut f = gif::Frame::from_indexed_pixels(w as u16, h as u16, &idx, None);
            f.delay = ((delay + 5) / 10) as u16;
            Ok(f)
        })
        .collect();
    let file = std::fs::File::create(path).map_err(|e| draw_err(path, e))?;
    let mut enc = gif::Encoder::new(std::io::BufWriter::new(file), w as u16, h as u16, &palette)
        .map_err(|e| draw_err(path, e))?;
    enc.set_repeat(gif::Repeat::Infinite)
        .map_err(|e| draw_err(path, e))?;
    for f in frames {
        let f = f.map_err(|e| draw_err(path, e))?;
        enc.write_frame(&f).map_err(|e| draw_err(path, e))?;
    }
    drop(enc);
    match std::fs::metadata(path) {
        Ok(m) if m.len() > 0 => Ok(()),
        _ => Err(draw_err(path, "no animation was written")),
    }
}

/// Frame `k` of the kept frames drawn as in `passage.gif`, as a PNG of the same size (for
/// documentation pages and for looking at one frame without a GIF viewer).
pub fn write_passage_frame_png(
    path: &Path,
    case: &Case,
    grid: &Grid,
    t: &TransientRecord,
    k: usize,
) -> Result<()> {
    if k >= t.frames.len() {
        return Err(draw_err(
            path,
            format!("frame {k} asked, the run kept {}", t.frames.len()),
        ));
    }
    let shown = gif_frame_indices(t.frames.len(), GIF_MAX_FRAMES);
    write_passage_frame_png_of(path, case, grid, t, k, &shown)
}

/// [`write_passage_frame_png`] with the axes and colour scale of the frames `shown` of `t`.
pub(super) fn write_passage_frame_png_of(
    path: &Path,
    case: &Case,
    grid: &Grid,
    t: &TransientRecord,
    k: usize,
    shown: &[usize],
) -> Result<()> {
    let passage = Passage::new(case, grid, t, shown);
    render_sized(path, (GIF_WIDTH, GIF_HEIGHT), |root| passage.draw(root, k))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The friction panel's axis is fitted to its series: a negative series (the thesis
    /// pit's, -4.2e-4 .. -4.65e-4) with at least 2 % of its magnitude above and below, and no
    /// zero; a flat one centred in +-2 % of its magnitude; a positive one zoomed too (a 3 %
    /// change of 5.8e-3 fills over a third of the panel); a wide one with 12 % of its span; NaN
    /// gaps ignored; no values give 0..1.
    #[test]
    fn the_friction_axis_is_fitted_to_its_series() {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-300);
        let r = fitted([-4.2e-4, -4.65e-4, f64::NAN].into_iter());
        let pad = 0.02 * 4.65e-4;
        assert!(
            close(r.start, -4.65e-4 - pad) && close(r.end, -4.2e-4 + pad),
            "{r:?}"
        );
        assert!(r.end < 0.0, "{r:?}");
        let r = fitted([-4.375e-4, -4.38e-4].into_iter());
        let mid = 0.5 * (r.start + r.end);
        assert!((mid + 4.3775e-4).abs() < 1e-9, "{r:?}");
        assert!(r.end - r.start >= 0.04 * 4.375e-4, "{r:?}");
        let r = fitted([5.8e-3, 5.97e-3].into_iter());
        assert!(r.start > 5.0e-3 && r.end < 6.5e-3, "{r:?}");
        assert!((5.97e-3 - 5.8e-3) / (r.end - r.start) > 0.35, "{r:?}");
        let span = 1.0;
        let r = fitted([0.0, span].into_iter());
        assert!(close(r.start, -0.12) && close(r.end, 1.12), "{r:?}");
        assert_eq!(fitted(std::iter::empty()), 0.0..1.0);
        assert_eq!(fitted([f64::NAN].into_iter()), 0.0..1.0);
    }

    /// The crop keeps exactly the rows inside the window, with their values, on a grid whose
    /// cells are the original ones.
    #[test]
    fn crop_keeps_the_rows_inside_the_window() {
        let g = Grid::new(4, 10, -2.0, 2.0, -5.0, 5.0);
        let field: Vec<f64> = (0..g.len()).map(|k| k as f64).collect();
        let s = Solution {
            stress: None,
            temperature: None,
            grid: g,
            fields: Fields {
                pressure: field.clone(),
                deformation: field.clone(),
                film: Some(field.clone()),
                viscosity: None,
                density: None,
            },
            summary: Summary::default(),
            transient: None,
        };
        // cell centres at y = -4.5, -3.5, ..., 4.5: the window -1.2 .. 2.7 holds -0.5 .. 2.5
        let z = crop_y(&s, -1.2, 2.7).expect("4 rows");
        assert_eq!((z.grid.nx, z.grid.ny), (4, 4));
        assert_eq!((z.grid.dx, z.grid.dy), (g.dx, g.dy));
        assert!((z.grid.y(0) + 0.5).abs() < 1e-12 && (z.grid.y(3) - 2.5).abs() < 1e-12);
        assert_eq!(z.fields.pressure, field[16..32].to_vec());
        assert_eq!(z.fields.film.as_deref(), Some(&field[16..32]));
        assert_eq!(z.summary.max_pressure_pa, 31.0);
        // too narrow a window: no crop
        assert!(crop_y(&s, 0.0, 2.0).is_none());
    }
}
