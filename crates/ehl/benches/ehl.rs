//! EHL solver benchmarks (criterion, sample size 10): time to the default tolerance (1e-6).
//!
//! * infinite line contact (M = 100, L = 10, Roelands + Dowson-Higginson) on 256, 512, 1024 cells
//!   over [-4.5 b, 1.5 b] (growth with N);
//! * ball on glass (the EHL-FBNS case: R = 12.5 mm, E' = 110 GPa, F = 15 N, u_e = 0.09 m/s,
//!   eta0 = 0.25 Pa s, alpha = 22 GPa^-1) on 65^2, 129^2 and 257^2 cells over [-3a, 3a]^2;
//! * the thesis ch. 2 roller (`examples/ehl_thesis_ch2_roller.toml`: R = 60 mm, L = 9.5 mm,
//!   6 kN, Roelands + Dowson-Higginson, 1 mirror level + psi) through `run::solve` (dry
//!   contact, then EHL; no output files) on 64 x 128, 128 x 256 and 256 x 512 cells.
//!
//! * transient runs (see [`transient`]).
//!
//! Run: `cargo bench -p ehl --bench ehl` (`-- ehl_transient` for the transient group only).
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use ehl::case::{DensityModel, Lubricant, Rheology, ViscosityModel};
use ehl::ehl::{solve_steady, EhlParams, EhlProblem};
use ehl::elastic::{Deflection, FftDeflection};
use ehl::grid::Grid;
use ehl::units;

fn lub(eta0: f64, alpha: f64) -> Lubricant {
    Lubricant {
        viscosity: eta0,
        pressure_viscosity_coefficient: alpha,
        density: 850.0,
        viscosity_model: ViscosityModel::Roelands,
        density_model: DensityModel::DowsonHigginson,
        rheology: Rheology::Newtonian,
    }
}

fn line(c: &mut Criterion) {
    let (e, r, eta0, alpha): (f64, f64, f64, f64) = (2.2e11, 0.02, 0.04, 2.0e-8);
    let (m, l): (f64, f64) = (100.0, 10.0);
    // Moes groups with 2U: L = G (2U)^(1/4), M = W (2U)^(-1/2)
    let u2 = (l / (alpha * e)).powi(4);
    let w = m * u2.sqrt() * e * r;
    let ue = 0.5 * u2 * e * r / eta0;
    let b = units::hertz_line_half_width(w, r, e);
    let ph = units::hertz_line_pressure(w, r, e);
    let lub = lub(eta0, alpha);
    let gap = move |x: f64, _y: f64| x * x / (2.0 * r);
    let op = move |g: Grid| -> Box<dyn Deflection> { Box::new(FftDeflection::line(g, e)) };
    let mut group = c.benchmark_group("ehl_line_M100_L10");
    group.sample_size(10);
    for &nx in &[256usize, 512, 1024] {
        let grid = Grid::new(nx, 1, -4.5 * b, 1.5 * b, -0.5, 0.5);
        let prob = EhlProblem {
            grid,
            gap: &gap,
            operator: &op,
            load: w,
            lubricant: &lub,
            entrainment_speed: ue,
            reduced_radius: r,
            reduced_modulus: e,
            hertz_half_width: b,
            hertz_pressure: ph,
            initial_pressure: None,
        };
        let params = EhlParams::default();
        let res = solve_steady(&prob, &params);
        eprintln!(
            "line nx {nx}: {} Newton {} GMRES {} operator applications {}",
            res.termination, res.iterations, res.linear_iterations, res.operator_applications
        );
        group.bench_with_input(BenchmarkId::from_parameter(nx), &nx, |bch, _| {
            bch.iter(|| solve_steady(&prob, &params))
        });
    }
    group.finish();
}

fn ball(c: &mut Criterion) {
    let (r, e, f, ue, eta0, alpha) = (0.0125, 110e9, 15.0, 0.09, 0.25, 22e-9);
    let hz = units::hertz_point(f, r, e);
    let lub = lub(eta0, alpha);
    let a = hz.a;
    let gap = move |x: f64, y: f64| (x * x + y * y) / (2.0 * r);
    let op = move |g: Grid| -> Box<dyn Deflection> { Box::new(FftDeflection::half_space(g, e)) };
    let mut group = c.benchmark_group("ehl_ball_on_glass");
    group.sample_size(10);
    for &n in &[65usize, 129, 257] {
        let grid = Grid::new(n, n, -3.0 * a, 3.0 * a, -3.0 * a, 3.0 * a);
        let prob = EhlProblem {
            grid,
            gap: &gap,
            operator: &op,
            load: f,
            lubricant: &lub,
            entrainment_speed: ue,
            reduced_radius: r,
            reduced_modulus: e,
            hertz_half_width: a,
            hertz_pressure: hz.p0,
            initial_pressure: None,
        };
        let params = EhlParams::default();
        let res = solve_steady(&prob, &params);
        eprintln!(
            "ball {n}^2: {} Newton {} GMRES {} operator applications {}",
            res.termination, res.iterations, res.linear_iterations, res.operator_applications
        );
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |bch, _| {
            bch.iter(|| solve_steady(&prob, &params))
        });
    }
    group.finish();
}

