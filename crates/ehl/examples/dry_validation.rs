//! Dry contact against Hertz at three (or four) grid sizes, through the same pipeline as
//! `ehl run` (case file -> geometry -> DC-FFT operator -> dry solver):
//!
//! 1. ball on flat (`examples/dry_ball_on_flat.toml`): p0, contact radius, approach vs Hertz
//!    point contact (Johnson, Contact Mechanics, 1985, eq. 4.22-4.23);
//! 2. infinite line contact (`length = inf`, ny = 1): p_max and half-width vs Hertz line contact;
//! 3. a long straight roller (R = 5 mm, L = 10 mm, 2 kN on a flat: L = 95 b, no mirroring):
//!    pressure at mid-length vs Hertz line contact for the load per unit length carried there,
//!    w'_mid = integral of p(x, 0) dx.
//!
//! Prints markdown tables (pasted into docs/dry-contact.md).
//!
//! `cargo run --release -p ehl --example dry_validation`
mod common;

use common::{case, case_text, half_width, mid_row, run, sets};
use ehl::units;
use std::f64::consts::PI;

fn pct(v: f64) -> String {
    format!("{:+.3} %", 100.0 * v)
}

fn main() {
    // ------------------------------------------------------------------ ball on flat
    println!("### Ball on flat (R = 12.7 mm, 500 N, E = 210 GPa, nu = 0.3; domain +-1.5 a)\n");
    println!("| cells | a / dx | p0 (GPa) | error | a from area (um) | error | a from edge (um) | error | approach (um) | error | iterations | time (s) |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for n in [64usize, 128, 256] {
        let c = case(
            "dry_ball_on_flat",
            &sets(&[("grid.nx", n.to_string()), ("grid.ny", n.to_string())]),
        );
        let hz = units::hertz_point(c.load.force, c.reduced_radius(), c.reduced_modulus());
        let s = run(&c);
        let g = s.grid;
        let p0 = s.summary.max_pressure_pa;
        let a_area = (s.summary.contact_area_m2.unwrap() / PI).sqrt();
        let a_edge = half_width(&g.xs(), &mid_row(&s));
        let d = s.summary.approach_m.unwrap();
        println!(
            "| {n}^2 | {:.1} | {:.4} | {} | {:.2} | {} | {:.2} | {} | {:.3} | {} | {} | {:.2} |",
            hz.a / g.dx,
            p0 / 1e9,
            pct(p0 / hz.p0 - 1.0),
            a_area * 1e6,
            pct(a_area / hz.a - 1.0),
            a_edge * 1e6,
            pct(a_edge / hz.a - 1.0),
            d * 1e6,
            pct(d / hz.approach - 1.0),
            s.summary.iterations,
            s.summary.wall_time_s
        );
        if n == 64 {
            eprintln!(
                "Hertz: p0 = {:.4} GPa, a = {:.2} um, approach = {:.3} um",
                hz.p0 / 1e9,
                hz.a * 1e6,
                hz.approach * 1e6
            );
        }
    }

    // ------------------------------------------------------------------ infinite line
    let line = r#"
title = "Infinite line contact: roller R = 10 mm on a flat, 500 kN/m"
kind = "dry"
[body1]
shape = "roller"
radius = 0.010
length = inf
youngs_modulus = 210e9
poisson_ratio = 0.3
[body2]
shape = "flat"
youngs_modulus = 210e9
poisson_ratio = 0.3
[load]
force_per_length = 5e5
[grid]
x_min = -1.5
x_max = 1.5
[solver]
tolerance = 1e-10
max_iterations = 500
"#;
    println!("\n### Infinite line contact (R = 10 mm on a flat, w' = 500 kN/m, E = 210 GPa, nu = 0.3; ny = 1, domain +-1.5 b)\n");
    println!("| nx | b / dx | p_max (GPa) | error | half-width (um) | error | iterations |");
    println!("| --- | --- | --- | --- | --- | --- | --- |");
    for per_b in [25usize, 50, 100, 200] {
        let nx = 3 * per_b;
        let c = case_text(line, &sets(&[("grid.nx", nx.to_string())]));
        let (w, r, e) = (
            c.load.force_per_length,
            c.reduced_radius(),
            c.reduced_modulus(),
        );
        let (ph, b) = (
            units::hertz_line_pressure(w, r, e),
            units::hertz_line_half_width(w, r, e),
        );
        let s = run(&c);
        let p = mid_row(&s);
        let bw = half_width(&s.grid.xs(), &p);
        println!(
            "| {nx} | {:.0} | {:.4} | {} | {:.3} | {} | {} |",
            b / s.grid.dx,
            s.summary.max_pressure_pa / 1e9,
            pct(s.summary.max_pressure_pa / ph - 1.0),
            bw * 1e6,
            pct(bw / b - 1.0),
            s.summary.iterations
        );
        if per_b == 25 {
            eprintln!(
                "Hertz line: p_h = {:.4} GPa, b = {:.3} um",
                ph / 1e9,
                b * 1e6
            );
        }
    }

    // ------------------------------------------------------------------ long roller
    let roller = r#"
title = "Long straight roller R = 5 mm, L = 10 mm on a flat, 2 kN, plain half-space"
kind = "dry"
[body1]
shape = "roller"
radius = 0.005
length = 10.0e-3
youngs_modulus = 210e9
poisson_ratio = 0.3
[body2]
shape = "flat"
youngs_modulus = 210e9
poisson_ratio = 0.3
[load]
force = 2000.0
[grid]
x_min = -1.6
x_max = 1.6
[solver]
tolerance = 1e-10
max_iterations = 500
mirror_levels = 0
free_end_correction = false
"#;
    println!("\n### Long straight roller (R = 5 mm, L = 10 mm on a flat, 2 kN; nominal b = L / 95; no mirroring; y over the roller length)\n");
    println!("| cells nx x ny | b / dx | w'_mid (N/m) | w'_mid / (F/L) | p_max mid (GPa) | Hertz p_h(w'_mid) | error | half-width mid (um) | Hertz b(w'_mid) | error | time (s) |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for (nx, ny) in [(32usize, 104usize), (64, 208), (128, 416)] {
        let c = case_text(
            roller,
            &sets(&[("grid.nx", nx.to_string()), ("grid.ny", ny.to_string())]),
        );
        let (r, e) = (c.reduced_radius(), c.reduced_modulus());
        let s = run(&c);
        let p = mid_row(&s);
        let w_mid = p.iter().sum::<f64>() * s.grid.dx;
        let (ph, b) = (
            units::hertz_line_pressure(w_mid, r, e),
            units::hertz_line_half_width(w_mid, r, e),
        );
        let pmax = p.iter().cloned().fold(0.0, f64::max);
        let bw = half_width(&s.grid.xs(), &p);
        println!(
            "| {nx} x {ny} | {:.1} | {:.4e} | {:.4} | {:.4} | {:.4} | {} | {:.2} | {:.2} | {} | {:.2} |",
            b / s.grid.dx,
            w_mid,
            w_mid / (c.load.force / 0.010),
            pmax / 1e9,
            ph / 1e9,
            pct(pmax / ph - 1.0),
            bw * 1e6,
            b * 1e6,
            pct(bw / b - 1.0),
            s.summary.wall_time_s
        );
    }
}
