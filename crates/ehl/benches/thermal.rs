//! Thermal EHL benchmarks (criterion, sample size 10), each beside its isothermal twin so that
//! the ratio the issue bounds (thermal <= 3x isothermal) reads off one run:
//!
//! * `thermal_line`: the thesis Table 3.7 line (`examples/ehl_thermal_line.toml`: R = 20 mm,
//!   W = 1.3e-4, U = 7.3e-11, G = 3500, Carreau with n(T), SRR 0.3, 7 points across the film)
//!   through `run::solve` (no output files) on 256 and 512 cells, thermal and with `[thermal]`
//!   removed;
//! * `thermal_roller`: the thesis ch. 2 roller (`examples/ehl_thesis_ch2_roller.toml`) with the
//!   same `[thermal]` table, Carreau (G = 4.5 MPa, n = 0.57) at SRR 0.3 on 128 x 64 cells;
//! * `thermal_ball`: `examples/ehl_thermal_ball.toml` (a steel ball, R = 12.5 mm, on a glass
//!   disc at 15 N, 0.09 m/s, SRR 0.5, 129 x 129 cells), one of the two cases the 3x
//!   bound names, thermal and with `[thermal]` removed;
//! * `thermal_film`: one film solve of a 256-cell line (`thermal::film_energy::solve_line`) at
//!   the thermal line's laws: h from 0.5 to 3 um, 1 GPa, dp/dx = 1e13 Pa/m, SRR 0.3 at 6 m/s.
//!
//! Run: `cargo bench -p ehl --bench thermal`.
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use ehl::lubricant::temperature::ThermalLaws;
use ehl::thermal::collocation::Lobatto;
use ehl::thermal::film::OilThermal;
use ehl::thermal::film_energy::{solve_line, Line, LineOptions};

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/");

fn load(file: &str, set: &[String]) -> ehl::case::Case {
    ehl::case::load_file(std::path::Path::new(&format!("{DIR}{file}")), set).expect("example case")
}

fn bench_solves(c: &mut Criterion, group: &str, cases: Vec<(String, ehl::case::Case)>) {
    let mut group = c.benchmark_group(group);
    group.sample_size(10);
    for (name, case) in cases {
        let sol = ehl::run::solve(&case, &ehl::run::Silent).expect("solve");
        eprintln!(
            "{name}: {} ({} Newton, {:?} outer)",
            sol.summary.termination, sol.summary.iterations, sol.summary.thermal_iterations
        );
        group.bench_with_input(BenchmarkId::from_parameter(&name), &case, |b, case| {
            b.iter(|| ehl::run::solve(case, &ehl::run::Silent))
        });
    }
    group.finish();
}

fn thermal_line(c: &mut Criterion) {
    let mut cases = Vec::new();
    for nx in [256usize, 512] {
        let thermal = load("ehl_thermal_line.toml", &[format!("grid.nx={nx}")]);
        let mut iso = thermal.clone();
        iso.thermal = None;
        cases.push((format!("thermal_{nx}"), thermal));
        cases.push((format!("isothermal_{nx}"), iso));
    }
    bench_solves(c, "thermal_line", cases);
}

fn thermal_roller(c: &mut Criterion) {
    let line = load("ehl_thermal_line.toml", &[]);
    let set = [
        "grid.nx=128".to_string(),
        "grid.ny=64".to_string(),
        "motion.slide_to_roll=0.3".to_string(),
        "lubricant.rheology={model=\"carreau\",shear_modulus=4.5e6,power_law_index=0.57}"
            .to_string(),
    ];
    let iso = load("ehl_thesis_ch2_roller.toml", &set);
    let mut thermal = iso.clone();
    thermal.thermal = line.thermal.clone();
    bench_solves(
        c,
        "thermal_roller",
        vec![
            ("thermal_128x64".to_string(), thermal),
            ("isothermal_128x64".to_string(), iso),
        ],
    );
}

fn thermal_ball(c: &mut Criterion) {
    let thermal = load("ehl_thermal_ball.toml", &[]);
    let mut iso = thermal.clone();
    iso.thermal = None;
    bench_solves(
        c,
        "thermal_ball",
        vec![
            ("thermal_129x129".to_string(), thermal),
            ("isothermal_129x129".to_string(), iso),
        ],
    );
}

fn thermal_film(c: &mut Criterion) {
    let case = load("ehl_thermal_line.toml", &[]);
    let laws = ThermalLaws::new(
        case.lubricant.as_ref().unwrap(),
        &case.thermal.as_ref().unwrap().lubricant,
    );
    let th = &laws.thermal;
    let oil = OilThermal::constant(th.conductivity, th.heat_capacity);
    let t0 = th.inlet_temperature;
    let rule = Lobatto::new(7);
    let nx = 256;
    let h: Vec<f64> = (0..nx)
        .map(|i| 0.5e-6 + 2.5e-6 * ((i as f64 - 128.0) / 128.0).powi(2))
        .collect();
    let p = vec![1e9; nx];
    let dpdx = vec![1e13; nx];
    let zeros = vec![0.0; nx];
    let walls = vec![t0; nx];
    let line = Line {
        dx: 1e-6,
        h: &h,
        p: &p,
        dpdx: &dpdx,
        dpdy: &zeros,
        u1: 6.9,
        u2: 5.1,
        t1: &walls,
        t2: &walls,
        t_in: t0,
        poiseuille_flux_x: None,
        transient: None,
        side: None,
    };
    let opts = LineOptions::default();
    let s = solve_line(&rule, &laws, &oil, &line, None, &opts).expect("film");
    eprintln!(
        "film 256 x 7: {} iterations, converged {}, max T {:.1} K",
        s.iterations,
        s.converged,
        s.t.iter().fold(0.0f64, |m, v| m.max(*v))
    );
    let mut group = c.benchmark_group("thermal_film");
    group.sample_size(10);
    group.bench_function("line_256x7", |b| {
        b.iter(|| solve_line(&rule, &laws, &oil, &line, None, &opts))
    });
    group.finish();
}

criterion_group!(
    benches,
    thermal_line,
    thermal_roller,
    thermal_ball,
    thermal_film
);
criterion_main!(benches);
