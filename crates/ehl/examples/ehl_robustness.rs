//! Convergence envelope of the steady EHL solver: for Hertz pressures 0.3-2.5 GPa and Moes
//! M = 10-1000, L = 3-20 (issue 3), run the case through the same pipeline as `ehl run` (dry
//! solution first, then EHL from it) and print whether it converged, the Newton iterations, the
//! time and the central film against the fit made with the same laws (Barus + incompressible):
//!
//! * `line` (default): infinite line contact, 1024 cells, against Moes' line fit;
//! * `roller`: two straight rollers R = 10 mm, length 10 mm, 1 mirror level + psi, 256 x 128
//!   cells, mid-length central film against Moes' line fit at the mean load per length;
//! * `ball`: ball R = 10 mm on a flat, 128 x 128 cells, against the Nijenbanning-Venner-Moes
//!   circular-contact fit (Moes' point groups).
//!
//! `cargo run --release -p ehl --example ehl_robustness [line|roller|ball] [fine]`
//!
//! With `fine`, only the M = 1000 points at p_h = 1 GPa, on grids that resolve their few-nanometre films
//! (roller: 1024 x 128 cells over x in [-2.5 b, 1.5 b]; ball: 256 x 256 over
//! [-2.5 a, 1.5 a] x [-2 a, 2 a]); the default grids are too coarse for them.

use ehl::case::parse_str;
use ehl::reference::film::{moes_line_central_film, nijenbanning_circular_central};
use ehl::run::{solve, Silent};
use std::time::Instant;

fn main() {
    let kind = std::env::args().nth(1).unwrap_or_else(|| "line".into());
    let fine = std::env::args().nth(2).is_some_and(|a| a == "fine");
    let (e, nu, r, eta0) = (200e9_f64, 0.3_f64, 0.01_f64, 0.04_f64);
    let e_red = 2.0 / (2.0 * (1.0 - nu * nu) / e);
    println!("{kind}:\n");
    println!("| p_h (GPa) | M | L | converged | Newton | time (s) | h_c (um) | h_c / fit |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- |");
    let mut cases = Vec::new();
    for &ph in &[0.3e9, 1.0e9, 2.5e9] {
        for &m in &[10.0, 30.0, 100.0, 300.0, 1000.0] {
            cases.push((ph, m, 10.0));
        }
    }
    for &l in &[3.0, 20.0] {
        for &m in &[10.0, 100.0, 1000.0] {
            cases.push((1.0e9, m, l));
        }
    }
    if fine {
        cases.retain(|c| c.1 >= 1000.0 && c.0 == 1.0e9);
    }
    if kind == "ball" {
        return balls(&cases, e, nu, r, eta0, e_red, fine);
    }
    let roller = kind == "roller";
    for (ph, m, l) in cases {
        // W from p_h; 2U from M = W (2U)^-1/2; G from L = G (2U)^1/4 (Venner & Lubrecht groups)
        let w = 2.0 * std::f64::consts::PI * ph * ph / (e_red * e_red);
        let two_u = (w / m).powi(2);
        let u = 0.5 * two_u;
        let g = l / two_u.powf(0.25);
        let (length, grid) = if roller && fine {
            ("10e-3", "nx = 1024\nny = 128\nx_min = -2.5\nx_max = 1.5")
        } else if roller {
            ("10e-3", "nx = 256\nny = 128\nx_min = -4.5\nx_max = 1.5")
        } else {
            ("inf", "nx = 1024\nny = 1\nx_min = -6.0\nx_max = 1.5")
        };
        // a finite roller carries p_h at mid-length with w = F / length
        let body = format!(
            "shape = \"roller\"\nradius = {}\nlength = {length}\nyoungs_modulus = {e}\npoisson_ratio = {nu}",
            2.0 * r
        );
        let load = if roller {
            format!("force = {}", w * e_red * r * 10e-3)
        } else {
            format!("max_hertz_pressure = {ph}")
        };
        let solver = "mirror_levels = 1\nfree_end_correction = true";
        let text = case_text(&body, &body, &load, u, g, eta0, grid, solver);
        let moes = moes_line_central_film(w, u, g) * r;
        row(&text, ph, m, l, moes);
    }
}

/// The ball-on-flat envelope: p_h sets the load, M and L the speed and G (Moes point groups).
fn balls(cases: &[(f64, f64, f64)], e: f64, nu: f64, r: f64, eta0: f64, e_red: f64, fine: bool) {
    for &(ph, m, l) in cases {
        let f = ehl::units::point_load_for_pressure(ph, r, e_red);
        let w = f / (e_red * r * r);
        // M = W (2U)^-3/4, L = G (2U)^1/4
        let two_u = (w / m).powf(4.0 / 3.0);
        let u = 0.5 * two_u;
        let g = l / two_u.powf(0.25);
        let ball =
            format!("shape = \"ball\"\nradius = {r}\nyoungs_modulus = {e}\npoisson_ratio = {nu}");
        let flat = format!("shape = \"flat\"\nyoungs_modulus = {e}\npoisson_ratio = {nu}");
        let grid = if fine {
            "nx = 256\nny = 256\nx_min = -2.5\nx_max = 1.5\ny_min = -2.0\ny_max = 2.0"
        } else {
            "nx = 128\nny = 128\nx_min = -4.5\nx_max = 1.5\ny_min = -3.0\ny_max = 3.0"
        };
        let text = case_text(&ball, &flat, &format!("force = {f}"), u, g, eta0, grid, "");
        let fit = nijenbanning_circular_central(m, l) * two_u.sqrt() * r;
        row(&text, ph, m, l, fit);
    }
}

/// Solve one case and print its table row: converged, Newton steps, time, central film and its
/// ratio to `fit` (m).
fn row(text: &str, ph: f64, m: f64, l: f64, fit: f64) {
    let case = match parse_str(text, "robustness.toml", &[]) {
        Ok(c) => c,
        Err(err) => {
            println!(
                "| {:.1} | {m} | {l} | case refused: {err} | | | | |",
                ph * 1e-9
            );
            return;
        }
    };
    let t = Instant::now();
    let sol = solve(&case, &Silent).expect("solve");
    let secs = t.elapsed().as_secs_f64();
    let s = &sol.summary;
    let hc = s.central_film_m.unwrap_or(f64::NAN);
    println!(
        "| {:.1} | {m} | {l} | {} | {} | {secs:.2} | {:.4} | {:.3} |",
        ph * 1e-9,
        if s.converged { "yes" } else { "**no**" },
        s.iterations,
        hc * 1e6,
        hc / fit
    );
}

/// The case file of one study point: the two bodies' tables, the [load] line, dimensionless
/// speed U and material G, Barus + incompressible laws, the [grid] lines and extra [solver] lines.
#[allow(clippy::too_many_arguments)]
fn case_text(
    body1: &str,
    body2: &str,
    load: &str,
    u: f64,
    g: f64,
    eta0: f64,
    grid: &str,
    solver: &str,
) -> String {
    format!(
        r#"
title = "robustness"
kind = "ehl"
[body1]
{body1}
[body2]
{body2}
[load]
{load}
[motion]
dimensionless_speed = {u}
[lubricant]
viscosity = {eta0}
dimensionless_material = {g}
density = 850.0
viscosity_model = "barus"
density_model = "constant"
[grid]
{grid}
[solver]
tolerance = 1e-6
max_iterations = 100
{solver}
"#
    )
}
