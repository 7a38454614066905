//! Dry contact solver benchmarks (issue 2, "Speed"): ball on flat (Hertz) on 512^2 and 1024^2
//! cells to a relative residual of 1e-10, and a straight roller R = 5 mm on a flat, L = 10 mm,
//! 5 kN, E = 210 GPa, nu = 0.3, on 256 x 2048 cells.
//!
//! Run: `cargo bench -p ehl --bench dry -- --sample-size 10`
//! The time split (operator applications against the rest) is printed by
//! `cargo test -p ehl --release --test dry_profile -- --ignored --nocapture`.
use criterion::{criterion_group, criterion_main, Criterion};
use ehl::dry::{solve, DryParams, DryProblem};
use ehl::elastic::operator::FftDeflection;
use ehl::elastic::Deflection;
use ehl::grid::Grid;
use ehl::units;
use std::time::Duration;

fn ball(c: &mut Criterion) {
    let e_red = 2.2e11;
    let (r, f) = (0.01, 100.0);
    let hz = units::hertz_point(f, r, e_red);
    let gap = move |x: f64, y: f64| (x * x + y * y) / (2.0 * r);
    let op = move |g: Grid| Box::new(FftDeflection::half_space(g, e_red)) as Box<dyn Deflection>;
    let mut group = c.benchmark_group("dry");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(10));
    for &n in &[512usize, 1024] {
        let l = 1.5 * hz.a;
        let grid = Grid::new(n, n, -l, l, -l, l);
        let problem = DryProblem {
            grid,
            gap: &gap,
            operator: &op,
            load: f,
        };
        let params = DryParams::default();
        let res = solve(&problem, &params);
        eprintln!(
            "ball {n}^2: converged {}, residual {:.2e}, fine iterations {}, total {}, applications {}",
            res.converged, res.residual, res.iterations, res.total_iterations, res.applications
        );
        group.bench_function(format!("ball_on_flat_{n}x{n}"), |b| {
            b.iter(|| solve(&problem, &params))
        });
    }
    let (e, nu) = (2.1e11, 0.3);
    let e_red = units::reduced_modulus(e, nu, e, nu);
    let (r, len, f) = (0.005, 0.010, 5000.0);
    let bw = units::hertz_line_half_width(f / len, r, e_red);
    let gap = move |x: f64, y: f64| {
        if y.abs() <= 0.5 * len {
            x * x / (2.0 * r)
        } else {
            f64::INFINITY
        }
    };
    let op = move |g: Grid| Box::new(FftDeflection::half_space(g, e_red)) as Box<dyn Deflection>;
    let grid = Grid::new(256, 2048, -1.5 * bw, 1.5 * bw, -0.55 * len, 0.55 * len);
    let problem = DryProblem {
        grid,
        gap: &gap,
        operator: &op,
        load: f,
    };
    let params = DryParams::default();
    let res = solve(&problem, &params);
    eprintln!(
        "roller 256x2048: converged {}, residual {:.2e}, fine iterations {}, total {}, applications {}",
        res.converged, res.residual, res.iterations, res.total_iterations, res.applications
    );
    group.bench_function("roller_256x2048", |b| b.iter(|| solve(&problem, &params)));
    group.finish();
}

criterion_group!(benches, ball);
criterion_main!(benches);
