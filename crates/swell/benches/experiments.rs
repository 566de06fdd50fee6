//! Kernels of the papers' timing experiments (`swell bench`), organised by stage, for criterion.
//!
//! - `paper000/evaluate`: Gerstner displacement and normals of the 100 x 100 grid of paper 000's
//!   experiments with the main wave and 3 added waves (the simulation half of a frame);
//! - `paper000/frame`: that plus rendering at 800 x 600 (`World::update` + `Renderer::render`);
//! - `paper001/zbuffer`: flat-shaded z-buffer drawing of a 129 x 129 heightmap at 800 x 800, on one
//!   thread and on all.
//!
//! The CLI's `swell bench` reproduces the papers' tables; these isolate the kernels for tuning.
//! Run with `cargo bench -p swell --bench experiments`.

use criterion::{criterion_group, criterion_main, Criterion};
use glam::{Vec2, Vec3, Vec4};
use swell::math::GridSpec;
use swell::mesh::SurfaceMesh;
use swell::raster::{draw, ClipVertex, Cull, Framebuffer};
use swell::render::Renderer;
use swell::scene::{preset, WaterModelSpec};
use swell::water::{Gerstner, GerstnerWave, WaveModel};
use swell::world::World;

/// Paper 000 figure 4.1's main wave (1 unit = 0.1 m, A/L = 0.07) and 3 added waves.
fn paper000_waves() -> Vec<GerstnerWave> {
    let main =
        GerstnerWave { amplitude: 0.35, wavelength: 5.0, speed: 2.0, direction: Vec2::new(1.0, 1.0), steepness: 0.02 };
    let mut waves = vec![main];
    for (k, d) in [[1.0, 0.0], [0.0, 1.0], [-1.0, 2.0]].into_iter().enumerate() {
        let r = 0.85f32.powi(k as i32 + 1);
        waves.push(GerstnerWave {
            amplitude: main.amplitude * r,
            wavelength: main.wavelength * r,
            speed: main.speed * r.sqrt(),
            direction: Vec2::from_array(d),
            ..main
        });
    }
    waves
}

fn paper000(c: &mut Criterion) {
    let mut g = c.benchmark_group("paper000");
    let model = Gerstner::new(paper000_waves()).unwrap();
    let grid = GridSpec::centered(Vec2::splat(40.0), 100, 100).unwrap();
    let mut mesh = SurfaceMesh::new(grid);
    let mut t = 0.0;
    g.bench_function("evaluate/100x100/4-waves", |b| {
        b.iter(|| {
            t += 1.0 / 30.0;
            model.evaluate(&mesh.grid, t, &mut mesh.positions, &mut mesh.normals);
        })
    });
    // The sea preset's camera and light over the paper's grid and waves.
    let mut scene = preset("sea").unwrap();
    let water = scene.water.as_mut().unwrap();
    water.surface.size = Vec2::splat(40.0);
    water.surface.cells = [100, 100];
    water.model = WaterModelSpec::Gerstner(swell::scene::GerstnerSpec { waves: paper000_waves() });
    scene.camera.eye = Vec3::new(0.0, 30.0, 40.0);
    scene.camera.target = Vec3::ZERO;
    let mut world = World::new(scene).unwrap();
    let mut renderer = Renderer::new();
    g.bench_function("frame/100x100/4-waves/800x600", |b| {
        b.iter(|| {
            t += 1.0 / 30.0;
            world.update(t).unwrap();
            renderer.render_size(&world, 800, 600);
        })
    });
    g.finish();
}

fn paper001(c: &mut Criterion) {
    let mut g = c.benchmark_group("paper001");
    g.sample_size(20);
    let size = 129u32;
    let mut mesh = SurfaceMesh::new(GridSpec::centered(Vec2::splat(100.0), size - 1, size - 1).unwrap());
    for p in &mut mesh.positions {
        p.y = 8.0 * (0.09 * p.x).sin() * (0.07 * p.z).cos() + 2.0 * (0.3 * p.x + 0.2 * p.z).sin();
    }
    let clip_from_world = glam::camera::rh::proj::opengl::perspective(45f32.to_radians(), 1.0, 1.0, 1000.0)
        * glam::camera::rh::view::look_at_mat4(Vec3::new(0.0, 85.0, 100.0), Vec3::new(0.0, -8.0, 0.0), Vec3::Y);
    let mut clip = vec![ClipVertex::<()>::default(); mesh.positions.len()];
    let mut faces = vec![Vec3::ZERO; mesh.indices.len() / 3];
    let mut target = Framebuffer::new(800, 800);
    let mut frame = || {
        target.clear_with(|_, _| Vec3::new(0.6, 0.7, 0.8));
        for (c, &p) in clip.iter_mut().zip(&mesh.positions) {
            c.position = clip_from_world * Vec4::from((p, 1.0));
        }
        for (f, t) in faces.iter_mut().zip(mesh.indices.chunks_exact(3)) {
            let [a, b, d] = [0, 1, 2].map(|k| mesh.positions[t[k] as usize]);
            *f = Vec3::new(0.35, 0.45, 0.25) * (b - a).cross(d - a).normalize_or(Vec3::Y).y.abs();
        }
        let faces = &faces;
        draw(&mut target, &clip, &mesh.indices, Cull::None, &|f| faces[f.primitive as usize]);
    };
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    g.bench_function("zbuffer/129x129/800x800/1-thread", |b| b.iter(|| one.install(&mut frame)));
    g.bench_function("zbuffer/129x129/800x800/all-threads", |b| b.iter(&mut frame));
    g.finish();
}

criterion_group!(benches, paper000, paper001);
criterion_main!(benches);
