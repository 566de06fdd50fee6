//! A drifting, evolving Perlin-noise water surface (paper 003 §1.1.1).
//!
//! Run: `cargo run --release -p swell --example noise_waves [OUT.png]` (default `noise_waves.png`).

use std::path::PathBuf;

use swell::export::write_png;
use swell::render::Renderer;
use swell::scene::{preset, WaterModelSpec};
use swell::water::NoiseParams;
use swell::world::World;

fn main() -> swell::Result<()> {
    // Start from a preset for the camera, lights and sky, then set the model through the library.
    let mut scene = preset("noise")?;
    let water = scene.water.as_mut().expect("the preset has water");
    // Rougher, faster-changing noise than the preset.
    water.model = WaterModelSpec::Noise(NoiseParams {
        amplitude: 0.8,
        scale: 12.0,
        octaves: 6,
        evolution: 0.4,
        ..Default::default()
    });
    let (width, height) = (scene.render.width / 2, scene.render.height / 2);
    let mut world = World::new(scene)?;
    world.update(3.0)?;
    let mut rgba = Vec::new();
    Renderer::new().render_size(&world, width, height).encode_rgba8(&world.scene.render.display_encoding(), &mut rgba);
    let out = std::env::args().nth(1).map_or_else(|| PathBuf::from("noise_waves.png"), PathBuf::from);
    write_png(&out, width, height, &rgba)?;
    println!("wrote {}", out.display());
    Ok(())
}
