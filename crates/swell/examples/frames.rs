//! Times the frames of one preset at 1280 x 720, as `swell bench realtime` does for all of them:
//! for profiling one preset (`perf record`, `valgrind --tool=callgrind`) without the others.
//!
//! ```sh
//! cargo run --release -p swell --example frames -- ocean 120
//! ```
//! prints the median frame time (ms) and frames per second of `World::update` +
//! `Renderer::render_size` over the given number of frames (default 60), after 5 warm-up frames,
//! and the median of each of the renderer's stages (`RenderStages`).

use std::time::Instant;

use swell::render::Renderer;
use swell::scene::preset;
use swell::world::World;

fn main() -> swell::Result<()> {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "sea".into());
    let frames: usize = args.next().and_then(|n| n.parse().ok()).unwrap_or(60);
    let mut world = World::new(preset(&name)?)?;
    let mut renderer = Renderer::new();
    let (mut times, mut updates) = (Vec::with_capacity(frames), Vec::with_capacity(frames));
    let mut stages: [Vec<f64>; 5] = Default::default();
    for k in 0..frames + 5 {
        let start = Instant::now();
        world.update(k as f64 / 30.0)?;
        let updated = start.elapsed().as_secs_f64() * 1e3;
        renderer.render_size(&world, 1280, 720);
        if k >= 5 {
            times.push(start.elapsed().as_secs_f64() * 1e3);
            updates.push(updated);
            let s = renderer.last_stages();
            for (v, d) in stages.iter_mut().zip([s.terrain, s.sea_filter, s.water, s.far_field, s.sky]) {
                v.push(d.as_secs_f64() * 1e3);
            }
        }
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (frame, update) = (median(&mut times), median(&mut updates));
    println!(
        "{name}: median {frame:.2} ms ({:.1} fps) over {frames} frames; World::update {update:.2} ms",
        1e3 / frame
    );
    let [terrain, filter, water, far, sky] = stages.map(|mut v| median(&mut v));
    println!("  stages (ms): terrain {terrain:.2}, sea filter {filter:.2}, water {water:.2}, far field {far:.2}, sky {sky:.2}");
    Ok(())
}
