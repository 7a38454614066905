//! The stress outputs of `[stress]`: `stress.npz`, `stress_profiles.csv`, `stress.png` and
//! `stress.vtr` (docs/stress.md; contract in interface.md).
//!
//! * `stress.npz`: `x` (nx), `y` (ny), `z` (nz) in m, and for each body k computed
//!   `sxx_k syy_k szz_k syz_k sxz_k sxy_k von_mises_k tresca_k`, each (nz, ny, nx) float32 in Pa
//!   (`tresca` is the maximum shear (s1 - s3)/2). Body frame, z depth, tension positive.
//! * `stress_profiles.csv`: the components and derived values against depth below the pressure
//!   maximum and below the centre of each feature, for each body.
//! * `stress.png`: an x-z section of von Mises through the worst point of the worst body, depth
//!   in um (and b), the maximum marked.
//! * `stress.vtr`: the volume (ParaView), z pointing down as negative coordinates; the fields
//!   in single precision (`Float32`, as computed), the coordinates in double.
//! * `stress_passage.npz` (transient runs): `x_body` (nx_body, m; the material frame of body k,
//!   x_body = x - u_k t), `y` (ny), `z` (window layers, m), and for each body k computed
//!   `max_von_mises_k`, `tau_xz_range_k` (Pa) and with `fatigue.dang_van` `dang_van_k`
//!   (dimensionless), each (nz, ny, nx_body) float32, NaN where a column was never sampled;
//!   `x_body_k` (its own columns, m), `x_contact_start_k` / `x_contact_end_k` (nx_body, m): the
//!   contact-frame x of each material column at its first and last evaluation (a column whose
//!   span covers the loaded zone saw the whole passage), and `x_feature` (1, m) where
//!   `features[0]`'s centre sits in its body's frame (absent without a feature).
//! * `stress_passage.png`: x-z sections of the max-over-passage von Mises and of the tau_xz
//!   range through `features[0]`'s centre line, depth in um, maxima marked.

use super::colormap::ColorMap;
use super::plot::{draw_colorbar_on, draw_err, fmt_sig, render_sized, text_style, Fonts};
use crate::case::Case;
use crate::run::stress::{PassageRun, StressAnalysis};
use crate::solution::Solution;
use crate::stress::derived;
use crate::stress::kernel::COMPONENTS;
use crate::stress::passage::{Passage, PassageMaps};
use crate::Result;
use ndarray::{Array1, Array3};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

pub const STRESS_NPZ: &str = "stress.npz";
pub const STRESS_PROFILES_CSV: &str = "stress_profiles.csv";
pub const STRESS_PNG: &str = "stress.png";
pub const STRESS_VTR: &str = "stress.vtr";
pub const STRESS_PASSAGE_NPZ: &str = "stress_passage.npz";
pub const STRESS_PASSAGE_PNG: &str = "stress_passage.png";

/// Writes the stress files into `dir` when the solution has a stress analysis.
pub fn write(dir: &Path, case: &Case, solution: &Solution) -> Result<()> {
    if let Some(run) = solution.transient.as_ref().and_then(|t| t.passage.as_ref()) {
        write_passage(dir, case, solution, run)?;
    }
    let Some(a) = &solution.stress else {
        return Ok(());
    };
    write_npz(&dir.join(STRESS_NPZ), a)?;
    let csv = profiles_csv(case, solution, a);
    std::fs::write(dir.join(STRESS_PROFILES_CSV), csv)
        .map_err(|e| super::io_err(&dir.join(STRESS_PROFILES_CSV), e))?;
    write_png(&dir.join(STRESS_PNG), solution, a)?;
    write_vtr(&dir.join(STRESS_VTR), a)
}

fn write_npz(path: &Path, a: &StressAnalysis) -> Result<()> {
    let g = &a.grid;
    let mut npz = super::npz::Npz::create(path)?;
    npz.add_grid(g)?;
    let z = a
        .bodies
        .first()
        .map(|b| b.field.z.clone())
        .unwrap_or_default();
    npz.add("z", &Array1::from(z.clone()))?;
    let shape = (z.len(), g.ny, g.nx);
    for b in &a.bodies {
        let named = COMPONENTS
            .iter()
            .zip(b.field.components.iter())
            .map(|(n, v)| (n.to_string(), v))
            .chain([
                ("von_mises".to_string(), &b.von_mises),
                ("tresca".to_string(), &b.max_shear),
            ]);
        for (name, v) in named {
            let arr = Array3::from_shape_vec(shape, v.clone()).map_err(|e| npz.err(e))?;
            npz.add(&format!("{name}_{}", b.body), &arr)?;
        }
    }
    npz.finish()
}

