//! The thesis chapter 2 EHL case (fig. 2.4-2.14): two steel rollers R = 60 mm, L = 9.5 mm,
//! Table 3.7 lubricant, 1 mirror level + psi (`examples/ehl_thesis_ch2_roller.toml`).
//!
//! * the base case (F = 6000 N, u_e = 2.7 m/s): centreline pressure beside the dry contact of the
//!   same rollers (fig. 2.5), centreline film, and the axial profiles that show the end
//!   constriction;
//! * a load sweep 4-7 kN at u_e = 2.7 m/s (fig. 2.6, 2.9, 2.11, 2.13) and a speed sweep
//!   u_e = 1-5 m/s at F = 5000 N (fig. 2.7, 2.10, 2.12, 2.14): overlaid centreline pressure, film,
//!   viscosity and density;
//! * an axial grid refinement of the end film.
//!
//! Every case is parsed with `ehl::case::parse_str` from the example file's text plus overrides
//! and solved with `ehl::run::solve` (the `ehl run` pipeline). Prints markdown tables and draws the
//! charts into `target/studies/ehl_ch2/`.
//!
//! `cargo run --release -p ehl --example ehl_thesis_ch2`
mod common;

use common::{case_text, charts, out_dir, repo, run, sets, Panel, Series};
use ehl::case::Case;
use ehl::output::plot::{write_xy, Series as XySeries};
use ehl::reference::film::{pan_hamrock_central, pan_hamrock_min};
use ehl::solution::Solution;
use ehl::units;
use plotters::chart::SeriesLabelPosition;
use plotters::style::RGBColor;

const COLORS: [RGBColor; 5] = [
    RGBColor(20, 90, 180),
    RGBColor(30, 150, 70),
    RGBColor(230, 130, 0),
    RGBColor(200, 40, 30),
    RGBColor(120, 60, 160),
];

/// A field along x at mid-length (mean of the two rows either side of y = 0 when y = 0 is a face).
fn mid(s: &Solution, f: &[f64]) -> Vec<f64> {
    let g = &s.grid;
    let nx = g.nx;
    let r = |j: usize| &f[j * nx..(j + 1) * nx];
    if g.ny % 2 == 0 {
        let (a, b) = (r(g.ny / 2 - 1), r(g.ny / 2));
        a.iter().zip(b).map(|(u, v)| 0.5 * (u + v)).collect()
    } else {
        r(g.ny / 2).to_vec()
    }
}

/// A field along y in column `i`.
fn col(s: &Solution, f: &[f64], i: usize) -> Vec<f64> {
    (0..s.grid.ny).map(|j| f[s.grid.idx(i, j)]).collect()
}

fn xs_mm(s: &Solution) -> Vec<f64> {
    s.grid.xs().iter().map(|x| x * 1e3).collect()
}

fn pts(x: &[f64], y: &[f64], scale: f64) -> Vec<(f64, f64)> {
    x.iter().zip(y).map(|(a, b)| (*a, b * scale)).collect()
}

fn line(label: String, points: Vec<(f64, f64)>, color: RGBColor) -> Series {
    Series {
        label,
        points,
        color,
        dashed: false,
        markers: false,
    }
}

/// Mean-speed groups (W, U, G) and R of a roller case at mid-length.
fn groups(c: &Case) -> (f64, f64, f64, f64) {
    let e = units::reduced_modulus(
        c.body1.youngs_modulus,
        c.body1.poisson_ratio,
        c.body2.youngs_modulus,
        c.body2.poisson_ratio,
    );
    let r = units::reduced_radius(c.body1.radius, c.body2.radius);
    let lub = c.lubricant.as_ref().unwrap();
    let m = c.motion.as_ref().unwrap();
    (
        units::line_load_parameter(c.load.force_per_length, e, r),
        units::speed_parameter(lub.viscosity, m.entrainment_speed, e, r),
        units::material_parameter(lub.pressure_viscosity_coefficient, e),
        r,
    )
}

/// Pressure-spike height and position: the largest local maximum of the mid-length pressure
/// downstream of x = 0.3 b (None when the pressure falls monotonically there).
fn spike(s: &Solution, p: &[f64]) -> Option<(f64, f64)> {
    let b = s.summary.hertz_half_width_m;
    let g = &s.grid;
    (1..g.nx - 1)
        .filter(|&i| g.x(i) > 0.3 * b && p[i] > p[i - 1] && p[i] >= p[i + 1])
        .map(|i| (p[i], g.x(i)))
        .max_by(|a, b| a.0.total_cmp(&b.0))
}

struct Row {
    label: String,
    s: Solution,
    c: Case,
}

fn solve_set(text: &str, over: &[(&str, String)], label: String) -> Row {
    let c = case_text(text, &sets(over));
    let s = run(&c);
    Row { label, s, c }
}

