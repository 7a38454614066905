//! The pictures: `pressure.png`, `film.png`, `centerline.png` (1000 x 700 px, plotters bitmap
//! backend, DejaVu Sans embedded so that no system font is needed).
//!
//! * `pressure.png`: a colour map of the pressure over the contact, x (rolling direction, inlet on
//!   the left) horizontal and y (roller axis) vertical, both in mm, colour bar in GPa (inferno:
//!   black = no pressure, pale yellow = maximum), the maximum marked with a cross. The axes are
//!   scaled to fill the frame, not to scale: a roller contact is ~20 times longer than wide; the
//!   stretch factor is printed under the map. An infinite line contact (`ny == 1`) has no map: the
//!   pressure profile along x is drawn instead, with the dry Hertz profile as a dashed reference.
//! * `film.png` (when the solution has a film): the same map of the film (gap after loading for
//!   a dry contact), in µm, or nm when the film is below 1 µm (viridis: dark = thin), the minimum
//!   marked with a circle. The film grows quickly outside the contact, so the colour scale covers
//!   the film over the loaded zone (cells above 5 % of the maximum pressure) and saturates beyond;
//!   the subtitle says where. Cells with no material are grey. `ny == 1`: the film profile.
//! * `centerline.png`: pressure (GPa, left axis) and film (right axis, when present) along x at
//!   the axial centre (the row nearest y = 0), with the dry Hertz pressure
//!   `p_h sqrt(1 - (x/b)^2)` (`summary.hertz_pressure_pa`, `summary.hertz_half_width_m`) dashed.

use super::colormap::ColorMap;
use crate::case::{Case, Kind, Shape};
use crate::grid::Grid;
use crate::solution::Solution;
use crate::{Error, Result};
use plotters::chart::{DualCoordChartContext, MeshStyle, SeriesLabelStyle};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::{CoordTranslate, Shift};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::ops::Range;
use std::path::Path;
use std::sync::OnceLock;

/// Picture size (px).
pub const WIDTH: u32 = 1000;
pub const HEIGHT: u32 = 700;

const FONT: &str = "sans-serif";
static DEJAVU: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

type DrawResult<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// Registers the embedded DejaVu Sans as plotters' "sans-serif" (once per process). Public so
/// that study programs drawing their own charts use the same font.
pub fn ensure_font() -> std::result::Result<(), String> {
    static DONE: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        for style in [FontStyle::Normal, FontStyle::Bold] {
            plotters::style::register_font(FONT, style, DEJAVU)
                .map_err(|_| "the embedded DejaVu Sans font is invalid".to_string())?;
        }
        Ok(())
    })
    .clone()
}

pub(super) fn draw_err(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Output {
        path: path.to_path_buf(),
        message: format!("drawing the picture: {e}"),
    }
}

/// Renders a picture of the standard size into `path` (a PNG): [`render_sized`].
fn render(
    path: &Path,
    f: impl FnOnce(&DrawingArea<BitMapBackend, Shift>) -> DrawResult<()>,
) -> Result<()> {
    render_sized(path, (WIDTH, HEIGHT), f)
}

/// Renders a picture of `size` (px) into `path` (a PNG) on white, with the embedded font; the
/// error names the file.
pub(super) fn render_sized(
    path: &Path,
    size: (u32, u32),
    f: impl FnOnce(&DrawingArea<BitMapBackend, Shift>) -> DrawResult<()>,
) -> Result<()> {
    ensure_font().map_err(|e| draw_err(path, e))?;
    let root = BitMapBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| draw_err(path, e))?;
    f(&root).map_err(|e| draw_err(path, e))?;
    root.present().map_err(|e| draw_err(path, e))?;
    // the backend reports encoder failures only on drop in some versions: check the file
    drop(root);
    match std::fs::metadata(path) {
        Ok(m) if m.len() > 0 => Ok(()),
        _ => Err(draw_err(path, "no picture was written")),
    }
}

// ---------------------------------------------------------------- number formatting

/// `v` with `sig` significant digits, no exponent (for values of order 1e-3 .. 1e4).
pub fn fmt_sig(v: f64, sig: usize) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let mag = v.abs().log10().floor() as i64;
    let dec = (sig as i64 - 1 - mag).clamp(0, 12) as usize;
    fmt_fixed(v, dec)
}

/// `v` with `dec` decimals, `-0.000` written `0.000`.
pub(super) fn fmt_fixed(v: f64, dec: usize) -> String {
    let s = format!("{v:.dec$}");
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// A tick label for `v` on an axis spanning `span`: enough decimals for the tick step, trailing
/// zeros trimmed ("0.25", "5", "-0.1").
pub fn fmt_tick(v: f64, span: f64) -> String {
    let dec = if span > 0.0 && span.is_finite() {
        (2 - span.log10().floor() as i64).clamp(0, 12) as usize
    } else {
        3
    };
    let mut s = format!("{v:.dec$}");
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
        if s.ends_with('.') {
            s.pop();
        }
    }
    if s == "-0" {
        s = "0".into();
    }
    s
}

/// Display unit for a film or gap of typical size `h` (m): µm, or nm below 1 µm.
pub fn film_unit(h: f64) -> (&'static str, f64) {
    if h.abs() < 1e-6 {
        ("nm", 1e9)
    } else {
        ("µm", 1e6)
    }
}

// ---------------------------------------------------------------- layout helpers

pub(super) fn text_style(size: f64, color: RGBColor) -> TextStyle<'static> {
    (FONT, size).into_font().color(&color)
}

pub(super) const GREY: RGBColor = RGBColor(90, 90, 90);
pub(super) const PRESSURE_COLOR: RGBColor = RGBColor(200, 40, 30);
pub(super) const FILM_COLOR: RGBColor = RGBColor(20, 90, 180);
const HERTZ_COLOR: RGBColor = RGBColor(60, 60, 60);

/// Title band: the case title (large) and up to two lines of figures; returns the area below.
pub(super) fn titled<'a>(
    root: &DrawingArea<BitMapBackend<'a>, Shift>,
    title: &str,
    lines: &[String],
) -> DrawResult<DrawingArea<BitMapBackend<'a>, Shift>> {
    let height = 44 + 24 * lines.len() as u32;
    let (band, rest) = root.split_vertically(height);
    let t = if title.trim().is_empty() {
        "(untitled case)"
    } else {
        title.trim()
    };
    band.draw_text(&fit(&band, t, 26.0)?, &text_style(26.0, BLACK), (24, 12))?;
    for (k, line) in lines.iter().enumerate() {
        band.draw_text(
            &fit(&band, line, 18.0)?,
            &text_style(18.0, GREY),
            (24, 46 + 24 * k as i32),
        )?;
    }
    Ok(rest)
}

/// `text` shortened with an ellipsis to fit the width of `area` (less 48 px of margins).
pub(super) fn fit<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    size: f64,
) -> DrawResult<String>
where
    DB::ErrorType: 'static,
{
    let max = area.dim_in_pixel().0.saturating_sub(48);
    let style = text_style(size, BLACK);
    let mut t = text.to_string();
    let mut n = t.chars().count();
    while n > 1 && area.estimate_text_size(&t, &style)?.0 > max {
        n -= 1;
        t = text.chars().take(n).collect::<String>() + "…";
    }
    Ok(t)
}

