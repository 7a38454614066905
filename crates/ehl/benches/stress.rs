//! Stress below the surface: the full tensor of a 256 x 256 contact on 64 depth layers from
//! pressure and shear traction (issue 12's speed target: <= 1.2 s, goal 0.6 s, on 2 cores), and
//! its parts (influence tables alone; a frictionless field, fewer kernel FFTs); a passage's
//! evaluation of a 24-layer window from kept kernel spectra, and building them.
//!
//! `cargo bench -p ehl --bench stress`

use criterion::{criterion_group, criterion_main, Criterion};
use ehl::grid::Grid;
use ehl::stress::field::{stress_field, StressKernels, DEFAULT_CACHE_BYTES};
use ehl::stress::kernel::LayerKernel;
use std::hint::black_box;

fn hertz_circle(n: usize) -> (Grid, Vec<f64>, Vec<f64>) {
    let grid = Grid::new(n, n, -2.0, 2.0, -2.0, 2.0);
    let mut p = vec![0.0; n * n];
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (grid.x(i), grid.y(j));
            p[j * n + i] = (1.0 - x * x - y * y).max(0.0).sqrt();
        }
    }
    let q = p.iter().map(|v| 0.1 * v).collect();
    (grid, p, q)
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("stress");
    g.sample_size(10);
    let (grid, p, q) = hertz_circle(256);
    let depths: Vec<f64> = (1..=64).map(|k| 0.05 * k as f64).collect();
    g.bench_function("tensor_256x256x64_pressure_and_shear", |b| {
        b.iter(|| black_box(stress_field(&grid, &p, Some(&q), 0.3, &depths, false)))
    });
    g.bench_function("tensor_256x256x64_pressure_only", |b| {
        b.iter(|| black_box(stress_field(&grid, &p, None, 0.3, &depths, false)))
    });
    // a transient passage's evaluation: the 24-layer window's kernel spectra kept (69.7 MB)
    let window = &depths[..24];
    let kernels = StressKernels::new(&grid, 0.3, window, false, DEFAULT_CACHE_BYTES);
    g.bench_function("tensor_256x256x24_cached_kernels_pressure_and_shear", |b| {
        b.iter(|| black_box(kernels.field(&p, Some(&q))))
    });
    g.bench_function("kernel_spectra_256x256x24_build", |b| {
        b.iter(|| {
            black_box(StressKernels::new(
                &grid,
                0.3,
                window,
                false,
                DEFAULT_CACHE_BYTES,
            ))
        })
    });
    g.bench_function("influence_tables_256x256_one_layer", |b| {
        b.iter(|| black_box(LayerKernel::new(256, 256, grid.dx, grid.dy, 0.5, 0.3)))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