/// The depth profiles: for each body, below the pressure maximum and below each feature's centre.
fn profiles_csv(case: &Case, solution: &Solution, a: &StressAnalysis) -> String {
    let g = &a.grid;
    let p = &solution.fields.pressure;
    let kmax = (0..p.len()).fold(0, |m, k| if p[k] > p[m] { k } else { m });
    let mut places = vec![("pressure_maximum".to_string(), kmax % g.nx, kmax / g.nx)];
    // a transient step: the features of features[0]'s body have moved with it to x_p
    let (shift, moved_body) = match (a.step, case.features.first()) {
        (Some((_, xp)), Some(f0)) => (xp - f0.feature.centre.0, f0.body),
        _ => (0.0, 0),
    };
    for (n, f) in case.features.iter().enumerate() {
        let (mut x, y) = f.feature.centre;
        if f.body == moved_body {
            x += shift;
        }
        let i = (((x - g.x_min) / g.dx).floor().max(0.0) as usize).min(g.nx - 1);
        let j = (((y - g.y_min) / g.dy).floor().max(0.0) as usize).min(g.ny - 1);
        places.push((format!("features[{n}]"), i, j));
    }
    let mut out = String::from(
        "# stress against depth z (m) in each body's frame, tension positive (Pa); tresca = (s1 - s3)/2\n\
         place,body,x_m,y_m,z_m,sxx_pa,syy_pa,szz_pa,syz_pa,sxz_pa,sxy_pa,von_mises_pa,tresca_pa,s1_pa,s2_pa,s3_pa,hydrostatic_pa\n",
    );
    for b in &a.bodies {
        let plane = g.nx * g.ny;
        for (name, i, j) in &places {
            for (k, z) in b.field.z.iter().enumerate() {
                let n = k * plane + j * g.nx + i;
                let s = b.field.tensor(n);
                let pr = derived::principal(&s);
                let _ = write!(out, "{name},{},{:e},{:e},{z:e}", b.body, g.x(*i), g.y(*j));
                for v in s.iter().chain(&[
                    derived::von_mises(&s),
                    0.5 * (pr[0] - pr[2]),
                    pr[0],
                    pr[1],
                    pr[2],
                    derived::hydrostatic(&s),
                ]) {
                    let _ = write!(out, ",{v:e}");
                }
                out.push('\n');
            }
        }
    }
    out
}

fn write_vtr(path: &Path, a: &StressAnalysis) -> Result<()> {
    let g = &a.grid;
    let z: Vec<f64> = a
        .bodies
        .first()
        .map(|b| b.field.z.iter().map(|v| -v).collect())
        .unwrap_or_default();
    let mut names = Vec::new();
    // the fields as computed, in single precision (Float32)
    let mut data: Vec<&[f32]> = Vec::new();
    for b in &a.bodies {
        for (n, v) in COMPONENTS.iter().zip(b.field.components.iter()) {
            names.push(format!("{n}_{}", b.body));
            data.push(v);
        }
        names.push(format!("von_mises_{}", b.body));
        data.push(&b.von_mises);
        names.push(format!("tresca_{}", b.body));
        data.push(&b.max_shear);
    }
    let fields: Vec<(&str, &[f32])> = names.iter().map(|n| n.as_str()).zip(data).collect();
    let bytes = super::vtk::rectilinear_volume_xml(&g.xs(), &g.ys(), &z, &fields, None);
    std::fs::write(path, bytes).map_err(|e| super::io_err(path, e))
}