/// A label with a white box behind it, anchored at its left-centre on `at` (px).
fn boxed_label<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    at: (i32, i32),
) -> DrawResult<()>
where
    DB::ErrorType: 'static,
{
    let style = text_style(16.0, BLACK);
    let (w, h) = area.estimate_text_size(text, &style)?;
    let (aw, ah) = area.dim_in_pixel();
    // keep the label inside the area: flip to the left of the point near the right edge
    let x = if at.0 + 16 + w as i32 + 6 > aw as i32 {
        at.0 - 16 - w as i32 - 6
    } else {
        at.0 + 16
    };
    let y = (at.1 - h as i32 / 2 - 3).clamp(2, ah as i32 - h as i32 - 8);
    area.draw(&Rectangle::new(
        [(x - 4, y - 2), (x + w as i32 + 4, y + h as i32 + 6)],
        ShapeStyle::from(&WHITE.mix(0.85)).filled(),
    ))?;
    area.draw(&Rectangle::new(
        [(x - 4, y - 2), (x + w as i32 + 4, y + h as i32 + 6)],
        ShapeStyle::from(&BLACK).stroke_width(1),
    ))?;
    area.draw_text(text, &style, (x, y + 1))?;
    Ok(())
}

// ---------------------------------------------------------------- maps

/// A field sampled between cell centres (bilinear; nearest where a neighbour is not finite).
pub(super) struct Sampler<'a> {
    pub(super) g: &'a Grid,
    pub(super) v: &'a [f64],
}

impl Sampler<'_> {
    pub(super) fn at(&self, x: f64, y: f64) -> f64 {
        let g = self.g;
        let fi = ((x - g.x_min) / g.dx - 0.5).clamp(0.0, (g.nx - 1) as f64);
        let fj = ((y - g.y_min) / g.dy - 0.5).clamp(0.0, (g.ny - 1) as f64);
        let (i0, j0) = (fi.floor() as usize, fj.floor() as usize);
        let (i1, j1) = ((i0 + 1).min(g.nx - 1), (j0 + 1).min(g.ny - 1));
        let (tx, ty) = (fi - i0 as f64, fj - j0 as f64);
        let c = [
            self.v[g.idx(i0, j0)],
            self.v[g.idx(i1, j0)],
            self.v[g.idx(i0, j1)],
            self.v[g.idx(i1, j1)],
        ];
        if c.iter().all(|v| v.is_finite()) {
            (c[0] * (1.0 - tx) + c[1] * tx) * (1.0 - ty) + (c[2] * (1.0 - tx) + c[3] * tx) * ty
        } else {
            let i = if tx < 0.5 { i0 } else { i1 };
            let j = if ty < 0.5 { j0 } else { j1 };
            self.v[g.idx(i, j)]
        }
    }
}

/// The colour of map cells with no material (non-finite values, e.g. the film beyond the end of
/// the shorter roller).
pub(super) const NO_MATERIAL: RGBColor = RGBColor(190, 190, 190);

/// A chart over f64 x f64 (a map, a colour bar, a line chart).
pub(super) type Chart2d<'a, 'b> =
    ChartContext<'a, BitMapBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Font sizes (px) of the tick labels and of the axis descriptions of a chart.
#[derive(Clone, Copy)]
pub(super) struct Fonts {
    pub(super) label: f64,
    pub(super) desc: f64,
}

/// The x and y ranges (mm) of a map of a field on `g`.
pub(super) fn map_ranges(g: &Grid) -> (Range<f64>, Range<f64>) {
    (
        drawable(x_range_mm(g)),
        drawable(g.y_min * 1e3..g.y_max() * 1e3),
    )
}

/// Draws the axes of a field map on `chart` (built over [`map_ranges`]): no grid lines, 9 x and
/// `y_labels` y tick labels with as many decimals as the ranges need, `x_desc` (when given) and
/// `y_desc`.
pub(super) fn draw_map_axes(
    chart: &mut Chart2d,
    y_labels: usize,
    fonts: Fonts,
    x_desc: Option<&str>,
    y_desc: &str,
) -> DrawResult<()> {
    let (xr, yr) = (chart.x_range(), chart.y_range());
    let (xspan, yspan) = (xr.end - xr.start, yr.end - yr.start);
    let x_fmt = move |v: &f64| fmt_tick(*v, xspan);
    let y_fmt = move |v: &f64| fmt_tick(*v, yspan);
    let mut mesh = chart.configure_mesh();
    mesh.disable_mesh()
        .x_labels(9)
        .y_labels(y_labels)
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .label_style(text_style(fonts.label, BLACK))
        .axis_desc_style(text_style(fonts.desc, BLACK))
        .y_desc(y_desc);
    if let Some(d) = x_desc {
        mesh.x_desc(d);
    }
    mesh.draw()?;
    Ok(())
}

/// Paints a field map into the plotting area of `chart` (built over [`map_ranges`] of `g`, y
/// up), pixel by pixel: `values` (SI, row-major on `g`) sampled at each pixel's centre, times
/// `scale`, coloured by `cmap` over `range` (drawable); non-finite values in [`NO_MATERIAL`]
/// grey. Frames the map and returns its plotting area (pixel coordinates).
pub(super) fn paint_map<'b>(
    chart: &Chart2d<'_, 'b>,
    g: &Grid,
    values: &[f64],
    scale: f64,
    range: Range<f64>,
    cmap: ColorMap,
) -> DrawResult<DrawingArea<BitMapBackend<'b>, Shift>> {
    let mm = 1e3;
    let (xr, yr) = (chart.x_range(), chart.y_range());
    let (xspan, yspan) = (xr.end - xr.start, yr.end - yr.start);
    let plot = chart.plotting_area().strip_coord_spec();
    let (w, h) = plot.dim_in_pixel();
    let sampler = Sampler { g, v: values };
    let Range { start: lo, end: hi } = range;
    for py in 0..h {
        let y = (yr.end - (py as f64 + 0.5) / h as f64 * yspan) / mm;
        for px in 0..w {
            let x = (xr.start + (px as f64 + 0.5) / w as f64 * xspan) / mm;
            let v = sampler.at(x, y);
            let c = if v.is_finite() {
                let (r, gg, b) = cmap.color((v * scale - lo) / (hi - lo));
                RGBColor(r, gg, b)
            } else {
                NO_MATERIAL
            };
            plot.draw_pixel((px as i32, py as i32), &c)?;
        }
    }
    draw_frame(&plot)?;
    Ok(plot)
}

/// A thin black frame around the whole of `area`.
fn draw_frame(area: &DrawingArea<BitMapBackend, Shift>) -> DrawResult<()> {
    let (w, h) = area.dim_in_pixel();
    area.draw(&Rectangle::new(
        [(0, 0), (w as i32 - 1, h as i32 - 1)],
        ShapeStyle::from(&BLACK).stroke_width(1),
    ))?;
    Ok(())
}

/// Draws a colour bar on `bar` (a chart over `0..1` x the colour range, with a right label
/// area): `y_labels` tick labels on the right (ticks `tick_size` px long when given), `desc`,
/// and the colours of `cmap` from the bottom to the top, framed.
pub(super) fn draw_colorbar_on(
    bar: &mut Chart2d,
    cmap: ColorMap,
    y_labels: usize,
    fonts: Fonts,
    tick_size: Option<i32>,
    desc: &str,
) -> DrawResult<()> {
    let range = bar.y_range();
    let span = range.end - range.start;
    let fmt = move |v: &f64| fmt_tick(*v, span);
    let mut mesh = bar.configure_mesh();
    mesh.disable_mesh()
        .disable_x_axis()
        .y_labels(y_labels)
        .y_label_formatter(&fmt)
        .label_style(text_style(fonts.label, BLACK))
        .axis_desc_style(text_style(fonts.desc, BLACK))
        .y_desc(desc);
    if let Some(size) = tick_size {
        mesh.set_tick_mark_size(LabelAreaPosition::Right, size);
    }
    mesh.draw()?;
    let plot = bar.plotting_area().strip_coord_spec();
    let (w, h) = plot.dim_in_pixel();
    for py in 0..h {
        let t = 1.0 - (py as f64 + 0.5) / h as f64;
        let (r, g, b) = cmap.color(t);
        plot.draw(&PathElement::new(
            vec![(0, py as i32), (w as i32 - 1, py as i32)],
            ShapeStyle::from(&RGBColor(r, g, b)).stroke_width(1),
        ))?;
    }
    draw_frame(&plot)
}

