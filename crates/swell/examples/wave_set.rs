//! A set of Gerstner waves generated from wind direction, spread, medians and a seed (paper 000 §2.4).
//!
//! Run: `cargo run --release -p swell --example wave_set [OUT.png]` (default `wave_set.png`).

use std::path::PathBuf;

use swell::export::write_png;
use swell::render::Renderer;
use swell::scene::{preset, WaterModelSpec};
use swell::water::{wave_set, WaveSetParams};
use swell::world::World;

fn main() -> swell::Result<()> {
    // Start from a preset for the camera, lights and sky, then set the model through the library.
    let mut scene = preset("sea")?;
    let water = scene.water.as_mut().expect("the preset has water");
    // Nine waves from a south-westerly wind; the generated list can be printed or edited.
    let params = WaveSetParams { wind_direction_deg: 45.0, spread_deg: 50.0, count: 9, seed: 11, ..Default::default() };
    for w in wave_set(&params)? {
        println!("L = {:5.1} m  A = {:.3} m  c = {:.2} m/s", w.wavelength, w.amplitude, w.speed);
    }
    water.model = WaterModelSpec::WaveSet(params);
    let (width, height) = (scene.render.width / 2, scene.render.height / 2);
    let mut world = World::new(scene)?;
    world.update(0.0)?;
    let mut rgba = Vec::new();
    Renderer::new().render_size(&world, width, height).encode_rgba8(&world.scene.render.display_encoding(), &mut rgba);
    let out = std::env::args().nth(1).map_or_else(|| PathBuf::from("wave_set.png"), PathBuf::from);
    write_png(&out, width, height, &rgba)?;
    println!("wrote {}", out.display());
    Ok(())
}
