//! issue 19: one million point queries at one time, through the query API ([`swell::Water`]).
//! Target: under 2 s on 2 cores, FFT ocean included.
//!
//! `heights_1m/<preset>` moves to a new time every iteration, so each sample pays for the model's
//! state at that time (the FFT ocean's synthesis) plus the million heights; `normals_100k` is a
//! tenth as many normals (five heights each). Points are uniform over 1 km², seeded.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use swell::scene::preset;
use swell::Water;

const POINTS: usize = 1_000_000;

fn points(n: usize) -> Vec<Vec2> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(19);
    (0..n).map(|_| Vec2::new(rng.gen_range(-500.0..500.0), rng.gen_range(-500.0..500.0))).collect()
}

fn bench(c: &mut Criterion) {
    let pts = points(POINTS);
    let mut g = c.benchmark_group("query");
    g.sample_size(10);
    for name in ["ocean", "sea"] {
        let mut water = Water::from_scene(&preset(name).unwrap()).unwrap();
        let mut out = vec![0.0f32; POINTS];
        let mut t = 0.0;
        g.bench_function(BenchmarkId::new("heights_1m", name), |b| {
            b.iter(|| {
                t += 1.0 / 24.0;
                water.heights_at(t, &pts, &mut out).unwrap();
            })
        });
        let mut normals = vec![Vec3::ZERO; POINTS / 10];
        g.bench_function(BenchmarkId::new("normals_100k", name), |b| {
            b.iter(|| {
                t += 1.0 / 24.0;
                water.normals_at(t, &pts[..POINTS / 10], &mut normals).unwrap();
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
