//! Bake throughput on the sea preset at 512 x 512 cells: the simulation step, one EXR map, and
//! whole frames (simulate + displacement, normal EXRs, written atomically to a temporary directory).
//!
//! Also the bake case: the `ocean` preset's FFT ocean at a 512 x 512 FFT grid and 512 x 512
//! cells over one 250 m patch, tiled 512 x 512 maps (displacement, normal, foam).
//!
//! `cargo bench -p swell --bench bake`; set RAYON_NUM_THREADS=2 for the 2-core figure.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::Vec3;
use swell::export::{write_exr_rgb, Bake, BakeSettings, ExrCompression, FrameRange};
use swell::scene::preset;
use swell::world::World;

/// Frames per measured bake iteration: enough to fill the simulate/write pipeline.
const FRAMES: u32 = 16;

fn sea_512() -> World {
    let mut scene = preset("sea").unwrap();
    scene.water.as_mut().unwrap().surface.cells = [512, 512];
    World::new(scene).unwrap()
}

/// The `ocean` preset with a 512² FFT grid whose mesh covers exactly one patch (so `tile` holds).
fn ocean_512() -> World {
    let text = include_str!("../presets/ocean.toml")
        .replace("size = [400.0, 400.0]", "size = [256.0, 256.0]")
        .replace("cells = [400, 400]", "cells = [512, 512]")
        .replace("grid = 256", "grid = 512");
    World::new(swell::scene::Scene::from_toml(&text, "ocean 512").unwrap()).unwrap()
}

fn bench_ocean(c: &mut Criterion) {
    let mut world = ocean_512();
    let dir = tempfile::tempdir().unwrap();
    let mut g = c.benchmark_group("bake_ocean_512");
    g.sample_size(10);
    g.throughput(Throughput::Elements(u64::from(FRAMES)));
    g.bench_function(format!("bake_{FRAMES}_frames"), |b| {
        b.iter(|| {
            let mut s = BakeSettings::new(FrameRange::new("f", 0, FRAMES - 1).unwrap());
            s.tile = true;
            let bake = Bake::prepare(&mut world, dir.path(), s).unwrap();
            bake.run(&mut world, &|_| {}).unwrap();
        })
    });
    g.finish();
}

fn bench(c: &mut Criterion) {
    let mut world = sea_512();
    let mut g = c.benchmark_group("bake_sea_512");
    g.sample_size(10);
    let mut t = 0.0;
    g.bench_function("simulate_frame", |b| {
        b.iter(|| {
            t += 1.0 / 24.0;
            world.update(t).unwrap()
        })
    });
    let dir = tempfile::tempdir().unwrap();
    let field = vec![Vec3::new(0.1, 0.2, 0.3); 513 * 513];
    for c in [ExrCompression::None, ExrCompression::Zip] {
        g.bench_function(format!("write_exr_rgb_{c:?}"), |b| {
            b.iter(|| write_exr_rgb(&dir.path().join("f.exr"), 513, 513, &field, c).unwrap())
        });
    }
    g.throughput(Throughput::Elements(u64::from(FRAMES)));
    g.bench_function(format!("bake_{FRAMES}_frames"), |b| {
        b.iter(|| {
            let mut s = BakeSettings::new(FrameRange::new("f", 0, FRAMES - 1).unwrap());
            s.compression = ExrCompression::None;
            let bake = Bake::prepare(&mut world, dir.path(), s).unwrap();
            bake.run(&mut world, &|_| {}).unwrap();
        })
    });
    g.finish();
}

criterion_group!(benches, bench, bench_ocean);
criterion_main!(benches);
