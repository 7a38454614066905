//! The outputs of a thermal run (`[thermal]`; contract in interface.md):
//!
//! * `temperature.npz`: `x`, `y` (m); `mid_film`, `max_film`, `surface_1`, `surface_2` (K,
//!   (ny, nx); the film maps NaN on cells where no film temperature is solved); `film_section` (K) and `section_z` (m), (nz, nx), the film temperature at the
//!   collocation points across z along the centre grid line (`section_y`, m).
//! * `temperature.png`: along the centre line, the temperature rise above the inlet of the film
//!   (its maximum across z and mid-film) and of both surfaces; below, the film temperature
//!   across the film (z/h from body 1 to body 2) against x. On a 2D grid (a finite roller, a
//!   ball) three maps follow, on one colour scale: the film's largest rise across z and the
//!   rise of each surface, each with its maximum marked.

use super::colormap::ColorMap;
use super::plot::{
    draw_colorbar_on, draw_err, draw_map, fmt_sig, nonempty, render_sized, text_style,
    y_axis_label, Fonts, MapSpec,
};
use crate::case::Case;
use crate::solution::{Solution, TemperatureFields};
use crate::Result;
use ndarray::{Array1, Array2};
use plotters::prelude::*;
use std::path::Path;

pub const TEMPERATURE_NPZ: &str = "temperature.npz";
pub const TEMPERATURE_PNG: &str = "temperature.png";

/// Writes the temperature files of `case` into `dir` when the solution has temperatures.
pub fn write(dir: &Path, case: &Case, solution: &Solution) -> Result<()> {
    let Some(t) = &solution.temperature else {
        return Ok(());
    };
    write_npz(&dir.join(TEMPERATURE_NPZ), solution, t)?;
    write_png(&dir.join(TEMPERATURE_PNG), case, solution, t)
}

/// The height (px) of the centre-line panels of `temperature.png`, and of each map below them
/// on a 2D grid.
pub const LINE_PANELS: u32 = 860;
pub const MAP_HEIGHT: u32 = 560;

fn write_npz(path: &Path, solution: &Solution, t: &TemperatureFields) -> Result<()> {
    let g = &solution.grid;
    let mut npz = super::npz::Npz::create(path)?;
    npz.add_grid(g)?;
    for (name, v) in [
        ("mid_film", &t.mid_film),
        ("max_film", &t.max_film),
        ("surface_1", &t.surface_1),
        ("surface_2", &t.surface_2),
    ] {
        let a = Array2::from_shape_vec((g.ny, g.nx), v.clone()).map_err(|e| npz.err(e))?;
        npz.add(name, &a)?;
    }
    for (name, v) in [
        ("film_section", &t.film_section),
        ("section_z", &t.section_z),
    ] {
        let a = Array2::from_shape_vec((t.nz, g.nx), v.clone()).map_err(|e| npz.err(e))?;
        npz.add(name, &a)?;
    }
    npz.add("section_y", &Array1::from(vec![g.y(t.section_row)]))?;
    npz.add("inlet_temperature", &Array1::from(vec![t.inlet]))?;
    npz.finish()
}