/// The fonts of `pressure.png`, `film.png` and `centerline.png`.
const MAP_FONTS: Fonts = Fonts {
    label: 16.0,
    desc: 18.0,
};

/// What a map shows.
pub(super) struct MapSpec<'a> {
    pub title: &'a str,
    pub lines: Vec<String>,
    pub grid: &'a Grid,
    /// values in SI, row-major
    pub values: &'a [f64],
    /// SI -> display unit factor
    pub scale: f64,
    /// colour range in display units
    pub range: Range<f64>,
    pub cmap: ColorMap,
    pub bar_label: String,
    pub y_label: &'a str,
    /// (x, y) in m, label; drawn as a cross (`cross`) or a circle
    pub marker: Option<(f64, f64, String)>,
    pub cross: bool,
}

/// A map of `spec` on `root` ([`WIDTH`] wide): the title band, the map with its axes and
/// marker, its colour bar.
pub(super) fn draw_map(root: &DrawingArea<BitMapBackend, Shift>, spec: &MapSpec) -> DrawResult<()> {
    let g = spec.grid;
    let area = titled(root, spec.title, &spec.lines)?;
    let (main, bar_area) = area.split_horizontally(WIDTH - 150);
    let mm = 1e3;
    let (xr, yr) = map_ranges(g);
    let (xspan, yspan) = (xr.end - xr.start, yr.end - yr.start);
    // equal scales when that costs at most half of the frame (a ball's contact looks round; the
    // map then keeps next to its colour bar); otherwise fill the frame and say how much the
    // picture is stretched
    let (mw, mh) = main.dim_in_pixel();
    let (w0, h0) = (mw as f64 - 116.0, mh as f64 - 96.0);
    let stretch = (w0 / xspan) / (h0 / yspan);
    let (mut hextra, mut vextra) = (0.0, 0.0);
    if (0.5..=2.0).contains(&stretch) {
        if stretch > 1.0 {
            hextra = w0 - w0 / stretch;
        } else {
            vextra = h0 - h0 * stretch;
        }
    }
    let (hpad, vpad) = ((hextra / 2.0).round() as i32, (vextra / 2.0).round() as i32);
    let mut chart = ChartBuilder::on(&main)
        .margin_left(10 + 2 * hpad)
        .margin_right(20)
        .margin_top(10 + vpad)
        .margin_bottom(24 + vpad)
        .x_label_area_size(62)
        .y_label_area_size(86)
        .build_cartesian_2d(xr, yr)?;
    draw_map_axes(
        &mut chart,
        9,
        MAP_FONTS,
        Some("x, rolling direction (mm)   —   inlet ← → outlet"),
        spec.y_label,
    )?;
    // the image, pixel by pixel
    let plot = paint_map(
        &chart,
        g,
        spec.values,
        spec.scale,
        drawable(spec.range.clone()),
        spec.cmap,
    )?;
    let (w, h) = plot.dim_in_pixel();
    if let Some((mx, my, label)) = &spec.marker {
        let p = chart.backend_coord(&(mx * mm, my * mm));
        let base = chart.plotting_area().get_base_pixel();
        let q = (p.0 - base.0, p.1 - base.1);
        if spec.cross {
            for (d, style) in [
                (9, ShapeStyle::from(&WHITE).stroke_width(5)),
                (8, ShapeStyle::from(&BLACK).stroke_width(2)),
            ] {
                plot.draw(&PathElement::new(
                    vec![(q.0 - d, q.1), (q.0 + d, q.1)],
                    style,
                ))?;
                plot.draw(&PathElement::new(
                    vec![(q.0, q.1 - d), (q.0, q.1 + d)],
                    style,
                ))?;
            }
        } else {
            plot.draw(&Circle::new(q, 8, ShapeStyle::from(&WHITE).stroke_width(4)))?;
            plot.draw(&Circle::new(q, 8, ShapeStyle::from(&BLACK).stroke_width(2)))?;
        }
        boxed_label(&plot, label, q)?;
    }
    // the aspect note
    let stretch = (w as f64 / xspan) / (h as f64 / yspan);
    let note = if stretch > 1.05 {
        format!(
            "not to scale: x stretched {}× relative to y",
            fmt_sig(stretch, 2)
        )
    } else if stretch < 1.0 / 1.05 {
        format!(
            "not to scale: y stretched {}× relative to x",
            fmt_sig(1.0 / stretch, 2)
        )
    } else {
        String::new()
    };
    if !note.is_empty() {
        let (_, mh) = main.dim_in_pixel();
        main.draw_text(
            &note,
            &text_style(15.0, GREY).pos(Pos::new(HPos::Right, VPos::Bottom)),
            ((WIDTH - 150) as i32 - 20, mh as i32 - 4),
        )?;
    }
    draw_colorbar(&bar_area, spec, vpad)?;
    Ok(())
}

fn draw_colorbar(
    area: &DrawingArea<BitMapBackend, Shift>,
    spec: &MapSpec,
    vpad: i32,
) -> DrawResult<()> {
    let mut bar = ChartBuilder::on(area)
        .margin_top(10 + vpad)
        .margin_bottom(24 + vpad)
        .margin_left(8)
        .margin_right(10)
        .x_label_area_size(62)
        .right_y_label_area_size(80)
        .build_cartesian_2d(0.0..1.0, drawable(spec.range.clone()))?;
    draw_colorbar_on(
        &mut bar,
        spec.cmap,
        8,
        MAP_FONTS,
        Some(6),
        spec.bar_label.as_str(),
    )
}

// ---------------------------------------------------------------- profiles

/// One curve of a profile plot.
struct Curve {
    pts: Vec<(f64, f64)>,
    color: RGBColor,
    dashed: bool,
    label: String,
}

/// One y axis of a profile plot.
struct Axis {
    label: String,
    range: Range<f64>,
    curves: Vec<Curve>,
}

/// Splits a polyline into the pieces inside `range` (in y), with the crossing points added, so
/// that a clipped curve leaves the frame cleanly.
pub(super) fn clip(pts: &[(f64, f64)], range: &Range<f64>) -> Vec<Vec<(f64, f64)>> {
    clip_all(pts, range)
        .into_iter()
        .map(|piece| thin(&piece, THIN_BUCKETS))
        .collect()
}

/// Buckets along x for [`thin`]: about one per two pixels of the widest line chart.
const THIN_BUCKETS: usize = 150;

/// A polyline with more than two points per bucket of its x extent (`buckets` buckets) reduced
/// to the lowest and the highest point of each bucket, in x order: thick lines drawn through
/// several points per pixel come out ragged in the bitmap backend, while the envelope keeps
/// every spike. Shorter lines, and lines whose x does not increase, are returned unchanged.
pub(super) fn thin(pts: &[(f64, f64)], buckets: usize) -> Vec<(f64, f64)> {
    if pts.len() <= 2 * buckets || pts.windows(2).any(|w| !(w[1].0 >= w[0].0)) {
        return pts.to_vec();
    }
    let (x0, x1) = (pts[0].0, pts[pts.len() - 1].0);
    let span = x1 - x0;
    if !(span > 0.0) {
        return pts.to_vec();
    }
    let bucket = |x: f64| (((x - x0) / span * buckets as f64) as usize).min(buckets - 1);
    let mut out = Vec::with_capacity(2 * buckets + 2);
    let mut k = 0;
    while k < pts.len() {
        let b = bucket(pts[k].0);
        let (mut lo, mut hi) = (k, k);
        let mut e = k;
        while e < pts.len() && bucket(pts[e].0) == b {
            if pts[e].1 < pts[lo].1 {
                lo = e;
            }
            if pts[e].1 > pts[hi].1 {
                hi = e;
            }
            e += 1;
        }
        let (a, c) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        out.push(pts[a]);
        if c != a {
            out.push(pts[c]);
        }
        k = e;
    }
    // keep the ends exact
    if out.last() != pts.last() {
        out.push(pts[pts.len() - 1]);
    }
    if out.first() != pts.first() {
        out.insert(0, pts[0]);
    }
    out
}

