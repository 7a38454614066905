//! Friction coefficient against slide-to-roll ratio for the thesis Table 3.7 line contact
//! (`examples/ehl_friction_line.toml`, U = 7.3e-11) with three rheologies: Newtonian (thesis
//! eq. 2.12, no limit), Newtonian with the limiting shear stress tau_L = 0.06 p (Carreau with
//! n = 1, eq. 2.13-2.14) and the case's Carreau law (G_f = 4.5 MPa, n = 0.57, eq. 2.15) with the
//! same limit. SRR from 0 to 0.1 (the thesis range) and, to show where the limit takes over, up
//! to SRR = 2.
//!
//! Prints a markdown table and draws `target/studies/ehl_friction/friction_models.png`.
//!
//! `cargo run --release -p ehl --example ehl_friction`
mod common;

use common::{case_text, charts, out_dir, repo, run, sets, Panel, Series};
use plotters::chart::SeriesLabelPosition;
use plotters::style::RGBColor;

fn main() {
    let dir = out_dir("ehl_friction");
    let text = std::fs::read_to_string(repo().join("examples/ehl_friction_line.toml")).unwrap();
    let models = [
        (
            "Newtonian, no limit",
            r#"{ model = "newtonian" }"#,
            RGBColor(60, 60, 60),
        ),
        (
            "Newtonian + tau_L = 0.06 p",
            r#"{ model = "carreau", shear_modulus = 4.5e6, power_law_index = 1.0, limiting_shear_coefficient = 0.06 }"#,
            RGBColor(20, 90, 180),
        ),
        (
            "Carreau n = 0.57 + tau_L = 0.06 p (the case)",
            r#"{ model = "carreau", shear_modulus = 4.5e6, power_law_index = 0.57, limiting_shear_coefficient = 0.06 }"#,
            RGBColor(200, 40, 30),
        ),
    ];
    let low: Vec<f64> = (0..=10).map(|k| 0.01 * k as f64).collect();
    let high = [0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0];
    let mut near = Vec::new();
    let mut far = Vec::new();
    let mut rows: Vec<(f64, Vec<f64>)> = low.iter().map(|&s| (s, vec![])).collect();
    for (label, rheo, color) in models {
        let mut pts_low = Vec::new();
        let mut pts_high = Vec::new();
        let mut srrs: Vec<f64> = low.clone();
        srrs.extend(high.iter().filter(|v| **v > 0.1));
        for srr in srrs {
            let c = case_text(
                &text,
                &sets(&[
                    ("lubricant.rheology", rheo.to_string()),
                    ("motion.slide_to_roll", format!("{srr}")),
                ]),
            );
            let s = run(&c);
            let f = s.summary.friction_coefficient.unwrap();
            if srr <= 0.1 + 1e-12 {
                pts_low.push((srr, f));
                if let Some(r) = rows.iter_mut().find(|r| (r.0 - srr).abs() < 1e-12) {
                    r.1.push(f);
                }
            }
            if high.iter().any(|h| (h - srr).abs() < 1e-12) {
                pts_high.push((srr, f));
            }
        }
        near.push(Series {
            label: label.into(),
            points: pts_low,
            color,
            dashed: false,
            markers: true,
        });
        far.push(Series {
            label: label.into(),
            points: pts_high,
            color,
            dashed: false,
            markers: true,
        });
    }
    println!("| SRR | Newtonian | Newtonian + limit | Carreau + limit |");
    println!("| --- | --- | --- | --- |");
    for (srr, f) in &rows {
        println!("| {srr:.2} | {:.4} | {:.4} | {:.4} |", f[0], f[1], f[2]);
    }
    println!("\nSRR > 0.1:");
    for s in &far {
        println!(
            "{}: {:?}",
            s.label,
            s.points
                .iter()
                .map(|(a, b)| format!("{a}: {b:.4}"))
                .collect::<Vec<_>>()
        );
    }
    far.push(Series {
        label: "Lambda = 0.06".into(),
        points: vec![(0.01, 0.06), (2.0, 0.06)],
        color: RGBColor(120, 120, 120),
        dashed: true,
        markers: false,
    });
    let ymax = near
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .fold(0.0, f64::max)
        .max(0.07)
        * 1.1;
    charts(
        &dir.join("friction_models.png"),
        (1600, 620),
        &[
            Panel {
                title: "U = 7.3e-11: friction against SRR, thesis range",
                x_label: "slide-to-roll ratio SRR (-)",
                y_label: "friction coefficient (-)",
                x_range: -0.002..0.102,
                y_range: -0.005..ymax,
                log_x: false,
                series: near,
                legend: SeriesLabelPosition::UpperLeft,
            },
            Panel {
                title: "the same up to SRR = 2: the limiting shear stress takes over",
                x_label: "slide-to-roll ratio SRR (-), log scale",
                y_label: "friction coefficient (-)",
                x_range: 0.009..2.2,
                y_range: 0.0..ymax,
                log_x: true,
                series: far,
                legend: SeriesLabelPosition::UpperLeft,
            },
        ],
    )
    .unwrap();
}
