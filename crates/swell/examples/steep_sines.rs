//! Paper 003's steep sum of sines, A ((sin S + 1) / 2)^k.
//!
//! Run: `cargo run --release -p swell --example steep_sines [OUT.png]` (default `steep_sines.png`).

use std::path::PathBuf;

use glam::Vec2;
use swell::export::write_png;
use swell::render::Renderer;
use swell::scene::{preset, WaterModelSpec};
use swell::water::{SteepSineWave, SteepSinesParams};
use swell::world::World;

fn main() -> swell::Result<()> {
    // Start from a preset for the camera, lights and sky, then set the model through the library.
    let mut scene = preset("steep-sines")?;
    let water = scene.water.as_mut().expect("the preset has water");
    // Two waves; a larger exponent gives narrower crests.
    let wave = |amplitude, wavelength: f32, exponent| SteepSineWave {
        amplitude,
        frequency: std::f32::consts::TAU / wavelength,
        velocity: 5.0,
        direction: Vec2::new(1.0, 0.3),
        exponent,
    };
    water.model =
        WaterModelSpec::SteepSines(SteepSinesParams { waves: vec![wave(1.0, 25.0, 3.0), wave(0.3, 9.0, 1.5)] });
    let (width, height) = (scene.render.width / 2, scene.render.height / 2);
    let mut world = World::new(scene)?;
    world.update(0.0)?;
    let mut rgba = Vec::new();
    Renderer::new().render_size(&world, width, height).encode_rgba8(&world.scene.render.display_encoding(), &mut rgba);
    let out = std::env::args().nth(1).map_or_else(|| PathBuf::from("steep_sines.png"), PathBuf::from);
    write_png(&out, width, height, &rgba)?;
    println!("wrote {}", out.display());
    Ok(())
}
