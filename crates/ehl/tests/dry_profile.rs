//! Where the dry solver's time goes (not a timed test: `#[ignore]`, run by hand with
//! `cargo test -p ehl --test dry_profile -- --ignored --nocapture`). The criterion benchmark is
//! `benches/dry.rs`; this prints the split between operator applications and the rest.
mod dry_support;

use ehl::dry::{solve, DryParams, DryProblem};
use ehl::elastic::Deflection;
use ehl::grid::Grid;
use ehl::units;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Instant;

struct Timed {
    inner: Box<dyn Deflection>,
    nanos: Arc<AtomicU64>,
}

impl Deflection for Timed {
    fn grid(&self) -> &Grid {
        self.inner.grid()
    }
    fn apply(&mut self, p: &[f64], out: &mut [f64]) {
        let t = Instant::now();
        self.inner.apply(p, out);
        self.nanos
            .fetch_add(t.elapsed().as_nanos() as u64, Ordering::Relaxed);
    }
    fn coefficient(&self, di: isize, dj: isize) -> f64 {
        self.inner.coefficient(di, dj)
    }
}

fn run(
    label: &str,
    grid: Grid,
    gap: &dyn ehl::geometry::GapSampler,
    e_red: f64,
    load: f64,
    params: &DryParams,
) {
    let nanos = Arc::new(AtomicU64::new(0));
    let build = Arc::new(AtomicU64::new(0));
    let base = dry_support::half_space(e_red);
    let (n2, b2) = (nanos.clone(), build.clone());
    let op = move |g: Grid| {
        let t = Instant::now();
        let inner = base(g);
        b2.fetch_add(t.elapsed().as_nanos() as u64, Ordering::Relaxed);
        Box::new(Timed {
            inner,
            nanos: n2.clone(),
        }) as Box<dyn Deflection>
    };
    let t = Instant::now();
    let res = solve(
        &DryProblem {
            grid,
            gap,
            operator: &op,
            load,
        },
        params,
    );
    let total = t.elapsed().as_secs_f64();
    let apply = nanos.load(Ordering::Relaxed) as f64 * 1e-9;
    let build = build.load(Ordering::Relaxed) as f64 * 1e-9;
    println!(
        "{label} {}x{}: {:.3} s total, operator apply {:.3} s, operator build {:.3} s, rest {:.3} s; fine iterations {}, total {}, applications {}, residual {:.2e}, converged {}",
        grid.nx, grid.ny, total, apply, build, total - apply - build, res.iterations, res.total_iterations, res.applications, res.residual, res.converged
    );
    for l in &res.levels {
        println!(
            "    level {}x{}: {} iterations, {} applications, residual {:.2e}",
            l.nx, l.ny, l.iterations, l.applications, l.residual
        );
    }
}

#[test]
#[ignore]
fn profile_ball_and_roller() {
    let e_red = 2.2e11;
    let (r, f) = (0.01, 100.0);
    let hz = units::hertz_point(f, r, e_red);
    let gap = move |x: f64, y: f64| (x * x + y * y) / (2.0 * r);
    let env = |k: &str, d: f64| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let sizes: Vec<usize> = std::env::var("DRY_N")
        .ok()
        .map(|v| v.split(',').map(|s| s.parse().unwrap()).collect())
        .unwrap_or(vec![256, 512, 1024]);
    for &cs in &[true, false] {
        let params = DryParams {
            coarse_start: cs,
            correction_fraction: env("DRY_CF", DryParams::default().correction_fraction),
            coarse_tolerance: env("DRY_CT", DryParams::default().coarse_tolerance),
            max_iterations: env("DRY_MAXIT", 1000.0) as usize,
            ..DryParams::default()
        };
        if !cs && env("DRY_NOCOLD", 0.0) > 0.0 {
            continue;
        }
        for &n in &sizes {
            if !cs && n > 512 {
                continue;
            }
            let l = 1.5 * hz.a;
            run(
                &format!("ball coarse_start={cs}"),
                Grid::new(n, n, -l, l, -l, l),
                &gap,
                e_red,
                f,
                &params,
            );
        }
    }
    // the benchmark roller: R = 5 mm on a flat, L = 10 mm, 5 kN, E = 210 GPa, nu = 0.3
    let e_red = units::reduced_modulus(2.1e11, 0.3, 2.1e11, 0.3);
    let (r, len, f) = (0.005, 0.010, 5000.0);
    let bw = units::hertz_line_half_width(f / len, r, e_red);
    let gap = move |x: f64, y: f64| {
        if y.abs() <= 0.5 * len {
            x * x / (2.0 * r)
        } else {
            f64::INFINITY
        }
    };
    for &(nx, ny) in &[(64usize, 512usize), (128, 1024), (256, 2048)] {
        let grid = Grid::new(nx, ny, -1.5 * bw, 1.5 * bw, -0.55 * len, 0.55 * len);
        run("roller", grid, &gap, e_red, f, &DryParams::default());
    }
}
