//! Convergence envelope of the steady EHL solver on the infinite line contact: for Hertz
//! pressures 0.5-2.5 GPa and Moes M = 10-1000, L = 3-20 (issue 3), run the case through the same
//! pipeline as `ehl run` and print whether it converged, the Newton iterations, the time and the
//! central film against Moes' fit. The laws are Barus + incompressible, the ones the Moes fit was
//! made with, so the ratio is a like-for-like check where the solver converges.
//!
//! `cargo run --release -p ehl --example ehl_robustness`

use ehl::case::parse_str;
use ehl::reference::film::moes_line_central_film;
use ehl::run::{solve, Silent};
use std::time::Instant;

fn main() {
    let (e, nu, r, eta0) = (200e9_f64, 0.3_f64, 0.01_f64, 0.04_f64);
    let e_red = 2.0 / (2.0 * (1.0 - nu * nu) / e);
    println!("| p_h (GPa) | M | L | converged | Newton | time (s) | h_c (um) | h_c / Moes |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- |");
    let mut cases = Vec::new();
    for &ph in &[0.5e9, 1.0e9, 2.5e9] {
        for &m in &[10.0, 30.0, 100.0, 300.0, 1000.0] {
            cases.push((ph, m, 10.0));
        }
    }
    for &l in &[3.0, 20.0] {
        for &m in &[10.0, 100.0, 1000.0] {
            cases.push((1.0e9, m, l));
        }
    }
    for (ph, m, l) in cases {
        // W from p_h; 2U from M = W (2U)^-1/2; G from L = G (2U)^1/4 (Venner & Lubrecht groups)
        let w = 2.0 * std::f64::consts::PI * ph * ph / (e_red * e_red);
        let two_u = (w / m).powi(2);
        let u = 0.5 * two_u;
        let g = l / two_u.powf(0.25);
        let text = format!(
            r#"
title = "robustness"
kind = "ehl"
[body1]
shape = "roller"
radius = {r2}
length = inf
youngs_modulus = {e}
poisson_ratio = {nu}
[body2]
shape = "roller"
radius = {r2}
length = inf
youngs_modulus = {e}
poisson_ratio = {nu}
[load]
max_hertz_pressure = {ph}
[motion]
dimensionless_speed = {u}
[lubricant]
viscosity = {eta0}
dimensionless_material = {g}
density = 850.0
viscosity_model = "barus"
density_model = "constant"
[grid]
nx = 1024
ny = 1
x_min = -6.0
x_max = 1.5
[solver]
tolerance = 1e-6
max_iterations = 100
"#,
            r2 = 2.0 * r
        );
        let case = match parse_str(&text, "robustness.toml", &[]) {
            Ok(c) => c,
            Err(err) => {
                println!(
                    "| {:.1} | {m} | {l} | case refused: {err} | | | | |",
                    ph * 1e-9
                );
                continue;
            }
        };
        let t = Instant::now();
        let sol = solve(&case, &Silent).expect("solve");
        let secs = t.elapsed().as_secs_f64();
        let s = &sol.summary;
        let hc = s.central_film_m.unwrap_or(f64::NAN);
        let moes = moes_line_central_film(w, u, g) * r;
        println!(
            "| {:.1} | {m} | {l} | {} | {} | {secs:.2} | {:.4} | {:.3} |",
            ph * 1e-9,
            if s.converged { "yes" } else { "**no**" },
            s.iterations,
            hc * 1e6,
            hc / moes
        );
    }
}