fn clip_all(pts: &[(f64, f64)], range: &Range<f64>) -> Vec<Vec<(f64, f64)>> {
    let inside = |y: f64| y.is_finite() && y >= range.start && y <= range.end;
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    for k in 0..pts.len() {
        let (x, y) = pts[k];
        if inside(y) {
            if cur.is_empty() && k > 0 && pts[k - 1].1.is_finite() {
                cur.push(crossing(pts[k - 1], (x, y), range));
            }
            cur.push((x, y));
        } else if !cur.is_empty() {
            if y.is_finite() {
                cur.push(crossing(pts[k - 1], (x, y), range));
            }
            out.push(std::mem::take(&mut cur));
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

fn crossing(a: (f64, f64), b: (f64, f64), range: &Range<f64>) -> (f64, f64) {
    let edge = if a.1.max(b.1) > range.end {
        range.end
    } else {
        range.start
    };
    let t = if b.1 != a.1 {
        (edge - a.1) / (b.1 - a.1)
    } else {
        0.0
    };
    (a.0 + t.clamp(0.0, 1.0) * (b.0 - a.0), edge)
}

/// A chart over f64 x f64 with a second y axis on the right.
pub(super) type DualChart2d<'a, 'b> = DualCoordChartContext<
    'a,
    BitMapBackend<'b>,
    Cartesian2d<RangedCoordf64, RangedCoordf64>,
    Cartesian2d<RangedCoordf64, RangedCoordf64>,
>;

/// Draws the right y axis of `chart` (its secondary range, `range`) in the film colour: `y_labels`
/// tick labels with as many decimals as the range needs, and `desc`.
pub(super) fn draw_right_axis(
    chart: &mut DualChart2d,
    range: &Range<f64>,
    y_labels: usize,
    fonts: Fonts,
    desc: &str,
) -> DrawResult<()> {
    let span = range.end - range.start;
    let fmt = move |v: &f64| fmt_tick(*v, span);
    chart
        .configure_secondary_axes()
        .y_labels(y_labels)
        .y_label_formatter(&fmt)
        .label_style(text_style(fonts.label, FILM_COLOR))
        .axis_desc_style(text_style(fonts.desc, FILM_COLOR))
        .y_desc(desc)
        .draw()?;
    Ok(())
}

/// Draws a profile plot along x (mm) with a left axis and an optional right axis.
fn draw_profile(
    root: &DrawingArea<BitMapBackend, Shift>,
    title: &str,
    lines: &[String],
    x_range: Range<f64>,
    left: &Axis,
    right: Option<&Axis>,
    marks: &[(f64, f64, bool, String, RGBColor)],
) -> DrawResult<()> {
    let area = titled(root, title, lines)?;
    let x_range = drawable(x_range);
    let lrange = drawable(left.range.clone());
    let xspan = x_range.end - x_range.start;
    let lspan = lrange.end - lrange.start;
    let x_fmt = move |v: &f64| fmt_tick(*v, xspan);
    let l_fmt = move |v: &f64| fmt_tick(*v, lspan);
    let rrange = drawable(right.map(|r| r.range.clone()).unwrap_or(0.0..1.0));
    let mut chart = ChartBuilder::on(&area)
        .margin_left(10)
        .margin_right(if right.is_some() { 10 } else { 40 })
        .margin_top(10)
        .margin_bottom(20)
        .x_label_area_size(62)
        .y_label_area_size(86)
        .right_y_label_area_size(if right.is_some() { 86 } else { 0 })
        .build_cartesian_2d(x_range.clone(), lrange.clone())?
        .set_secondary_coord(x_range.clone(), rrange.clone());
    line_chart_mesh(&mut chart.configure_mesh())
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&l_fmt)
        .x_desc("x, rolling direction (mm)   —   inlet ← → outlet")
        .y_desc(left.label.as_str())
        .draw()?;
    if let Some(r) = right {
        draw_right_axis(&mut chart, &rrange, 8, MAP_FONTS, r.label.as_str())?;
    }
    for c in &left.curves {
        let style = ShapeStyle::from(&c.color).stroke_width(if c.dashed { 2 } else { 3 });
        let mut first = true;
        for piece in clip(&c.pts, &lrange) {
            let anno = if c.dashed {
                chart.draw_series(DashedLineSeries::new(piece, 10, 7, style))?
            } else {
                chart.draw_series(LineSeries::new(piece, style))?
            };
            if first {
                let anno = anno.label(c.label.as_str());
                if c.dashed {
                    anno.legend(move |(x, y)| {
                        EmptyElement::at((x, y))
                            + PathElement::new(vec![(0, 0), (8, 0)], style)
                            + PathElement::new(vec![(13, 0), (21, 0)], style)
                    });
                } else {
                    anno.legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 21, y)], style));
                }
                first = false;
            }
        }
    }
    if let Some(r) = right {
        for c in &r.curves {
            let style = ShapeStyle::from(&c.color).stroke_width(if c.dashed { 2 } else { 3 });
            let mut first = true;
            for piece in clip(&c.pts, &rrange) {
                let anno = chart.draw_secondary_series(LineSeries::new(piece, style))?;
                if first {
                    anno.label(c.label.as_str())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 21, y)], style));
                    first = false;
                }
            }
        }
    }
    let plot = chart.plotting_area().strip_coord_spec();
    let base = chart.plotting_area().get_base_pixel();
    for (x, y, on_right, label, color) in marks {
        let yr = if *on_right { &rrange } else { &lrange };
        if !(x_range.contains(x) || *x == x_range.end) || !(yr.contains(y) || *y == yr.end) {
            continue; // outside the frame (or not finite): plotters' pixels would overflow
        }
        let p = if *on_right {
            chart.borrow_secondary().backend_coord(&(*x, *y))
        } else {
            chart.backend_coord(&(*x, *y))
        };
        let q = (p.0 - base.0, p.1 - base.1);
        plot.draw(&Circle::new(q, 6, ShapeStyle::from(color).filled()))?;
        plot.draw(&Circle::new(q, 6, ShapeStyle::from(&BLACK).stroke_width(1)))?;
        boxed_label(&plot, label, q)?;
    }
    // an axis with nothing finite to draw says so instead of staying silently empty
    let (pw, ph) = plot.dim_in_pixel();
    let empty: Vec<&Axis> = std::iter::once(left)
        .chain(right)
        .filter(|a| {
            !a.curves
                .iter()
                .flat_map(|c| &c.pts)
                .any(|p| p.0.is_finite() && p.1.is_finite())
        })
        .collect();
    for (k, a) in empty.iter().enumerate() {
        plot.draw_text(
            &format!(
                "{}: no material on this line (nothing finite to draw)",
                a.label
            ),
            &text_style(18.0, GREY).pos(Pos::new(HPos::Center, VPos::Center)),
            (pw as i32 / 2, ph as i32 / 3 + 28 * k as i32),
        )?;
    }
    // the legend last, so that nothing covers it
    draw_legend(
        chart.configure_series_labels(),
        SeriesLabelPosition::UpperRight,
        LEGEND,
    )
}

// ---------------------------------------------------------------- the three pictures

fn gpa(p: f64) -> f64 {
    p * 1e-9
}

fn is_dry(case: &Case) -> bool {
    case.kind == Kind::Dry
}

pub(super) fn y_axis_label(case: &Case) -> &'static str {
    if case.body1.shape == Shape::Roller || case.body2.shape == Shape::Roller {
        "y, roller axis (mm)"
    } else {
        "y (mm)"
    }
}