fn table(rows: &[Row]) {
    println!(
        "| case | p_max (GPa) | spike (GPa) at x (um) | h_c (um) | h_min centreline (um) | h_min overall (um) at (x, y) mm | Pan-Hamrock h_c / h_min (um) | iterations | time (s) |"
    );
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for r in rows {
        let s = &r.s;
        let p = mid(s, &s.fields.pressure);
        let h = mid(s, s.fields.film.as_ref().unwrap());
        let hmin_c = h.iter().cloned().fold(f64::INFINITY, f64::min);
        let sp = spike(s, &p)
            .map(|(v, x)| format!("{:.3} at {:.0}", v / 1e9, x * 1e6))
            .unwrap_or_else(|| "none".into());
        let (w, u, gg, rr) = groups(&r.c);
        let at = s.summary.min_film_at_m.unwrap();
        println!(
            "| {} | {:.4} | {} | {:.3} | {:.3} | {:.3} at ({:.3}, {:.2}) | {:.3} / {:.3} | {} | {:.1} |",
            r.label,
            s.summary.max_pressure_pa / 1e9,
            sp,
            s.summary.central_film_m.unwrap() * 1e6,
            hmin_c * 1e6,
            s.summary.min_film_m.unwrap() * 1e6,
            at[0] * 1e3,
            at[1] * 1e3,
            pan_hamrock_central(w, u, gg) * rr * 1e6,
            pan_hamrock_min(w, u, gg) * rr * 1e6,
            s.summary.iterations,
            s.summary.wall_time_s
        );
    }
}

/// Four overlaid centreline charts (pressure, film | viscosity, density) for a sweep.
fn sweep_charts(rows: &[Row], name: &str, what: &str, dir: &std::path::Path) {
    let x_range = -0.9..0.7;
    let mut pp = Vec::new();
    let mut hh = Vec::new();
    let mut vv = Vec::new();
    let mut dd = Vec::new();
    for (k, r) in rows.iter().enumerate() {
        let s = &r.s;
        let x = xs_mm(s);
        let col = COLORS[k % COLORS.len()];
        let p = mid(s, &s.fields.pressure);
        let h = mid(s, s.fields.film.as_ref().unwrap());
        let v: Vec<f64> = mid(s, s.fields.viscosity.as_ref().unwrap())
            .iter()
            .map(|e| e.log10())
            .collect();
        let d = mid(s, s.fields.density.as_ref().unwrap());
        pp.push(line(r.label.clone(), pts(&x, &p, 1e-9), col));
        hh.push(line(r.label.clone(), pts(&x, &h, 1e6), col));
        vv.push(line(r.label.clone(), pts(&x, &v, 1.0), col));
        dd.push(line(r.label.clone(), pts(&x, &d, 1.0), col));
    }
    let xl = "x, rolling direction (mm), inlet left";
    charts(
        &dir.join(format!("{name}_pressure_film.png")),
        (1600, 620),
        &[
            Panel {
                title: &format!("{what}: pressure at mid-length"),
                x_label: xl,
                y_label: "pressure (GPa)",
                x_range: x_range.clone(),
                y_range: 0.0..1.05,
                log_x: false,
                series: pp,
                legend: SeriesLabelPosition::UpperLeft,
            },
            Panel {
                title: &format!("{what}: film at mid-length"),
                x_label: xl,
                y_label: "film thickness (um)",
                x_range: x_range.clone(),
                y_range: 0.0..2.5,
                log_x: false,
                series: hh,
                legend: SeriesLabelPosition::UpperRight,
            },
        ],
    )
    .unwrap();
    charts(
        &dir.join(format!("{name}_viscosity_density.png")),
        (1600, 620),
        &[
            Panel {
                title: &format!("{what}: viscosity at mid-length (Roelands)"),
                x_label: xl,
                y_label: "log10 viscosity (Pa s)",
                x_range: x_range.clone(),
                y_range: -1.5..3.0,
                log_x: false,
                series: vv,
                legend: SeriesLabelPosition::UpperLeft,
            },
            Panel {
                title: &format!("{what}: density at mid-length (Dowson-Higginson)"),
                x_label: xl,
                y_label: "density (kg/m^3)",
                x_range,
                y_range: 840.0..1040.0,
                log_x: false,
                series: dd,
                legend: SeriesLabelPosition::UpperLeft,
            },
        ],
    )
    .unwrap();
}

