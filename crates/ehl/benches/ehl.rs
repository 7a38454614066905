//! EHL solver benchmarks (criterion, small sample size).
//!
//! So far only the infinite line contact (ny == 1): a fixed budget of 5 V-cycles on 256, 512 and
//! 1024 cells (the solver does not yet converge to 1e-6, so a time-to-tolerance bench would be
//! meaningless; this measures the cost per cycle and its growth with N). The 1D operator is a
//! direct Toeplitz sum with cached coefficients until the lead's FFT line operator lands.
//! Run: `cargo bench -p ehl --bench ehl`.
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use ehl::case::{DensityModel, Lubricant, Rheology, ViscosityModel};
use ehl::ehl::{solve_steady, EhlParams, EhlProblem};
use ehl::elastic::{dense::DenseDeflection, Deflection};
use ehl::grid::Grid;
use ehl::units;

struct ToeplitzLine {
    grid: Grid,
    dense: DenseDeflection,
    c: Vec<f64>,
}

impl Deflection for ToeplitzLine {
    fn grid(&self) -> &Grid {
        &self.grid
    }
    fn apply(&mut self, p: &[f64], out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = p.iter().enumerate().map(|(k, &pk)| pk * self.c[i.abs_diff(k)]).sum();
        }
    }
    fn coefficient(&self, di: isize, dj: isize) -> f64 {
        self.dense.coefficient(di, dj)
    }
}

fn line(c: &mut Criterion) {
    let (e, r, eta0, alpha): (f64, f64, f64, f64) = (2.2e11, 0.02, 0.04, 2.0e-8);
    let (m, l): (f64, f64) = (100.0, 10.0);
    let u = (l / (alpha * e)).powi(4);
    let w = m * u.sqrt() * e * r;
    let ue = u * e * r / eta0;
    let b = units::hertz_line_half_width(w, r, e);
    let ph = units::hertz_line_pressure(w, r, e);
    let lub = Lubricant {
        viscosity: eta0,
        pressure_viscosity_coefficient: alpha,
        density: 850.0,
        viscosity_model: ViscosityModel::Roelands,
        density_model: DensityModel::DowsonHigginson,
        rheology: Rheology::Newtonian,
    };
    let gap = move |x: f64, _y: f64| x * x / (2.0 * r);
    let op = move |g: Grid| -> Box<dyn Deflection> {
        let dense = DenseDeflection::line(g, e);
        let c = (0..g.nx).map(|d| dense.coefficient(d as isize, 0)).collect();
        Box::new(ToeplitzLine { grid: g, dense, c })
    };
    let mut group = c.benchmark_group("ehl_line_5_vcycles");
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
        let params = EhlParams { max_iterations: 5, tolerance: 0.0, ..EhlParams::default() };
        group.bench_with_input(BenchmarkId::from_parameter(nx), &nx, |bch, _| {
            bch.iter(|| solve_steady(&prob, &params))
        });
    }
    group.finish();
}

criterion_group!(benches, line);
criterion_main!(benches);