/// x-z section of von Mises through the worst point of the worst body.
fn write_png(path: &Path, solution: &Solution, a: &StressAnalysis) -> Result<()> {
    let Some(b) = a
        .bodies
        .iter()
        .max_by(|x, y| x.peak_von_mises.value.total_cmp(&y.peak_von_mises.value))
    else {
        return Ok(());
    };
    let g = &a.grid;
    let peak = b.peak_von_mises;
    let plane = g.nx * g.ny;
    let j = (peak.index % plane) / g.nx;
    let z = &b.field.z;
    let zmax = *z.last().unwrap_or(&1.0);
    let half_width = solution.summary.hertz_half_width_m;
    // x window: where the pressure of this row is non-zero, widened by the depth
    let row = &solution.fields.pressure[j * g.nx..(j + 1) * g.nx];
    let loaded: Vec<usize> = (0..g.nx).filter(|&i| row[i] > 0.0).collect();
    let (i0, i1) = match (loaded.first(), loaded.last()) {
        (Some(&a0), Some(&a1)) => (a0, a1),
        _ => (0, g.nx - 1),
    };
    let pad = zmax;
    let x_lo = (g.x(i0) - pad).max(g.x_min);
    let x_hi = (g.x(i1) + pad).min(g.x_max());
    let vmax = peak.value;
    let (um, mm, mpa) = (1e6, 1e3, 1e-6);
    let body = b;
    render_sized(path, (1000, 560), |root| {
        let (main, bar) = root.split_horizontally(880);
        let title = format!(
            "von Mises stress in body {}, section y = {} mm{}",
            body.body,
            fmt_sig(g.y(j) * mm, 4),
            a.step
                .map(|s| format!(", step {} (x_p = {} mm)", s.0, fmt_sig(s.1 * mm, 4)))
                .unwrap_or_default()
        );
        let mut chart = ChartBuilder::on(&main)
            .caption(title, text_style(20.0, BLACK))
            .margin(12)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(x_lo * mm..x_hi * mm, -zmax * um..0.0)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("x (mm), rolling direction")
            .y_desc(format!(
                "depth z (um); b = {} um",
                fmt_sig(half_width * um, 3)
            ))
            .y_label_formatter(&|v: &f64| fmt_sig(v.abs(), 3))
            .label_style(text_style(15.0, BLACK))
            .axis_desc_style(text_style(17.0, BLACK))
            .draw()?;
        let plot = chart.plotting_area().strip_coord_spec();
        let (w, h) = plot.dim_in_pixel();
        for py in 0..h {
            let depth = (py as f64 + 0.5) / h as f64 * zmax;
            // linear between the layers bracketing this depth (the first layer above it)
            let up = z.partition_point(|&v| v < depth).min(z.len() - 1);
            let lo = up.saturating_sub(1);
            let t = if up == lo {
                0.0
            } else {
                ((depth - z[lo]) / (z[up] - z[lo])).clamp(0.0, 1.0)
            };
            for px in 0..w {
                let x = x_lo + (px as f64 + 0.5) / w as f64 * (x_hi - x_lo);
                let i = (((x - g.x_min) / g.dx).floor().max(0.0) as usize).min(g.nx - 1);
                let a = body.von_mises[lo * plane + j * g.nx + i] as f64;
                let b = body.von_mises[up * plane + j * g.nx + i] as f64;
                let v = a + t * (b - a);
                let (r, gg, bb) = ColorMap::Inferno.color(v / vmax);
                plot.draw_pixel((px as i32, py as i32), &RGBColor(r, gg, bb))?;
            }
        }
        let (px, pz) = (peak.at[0] * mm, -peak.at[2] * um);
        chart.draw_series(std::iter::once(Cross::new(
            (px, pz),
            8,
            ShapeStyle::from(&CYAN).stroke_width(3),
        )))?;
        chart.draw_series(std::iter::once(Text::new(
            format!(
                "max {} MPa at z = {} um = {} b",
                fmt_sig(vmax * mpa, 4),
                fmt_sig(peak.at[2] * um, 3),
                fmt_sig(peak.at[2] / half_width, 3)
            ),
            (px + 0.03 * (x_hi - x_lo) * mm, pz + 0.03 * zmax * um),
            text_style(16.0, CYAN),
        )))?;
        let mut barc = ChartBuilder::on(&bar)
            .margin_top(40)
            .margin_bottom(60)
            .margin_right(10)
            .right_y_label_area_size(70)
            .build_cartesian_2d(0.0..1.0, 0.0..vmax * mpa)?;
        draw_colorbar_on(
            &mut barc,
            ColorMap::Inferno,
            8,
            Fonts {
                label: 14.0,
                desc: 16.0,
            },
            Some(5),
            "von Mises (MPa)",
        )
    })
    .map_err(|e| match e {
        crate::Error::Output { .. } => e,
        other => draw_err(path, other),
    })
}