fn roller(c: &mut Criterion) {
    let path = std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/ehl_thesis_ch2_roller.toml"
    ));
    let mut group = c.benchmark_group("ehl_thesis_roller");
    group.sample_size(10);
    for &(nx, ny) in &[(64usize, 128usize), (128, 256), (256, 512)] {
        let set = [format!("grid.nx={nx}"), format!("grid.ny={ny}")];
        let case = ehl::case::load_file(path, &set).expect("example case");
        let sol = ehl::run::solve(&case, &ehl::run::Silent).expect("solve");
        let sm = &sol.summary;
        eprintln!(
            "roller {nx} x {ny}: {} Newton {} residual {:.2e}",
            sm.termination,
            sm.iterations,
            sm.residual.unwrap_or(f64::NAN)
        );
        group.bench_with_input(
            BenchmarkId::from_parameter(format!("{nx}x{ny}")),
            &case,
            |bch, case| bch.iter(|| ehl::run::solve(case, &ehl::run::Silent)),
        );
    }
    group.finish();
}

/// Transient runs through `run::solve` (steady start, time loop, friction per step; no output
/// files): the thesis ch. 3 single pit made 1 um deep (`examples/ehl_thesis_ch3_single_pit.toml`)
/// over its first 10 steps on 64^2, 128^2 and 256^2 cells, and the waviness line
/// (`examples/ehl_transient_line_waviness.toml`), 100 steps on 1024 and 2048 cells. The time
/// per step is the median over the run (the steady start included).
fn transient(c: &mut Criterion) {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/");
    let mut group = c.benchmark_group("ehl_transient");
    group.sample_size(10);
    let mut cases = Vec::new();
    for n in [64usize, 128, 256] {
        let set = vec![
            format!("grid.nx={n}"),
            format!("grid.ny={n}"),
            "features[0].depth=1e-6".to_string(),
            format!("motion.travel.steps={}", 150 * n / 256),
            "output.animation=false".to_string(),
            "output.snapshots=[]".to_string(),
        ];
        cases.push((
            format!("pit_{n}x{n}"),
            "ehl_thesis_ch3_single_pit.toml",
            set,
            10,
        ));
    }
    for n in [1024usize, 2048] {
        let set = vec![
            format!("grid.nx={n}"),
            "motion.travel.steps=100".to_string(),
            format!(
                "motion.travel.duration={}",
                1.2e-4 * 100.0 / 2000.0 * 2048.0 / n as f64
            ),
        ];
        cases.push((
            format!("waviness_{n}"),
            "ehl_transient_line_waviness.toml",
            set,
            100,
        ));
    }
    for (name, file, mut set, steps) in cases {
        if name.starts_with("pit") {
            // only the first `steps` steps of the travel, at the travel's step length
            let full: usize = set[3]
                .trim_start_matches("motion.travel.steps=")
                .parse()
                .unwrap();
            set[3] = format!("motion.travel.steps={steps}");
            set.push(format!(
                "motion.travel.to={}",
                -1.0e-3 + 2.0e-3 * steps as f64 / full as f64
            ));
        }
        let case = ehl::case::load_file(std::path::Path::new(&format!("{dir}{file}")), &set)
            .expect("example case");
        let sol = ehl::run::solve(&case, &ehl::run::Silent).expect("solve");
        let sm = &sol.summary;
        eprintln!(
            "{name}: {} ({} Newton in all)",
            sm.termination, sm.iterations
        );
        group.bench_with_input(BenchmarkId::from_parameter(&name), &case, |bch, case| {
            bch.iter(|| ehl::run::solve(case, &ehl::run::Silent))
        });
    }
    group.finish();
}

criterion_group!(benches, line, ball, roller, transient);
criterion_main!(benches);
