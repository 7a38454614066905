//! The EHL-FBNS ball-on-flat case (`examples/ehl_ball_on_glass.toml`: E' = 110 GPa, R = 12.5 mm,
//! F = 15 N, u_m = 0.09 m/s, eta0 = 0.25 Pa s, Roelands alpha = 22 /GPa, Dowson-Higginson density,
//! domain [-3a, 3a]^2) on 65^2, 129^2 and 257^2 cells, beside the EHL-FBNS result on 129^2
//! (h_c = 225.8 nm, h_min = 125.5 nm, p_max = 0.388 GPa) and the Hamrock-Dowson fits.
//!
//! Prints a markdown table and draws `target/studies/ehl_ball/ball_profiles.png` (film along x at
//! y = 0 and along y through the minimum film, each grid).
//!
//! `cargo run --release -p ehl --example ehl_ball`
mod common;

use common::{case_text, charts, out_dir, repo, run, sets, Panel, Series};
use ehl::reference::film::{hamrock_dowson_central, hamrock_dowson_min};
use ehl::units;
use plotters::chart::SeriesLabelPosition;
use plotters::style::RGBColor;

const FBNS: (f64, f64, f64) = (225.8e-9, 125.5e-9, 0.388e9);

fn main() {
    let dir = out_dir("ehl_ball");
    let text = std::fs::read_to_string(repo().join("examples/ehl_ball_on_glass.toml")).unwrap();
    let c0 = case_text(&text, &[]);
    let lub = c0.lubricant.as_ref().unwrap();
    let e = units::reduced_modulus(
        c0.body1.youngs_modulus,
        c0.body1.poisson_ratio,
        c0.body2.youngs_modulus,
        c0.body2.poisson_ratio,
    );
    let r = c0.body1.radius;
    let w = units::point_load_parameter(c0.load.force, e, r);
    let u = units::speed_parameter(
        lub.viscosity,
        c0.motion.as_ref().unwrap().entrainment_speed,
        e,
        r,
    );
    let g = units::material_parameter(lub.pressure_viscosity_coefficient, e);
    let hd_c = hamrock_dowson_central(w, u, g, 1.0) * r;
    let hd_m = hamrock_dowson_min(w, u, g, 1.0) * r;
    let (m, l) = units::moes_point(w, u, g);
    println!(
        "E' = {:.2} GPa, W = {w:.4e}, U = {u:.4e}, G = {g:.0}, Moes M = {m:.1}, L = {l:.2}; Hamrock-Dowson h_c = {:.1} nm, h_min = {:.1} nm\n",
        e / 1e9,
        hd_c * 1e9,
        hd_m * 1e9
    );
    println!("| cells | a / dx | h_c (nm) | / EHL-FBNS | / Hamrock-Dowson | h_min (nm) | / EHL-FBNS | / Hamrock-Dowson | p_max (GPa) | / EHL-FBNS | iterations | time (s) |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    let colors = [
        RGBColor(230, 130, 0),
        RGBColor(20, 90, 180),
        RGBColor(200, 40, 30),
    ];
    let (mut along_x, mut along_y) = (Vec::new(), Vec::new());
    for (k, n) in [65usize, 129, 257].into_iter().enumerate() {
        let c = case_text(
            &text,
            &sets(&[("grid.nx", n.to_string()), ("grid.ny", n.to_string())]),
        );
        let s = run(&c);
        let sm = &s.summary;
        let (hc, hm, pm) = (
            sm.central_film_m.unwrap(),
            sm.min_film_m.unwrap(),
            sm.max_pressure_pa,
        );
        println!(
            "| {n}^2 | {:.1} | {:.1} | {:.3} | {:.3} | {:.1} | {:.3} | {:.3} | {:.4} | {:.3} | {} | {:.2} |",
            sm.hertz_half_width_m / s.grid.dx,
            hc * 1e9,
            hc / FBNS.0,
            hc / hd_c,
            hm * 1e9,
            hm / FBNS.1,
            hm / hd_m,
            pm / 1e9,
            pm / FBNS.2,
            sm.iterations,
            sm.wall_time_s
        );
        let gr = &s.grid;
        let h = s.fields.film.as_ref().unwrap();
        let jm = gr.ny / 2; // odd n: the centre row is y = 0
        let at = sm.min_film_at_m.unwrap();
        let im = (0..gr.nx)
            .min_by(|&a, &b| (gr.x(a) - at[0]).abs().total_cmp(&(gr.x(b) - at[0]).abs()))
            .unwrap();
        along_x.push(Series {
            label: format!("{n}^2 cells"),
            points: (0..gr.nx)
                .map(|i| (gr.x(i) * 1e3, h[gr.idx(i, jm)] * 1e9))
                .collect(),
            color: colors[k],
            dashed: false,
            markers: false,
        });
        along_y.push(Series {
            label: format!("{n}^2 cells, x = {:.3} mm", gr.x(im) * 1e3),
            points: (0..gr.ny)
                .map(|j| (gr.y(j) * 1e3, h[gr.idx(im, j)] * 1e9))
                .collect(),
            color: colors[k],
            dashed: false,
            markers: false,
        });
    }
    println!(
        "| EHL-FBNS (Octave), 129^2 | 21.3 | {:.1} | 1 | {:.3} | {:.1} | 1 | {:.3} | {:.3} | 1 | - | 40 |",
        FBNS.0 * 1e9,
        FBNS.0 / hd_c,
        FBNS.1 * 1e9,
        FBNS.1 / hd_m,
        FBNS.2 / 1e9
    );
    let flat = |v: f64, lo: f64, hi: f64| vec![(lo, v), (hi, v)];
    for (list, lo, hi) in [(&mut along_x, -0.3, 0.3), (&mut along_y, -0.3, 0.3)] {
        list.push(Series {
            label: "EHL-FBNS h_c (129^2)".into(),
            points: flat(FBNS.0 * 1e9, lo, hi),
            color: RGBColor(60, 60, 60),
            dashed: true,
            markers: false,
        });
        list.push(Series {
            label: "EHL-FBNS h_min (129^2)".into(),
            points: flat(FBNS.1 * 1e9, lo, hi),
            color: RGBColor(150, 150, 150),
            dashed: true,
            markers: false,
        });
    }
    charts(
        &dir.join("ball_profiles.png"),
        (1600, 620),
        &[
            Panel {
                title: "film along x at y = 0 (inlet left)",
                x_label: "x, rolling direction (mm)",
                y_label: "film thickness (nm)",
                x_range: -0.3..0.3,
                y_range: 0.0..500.0,
                log_x: false,
                series: along_x,
                legend: SeriesLabelPosition::LowerMiddle,
            },
            Panel {
                title: "film along y through the minimum (the horseshoe's side lobes)",
                x_label: "y, across the rolling direction (mm)",
                y_label: "film thickness (nm)",
                x_range: -0.3..0.3,
                y_range: 0.0..500.0,
                log_x: false,
                series: along_y,
                legend: SeriesLabelPosition::LowerMiddle,
            },
        ],
    )
    .unwrap();
}