/// `stress_passage.npz` and `stress_passage.png`.
fn write_passage(dir: &Path, case: &Case, solution: &Solution, run: &PassageRun) -> Result<()> {
    let Some(first) = run.passages.first() else {
        return Ok(());
    };
    let path = dir.join(STRESS_PASSAGE_NPZ);
    let mut npz = super::npz::Npz::create(&path)?;
    let g = &first.grid;
    let maps: Vec<PassageMaps> = run.passages.iter().map(|p| p.maps()).collect();
    npz.add("x_body", &Array1::from(first.xs_body()))?;
    npz.add("y", &Array1::from(g.ys()))?;
    npz.add("z", &Array1::from(first.z.clone()))?;
    if let Some(xf) = feature_x_body(case, solution) {
        npz.add("x_feature", &Array1::from(vec![xf]))?;
    }
    for (p, m) in run.passages.iter().zip(&maps) {
        let k = p.body;
        let shape = (p.z.len(), g.ny, p.nx_body);
        npz.add(&format!("x_body_{k}"), &Array1::from(p.xs_body()))?;
        npz.add(
            &format!("x_contact_start_{k}"),
            &Array1::from(p.contact_span.iter().map(|s| s[0]).collect::<Vec<f64>>()),
        )?;
        npz.add(
            &format!("x_contact_end_{k}"),
            &Array1::from(p.contact_span.iter().map(|s| s[1]).collect::<Vec<f64>>()),
        )?;
        let named = [
            ("max_von_mises", Some(&m.max_von_mises)),
            ("tau_xz_range", Some(&m.tau_xz_range)),
            ("dang_van", m.dang_van.as_ref()),
        ];
        for (name, v) in named {
            if let Some(v) = v {
                let arr = Array3::from_shape_vec(shape, v.clone()).map_err(|e| npz.err(e))?;
                npz.add(&format!("{name}_{k}"), &arr)?;
            }
        }
    }
    npz.finish()?;
    // the picture: the body carrying features[0] when it is computed, else the first
    let f0_body = case.features.first().map(|f| f.body);
    let pick = run
        .passages
        .iter()
        .position(|p| Some(p.body) == f0_body)
        .unwrap_or(0);
    write_passage_png(
        &dir.join(STRESS_PASSAGE_PNG),
        case,
        solution,
        &run.passages[pick],
        &maps[pick],
    )
}

/// Where `features[0]`'s centre sits in its body's material frame (m): x_p(0) (x_body = x at t = 0).
fn feature_x_body(case: &Case, solution: &Solution) -> Option<f64> {
    case.features.first()?;
    solution
        .transient
        .as_ref()?
        .timeline
        .first()
        .map(|r| r.x_p_m)
}

