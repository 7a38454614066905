//! Load against approach for the crowned and the log-profile roller of `examples/`
//! (R = 5 mm, L = 10 mm on a flat, steel) from 1 to 10 kN, beside Palmgren's empirical law for one
//! roller contact, delta = 3.84e-5 Q^0.9 / L^0.8 (mm, N) ([`ehl::reference::palmgren_approach`]).
//! Each profile is run with the case's free-end correction (1 mirror level + psi) and, to show how
//! the half-space approach depends on the images, with the plain half-space (no images).
//!
//! Prints a markdown table (approach, ratio to Palmgren, fitted exponent of Q against delta) and
//! draws `target/studies/palmgren/palmgren.png`.
//!
//! `cargo run --release -p ehl --example palmgren`
mod common;

use common::{case, charts, log_slope, out_dir, run, sets, Panel, Series};
use ehl::reference::palmgren::palmgren_approach;
use plotters::chart::SeriesLabelPosition;
use plotters::style::RGBColor;

fn main() {
    let dir = out_dir("palmgren");
    let loads: Vec<f64> = (1..=10).map(|k| 1000.0 * k as f64).collect();
    let len = 0.010;
    let runs = [
        (
            "dry_crowned",
            "crowned, 1 level + psi",
            1usize,
            true,
            RGBColor(200, 40, 30),
        ),
        (
            "dry_log_profile",
            "log profile, 1 level + psi",
            1,
            true,
            RGBColor(20, 90, 180),
        ),
        (
            "dry_crowned",
            "crowned, plain half-space",
            0,
            false,
            RGBColor(240, 150, 130),
        ),
        (
            "dry_log_profile",
            "log profile, plain half-space",
            0,
            false,
            RGBColor(130, 170, 230),
        ),
    ];
    let mut series = Vec::new();
    let mut csv =
        String::from("profile,mirror_levels,psi,load_n,approach_m,palmgren_m,max_pressure_pa\n");
    println!("| roller | Q (kN) | approach (um) | Palmgren (um) | ratio | p_max (GPa) |");
    println!("| --- | --- | --- | --- | --- | --- |");
    let mut fits = Vec::new();
    for (name, label, levels, psi, color) in runs {
        let mut pts = Vec::new();
        for &q in &loads {
            let c = case(
                name,
                &sets(&[
                    ("load.force", format!("{q}")),
                    ("solver.mirror_levels", levels.to_string()),
                    ("solver.free_end_correction", psi.to_string()),
                ]),
            );
            let s = run(&c);
            let d = s.summary.approach_m.unwrap();
            let dp = palmgren_approach(q, len);
            if q == 1000.0 || q == 5000.0 || q == 10000.0 {
                println!(
                    "| {label} | {:.0} | {:.3} | {:.3} | {:.3} | {:.3} |",
                    q / 1e3,
                    d * 1e6,
                    dp * 1e6,
                    d / dp,
                    s.summary.max_pressure_pa / 1e9
                );
            }
            csv.push_str(&format!(
                "{name},{levels},{psi},{q},{d:e},{dp:e},{:e}\n",
                s.summary.max_pressure_pa
            ));
            pts.push((d * 1e6, q));
        }
        let ds: Vec<f64> = pts.iter().map(|p| p.0).collect();
        // Palmgren: delta ~ Q^0.9; fit delta ~ Q^k, and say it as Q ~ delta^(1/k)
        let k = log_slope(&loads, &ds);
        let k_hi = log_slope(&loads[4..], &ds[4..]);
        fits.push((label, k, k_hi));
        series.push(Series {
            label: label.to_string(),
            points: pts,
            color,
            dashed: false,
            markers: true,
        });
    }
    println!("\n| roller | exponent of delta ~ Q^k, 1-10 kN | 5-10 kN | Palmgren |");
    println!("| --- | --- | --- | --- |");
    for (label, k, k_hi) in &fits {
        println!("| {label} | {k:.3} | {k_hi:.3} | 0.9 |");
    }
    std::fs::write(dir.join("palmgren.csv"), csv).unwrap();

    let law: Vec<(f64, f64)> = (0..=200)
        .map(|k| 500.0 + 10_000.0 * k as f64 / 200.0)
        .map(|q| (palmgren_approach(q, len) * 1e6, q))
        .collect();
    series.push(Series {
        label: "Palmgren, one contact: δ = 3.84e-5 Q^0.9 / L^0.8 (mm; Q in N, L in mm)".into(),
        points: law,
        color: RGBColor(30, 30, 30),
        dashed: true,
        markers: false,
    });
    let dmax = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .fold(0.0, f64::max);
    charts(
        &dir.join("palmgren.png"),
        (1000, 650),
        &[Panel {
            title: "Roller R = 5 mm, L = 10 mm on a flat (steel): load vs approach",
            x_label: "approach delta (µm)",
            y_label: "roller load Q (N)",
            x_range: 0.0..(1.05 * dmax),
            y_range: 0.0..10_500.0,
            log_x: false,
            series,
            legend: SeriesLabelPosition::UpperLeft,
        }],
    )
    .unwrap();
    eprintln!("wrote {}", dir.display());
}
