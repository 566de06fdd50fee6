//! Rasterizer throughput: paper 001's largest case (a 513 x 513 height field, 524,288 triangles, at
//! 800 x 800 with flat shading) on 1 and 2 threads, the `sea` preset at 1280 x 720 with its
//! simulation, the `valley-lake` preset's render (terrain reflected in the water), and the
//! `ocean` preset's whole viewer frame (FFT step, mesh, render and RGBA8 encoding) on 1 and 2
//! threads.
//!
//! Each case runs twice: under `wall/` with criterion's wall-clock timer, and under `cpu/` with
//! the CPU time of the whole process (summed over its threads, from Linux's
//! `/proc/self/task/*/schedstat`). On a shared, loaded machine wall time measures the other jobs;
//! the CPU time of a one-thread run is what that run takes on an idle core.

use criterion::measurement::{Measurement, ValueFormatter, WallTime};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::Vec3;
use swell::mesh::TriangleMesh;
use swell::render::{MeshLight, MeshRenderer, Renderer};
use swell::scene::Shading;
use swell::scene::{preset, Camera};
use swell::world::World;

/// A deterministic bumpy 513 x 513 grid over 100 m x 100 m: a sum of sines standing in for a
/// diamond-square terrain (which lives in another module), with the same triangle count.
fn height_field(n: u32) -> TriangleMesh {
    let size = 100.0;
    let h = |x: f32, z: f32| {
        6.0 * (0.07 * x).sin() * (0.05 * z).cos()
            + 2.5 * (0.23 * x + 0.4).sin() * (0.19 * z + 1.1).sin()
            + 0.7 * (0.9 * x + 0.3 * z).sin()
    };
    let mut mesh = TriangleMesh::default();
    for j in 0..n {
        for i in 0..n {
            let (x, z) = (size * (i as f32 / (n - 1) as f32 - 0.5), size * (j as f32 / (n - 1) as f32 - 0.5));
            mesh.positions.push(Vec3::new(x, h(x, z), z));
            let e = 0.01;
            let n = Vec3::new(h(x - e, z) - h(x + e, z), 2.0 * e, h(x, z - e) - h(x, z + e)).normalize();
            mesh.normals.push(n);
        }
    }
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = j * n + i;
            mesh.indices.extend_from_slice(&[a, a + n, a + 1, a + 1, a + n, a + n + 1]);
        }
    }
    mesh
}

fn terrain<M: Measurement + 'static>(c: &mut Criterion<M>, prefix: &str) {
    let mesh = height_field(513);
    assert_eq!(mesh.indices.len() / 3, 524_288);
    let camera = Camera {
        eye: Vec3::new(0.0, 70.0, 95.0),
        target: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::Y,
        fov_y_deg: 45.0,
        near: 0.5,
        far: 1000.0,
    };
    let light = MeshLight::default();
    let mut group = c.benchmark_group(format!("{prefix}/terrain_513_800x800_flat"));
    group.sample_size(30);
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let mut renderer = MeshRenderer::new();
        group.bench_function(format!("{threads}_threads"), |b| {
            b.iter(|| pool.install(|| renderer.render(&mesh, &camera, 800, 800, &light, Shading::Flat).color[0]))
        });
    }
    group.finish();
}

fn sea<M: Measurement + 'static>(c: &mut Criterion<M>, prefix: &str) {
    let mut group = c.benchmark_group(format!("{prefix}/sea_1280x720"));
    group.sample_size(20);
    for (name, shading) in [("gouraud", Shading::Gouraud), ("blinn_phong", Shading::BlinnPhong)] {
        let mut scene = preset("sea").unwrap();
        scene.water.as_mut().unwrap().material.shading = shading;
        let mut world = World::new(scene).unwrap();
        let mut renderer = Renderer::new();
        let mut t = 0.0;
        group.bench_function(format!("{name}_simulate_and_render"), |b| {
            b.iter(|| {
                t += 1.0 / 60.0;
                world.update(t).unwrap();
                renderer.render(&world).color[0]
            })
        });
    }
    group.finish();
}

