//! Terrain generation speed. Target (issue 5): diamond-square 1025^2 under 20 ms and 4097^2 under
//! 400 ms on 2 cores.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use glam::Vec2;
use swell::terrain::{diamond_square, DiamondSquareParams};

fn bench_diamond_square(c: &mut Criterion) {
    let mut group = c.benchmark_group("diamond_square");
    let params = DiamondSquareParams { seed: 7, ..Default::default() };
    for size in [1025u32, 4097] {
        if size > 1025 {
            group.sample_size(10);
        }
        group.bench_with_input(BenchmarkId::from_parameter(size), &size, |b, &size| {
            b.iter(|| diamond_square(size, Vec2::splat(1000.0), &params).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench_diamond_square);
criterion_main!(benches);
