//! Grid evaluation of the analytic wave models: positions + normals of a 256² and a 512² grid with
//! 12 Gerstner waves (targets: < 1 ms and < 4 ms on 2 cores).
//!
//! `gerstner_libm` is the straightforward path (one `f32::sin_cos` per wave and vertex through
//! `evaluate_pointwise`), kept as the baseline the fast path is measured against.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use glam::{Vec2, Vec3};
use swell::math::GridSpec;
use swell::water::{evaluate_pointwise, Gerstner, GerstnerWave, PointWave, SurfacePoint, WaveModel};

fn twelve_waves() -> Vec<GerstnerWave> {
    (0..12)
        .map(|i| {
            let l = 48.0 * 0.8f32.powi(i);
            let angle = (i as f32 * 0.7).sin() * 0.7;
            GerstnerWave {
                amplitude: 0.012 * l,
                wavelength: l,
                speed: (9.81 * l / std::f32::consts::TAU).sqrt(),
                direction: Vec2::new(angle.cos(), angle.sin()),
                steepness: 0.7,
            }
        })
        .collect()
}

/// The same sum with the C library's sin_cos, vertex by vertex (the pre-optimisation path).
struct LibmGerstner {
    waves: Vec<(Vec2, Vec2, f32, f32, f64)>,
}

impl PointWave for LibmGerstner {
    type Frame = [f32; 12];
    fn frame(&self, t: f64) -> Self::Frame {
        std::array::from_fn(|i| (self.waves[i].4 * t).rem_euclid(std::f64::consts::TAU) as f32)
    }
    fn sample(&self, frame: &Self::Frame, rest: Vec2) -> SurfacePoint {
        let mut o = Vec3::ZERO;
        let (mut sxx, mut sxz, mut szz, mut cx, mut cz) = (0.0f32, 0.0f32, 0.0f32, 0.0f32, 0.0f32);
        for (&(k, d, a, h, _), &ph) in self.waves.iter().zip(frame) {
            let (s, c) = (k.dot(rest) - ph).sin_cos();
            o += Vec3::new(h * d.x * c, a * s, h * d.y * c);
            sxx += h * s * k.x * d.x;
            sxz += h * s * k.x * d.y;
            szz += h * s * k.y * d.y;
            cx += a * k.x * c;
            cz += a * k.y * c;
        }
        let n = Vec3::new(-sxz, cz, 1.0 - szz).cross(Vec3::new(1.0 - sxx, cx, -sxz)).normalize();
        SurfacePoint { offset: o, normal: n }
    }
}

fn bench(c: &mut Criterion) {
    let waves = twelve_waves();
    let fast = Gerstner::new(waves.clone()).unwrap();
    let libm = LibmGerstner {
        waves: waves
            .iter()
            .map(|w| {
                let k = std::f32::consts::TAU / w.wavelength;
                let d = w.direction.normalize();
                (d * k, d, w.amplitude, w.steepness / (k * 12.0), f64::from(w.speed * k))
            })
            .collect(),
    };
    let mut group = c.benchmark_group("waves");
    for cells in [256u32, 512] {
        let grid = GridSpec::centered(Vec2::splat(200.0), cells - 1, cells - 1).unwrap();
        let mut p = vec![Vec3::ZERO; grid.vertex_count()];
        let mut n = p.clone();
        group.bench_with_input(BenchmarkId::new("gerstner_12", cells), &grid, |b, grid| {
            let mut t = 0.0;
            b.iter(|| {
                t += 0.04;
                fast.evaluate(grid, t, &mut p, &mut n);
            })
        });
        group.bench_with_input(BenchmarkId::new("gerstner_12_libm", cells), &grid, |b, grid| {
            let mut t = 0.0;
            b.iter(|| {
                t += 0.04;
                evaluate_pointwise(&libm, grid, t, &mut p, &mut n);
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