/// The `valley-lake` preset (257² terrain rising out of a 200² Gerstner lake) at 1280 x 720, render
/// only: terrain pass, the mirrored terrain for the water's reflection, water, sky.
fn valley_lake<M: Measurement + 'static>(c: &mut Criterion<M>, prefix: &str) {
    let mut group = c.benchmark_group(format!("{prefix}/valley_lake_1280x720"));
    group.sample_size(20);
    for (name, shading) in [("gouraud", Shading::Gouraud), ("blinn_phong", Shading::BlinnPhong)] {
        let mut scene = preset("valley-lake").unwrap();
        scene.water.as_mut().unwrap().material.shading = shading;
        let mut world = World::new(scene).unwrap();
        world.update(1.0).unwrap();
        let mut renderer = Renderer::new();
        group.bench_function(format!("{name}_render"), |b| b.iter(|| renderer.render(&world).color[0]));
    }
    group.finish();
}

/// The `ocean` preset's frame as the viewer pays it (issue 7): `World::update` (FFT step and
/// mesh), `Renderer::render_size` at 1280 x 720 and the RGBA8 encoding, on 1 and 2 threads.
/// `cpu/.../2_threads` against twice `wall/.../2_threads` shows the serial part on an idle machine.
fn ocean<M: Measurement + 'static>(c: &mut Criterion<M>, prefix: &str) {
    let mut group = c.benchmark_group(format!("{prefix}/ocean_1280x720"));
    group.sample_size(20);
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let mut world = World::new(preset("ocean").unwrap()).unwrap();
        let r = world.scene.render;
        let mut renderer = Renderer::new();
        let mut rgba = Vec::new();
        let mut t = 0.0;
        group.bench_function(format!("{threads}_threads_frame"), |b| {
            b.iter(|| {
                pool.install(|| {
                    t += 1.0 / 30.0;
                    world.update(t).unwrap();
                    renderer.render_size(&world, 1280, 720).encode_rgba8(&r.display_encoding(), &mut rgba);
                    rgba[0]
                })
            })
        });
    }
    group.finish();
}

/// Process CPU time in nanoseconds: the sum over its threads of the first field of `schedstat`.
fn process_cpu_ns() -> u64 {
    let mut total = 0;
    if let Ok(dir) = std::fs::read_dir("/proc/self/task") {
        for task in dir.flatten() {
            if let Ok(s) = std::fs::read_to_string(task.path().join("schedstat")) {
                total += s.split_whitespace().next().and_then(|v| v.parse::<u64>().ok()).unwrap_or(0);
            }
        }
    }
    total
}

/// Criterion measurement of process CPU time (see the module doc).
struct CpuTime;

struct NanosFormatter;

impl ValueFormatter for NanosFormatter {
    fn scale_values(&self, typical: f64, values: &mut [f64]) -> &'static str {
        let (factor, unit) = if typical < 1e3 {
            (1.0, "ns")
        } else if typical < 1e6 {
            (1e-3, "µs")
        } else if typical < 1e9 {
            (1e-6, "ms")
        } else {
            (1e-9, "s")
        };
        values.iter_mut().for_each(|v| *v *= factor);
        unit
    }
    fn scale_throughputs(&self, _: f64, _: &Throughput, values: &mut [f64]) -> &'static str {
        values.iter_mut().for_each(|_| {});
        "per-iteration"
    }
    fn scale_for_machines(&self, _: &mut [f64]) -> &'static str {
        "ns"
    }
}

impl Measurement for CpuTime {
    type Intermediate = u64;
    type Value = u64;
    fn start(&self) -> u64 {
        process_cpu_ns()
    }
    fn end(&self, i: u64) -> u64 {
        process_cpu_ns().saturating_sub(i)
    }
    fn add(&self, a: &u64, b: &u64) -> u64 {
        a + b
    }
    fn zero(&self) -> u64 {
        0
    }
    fn to_f64(&self, v: &u64) -> f64 {
        *v as f64
    }
    fn formatter(&self) -> &dyn ValueFormatter {
        &NanosFormatter
    }
}

fn wall(c: &mut Criterion<WallTime>) {
    terrain(c, "wall");
    sea(c, "wall");
    valley_lake(c, "wall");
    ocean(c, "wall");
}

fn cpu(c: &mut Criterion<CpuTime>) {
    terrain(c, "cpu");
    sea(c, "cpu");
    valley_lake(c, "cpu");
    ocean(c, "cpu");
}

criterion_group!(wall_benches, wall);
criterion_group! {
    name = cpu_benches;
    config = Criterion::default().with_measurement(CpuTime);
    targets = cpu
}
criterion_main!(wall_benches, cpu_benches);