/// Two x-z sections (max von Mises, tau_xz range) of one body's passage maps through the row of
/// `features[0]`'s centre (y = 0 without a feature), depth in um, maxima marked.
fn write_passage_png(
    path: &Path,
    case: &Case,
    solution: &Solution,
    p: &Passage,
    maps: &PassageMaps,
) -> Result<()> {
    let g = &p.grid;
    let y0 = case.features.first().map_or(0.0, |f| f.feature.centre.1);
    let j = if g.ny == 1 {
        0
    } else {
        (((y0 - g.y_min) / g.dy).floor().max(0.0) as usize).min(g.ny - 1)
    };
    let (nxb, z) = (p.nx_body, &p.z);
    let plane = nxb * g.ny;
    let zmax = *z.last().unwrap_or(&1.0);
    let sampled: Vec<usize> = (0..nxb)
        .filter(|&m| !p.contact_span[m][0].is_nan())
        .collect();
    let (Some(&m0), Some(&m1)) = (sampled.first(), sampled.last()) else {
        return Ok(());
    };
    let (x_lo, x_hi) = (p.x_body(m0) - 0.5 * g.dx, p.x_body(m1) + 0.5 * g.dx);
    let half_width = solution.summary.hertz_half_width_m;
    let xf = feature_x_body(case, solution)
        .filter(|_| case.features.first().map(|f| f.body) == Some(p.body));
    let (um, mm, mpa) = (1e6, 1e3, 1e-6);
    let panels: [(&str, &Vec<f32>, ColorMap); 2] = [
        (
            "max-over-passage von Mises",
            &maps.max_von_mises,
            ColorMap::Inferno,
        ),
        (
            "range of tau_xz over the passage",
            &maps.tau_xz_range,
            ColorMap::Viridis,
        ),
    ];
    render_sized(path, (1000, 900), |root| {
        let rows = root.split_evenly((2, 1));
        for (area, (name, v, cmap)) in rows.iter().zip(panels) {
            // the maximum of this section
            let mut best = (0usize, 0usize, f64::NEG_INFINITY);
            for k in 0..z.len() {
                for m in 0..nxb {
                    let x = v[k * plane + j * nxb + m] as f64;
                    if x.is_finite() && x > best.2 {
                        best = (k, m, x);
                    }
                }
            }
            let vmax = if best.2 > 0.0 { best.2 } else { 1.0 };
            let (main, bar) = area.split_horizontally(880);
            let title = format!(
                "body {}: {name}, section y = {} mm",
                p.body,
                fmt_sig(g.y(j) * mm, 4)
            );
            let mut chart = ChartBuilder::on(&main)
                .caption(title, text_style(19.0, BLACK))
                .margin(12)
                .x_label_area_size(46)
                .y_label_area_size(80)
                .build_cartesian_2d(x_lo * mm..x_hi * mm, -zmax * um..0.0)?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_desc("x_body (mm): material frame of the body, x - u t")
                .y_desc(format!(
                    "depth z (um); b = {} um",
                    fmt_sig(half_width * um, 3)
                ))
                .y_label_formatter(&|v: &f64| fmt_sig(v.abs(), 3))
                .label_style(text_style(15.0, BLACK))
                .axis_desc_style(text_style(16.0, BLACK))
                .draw()?;
            let plot = chart.plotting_area().strip_coord_spec();
            let (w, h) = plot.dim_in_pixel();
            for py in 0..h {
                let depth = (py as f64 + 0.5) / h as f64 * zmax;
                let up = z.partition_point(|&d| d < depth).min(z.len() - 1);
                let lo = up.saturating_sub(1);
                let t = if up == lo {
                    0.0
                } else {
                    ((depth - z[lo]) / (z[up] - z[lo])).clamp(0.0, 1.0)
                };
                for px in 0..w {
                    let x = x_lo + (px as f64 + 0.5) / w as f64 * (x_hi - x_lo);
                    let m = ((x - p.x_body(0)) / g.dx + 0.5)
                        .floor()
                        .clamp(0.0, (nxb - 1) as f64) as usize;
                    let a = v[lo * plane + j * nxb + m] as f64;
                    let b = v[up * plane + j * nxb + m] as f64;
                    let val = a + t * (b - a);
                    let color = if val.is_finite() {
                        let (r, gg, bb) = cmap.color(val / vmax);
                        RGBColor(r, gg, bb)
                    } else {
                        RGBColor(200, 200, 200)
                    };
                    plot.draw_pixel((px as i32, py as i32), &color)?;
                }
            }
            if let Some(xf) = xf {
                chart.draw_series(std::iter::once(PathElement::new(
                    vec![(xf * mm, 0.0), (xf * mm, -zmax * um)],
                    ShapeStyle::from(&WHITE).stroke_width(1),
                )))?;
                chart.draw_series(std::iter::once(Text::new(
                    "features[0] centre".to_string(),
                    (xf * mm + 0.01 * (x_hi - x_lo) * mm, -0.04 * zmax * um),
                    text_style(14.0, WHITE),
                )))?;
            }
            if best.2.is_finite() {
                let (px, pz) = (p.x_body(best.1) * mm, -z[best.0] * um);
                chart.draw_series(std::iter::once(Cross::new(
                    (px, pz),
                    8,
                    ShapeStyle::from(&CYAN).stroke_width(3),
                )))?;
                // the label on the side of the cross with more room
                let right = px < 0.5 * (x_lo + x_hi) * mm;
                let lx = if right {
                    px + 0.02 * (x_hi - x_lo) * mm
                } else {
                    px - 0.45 * (x_hi - x_lo) * mm
                };
                chart.draw_series(std::iter::once(Text::new(
                    format!(
                        "max {} MPa at z = {} um = {} b",
                        fmt_sig(best.2 * mpa, 4),
                        fmt_sig(z[best.0] * um, 3),
                        fmt_sig(z[best.0] / half_width, 3)
                    ),
                    (lx, (pz + 0.06 * zmax * um).min(-0.02 * zmax * um)),
                    text_style(15.0, CYAN),
                )))?;
            }
            let mut barc = ChartBuilder::on(&bar)
                .margin_top(40)
                .margin_bottom(56)
                .margin_right(10)
                .right_y_label_area_size(70)
                .build_cartesian_2d(0.0..1.0, 0.0..vmax * mpa)?;
            let label = if name.starts_with("max") {
                "von Mises (MPa)"
            } else {
                "tau_xz range (MPa)"
            };
            draw_colorbar_on(
                &mut barc,
                cmap,
                8,
                Fonts {
                    label: 14.0,
                    desc: 16.0,
                },
                Some(5),
                label,
            )?;
        }
        Ok(())
    })
    .map_err(|e| match e {
        crate::Error::Output { .. } => e,
        other => draw_err(path, other),
    })
}
