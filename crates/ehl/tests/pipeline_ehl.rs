//! Steady EHL of a finite roller pair through the whole pipeline (case text -> dry start ->
//! Newton-Krylov Reynolds solver -> summary), checked against conservation laws, symmetry and
//! the infinite line contact.

use ehl::case::parse_str;
use ehl::run::{solve, Silent};
use ehl::solution::Solution;

/// Two rollers R = 20 mm, L = 8 mm, p_h = 1 GPa (b = 0.18 mm, L = 44 b), u_e = 1 m/s, the thesis
/// lubricant: Moes M ~ 22, L ~ 8.6, a moderate EHL contact.
fn case_text(length: &str, ny: usize, mirror: usize) -> String {
    format!(
        r#"
title = "finite line test"
kind = "ehl"
[body1]
shape = "roller"
radius = 0.020
length = {length}
youngs_modulus = 200e9
poisson_ratio = 0.3
[body2]
shape = "roller"
radius = 0.020
length = {length}
youngs_modulus = 200e9
poisson_ratio = 0.3
[load]
max_hertz_pressure = 1.0e9
[motion]
entrainment_speed = 1.0
[lubricant]
viscosity = 0.04
pressure_viscosity_coefficient = 15.9e-9
density = 846.0
[grid]
nx = 96
ny = {ny}
x_min = -4.0
x_max = 1.5
[solver]
tolerance = 1e-7
mirror_levels = {mirror}
"#
    )
}

fn run(length: &str, ny: usize, mirror: usize) -> Solution {
    let case = parse_str(&case_text(length, ny, mirror), "finite_line.toml", &[]).unwrap();
    let s = solve(&case, &Silent).unwrap();
    assert!(s.summary.converged, "{}", s.summary.termination);
    s
}

#[test]
fn finite_line_conserves_mass_and_load_is_symmetric_and_constricts_at_the_ends() {
    let s = run("8.0e-3", 48, 0);
    let (g, p, h) = (s.grid, &s.fields.pressure, s.fields.film.as_ref().unwrap());
    let sum = &s.summary;
    // load balance through h0, to the solver tolerance (1e-7 requested, 1e-6 demanded)
    assert!(sum.load_error < 1e-6, "load error {:e}", sum.load_error);
    // mass: inflow = outflow + side leakage; the discretisation is conservative, so this holds
    // to the solver's residual (1e-7 of the wedge flow): 1e-4 leaves room for the cavitation
    // boundary's active-set cells
    let (qi, qo, qs) = (
        sum.mass_inflow_kg_s.unwrap(),
        sum.mass_outflow_kg_s.unwrap(),
        sum.side_leakage_kg_s.unwrap(),
    );
    assert!(qi > 0.0 && qs > 0.0, "inflow {qi:e}, side leakage {qs:e}");
    assert!(
        (qi - qo - qs).abs() < 1e-4 * qi,
        "in {qi:e} out {qo:e} side {qs:e}"
    );
    // aligned identical rollers: symmetric about mid-length to the solver tolerance
    let pmax = sum.max_pressure_pa;
    for j in 0..g.ny {
        for i in 0..g.nx {
            let d = (p[g.idx(i, j)] - p[g.idx(i, g.ny - 1 - j)]).abs();
            assert!(d < 1e-5 * pmax, "asymmetric at ({i},{j}): {d:e}");
        }
    }
    // With the ends treated as plain half-space edges (mirror_levels = 0) the classical
    // finite-line picture appears: side leakage and the stiff edge raise the pressure and
    // constrict the film near the ends. (With mirror images and psi the free ends are soft and
    // both effects nearly vanish: the thesis' dry fig. 1.10 shows the same end softening.)
    let row_max = |j: usize, f: &dyn Fn(usize) -> f64| {
        (0..g.nx)
            .map(|i| f(g.idx(i, j)))
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let end_p = row_max(0, &|k| p[k]);
    let mid_p = row_max(g.ny / 2, &|k| p[k]);
    assert!(end_p > 1.1 * mid_p, "end {end_p:e} vs mid {mid_p:e}");
    let [_, y_min] = sum.min_film_at_m.unwrap();
    assert!(y_min.abs() > 0.4 * 8.0e-3, "minimum film at y = {y_min}");
    let jm = g.ny / 2;
    let mid_min = (0..g.nx)
        .map(|i| h[g.idx(i, jm)])
        .fold(f64::INFINITY, f64::min);
    assert!(sum.min_film_m.unwrap() < 0.95 * mid_min);
}

#[test]
fn long_roller_mid_length_film_matches_the_infinite_line_contact() {
    // Same load per unit length, same x grid: at mid-length of a roller 44 b long the flow is
    // two-dimensional, so the central film must match the infinite line contact's within 5 %
    // (the issue's bound; the 3D side flow reaches only a few b in from the ends).
    let finite = run("8.0e-3", 48, 1);
    let line = run("inf", 1, 1);
    let (hf, hl) = (
        finite.summary.central_film_m.unwrap(),
        line.summary.central_film_m.unwrap(),
    );
    assert!((hf / hl - 1.0).abs() < 0.05, "finite {hf:e} vs line {hl:e}");
}
