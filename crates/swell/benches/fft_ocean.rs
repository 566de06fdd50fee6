//! FFT ocean: the full simulation step (evolve, eight fields by four packed inverse FFTs, Jacobian
//! and foam) and the displaced mesh with normals, at 256² and 1024².

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use glam::Vec2;
use swell::math::GridSpec;
use swell::mesh::SurfaceMesh;
use swell::water::{FftOcean, FftOceanParams, WaveModel};

fn ocean_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("fft_ocean");
    group.sample_size(20);
    for grid in [256u32, 1024] {
        let params = FftOceanParams { grid, choppiness: 1.2, wind_speed: 14.0, ..FftOceanParams::default() };
        let mut ocean = FftOcean::new(&params).unwrap();
        let mut t = 0.0;
        group.bench_function(BenchmarkId::new("step", grid), |b| {
            b.iter(|| {
                t += 1.0 / 60.0;
                ocean.advance(t).unwrap();
            })
        });
        let mesh_grid = GridSpec::new(Vec2::ZERO, Vec2::splat(params.patch_size), grid, grid).unwrap();
        let mut mesh = SurfaceMesh::new(mesh_grid);
        group.bench_function(BenchmarkId::new("mesh", grid), |b| b.iter(|| mesh.displace(&ocean, t)));
    }
    group.finish();
}

criterion_group!(benches, ocean_step);
criterion_main!(benches);