pub(super) fn film_word(case: &Case) -> &'static str {
    if is_dry(case) {
        "gap after loading"
    } else {
        "film thickness"
    }
}

/// (max, index) of the finite values.
pub(super) fn arg_max(v: &[f64]) -> (f64, usize) {
    v.iter().enumerate().filter(|(_, x)| x.is_finite()).fold(
        (f64::NEG_INFINITY, 0),
        |a, (k, &x)| if x > a.0 { (x, k) } else { a },
    )
}

pub(super) fn arg_min(v: &[f64]) -> (f64, usize) {
    v.iter()
        .enumerate()
        .filter(|(_, x)| x.is_finite())
        .fold(
            (f64::INFINITY, 0),
            |a, (k, &x)| if x < a.0 { (x, k) } else { a },
        )
}

/// A colour or axis range from `lo` to `hi`, made drawable by [`drawable_range`].
pub(super) fn nonempty(lo: f64, hi: f64) -> Range<f64> {
    drawable_range(lo, hi)
}

/// A value a picture can place: finite and within ±1e300 (plotters' pixel arithmetic overflows
/// beyond).
pub(super) fn usable(v: f64) -> bool {
    v.is_finite() && v.abs() <= 1e300
}

/// [`drawable_range`] of a range.
pub(super) fn drawable(r: Range<f64>) -> Range<f64> {
    drawable_range(r.start, r.end)
}

/// The one guard of every axis and colour range of the pictures: plotters loops forever on an
/// infinite or NaN range, and on one too narrow for its values to step through (`1..1+1e-16`).
/// Returns a finite range with `end > start` and a width of at least 1e-9 of its magnitude:
///
/// * non-finite (or beyond ±1e300) ends are dropped: one finite end is kept, none gives `0..1`;
/// * ends in the wrong order are swapped;
/// * values below 1e-100 in magnitude count as zero (no picture shows such numbers);
/// * a zero or too narrow width is widened by ±10 % of the magnitude, or to `0..1` at zero.
pub fn drawable_range(lo: f64, hi: f64) -> Range<f64> {
    let tiny = |v: f64| if v.abs() < 1e-100 { 0.0 } else { v };
    let (lo, hi) = match (usable(lo), usable(hi)) {
        (true, true) => (tiny(lo.min(hi)), tiny(lo.max(hi))),
        (true, false) => (tiny(lo), tiny(lo)),
        (false, true) => (tiny(hi), tiny(hi)),
        (false, false) => (0.0, 0.0),
    };
    let mag = lo.abs().max(hi.abs());
    if hi - lo >= 1e-9 * mag && hi > lo {
        return lo..hi;
    }
    if mag == 0.0 {
        return 0.0..1.0;
    }
    let d = 0.1 * mag;
    lo - d..hi + d
}

fn pmax_line(solution: &Solution, case: &Case) -> String {
    let s = &solution.summary;
    let mut t = format!(
        "p_max = {} GPa at x = {} mm",
        fmt_sig(gpa(s.max_pressure_pa), 4),
        fmt_sig(s.max_pressure_at_m[0] * 1e3, 3)
    );
    if solution.grid.ny > 1 {
        t += &format!(", y = {} mm", fmt_sig(s.max_pressure_at_m[1] * 1e3, 3));
    }
    if s.hertz_pressure_pa > 0.0 {
        t += &format!(
            "   (Hertz, dry: p_h = {} GPa, {} = {} mm)",
            fmt_sig(gpa(s.hertz_pressure_pa), 4),
            // a ball's Hertz scale is its contact radius (semi-axis along x) a
            if case.is_point() { "a" } else { "b" },
            fmt_sig(s.hertz_half_width_m * 1e3, 3)
        );
    }
    t
}

fn convergence_line(solution: &Solution, case: &Case) -> String {
    let s = &solution.summary;
    let kind = if is_dry(case) { "dry contact" } else { "EHL" };
    let load = if case.is_infinite_line() {
        format!("w' = {} N/mm", fmt_sig(s.load_n * 1e-3, 4))
    } else {
        format!("F = {} N", fmt_sig(s.load_n, 4))
    };
    format!(
        "{kind}, {load}, {} x {} cells, {}",
        solution.grid.nx,
        solution.grid.ny,
        if s.converged {
            format!("converged in {} iterations", s.iterations)
        } else {
            format!("NOT CONVERGED after {} iterations", s.iterations)
        }
    )
}

/// Hertz pressure along x (mm, GPa) over [-b, b], or nothing when the summary has no Hertz figures.
fn hertz_curve(solution: &Solution) -> Option<Curve> {
    let s = &solution.summary;
    let (ph, b) = (s.hertz_pressure_pa, s.hertz_half_width_m);
    if !(ph > 0.0 && b > 0.0 && ph.is_finite() && b.is_finite()) {
        return None;
    }
    let n = 200;
    let pts = (0..=n)
        .map(|k| {
            let x = -b + 2.0 * b * k as f64 / n as f64;
            let r = (1.0 - (x / b).powi(2)).max(0.0);
            (x * 1e3, gpa(ph * r.sqrt()))
        })
        .collect();
    Some(Curve {
        pts,
        color: HERTZ_COLOR,
        dashed: true,
        label: "Hertz, dry: p_h √(1 − (x/b)²)".into(),
    })
}

fn x_range_mm(g: &Grid) -> Range<f64> {
    g.x_min * 1e3..g.x_max() * 1e3
}

fn row(v: &[f64], g: &Grid, j: usize) -> Vec<f64> {
    v[j * g.nx..(j + 1) * g.nx].to_vec()
}

/// Pressure profile (+ Hertz) along row `j`: the left axis of the profile plots.
fn pressure_axis(solution: &Solution, j: usize) -> (Axis, (f64, f64)) {
    let g = &solution.grid;
    let p = row(&solution.fields.pressure, g, j);
    let xs = g.xs();
    let pts: Vec<(f64, f64)> = xs.iter().zip(&p).map(|(x, p)| (x * 1e3, gpa(*p))).collect();
    let (pm, k) = arg_max(&p);
    let top = pm.max(solution.summary.hertz_pressure_pa);
    let mut curves = vec![Curve {
        pts,
        color: PRESSURE_COLOR,
        dashed: false,
        label: "pressure (left axis)".into(),
    }];
    if let Some(h) = hertz_curve(solution) {
        curves.push(h);
    }
    (
        Axis {
            label: "pressure (GPa)".into(),
            range: nonempty(0.0, gpa(top) * 1.12),
            curves,
        },
        (xs[k] * 1e3, gpa(pm)),
    )
}