fn write_png(path: &Path, case: &Case, solution: &Solution, t: &TemperatureFields) -> Result<()> {
    let g = &solution.grid;
    let j = t.section_row;
    let row = |v: &[f64]| -> Vec<f64> {
        v[j * g.nx..(j + 1) * g.nx]
            .iter()
            .map(|x| x - t.inlet)
            .collect()
    };
    // (the maximum across z, wider and drawn first, shows on both sides of the line it
    // coincides with: the mid-film where the film is hottest in its middle, a surface's where
    // the heat flows into the film from that body, e.g. the glass disc under a ball)
    let series = [
        ("film, maximum across z", row(&t.max_film), RED, 5),
        ("film, mid-film", row(&t.mid_film), MAGENTA, 2),
        ("surface of body 1 (z = 0)", row(&t.surface_1), BLUE, 2),
        ("surface of body 2 (z = h)", row(&t.surface_2), GREEN, 2),
    ];
    let finite_max = |v: &[f64]| {
        v.iter()
            .cloned()
            .filter(|x| x.is_finite())
            .fold(0.0f64, f64::max)
    };
    let top = series
        .iter()
        .map(|s| finite_max(&s.1))
        .fold(0.0f64, f64::max)
        .max(1e-3);
    let low = series
        .iter()
        .flat_map(|s| s.1.iter().cloned())
        .filter(|x| x.is_finite())
        .fold(0.0f64, f64::min);
    // x window: the pressurised zone of the row widened by a third on each side
    let p = &solution.fields.pressure[j * g.nx..(j + 1) * g.nx];
    let loaded: Vec<usize> = (0..g.nx).filter(|&i| p[i] > 0.0).collect();
    let (x_lo, x_hi) = match (loaded.first(), loaded.last()) {
        (Some(&a), Some(&b)) if b > a => {
            let w = g.x(b) - g.x(a);
            (
                (g.x(a) - w / 3.0).max(g.x_min),
                (g.x(b) + w / 3.0).min(g.x_max()),
            )
        }
        _ => (g.x_min, g.x_max()),
    };
    let mm = 1e3;
    let xs: Vec<f64> = (0..g.nx).map(|i| g.x(i) * mm).collect();
    // the colour scale reaches below T0 where the film cools below the inlet (the outlet's
    // expansion at high speed: -50 K in pure rolling at L = 5), else it starts at T0
    let (tmin, tmax) = t
        .film_section
        .iter()
        .filter(|x| x.is_finite())
        .fold((t.inlet, t.inlet), |(a, b), &x| (a.min(x), b.max(x)));
    let lo = (tmin - t.inlet).min(0.0);
    let span = (tmax - t.inlet - lo).max(1e-3);
    // the maps of a 2D grid: rise above the inlet (K), NaN where no film was solved
    let maps: Vec<(&str, Vec<f64>)> = if g.ny > 1 {
        [
            ("film, largest across z", &t.max_film),
            ("surface of body 1", &t.surface_1),
            ("surface of body 2", &t.surface_2),
        ]
        .into_iter()
        .map(|(name, v)| (name, v.iter().map(|x| x - t.inlet).collect()))
        .collect()
    } else {
        Vec::new()
    };
    let (map_lo, map_hi) = maps
        .iter()
        .flat_map(|(_, v)| v.iter().copied())
        .filter(|x| x.is_finite())
        .fold((0.0f64, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
    let height = LINE_PANELS + MAP_HEIGHT * maps.len() as u32;
    render_sized(path, (1000, height), |root| {
        let (lines_area, maps_area) = root.split_vertically(LINE_PANELS);
        let mut rest = maps_area;
        for (name, rise) in &maps {
            let (area, below) = rest.split_vertically(MAP_HEIGHT);
            rest = below;
            let (top, k) = super::plot::arg_max(rise);
            let title = format!("Temperature rise above the inlet: {name}");
            draw_map(
                &area,
                &MapSpec {
                    title: &title,
                    lines: vec![
                        format!(
                            "largest {} K at x = {} mm, y = {} mm; one colour scale for the three maps",
                            fmt_sig(top, 3),
                            fmt_sig(g.x(k % g.nx) * mm, 3),
                            fmt_sig(g.y(k / g.nx) * mm, 3)
                        ),
                        "grey: outside the film the temperature is solved on (the far inlet, the cavitated outlet)".into(),
                    ],
                    grid: g,
                    values: rise,
                    scale: 1.0,
                    range: nonempty(map_lo, map_hi.max(map_lo + 1e-3)),
                    cmap: ColorMap::Inferno,
                    bar_label: "T - T0 (K)".into(),
                    y_label: y_axis_label(case),
                    marker: Some((
                        g.x(k % g.nx),
                        g.y(k / g.nx),
                        format!("{} K", fmt_sig(top, 3)),
                    )),
                    cross: true,
                },
            )?;
        }
        let (upper, lower) = lines_area.split_vertically(430);
        let title = format!(
            "Temperature rise above the inlet ({} K = {} degC), y = {} mm",
            fmt_sig(t.inlet, 4),
            fmt_sig(t.inlet - 273.15, 3),
            fmt_sig(g.y(j) * mm, 3)
        );
        let mut chart = ChartBuilder::on(&upper)
            .caption(title, text_style(20.0, BLACK))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(x_lo * mm..x_hi * mm, (low * 1.05)..(top * 1.1))?;
        chart
            .configure_mesh()
            .x_desc("x (mm), rolling direction")
            .y_desc("T - T0 (K)")
            .label_style(text_style(15.0, BLACK))
            .axis_desc_style(text_style(17.0, BLACK))
            .draw()?;
        for (name, v, color, width) in &series {
            let pts: Vec<(f64, f64)> = xs
                .iter()
                .zip(v)
                .filter(|(x, y)| y.is_finite() && **x >= x_lo * mm && **x <= x_hi * mm)
                .map(|(x, y)| (*x, *y))
                .collect();
            chart
                .draw_series(LineSeries::new(
                    pts,
                    ShapeStyle::from(color).stroke_width(*width),
                ))?
                .label(*name)
                .legend(move |(x, y)| {
                    PathElement::new(
                        vec![(x, y), (x + 20, y)],
                        ShapeStyle::from(color).stroke_width(*width),
                    )
                });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(text_style(14.0, BLACK))
            .draw()?;

        let (main, bar) = lower.split_horizontally(880);
        let mut sec = ChartBuilder::on(&main)
            .caption(
                "Film temperature across the film (z/h: 0 at body 1, 1 at body 2)",
                text_style(18.0, BLACK),
            )
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(x_lo * mm..x_hi * mm, 0.0..1.0)?;
        sec.configure_mesh()
            .disable_mesh()
            .x_desc("x (mm), rolling direction")
            .y_desc("z / h")
            .label_style(text_style(15.0, BLACK))
            .axis_desc_style(text_style(17.0, BLACK))
            .draw()?;
        let plot = sec.plotting_area().strip_coord_spec();
        let (w, h) = plot.dim_in_pixel();
        let nz = t.nz;
        for px in 0..w {
            let x = x_lo + (px as f64 + 0.5) / w as f64 * (x_hi - x_lo);
            let i = (((x - g.x_min) / g.dx).floor().max(0.0) as usize).min(g.nx - 1);
            let hz = t.section_z[(nz - 1) * g.nx + i];
            for py in 0..h {
                let zeta = 1.0 - (py as f64 + 0.5) / h as f64;
                // linear between the collocation points bracketing zeta
                let zk = |k: usize| {
                    if hz > 0.0 {
                        t.section_z[k * g.nx + i] / hz
                    } else {
                        k as f64 / (nz - 1) as f64
                    }
                };
                let mut k = 0;
                while k + 2 < nz && zk(k + 1) < zeta {
                    k += 1;
                }
                let (z0, z1) = (zk(k), zk(k + 1));
                let s = if z1 > z0 {
                    ((zeta - z0) / (z1 - z0)).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let a = t.film_section[k * g.nx + i];
                let b = t.film_section[(k + 1) * g.nx + i];
                let v = a + s * (b - a);
                let c = if v.is_finite() {
                    let (r, gg, bb) = ColorMap::Inferno.color((v - t.inlet - lo) / span);
                    RGBColor(r, gg, bb)
                } else {
                    RGBColor(255, 255, 255)
                };
                plot.draw_pixel((px as i32, py as i32), &c)?;
            }
        }
        let mut barc = ChartBuilder::on(&bar)
            .margin_top(40)
            .margin_bottom(55)
            .margin_right(10)
            .right_y_label_area_size(70)
            .build_cartesian_2d(0.0..1.0, lo..lo + span)?;
        draw_colorbar_on(
            &mut barc,
            ColorMap::Inferno,
            8,
            Fonts {
                label: 14.0,
                desc: 16.0,
            },
            Some(5),
            "T - T0 (K)",
        )
    })
    .map_err(|e| match e {
        crate::Error::Output { .. } => e,
        other => draw_err(path, other),
    })
}
