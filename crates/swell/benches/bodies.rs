//! issue 34: floating bodies. Target: 100 box bodies on the `ocean` preset, one simulated 1/60 s
//! (two 120 Hz steps) in at most 2 ms on 2 cores.
//!
//! `ocean_100_boxes` times `World::advance` over 1/60 s with 100 one-metre crates spread over
//! 100 m x 100 m of the sea: the bodies' two steps (every hull vertex's height and velocity from
//! the FFT ocean as drawn, pressure, drag, integration) and the ocean's synthesis at the step and
//! frame times. `ocean_no_bodies` is the same advance without bodies: what a frame pays anyway;
//! the difference is what the bodies cost.

use criterion::{criterion_group, criterion_main, Criterion};
use glam::Vec3;
use swell::body::{BodyShape, BodySpec};
use swell::scene::preset;
use swell::world::World;

/// The ocean preset with `n` crates (1 x 0.6 x 1.4 m, density 450) on a 10 m grid.
fn ocean(n: usize) -> World {
    let mut scene = preset("ocean").unwrap();
    let side = (n as f64).sqrt().ceil() as usize;
    scene.bodies = (0..n)
        .map(|k| {
            let (i, j) = ((k % side) as f32, (k / side) as f32);
            let mut b =
                BodySpec::new(BodyShape::Box, &[1.0, 0.6, 1.4], Vec3::new(10.0 * i - 45.0, 0.5, 10.0 * j - 45.0));
            b.density = Some(450.0);
            b.name = format!("crate{k}");
            b
        })
        .collect();
    let mut w = World::new(scene).unwrap();
    // Settled: the crates have landed and ride the waves.
    w.advance(5.0).unwrap();
    w
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("bodies");
    g.sample_size(30);
    for (name, n) in [("ocean_100_boxes", 100), ("ocean_no_bodies", 0)] {
        let mut w = ocean(n);
        let mut frame = 300u64;
        g.bench_function(name, |b| {
            b.iter(|| {
                frame += 1;
                w.advance(frame as f64 / 60.0).unwrap();
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