/// Writes `pressure.png`.
pub fn write_pressure(path: &Path, case: &Case, solution: &Solution) -> Result<()> {
    let g = &solution.grid;
    render(path, |root| {
        if g.ny == 1 {
            let (mut axis, peak) = pressure_axis(solution, 0);
            axis.curves[0].label = "pressure".into();
            let marks = [(
                peak.0,
                peak.1,
                false,
                format!("p_max = {} GPa", fmt_sig(peak.1, 4)),
                PRESSURE_COLOR,
            )];
            draw_profile(
                root,
                &case.title,
                &[
                    format!(
                        "pressure, infinite line contact — {}",
                        pmax_line(solution, case)
                    ),
                    convergence_line(solution, case),
                ],
                x_range_mm(g),
                &axis,
                None,
                &marks,
            )
        } else {
            let (pm, k) = arg_max(&solution.fields.pressure);
            let (i, j) = (k % g.nx, k / g.nx);
            // A few singular cells (the end peak of an uncorrected roller, tens of GPa) would
            // turn the whole contact black: when the maximum exceeds twice the 90th percentile
            // of the loaded cells, the colours saturate at 1.5 x that percentile (an EHL spike
            // or a Hertz peak never triggers this), and the subtitle says so.
            let mut loaded: Vec<f64> = solution
                .fields
                .pressure
                .iter()
                .copied()
                .filter(|&v| v > 0.0)
                .collect();
            loaded.sort_by(f64::total_cmp);
            let p90 = loaded
                .get(((loaded.len() as f64) * 0.9) as usize)
                .copied()
                .unwrap_or(pm);
            let top = if pm > 2.0 * p90 { 1.5 * p90 } else { pm };
            let mut lines = vec![
                format!("pressure — {}", pmax_line(solution, case)),
                convergence_line(solution, case),
            ];
            if top < pm {
                lines.push(format!(
                    "colours saturate above {} GPa (a few cells reach {} GPa)",
                    fmt_sig(gpa(top), 3),
                    fmt_sig(gpa(pm), 3)
                ));
            }
            draw_map(
                root,
                &MapSpec {
                    title: &case.title,
                    lines,
                    grid: g,
                    values: &solution.fields.pressure,
                    scale: 1e-9,
                    range: nonempty(0.0, gpa(top)),
                    cmap: ColorMap::Inferno,
                    bar_label: "pressure (GPa)".into(),
                    y_label: y_axis_label(case),
                    marker: Some((g.x(i), g.y(j), format!("p_max {} GPa", fmt_sig(gpa(pm), 4)))),
                    cross: true,
                },
            )
        }
    })
}

/// The film colour range (m): from the minimum to the film over the loaded zone (see the module
/// documentation); returns (lo, hi, saturates).
fn film_range(solution: &Solution, film: &[f64]) -> (f64, f64, bool) {
    let p = &solution.fields.pressure;
    let (pm, _) = arg_max(p);
    let (lo, _) = arg_min(film);
    let (top, _) = arg_max(film);
    let loaded = film
        .iter()
        .zip(p)
        .filter(|(h, p)| h.is_finite() && **p > 0.05 * pm)
        .map(|(h, _)| *h)
        .fold(f64::NEG_INFINITY, f64::max);
    let mut hi = if loaded.is_finite() && loaded > lo + 0.2 * lo.abs() && loaded > lo {
        // lubricated: the loaded zone has a film worth showing; give it most of the colours
        lo + 1.5 * (loaded - lo)
    } else {
        // dry (zero gap under load) or flat film: the median gap of the domain
        let mut v: Vec<f64> = film.iter().copied().filter(|h| h.is_finite()).collect();
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
    };
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        hi = top;
    }
    let saturates = top > hi;
    (lo, hi.min(top).max(lo), saturates)
}

/// Writes `film.png`; an error if the solution has no film.
pub fn write_film(path: &Path, case: &Case, solution: &Solution) -> Result<()> {
    let g = &solution.grid;
    let film = solution
        .fields
        .film
        .as_deref()
        .ok_or_else(|| draw_err(path, "the solution has no film"))?;
    let word = film_word(case);
    let (hmin, kmin) = arg_min(film);
    let (lo, hi, saturates) = film_range(solution, film);
    // a profile gets some headroom above the colour-map range
    let shown_top = if g.ny == 1 { 1.25 * hi } else { hi };
    let saturates = saturates && arg_max(film).0 > shown_top;
    let (unit, scale) = film_unit(hi.max(hmin.abs()));
    let hmin_text = format!("{} {unit}", fmt_sig(hmin * scale, 3));
    let (imin, jmin) = (kmin % g.nx, kmin / g.nx);
    let mut line1 = format!(
        "{word} — minimum {hmin_text} at x = {} mm",
        fmt_sig(g.x(imin) * 1e3, 3)
    );
    if g.ny > 1 {
        line1 += &format!(", y = {} mm", fmt_sig(g.y(jmin) * 1e3, 3));
    }
    if is_dry(case) {
        line1 = format!("{word} — zero over the contact (dark)");
        if let Some(area) = solution.summary.contact_area_m2 {
            line1 += &format!(", contact area {} mm²", fmt_sig(area * 1e6, 3));
        }
    }
    if let Some(hc) = solution.summary.central_film_m {
        line1 += &format!(";  central {} {unit}", fmt_sig(hc * scale, 3));
    }
    let dry = is_dry(case);
    let line2 = if saturates {
        let mut t = format!(
            "{} above {} {unit} (the {} away from the loaded zone is larger)",
            if g.ny == 1 {
                "axis clipped"
            } else {
                "colours saturate"
            },
            fmt_sig(shown_top * scale, 3),
            if dry { "gap" } else { "film" }
        );
        if film.iter().any(|h| !h.is_finite()) {
            t += "; grey: no material";
        }
        t
    } else {
        convergence_line(solution, case)
    };
    // a dry contact's minimum gap is zero anywhere in the contact: no marker then
    let film_marker = |x: f64, y: f64, label: String| if dry { None } else { Some((x, y, label)) };
    render(path, |root| {
        if g.ny == 1 {
            let xs = g.xs();
            let pts: Vec<(f64, f64)> = xs
                .iter()
                .zip(film)
                .map(|(x, h)| (x * 1e3, h * scale))
                .collect();
            let top = shown_top * scale;
            let axis = Axis {
                label: format!("{word} ({unit})"),
                range: nonempty(0.0, top),
                curves: vec![Curve {
                    pts,
                    color: FILM_COLOR,
                    dashed: false,
                    label: word.into(),
                }],
            };
            let marks: Vec<_> =
                film_marker(xs[imin] * 1e3, hmin * scale, format!("h_min = {hmin_text}"))
                    .map(|(x, y, l)| (x, y, false, l, FILM_COLOR))
                    .into_iter()
                    .collect();
            draw_profile(
                root,
                &case.title,
                &[line1, line2],
                x_range_mm(g),
                &axis,
                None,
                &marks,
            )
        } else {
            draw_map(
                root,
                &MapSpec {
                    title: &case.title,
                    lines: vec![line1, line2],
                    grid: g,
                    values: film,
                    scale,
                    range: nonempty(lo * scale, hi * scale),
                    cmap: ColorMap::Viridis,
                    bar_label: format!("{word} ({unit})"),
                    y_label: y_axis_label(case),
                    marker: film_marker(g.x(imin), g.y(jmin), format!("h_min {hmin_text}")),
                    cross: false,
                },
            )
        }
    })
}

