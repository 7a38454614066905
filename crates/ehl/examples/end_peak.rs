//! End-peak study of the straight roller of thesis Table 1.1 (R1 = R2 = 10 mm, L = 4 mm,
//! F = 30 kN, E = 200 GPa, nu = 0.3): no free-end correction, 1 and 2 mirror levels, and one
//! level with Guilbault's psi (thesis eq. 1.13), each at successive refinements along y (the
//! roller axis) with nx fixed. Prints a markdown table and draws
//! `target/studies/end_peak/end_peak.png` (peak against cells along y) and
//! `target/studies/end_peak/axial.png` (pressure along the axis on the finest grid, the
//! analogue of thesis fig. 1.11).
//!
//! `cargo run --release -p ehl --example end_peak`
mod common;

use common::{case, charts, column, mid_row, out_dir, run, sets, Panel, Series};
use plotters::chart::SeriesLabelPosition;
use plotters::style::RGBColor;

const VARIANTS: [(&str, &str); 4] = [
    ("dry_roller_mirror0", "plain half-space"),
    ("dry_roller_mirror1", "1 mirror level"),
    ("dry_roller_mirror2", "2 mirror levels"),
    ("dry_roller_mirror1_psi", "1 level + psi"),
];
const COLORS: [RGBColor; 4] = [
    RGBColor(200, 40, 30),
    RGBColor(230, 140, 20),
    RGBColor(40, 150, 60),
    RGBColor(20, 90, 180),
];
const NX: usize = 64;
const NYS: [usize; 4] = [64, 128, 256, 512];

fn main() {
    let dir = out_dir("end_peak");
    println!(
        "Thesis Table 1.1 rollers, nx = {NX} (b / dx = 20), y over the roller length L = 4 mm.\n"
    );
    println!("| correction | ny | dy (um) | max pressure (GPa) | at y (mm) | end-row max (GPa) | mid-length max (GPa) | approach (um) |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- |");
    let mut peaks: Vec<Vec<(f64, f64)>> = vec![Vec::new(); VARIANTS.len()];
    let mut axial: Vec<Vec<(f64, f64)>> = vec![Vec::new(); VARIANTS.len()];
    let mut csv = String::from(
        "correction,ny,dy_m,max_pressure_pa,max_at_y_m,end_row_max_pa,mid_max_pa,approach_m\n",
    );
    for (v, (name, label)) in VARIANTS.iter().enumerate() {
        for &ny in &NYS {
            let c = case(
                name,
                &sets(&[("grid.nx", NX.to_string()), ("grid.ny", ny.to_string())]),
            );
            let s = run(&c);
            let g = s.grid;
            let pmax = s.summary.max_pressure_pa;
            let at_y = s.summary.max_pressure_at_m[1];
            let end_row = (0..g.nx)
                .map(|i| s.fields.pressure[g.idx(i, g.ny - 1)])
                .fold(0.0, f64::max);
            let mid = mid_row(&s).into_iter().fold(0.0, f64::max);
            let d = s.summary.approach_m.unwrap();
            println!(
                "| {label} | {ny} | {:.1} | {:.3} | {:+.3} | {:.3} | {:.3} | {:.2} |",
                g.dy * 1e6,
                pmax / 1e9,
                at_y * 1e3,
                end_row / 1e9,
                mid / 1e9,
                d * 1e6
            );
            csv.push_str(&format!(
                "{label},{ny},{:e},{:e},{:e},{:e},{:e},{:e}\n",
                g.dy, pmax, at_y, end_row, mid, d
            ));
            peaks[v].push((ny as f64, pmax / 1e9));
            if ny == *NYS.last().unwrap() {
                // along the axis through the column of x = 0 (nx even: mean of the two middle columns)
                let (a, b) = (column(&s, g.nx / 2 - 1), column(&s, g.nx / 2));
                axial[v] = g
                    .ys()
                    .iter()
                    .zip(a.iter().zip(&b))
                    .map(|(y, (p, q))| (y * 1e3, 0.5 * (p + q) / 1e9))
                    .collect();
            }
        }
    }
    std::fs::write(dir.join("end_peak.csv"), csv).unwrap();

    let series = |data: &[Vec<(f64, f64)>], markers: bool| -> Vec<Series> {
        VARIANTS
            .iter()
            .zip(COLORS)
            .zip(data)
            .map(|(((_, label), color), pts)| Series {
                label: label.to_string(),
                points: pts.clone(),
                color,
                dashed: false,
                markers,
            })
            .collect()
    };
    let top = peaks.iter().flatten().map(|p| p.1).fold(0.0, f64::max);
    let corrected: Vec<Vec<(f64, f64)>> = peaks[1..].to_vec();
    let (lo, hi) = corrected
        .iter()
        .flatten()
        .fold((f64::INFINITY, 0.0f64), |(a, b), p| {
            (a.min(p.1), b.max(p.1))
        });
    let x_label = "cells along the roller axis, ny (L = 4 mm)";
    charts(
        &dir.join("end_peak.png"),
        (1400, 600),
        &[
            Panel {
                title: "Maximum pressure vs grid (nx = 64)",
                x_label,
                y_label: "maximum pressure (GPa)",
                x_range: 50.0..650.0,
                y_range: 0.0..(1.1 * top),
                log_x: true,
                series: series(&peaks, true),
                legend: SeriesLabelPosition::UpperLeft,
            },
            Panel {
                title: "The corrected cases, zoomed",
                x_label,
                y_label: "maximum pressure (GPa)",
                x_range: 50.0..650.0,
                y_range: (lo - 0.1)..(hi + 0.25),
                log_x: true,
                series: series(&peaks, true)[1..]
                    .iter()
                    .map(|s| Series {
                        label: s.label.clone(),
                        points: s.points.clone(),
                        color: s.color,
                        dashed: false,
                        markers: true,
                    })
                    .collect(),
                legend: SeriesLabelPosition::UpperLeft,
            },
        ],
    )
    .unwrap();
    let top = axial.iter().flatten().map(|p| p.1).fold(0.0, f64::max);
    charts(
        &dir.join("axial.png"),
        (1400, 600),
        &[
            Panel {
                title: "Pressure along the roller axis at x = 0 (ny = 512)",
                x_label: "y along the roller axis (mm)",
                y_label: "pressure (GPa)",
                x_range: -2.05..2.05,
                y_range: 0.0..(1.05 * top),
                log_x: false,
                series: series(&axial, false),
                legend: SeriesLabelPosition::UpperMiddle,
            },
            Panel {
                title: "Zoom on the end y = +2 mm (plain half-space leaves the frame)",
                x_label: "y along the roller axis (mm)",
                y_label: "pressure (GPa)",
                x_range: 1.5..2.0,
                y_range: 0.0..10.0,
                log_x: false,
                series: series(&axial, false),
                legend: SeriesLabelPosition::LowerLeft,
            },
        ],
    )
    .unwrap();
    eprintln!("wrote {}", dir.display());
}