fn main() {
    let dir = out_dir("ehl_ch2");
    let path = repo().join("examples/ehl_thesis_ch2_roller.toml");
    let text = std::fs::read_to_string(&path).unwrap();

    // ---------------------------------------------------------------- base case vs dry
    let base = solve_set(&text, &[], "F = 6000 N, u_e = 2.7 m/s".into());
    let dry = run(&case_text(&text, &sets(&[("kind", "\"dry\"".into())])));
    let s = &base.s;
    let g = &s.grid;
    println!(
        "grid {} x {}: dx = {:.2} um ({:.0} cells across 2b), dy = {:.1} um",
        g.nx,
        g.ny,
        g.dx * 1e6,
        2.0 * s.summary.hertz_half_width_m / g.dx,
        g.dy * 1e6
    );
    // symmetry about mid-length: the two ends of aligned rollers must mirror each other
    let mut asym: f64 = 0.0;
    for j in 0..g.ny {
        for i in 0..g.nx {
            let a = s.fields.pressure[g.idx(i, j)];
            let b = s.fields.pressure[g.idx(i, g.ny - 1 - j)];
            asym = asym.max((a - b).abs());
        }
    }
    let hf = s.fields.film.as_ref().unwrap();
    let mut hasym: f64 = 0.0;
    for j in 0..g.ny {
        for i in 0..g.nx {
            hasym = hasym.max((hf[g.idx(i, j)] - hf[g.idx(i, g.ny - 1 - j)]).abs());
        }
    }
    println!(
        "symmetry about mid-length: max |p(y) - p(-y)| = {:.3e} GPa ({:.2e} of p_max), max |h(y) - h(-y)| = {:.3e} um",
        asym / 1e9,
        asym / s.summary.max_pressure_pa,
        hasym * 1e6
    );
    println!(
        "dry contact of the same rollers: p_max {:.4} GPa, Hertz p_h {:.4} GPa, b {:.1} um",
        dry.summary.max_pressure_pa / 1e9,
        s.summary.hertz_pressure_pa / 1e9,
        s.summary.hertz_half_width_m * 1e6
    );

    let x = xs_mm(s);
    let p = mid(s, &s.fields.pressure);
    let pd = mid(&dry, &dry.fields.pressure);
    let h = mid(s, hf);
    charts(
        &dir.join("base_centreline.png"),
        (1600, 620),
        &[
            Panel {
                title: "F = 6 kN, u_e = 2.7 m/s: pressure at mid-length (fig. 2.5)",
                x_label: "x, rolling direction (mm), inlet left",
                y_label: "pressure (GPa)",
                x_range: -1.0..0.7,
                y_range: 0.0..1.0,
                log_x: false,
                series: vec![
                    line("EHL".into(), pts(&x, &p, 1e-9), COLORS[3]),
                    Series {
                        label: "dry contact, same rollers and grid".into(),
                        points: pts(&x, &pd, 1e-9),
                        color: RGBColor(60, 60, 60),
                        dashed: true,
                        markers: false,
                    },
                ],
                legend: SeriesLabelPosition::UpperLeft,
            },
            Panel {
                title: "film thickness at mid-length (fig. 2.5, 2.8)",
                x_label: "x, rolling direction (mm), inlet left",
                y_label: "film thickness (um)",
                x_range: -1.0..0.7,
                y_range: 0.0..3.0,
                log_x: false,
                series: vec![line("EHL film".into(), pts(&x, &h, 1e6), COLORS[0])],
                legend: SeriesLabelPosition::UpperRight,
            },
        ],
    )
    .unwrap();

    // axial profiles: at x = 0 and at the x of the mid-length minimum film (the outlet)
    let i0 = (0..g.nx)
        .min_by(|&a, &b| g.x(a).abs().total_cmp(&g.x(b).abs()))
        .unwrap();
    let io = (0..g.nx).min_by(|&a, &b| h[a].total_cmp(&h[b])).unwrap();
    let y: Vec<f64> = g.ys().iter().map(|v| v * 1e3).collect();
    let lab0 = format!("x = {:.3} mm (centre)", g.x(i0) * 1e3);
    let labo = format!("x = {:.3} mm (outlet constriction)", g.x(io) * 1e3);
    charts(
        &dir.join("base_axial.png"),
        (1600, 620),
        &[
            Panel {
                title: "pressure along the roller axis (fig. 2.4 seen from the side)",
                x_label: "y, roller axis (mm)",
                y_label: "pressure (GPa)",
                x_range: -4.9..4.9,
                y_range: 0.0..1.0,
                log_x: false,
                series: vec![
                    line(
                        lab0.clone(),
                        pts(&y, &col(s, &s.fields.pressure, i0), 1e-9),
                        COLORS[3],
                    ),
                    line(
                        labo.clone(),
                        pts(&y, &col(s, &s.fields.pressure, io), 1e-9),
                        COLORS[2],
                    ),
                ],
                legend: SeriesLabelPosition::LowerMiddle,
            },
            Panel {
                title: "film along the roller axis: the end constriction",
                x_label: "y, roller axis (mm)",
                y_label: "film thickness (um)",
                x_range: -4.9..4.9,
                y_range: 0.0..1.0,
                log_x: false,
                series: vec![
                    line(lab0, pts(&y, &col(s, hf, i0), 1e6), COLORS[0]),
                    line(labo, pts(&y, &col(s, hf, io), 1e6), COLORS[1]),
                ],
                legend: SeriesLabelPosition::LowerMiddle,
            },
        ],
    )
    .unwrap();

    // ---------------------------------------------------------------- load sweep, u_e = 2.7 m/s
    let loads: Vec<Row> = [4000.0, 5000.0, 6000.0, 7000.0]
        .iter()
        .map(|&f| {
            solve_set(
                &text,
                &[("load.force", format!("{f}"))],
                format!("F = {:.0} kN", f / 1e3),
            )
        })
        .collect();
    println!("\nload sweep, u_e = 2.7 m/s\n");
    table(&loads);
    sweep_charts(&loads, "load", "u_e = 2.7 m/s", &dir);

    // ---------------------------------------------------------------- speed sweep, F = 5000 N
    let speeds: Vec<Row> = [1.0, 2.0, 3.0, 4.0, 5.0]
        .iter()
        .map(|&u| {
            solve_set(
                &text,
                &[
                    ("load.force", "5000".into()),
                    ("motion.entrainment_speed", format!("{u}")),
                ],
                format!("u_e = {u:.0} m/s"),
            )
        })
        .collect();
    println!("\nspeed sweep, F = 5000 N\n");
    table(&speeds);
    sweep_charts(&speeds, "speed", "F = 5 kN", &dir);

    // film against speed: log-log slope (classical exponent about 0.7)
    let lx: Vec<f64> = speeds
        .iter()
        .map(|r| r.c.motion.as_ref().unwrap().entrainment_speed)
        .collect();
    let hc: Vec<f64> = speeds
        .iter()
        .map(|r| r.s.summary.central_film_m.unwrap())
        .collect();
    let hm: Vec<f64> = speeds
        .iter()
        .map(|r| {
            mid(&r.s, r.s.fields.film.as_ref().unwrap())
                .iter()
                .cloned()
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    println!(
        "\nfilm ~ u_e^n: central n = {:.3}, mid-length minimum n = {:.3} (Pan-Hamrock: 0.692, 0.694)",
        common::log_slope(&lx, &hc),
        common::log_slope(&lx, &hm)
    );
    let lf: Vec<f64> = loads.iter().map(|r| r.c.load.force).collect();
    let hcf: Vec<f64> = loads
        .iter()
        .map(|r| r.s.summary.central_film_m.unwrap())
        .collect();
    let hmf: Vec<f64> = loads
        .iter()
        .map(|r| {
            mid(&r.s, r.s.fields.film.as_ref().unwrap())
                .iter()
                .cloned()
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    println!(
        "film ~ F^n: central n = {:.3}, mid-length minimum n = {:.3} (Pan-Hamrock: -0.166, -0.128)",
        common::log_slope(&lf, &hcf),
        common::log_slope(&lf, &hmf)
    );
    write_xy(
        &dir.join("film_vs_speed.png"),
        "Film against entrainment speed, F = 5 kN (thesis ch. 2 rollers)",
        "mid-length central film and minimum film on the mid-length line",
        "entrainment speed u_e (m/s)",
        "film thickness (um)",
        &[
            XySeries {
                label: "central film".into(),
                points: pts(&lx, &hc, 1e6),
            },
            XySeries {
                label: "minimum film, mid-length line".into(),
                points: pts(&lx, &hm, 1e6),
            },
        ],
    )
    .unwrap();

    // ---------------------------------------------------------------- axial refinement of the end film
    println!("\nend film against the axial grid (nx = 128, F = 6 kN, u_e = 2.7 m/s)\n");
    println!("| ny | dy (um) | h_min overall (um) | at y (mm) | end-row p_max (GPa) | mid-length h_min (um) | iterations | time (s) |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- |");
    for ny in [128usize, 256, 512] {
        let r = solve_set(
            &text,
            &[("grid.nx", "128".into()), ("grid.ny", ny.to_string())],
            String::new(),
        );
        let s = &r.s;
        let g = &s.grid;
        let end_p = s.fields.pressure[..g.nx]
            .iter()
            .cloned()
            .fold(0.0, f64::max);
        let hmid = mid(s, s.fields.film.as_ref().unwrap())
            .iter()
            .cloned()
            .fold(f64::INFINITY, f64::min);
        println!(
            "| {} | {:.1} | {:.3} | {:.3} | {:.3} | {:.3} | {} | {:.1} |",
            ny,
            g.dy * 1e6,
            s.summary.min_film_m.unwrap() * 1e6,
            s.summary.min_film_at_m.unwrap()[1] * 1e3,
            end_p / 1e9,
            hmid * 1e6,
            s.summary.iterations,
            s.summary.wall_time_s
        );
    }
}