/// Writes `centerline.png`.
pub fn write_centerline(path: &Path, case: &Case, solution: &Solution) -> Result<()> {
    let g = &solution.grid;
    let j = super::centre_row(solution);
    let (axis, peak) = pressure_axis(solution, j);
    let mut marks = vec![(
        peak.0,
        peak.1,
        false,
        format!("{} GPa", fmt_sig(peak.1, 4)),
        PRESSURE_COLOR,
    )];
    let where_ = if g.ny == 1 {
        "infinite line contact".to_string()
    } else {
        format!(
            "along x at y = {} mm (axial centre)",
            fmt_sig(g.y(j) * 1e3, 3)
        )
    };
    let mut lines = vec![
        format!("centre line {where_}"),
        convergence_line(solution, case),
    ];
    let right = solution.fields.film.as_deref().map(|film| {
        let word = film_word(case);
        let h = row(film, g, j);
        let (hmin, k) = arg_min(&h);
        let (lo, hi, _) = film_range(solution, film);
        let _ = lo;
        // the film axis: from 0 to 2.5x the top of the loaded-zone film so the curve sits below
        // the pressure; dry: the whole gap along the line
        let top = if is_dry(case) {
            arg_max(&h).0
        } else {
            2.5 * hi
        };
        // no material on this line (the film is +inf all along it): the axis falls back to
        // drawable_range's default and the panel says so
        let top = if hmin.is_finite() { top } else { f64::NAN };
        let (unit, scale) = film_unit(if top.is_finite() { top } else { 1e-6 });
        let xs = g.xs();
        if !hmin.is_finite() {
            lines[0] += &format!(";  no material on this line (no {word})");
        } else if !is_dry(case) {
            marks.push((
                xs[k] * 1e3,
                hmin * scale,
                true,
                format!("{} {unit}", fmt_sig(hmin * scale, 3)),
                FILM_COLOR,
            ));
            lines[0] += &format!(
                ";  minimum {word} on this line {} {unit}",
                fmt_sig(hmin * scale, 3)
            );
        }
        Axis {
            label: format!("{word} ({unit})"),
            range: nonempty(0.0, top * scale),
            curves: vec![Curve {
                pts: xs
                    .iter()
                    .zip(&h)
                    .map(|(x, h)| (x * 1e3, h * scale))
                    .collect(),
                color: FILM_COLOR,
                dashed: false,
                label: format!("{word} (right axis)"),
            }],
        }
    });
    render(path, |root| {
        draw_profile(
            root,
            &case.title,
            &lines,
            x_range_mm(g),
            &axis,
            right.as_ref(),
            &marks,
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The legend goes where the data is not: a rising curve leaves the lower right free, a
    /// falling one the upper right (which is also the choice on a tie).
    #[test]
    fn legend_avoids_the_data() {
        let rising: Vec<(f64, f64)> = (0..=10).map(|i| (i as f64, (i as f64).sqrt())).collect();
        let r = (0.0, 10.0);
        let pos = legend_corner(&rising, r, (0.0, 3.2));
        assert!(matches!(pos, SeriesLabelPosition::LowerRight), "{pos:?}");
        let falling: Vec<(f64, f64)> = rising.iter().map(|&(x, y)| (x, 3.2 - y)).collect();
        let pos = legend_corner(&falling, r, (0.0, 3.2));
        assert!(matches!(pos, SeriesLabelPosition::UpperRight), "{pos:?}");
    }

    #[test]
    fn tick_and_sig_formats() {
        assert_eq!(fmt_tick(0.25, 0.55), "0.25");
        assert_eq!(fmt_tick(5.0, 10.0), "5");
        assert_eq!(fmt_tick(-0.0, 1.0), "0");
        assert_eq!(fmt_tick(0.30000000000000004, 1.0), "0.3");
        assert_eq!(fmt_sig(1.23456, 4), "1.235");
        assert_eq!(fmt_sig(0.0123456, 3), "0.0123");
        assert_eq!(fmt_sig(1234.6, 3), "1235");
        assert_eq!(film_unit(0.5e-6).0, "nm");
        assert_eq!(film_unit(2e-6).0, "µm");
    }

    /// Every range a picture can meet comes out finite, ordered and wide enough for plotters to
    /// step through (its tick search loops forever otherwise).
    #[test]
    fn every_range_is_drawable() {
        let nasty = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            1.0 + 1e-16,
            1e-300,
            -1e-300,
            1e300,
            -1e300,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            2.5e-9,
            1e6,
            1e6 + 1e-9,
        ];
        for &a in &nasty {
            for &b in &nasty {
                let r = drawable_range(a, b);
                assert!(r.start.is_finite() && r.end.is_finite(), "{a} {b} -> {r:?}");
                let mag = r.start.abs().max(r.end.abs());
                assert!(
                    r.end - r.start >= 1e-9 * mag && r.end > r.start,
                    "{a} {b} -> {r:?}"
                );
                let coord: plotters::coord::types::RangedCoordf64 = r.clone().into();
                let ticks = coord.key_points(10);
                assert!(!ticks.is_empty() && ticks.len() <= 11, "{a} {b} -> {r:?}");
            }
        }
        // ordinary ranges are kept as they are
        assert_eq!(drawable_range(0.0, 2.5), 0.0..2.5);
        assert_eq!(drawable_range(0.0, f64::NEG_INFINITY), 0.0..1.0);
        assert_eq!(drawable_range(2.0, 2.0), 1.8..2.2);
    }

    /// Runs `f` on a thread; fails (instead of hanging the suite) if it takes over a minute.
    fn within_a_minute(f: impl FnOnce() -> Result<()> + Send + 'static) {
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send(f().map_err(|e| e.to_string()));
        });
        match rx.recv_timeout(std::time::Duration::from_secs(60)) {
            Ok(r) => r.unwrap(),
            Err(_) => panic!("drawing hung"),
        }
    }

    /// The centre row has no material (film +inf all along it): centerline.png is drawn with
    /// a default film axis and says so (it looped inside plotters before).
    #[test]
    fn centerline_without_material_on_the_centre_row() {
        for dry in [true, false] {
            let (case, mut sol) = if dry {
                crate::output::synthetic::dry_roller()
            } else {
                crate::output::synthetic::ehl_ball(false)
            };
            let j = crate::output::centre_row(&sol);
            let nx = sol.grid.nx;
            for v in &mut sol.fields.film.as_mut().unwrap()[j * nx..(j + 1) * nx] {
                *v = f64::INFINITY;
            }
            for v in &mut sol.fields.pressure[j * nx..(j + 1) * nx] {
                *v = 0.0;
            }
            let root = tempfile::tempdir().unwrap();
            let path = root.path().join("centerline.png");
            within_a_minute(move || write_centerline(&path, &case, &sol));
        }
    }

    /// Maps and profiles of fields that are zero or constant everywhere, and x-y charts of
    /// nothing, one point, equal points or huge values, all draw.
    #[test]
    fn degenerate_data_draws() {
        let (case, mut sol) = crate::output::synthetic::dry_roller();
        sol.fields.pressure.iter_mut().for_each(|p| *p = 0.0);
        sol.fields
            .film
            .as_mut()
            .unwrap()
            .iter_mut()
            .for_each(|h| *h = 1e-6);
        let root = tempfile::tempdir().unwrap();
        let dir = root.path().to_path_buf();
        within_a_minute(move || {
            write_pressure(&dir.join("p.png"), &case, &sol)?;
            write_film(&dir.join("f.png"), &case, &sol)?;
            write_centerline(&dir.join("c.png"), &case, &sol)?;
            let xy = |pts: Vec<(f64, f64)>| {
                vec![Series {
                    label: "s".into(),
                    points: pts,
                }]
            };
            for (k, pts) in [
                vec![],
                vec![(f64::NAN, 1.0), (1.0, f64::INFINITY)],
                vec![(1.0, 2.0)],
                vec![(1.0, 2.0), (1.0, 2.0)],
                vec![(1.0, 1.0), (1.0 + 1e-16, 1.0 + 1e-16)],
                vec![(-1e308, 1e308), (1e308, -1e308)],
            ]
            .into_iter()
            .enumerate()
            {
                write_xy(&dir.join(format!("xy{k}.png")), "t", "", "x", "y", &xy(pts))?;
            }
            Ok(())
        });
    }

    #[test]
    fn thin_keeps_short_lines_and_the_envelope_of_long_ones() {
        let short: Vec<(f64, f64)> = (0..10).map(|i| (i as f64, (i % 3) as f64)).collect();
        assert_eq!(thin(&short, 450), short);
        // 4000 points, a spike at one point: kept, and at most 2 points per bucket plus ends
        let long: Vec<(f64, f64)> = (0..4000)
            .map(|i| {
                (
                    i as f64,
                    if i == 1234 {
                        10.0
                    } else {
                        (i as f64 * 0.01).sin()
                    },
                )
            })
            .collect();
        let t = thin(&long, 450);
        assert!(t.len() <= 2 * 450 + 2, "{}", t.len());
        assert!(t.contains(&(1234.0, 10.0)));
        assert_eq!(t[0], long[0]);
        assert_eq!(t[t.len() - 1], long[3999]);
        assert!(t.windows(2).all(|w| w[1].0 > w[0].0));
        let lo = t.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        assert!((lo + 1.0).abs() < 1e-3);
    }

    #[test]
    fn clip_splits_at_the_top() {
        let pts = [(0.0, 0.5), (1.0, 2.0), (2.0, 0.5)];
        let pieces = clip(&pts, &(0.0..1.0));
        assert_eq!(pieces.len(), 2);
        assert_eq!(pieces[0], vec![(0.0, 0.5), (1.0 / 3.0, 1.0)]);
        // the crossing is interpolated: equal to rounding
        assert!((pieces[1][0].0 - 5.0 / 3.0).abs() < 1e-15 && pieces[1][0].1 == 1.0);
        assert_eq!(pieces[1][1], (2.0, 0.5));
    }
}

