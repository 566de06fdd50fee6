//! Paper 002's radial pool wave y = a sin(k r - w t), centred in the pool.
//!
//! Run: `cargo run --release -p swell --example radial_wave [OUT.png]` (default `radial_wave.png`).

use std::path::PathBuf;

use glam::Vec2;
use swell::export::write_png;
use swell::render::Renderer;
use swell::scene::{preset, WaterModelSpec};
use swell::water::RadialWaveParams;
use swell::world::World;

fn main() -> swell::Result<()> {
    // Start from a preset for the camera, lights and sky, then set the model through the library.
    let mut scene = preset("pool")?;
    let water = scene.water.as_mut().expect("the preset has water");
    // Paper 002 constants, but the wave starts from the middle of the pool.
    water.model = WaterModelSpec::Radial(RadialWaveParams { center: Vec2::ZERO, ..Default::default() });
    let (width, height) = (scene.render.width / 2, scene.render.height / 2);
    let mut world = World::new(scene)?;
    world.update(1.0)?;
    let mut rgba = Vec::new();
    Renderer::new().render_size(&world, width, height).encode_rgba8(&world.scene.render.display_encoding(), &mut rgba);
    let out = std::env::args().nth(1).map_or_else(|| PathBuf::from("radial_wave.png"), PathBuf::from);
    write_png(&out, width, height, &rgba)?;
    println!("wrote {}", out.display());
    Ok(())
}
