//! issue 34: floating bodies. Target: 100 box bodies on the `ocean` preset, one simulated 1/60 s
//! (two 120 Hz steps) in at most 2 ms on 2 cores.
//!
//! `ocean_100_boxes` times `World::advance` over 1/60 s of the `flotsam` preset, the `ocean`
//! preset with 100 crates of about a metre on a jittered 10 m grid: the bodies' two steps (every
//! hull vertex's height and velocity from the FFT ocean as drawn, pressure, drag, contacts,
//! integration) and the ocean's synthesis at the step and frame times. `ocean_no_bodies` is the
//! same advance of `ocean`: what a frame pays anyway; the difference is what the bodies cost.

use criterion::{criterion_group, criterion_main, Criterion};
use swell::scene::preset;
use swell::world::World;

/// Preset `name` advanced 5 s: the crates have landed and ride the waves.
fn settled(name: &str) -> World {
    let mut w = World::new(preset(name).unwrap()).unwrap();
    w.advance(5.0).unwrap();
    w
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("bodies");
    g.sample_size(30);
    for (name, scene) in [("ocean_100_boxes", "flotsam"), ("ocean_no_bodies", "ocean")] {
        let mut w = settled(scene);
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