// ---------------------------------------------------------------- x-y charts (studies)

/// One curve of an x-y chart: a legend label and its points.
#[derive(Debug, Clone)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

pub(super) const SERIES_COLORS: [RGBColor; 6] = [
    RGBColor(200, 40, 30),
    RGBColor(20, 90, 180),
    RGBColor(30, 140, 60),
    RGBColor(150, 70, 170),
    RGBColor(230, 130, 0),
    RGBColor(60, 60, 60),
];

/// The mesh of the line charts (profiles, parameter studies): light grey grid at the major
/// ticks only, 10 x 8 labels, the fonts of every picture.
pub(super) fn line_chart_mesh<'m, 'a, 'b, X, Y, DB>(
    m: &'m mut MeshStyle<'a, 'b, X, Y, DB>,
) -> &'m mut MeshStyle<'a, 'b, X, Y, DB>
where
    X: Ranged,
    Y: Ranged,
    DB: DrawingBackend,
{
    m.x_labels(10)
        .y_labels(8)
        .max_light_lines(0)
        .bold_line_style(ShapeStyle::from(&RGBColor(225, 225, 225)).stroke_width(1))
        .label_style(text_style(16.0, BLACK))
        .axis_desc_style(text_style(18.0, BLACK))
}

/// The look of a legend box: font size (px), length of its line samples (px), distance to the
/// edge of the plot (px) and opacity of its white background.
#[derive(Clone, Copy)]
pub(super) struct LegendLook {
    pub(super) font: f64,
    pub(super) sample: u32,
    pub(super) margin: u32,
    pub(super) opacity: f64,
}

/// The legend of the pictures.
pub(super) const LEGEND: LegendLook = LegendLook {
    font: 16.0,
    sample: 36,
    margin: 12,
    opacity: 0.9,
};

/// Draws the legend `labels` (`chart.configure_series_labels()`) at `position`, in a box with a
/// grey border.
pub(super) fn draw_legend<'a, 'c: 'a, CT: CoordTranslate>(
    mut labels: SeriesLabelStyle<'a, '_, BitMapBackend<'c>, CT>,
    position: SeriesLabelPosition,
    look: LegendLook,
) -> DrawResult<()> {
    labels
        .position(position)
        .margin(look.margin)
        .legend_area_size(look.sample)
        .label_font(text_style(look.font, BLACK))
        .background_style(ShapeStyle::from(&WHITE.mix(look.opacity)).filled())
        .border_style(ShapeStyle::from(&RGBColor(150, 150, 150)))
        .draw()?;
    Ok(())
}

/// `text` in grey, `size` px, in the middle of the plotting area of `chart` (a panel with
/// nothing to draw).
pub(super) fn say_in_middle(chart: &Chart2d, text: &str, size: f64) -> DrawResult<()> {
    let plot = chart.plotting_area().strip_coord_spec();
    let (pw, ph) = plot.dim_in_pixel();
    plot.draw_text(
        text,
        &text_style(size, GREY).pos(Pos::new(HPos::Center, VPos::Center)),
        (pw as i32 / 2, ph as i32 / 2),
    )?;
    Ok(())
}

/// The corner of the plot area with the fewest data points (in its outer 45 % of x and 35 %
/// of y), so the legend hides as little of the curves as it can; upper right on a tie.
pub(super) fn legend_corner(
    pts: &[(f64, f64)],
    xr: (f64, f64),
    yr: (f64, f64),
) -> SeriesLabelPosition {
    let fx = |x: f64| (x - xr.0) / (xr.1 - xr.0);
    let fy = |y: f64| (y - yr.0) / (yr.1 - yr.0);
    let count = |right: bool, upper: bool| {
        pts.iter()
            .filter(|&&(x, y)| {
                let (u, v) = (fx(x), fy(y));
                (if right { u > 0.55 } else { u < 0.45 })
                    && (if upper { v > 0.65 } else { v < 0.35 })
            })
            .count()
    };
    [
        (SeriesLabelPosition::UpperRight, count(true, true)),
        (SeriesLabelPosition::LowerRight, count(true, false)),
        (SeriesLabelPosition::UpperLeft, count(false, true)),
        (SeriesLabelPosition::LowerLeft, count(false, false)),
    ]
    .into_iter()
    .min_by_key(|&(_, n)| n)
    .map_or(SeriesLabelPosition::UpperRight, |(p, _)| p)
}

/// A plain x-y chart with markers and a legend, for parameter studies (`sweep.png`, the
/// validation pages): `x_label` and `y_label` carry the units. Non-finite points are skipped;
/// with no finite point at all the chart is an empty panel that says so (default axes 0..1).
pub fn write_xy(
    path: &Path,
    title: &str,
    subtitle: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<()> {
    let pts: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|&(x, y)| usable(x) && usable(y))
        .collect();
    let (mut x0, mut x1, mut y0, mut y1) = pts.iter().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
    );
    let pad = |lo: &mut f64, hi: &mut f64| {
        let r = drawable_range(*lo, *hi);
        let span = r.end - r.start;
        let r = drawable_range(r.start - 0.05 * span, r.end + 0.05 * span);
        (*lo, *hi) = (r.start, r.end);
    };
    pad(&mut x0, &mut x1);
    if y0 >= 0.0 {
        y0 = 0.0; // magnitudes read best from zero
    }
    pad(&mut y0, &mut y1);
    let lines = if subtitle.is_empty() {
        vec![]
    } else {
        vec![subtitle.to_string()]
    };
    render(path, |root| {
        let area = titled(root, title, &lines)?;
        let (xs, ys) = (x1 - x0, y1 - y0);
        let x_fmt = move |v: &f64| fmt_tick(*v, xs);
        let y_fmt = move |v: &f64| fmt_tick(*v, ys);
        let mut chart = ChartBuilder::on(&area)
            .margin(20)
            .x_label_area_size(62)
            .y_label_area_size(96)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        line_chart_mesh(&mut chart.configure_mesh())
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt)
            .x_desc(x_label)
            .y_desc(y_label)
            .draw()?;
        if pts.is_empty() {
            return say_in_middle(&chart, "no finite point to draw", 20.0);
        }
        for (k, s) in series.iter().enumerate() {
            let color = SERIES_COLORS[k % SERIES_COLORS.len()];
            let style = ShapeStyle::from(&color).stroke_width(3);
            let mut p: Vec<(f64, f64)> = s
                .points
                .iter()
                .copied()
                .filter(|&(x, y)| usable(x) && usable(y))
                .collect();
            if p.is_empty() {
                continue;
            }
            p.sort_by(|a, b| a.0.total_cmp(&b.0));
            chart
                .draw_series(LineSeries::new(p.clone(), style))?
                .label(s.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 21, y)], style));
            chart.draw_series(
                p.iter()
                    .map(|&q| Circle::new(q, 4, ShapeStyle::from(&color).filled())),
            )?;
        }
        draw_legend(
            chart.configure_series_labels(),
            legend_corner(&pts, (x0, x1), (y0, y1)),
            LEGEND,
        )
    })
}
