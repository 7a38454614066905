//! Helpers shared by the validation studies in `crates/ehl/examples/` (not an example itself):
//! solving a case file of the repository's `examples/` folder with `--set`-style overrides, reading
//! a pressure row, the sub-cell half-width of a Hertz-type profile, and a small line chart drawn
//! with the program's embedded font.
#![allow(dead_code)]

use ehl::case::Case;
use ehl::run::{solve, Silent};
use ehl::solution::Solution;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// The repository root (two levels above this crate).
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Loads `examples/<name>.toml` with overrides (`"grid.ny=512"`), exactly as `ehl run --set` does.
pub fn case(name: &str, overrides: &[String]) -> Case {
    let path = repo().join("examples").join(format!("{name}.toml"));
    ehl::case::load_file(&path, overrides).unwrap_or_else(|e| panic!("{e}"))
}

/// Parses case text with overrides.
pub fn case_text(text: &str, overrides: &[String]) -> Case {
    ehl::case::parse_str(text, "<study>", overrides).unwrap_or_else(|e| panic!("{e}"))
}

/// Solves a case through the same pipeline as `ehl run`; panics if the solver did not converge
/// (a study must never report an unconverged number).
pub fn run(case: &Case) -> Solution {
    let s = solve(case, &Silent).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        s.summary.converged,
        "{}: not converged ({})",
        case.title, s.summary.termination
    );
    s
}

/// `"key=value"` strings.
pub fn sets(pairs: &[(&str, String)]) -> Vec<String> {
    pairs.iter().map(|(k, v)| format!("{k}={v}")).collect()
}

/// Pressure along x in grid row `j`.
pub fn row(s: &Solution, j: usize) -> Vec<f64> {
    let nx = s.grid.nx;
    s.fields.pressure[j * nx..(j + 1) * nx].to_vec()
}

/// Pressure along y in grid column `i`.
pub fn column(s: &Solution, i: usize) -> Vec<f64> {
    (0..s.grid.ny)
        .map(|j| s.fields.pressure[s.grid.idx(i, j)])
        .collect()
}

/// Pressure along x at mid-length: the row through y = 0, or the mean of the two rows either
/// side of it when y = 0 is a cell face.
pub fn mid_row(s: &Solution) -> Vec<f64> {
    let g = &s.grid;
    let t = (0.0 - g.y_min) / g.dy; // y = 0 in cell units from the lower face
    let j = t.floor() as usize;
    if (t - t.round()).abs() < 1e-9 && j > 0 {
        let (a, b) = (row(s, j - 1), row(s, j));
        a.iter().zip(&b).map(|(u, v)| 0.5 * (u + v)).collect()
    } else {
        row(s, j.min(g.ny - 1))
    }
}

/// Half-width of a contact from its pressure profile: the outermost contact cells' p^2
/// extrapolated linearly to zero (p^2 falls linearly at a Hertz-type edge where
/// p ~ sqrt(b - |x|)), averaged over both edges. Resolves the edge to a fraction of a cell.
pub fn half_width(xs: &[f64], p: &[f64]) -> f64 {
    let n = p.len();
    let first = p.iter().position(|&v| v > 0.0).expect("no contact");
    let last = n - 1 - p.iter().rev().position(|&v| v > 0.0).expect("no contact");
    let dx = xs[1] - xs[0];
    let edge = |k: usize, inner: usize| {
        let (a, b) = (p[k] * p[k], p[inner] * p[inner]);
        dx * a / (b - a)
    };
    0.5 * ((xs[last] + edge(last, last - 1)) - (xs[first] - edge(first, first + 1)))
}

/// Least-squares slope of log(y) against log(x).
pub fn log_slope(x: &[f64], y: &[f64]) -> f64 {
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let n = lx.len() as f64;
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

/// Where the studies write: `target/studies/<name>` (created).
pub fn out_dir(name: &str) -> PathBuf {
    let d = repo().join("target/studies").join(name);
    std::fs::create_dir_all(&d).expect("cannot create the study folder");
    d
}

// ------------------------------------------------------------------ a small line chart

/// The program's pictures use DejaVu Sans embedded in the library; studies register the same
/// font so their charts match them.
pub fn register_font() {
    ehl::output::plot::ensure_font().unwrap_or_else(|e| panic!("{e}"));
}

/// One curve of a [`chart`].
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub color: RGBColor,
    /// dashed line (a reference law) instead of a solid line
    pub dashed: bool,
    /// a dot at each point (computed values)
    pub markers: bool,
}

