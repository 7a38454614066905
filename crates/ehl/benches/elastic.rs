//! Cost of one elastic operator application (DC-FFT), the unit every solver pays per iteration.
//! Run: `cargo bench -p ehl --bench elastic`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use ehl::elastic::{guilbault_psi, BodyCompliance, Deflection, EndImages, FftDeflection};
use ehl::grid::Grid;

fn half_space(c: &mut Criterion) {
    let mut group = c.benchmark_group("elastic_apply_half_space");
    group.sample_size(20);
    for &n in &[256usize, 512, 1024] {
        let g = Grid::new(n, n, -1e-3, 1e-3, -1e-3, 1e-3);
        let mut op = FftDeflection::half_space(g, 2.2e11);
        let p = vec![1e9; g.len()];
        let mut w = vec![0.0; g.len()];
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| op.apply(&p, &mut w))
        });
    }
    group.finish();
}

fn roller_with_images(c: &mut Criterion) {
    let mut group = c.benchmark_group("elastic_apply_roller_images");
    group.sample_size(20);
    let g = Grid::new(256, 2048, -1e-4, 1e-4, -5e-3, 5e-3);
    for &levels in &[0usize, 1, 2] {
        let mut b = BodyCompliance::new(2.1e11, 0.3);
        b.images = Some(EndImages {
            ends: (-5e-3, 5e-3),
            levels,
            psi: guilbault_psi(0.3),
        });
        let mut op = FftDeflection::with_images(g, &[b, BodyCompliance::new(2.1e11, 0.3)]);
        let p = vec![1e9; g.len()];
        let mut w = vec![0.0; g.len()];
        group.bench_with_input(
            BenchmarkId::new("256x2048_levels", levels),
            &levels,
            |bch, _| bch.iter(|| op.apply(&p, &mut w)),
        );
    }
    group.finish();
}

criterion_group!(benches, half_space, roller_with_images);
criterion_main!(benches);