/// One chart: title, axis labels with units, ranges, curves.
pub struct Panel<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub x_range: std::ops::Range<f64>,
    pub y_range: std::ops::Range<f64>,
    pub log_x: bool,
    pub series: Vec<Series>,
    /// where the legend goes
    pub legend: SeriesLabelPosition,
}

/// A tick label without trailing zeros ("100", "0.5", "7.25"): the library's formatter with
/// three decimals.
fn tick(v: f64) -> String {
    ehl::output::plot::fmt_tick(v, 0.1)
}

/// Draws `panels` side by side into one picture of `size` px.
pub fn charts(
    path: &Path,
    size: (u32, u32),
    panels: &[Panel],
) -> Result<(), Box<dyn std::error::Error>> {
    register_font();
    let root = BitMapBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE)?;
    let areas = root.split_evenly((1, panels.len()));
    for (area, pn) in areas.iter().zip(panels) {
        let mut b = ChartBuilder::on(area);
        b.caption(pn.title, ("sans-serif", 22))
            .margin(18)
            .x_label_area_size(55)
            .y_label_area_size(70);
        macro_rules! body {
            ($c:expr) => {{
                let mut c = $c;
                c.configure_mesh()
                    .x_desc(pn.x_label)
                    .y_desc(pn.y_label)
                    .x_label_formatter(&|v| tick(*v))
                    .y_label_formatter(&|v| tick(*v))
                    .axis_desc_style(("sans-serif", 19))
                    .label_style(("sans-serif", 16))
                    .light_line_style(RGBColor(235, 235, 235))
                    .draw()?;
                // plotters does not clip: keep the points inside the frame
                let inside = |p: &(f64, f64)| {
                    pn.x_range.start <= p.0
                        && p.0 <= pn.x_range.end
                        && pn.y_range.start <= p.1
                        && p.1 <= pn.y_range.end
                };
                for s0 in &pn.series {
                    let s = Series {
                        label: s0.label.clone(),
                        points: s0.points.iter().filter(|p| inside(p)).cloned().collect(),
                        color: s0.color,
                        dashed: s0.dashed,
                        markers: s0.markers,
                    };
                    let color = s.color;
                    if s.dashed {
                        // dashes: every other segment of a finely sampled curve
                        let mut first = true;
                        for (_, w) in s.points.windows(2).enumerate().filter(|(k, _)| k % 2 == 0) {
                            let a =
                                c.draw_series(LineSeries::new(w.to_vec(), color.stroke_width(3)))?;
                            if first {
                                a.label(s.label.clone()).legend(move |(x, y)| {
                                    EmptyElement::at((x, y))
                                        + PathElement::new(
                                            vec![(0, 0), (8, 0)],
                                            color.stroke_width(3),
                                        )
                                        + PathElement::new(
                                            vec![(14, 0), (22, 0)],
                                            color.stroke_width(3),
                                        )
                                });
                                first = false;
                            }
                        }
                    } else {
                        c.draw_series(LineSeries::new(s.points.clone(), color.stroke_width(3)))?
                            .label(s.label.clone())
                            .legend(move |(x, y)| {
                                PathElement::new(vec![(x, y), (x + 22, y)], color.stroke_width(3))
                            });
                    }
                    if s.markers {
                        c.draw_series(s.points.iter().map(|&p| Circle::new(p, 5, color.filled())))?;
                    }
                }
                c.configure_series_labels()
                    .position(pn.legend.clone())
                    .background_style(WHITE.mix(0.9))
                    .border_style(BLACK)
                    .label_font(("sans-serif", 16))
                    .draw()?;
            }};
        }
        if pn.log_x {
            body!(b.build_cartesian_2d(pn.x_range.clone().log_scale(), pn.y_range.clone())?);
        } else {
            body!(b.build_cartesian_2d(pn.x_range.clone(), pn.y_range.clone())?);
        }
    }
    root.present()?;
    Ok(())
}
