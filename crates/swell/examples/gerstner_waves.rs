//! Gerstner waves (paper 000, GPU Gems form) built by editing the wave list one wave at a time.
//!
//! Run: `cargo run --release -p swell --example gerstner_waves [OUT.png]` (default `gerstner_waves.png`).

use std::path::PathBuf;

use glam::Vec2;
use swell::export::write_png;
use swell::render::Renderer;
use swell::scene::GerstnerSpec;
use swell::scene::{preset, WaterModelSpec};
use swell::water::{Gerstner, GerstnerWave};
use swell::world::World;

fn main() -> swell::Result<()> {
    // Start from a preset for the camera, lights and sky, then set the model through the library.
    let mut scene = preset("sea")?;
    let water = scene.water.as_mut().expect("the preset has water");
    // Paper 000 GUI style: edit the wave list one wave at a time (each edit is validated).
    let mut model = Gerstner::new(Vec::new())?;
    model.add_wave(GerstnerWave {
        amplitude: 0.5,
        wavelength: 40.0,
        speed: 7.9,
        direction: Vec2::X,
        steepness: 0.7,
    })?;
    model.add_wave(GerstnerWave {
        amplitude: 0.2,
        wavelength: 15.0,
        speed: 4.8,
        direction: Vec2::new(1.0, 0.6),
        steepness: 0.7,
    })?;
    let third = model.add_wave(GerstnerWave {
        amplitude: 0.1,
        wavelength: 7.0,
        speed: 3.3,
        direction: Vec2::Y,
        steepness: 0.7,
    })?;
    model.set_wave(
        third,
        GerstnerWave { amplitude: 0.08, wavelength: 6.0, speed: 3.06, direction: Vec2::new(0.4, 1.0), steepness: 0.7 },
    )?;
    water.model = WaterModelSpec::Gerstner(GerstnerSpec { waves: model.waves().to_vec() });
    let (width, height) = (scene.render.width / 2, scene.render.height / 2);
    let mut world = World::new(scene)?;
    world.update(2.0)?;
    let mut rgba = Vec::new();
    Renderer::new().render_size(&world, width, height).encode_rgba8(&world.scene.render.display_encoding(), &mut rgba);
    let out = std::env::args().nth(1).map_or_else(|| PathBuf::from("gerstner_waves.png"), PathBuf::from);
    write_png(&out, width, height, &rgba)?;
    println!("wrote {}", out.display());
    Ok(())
}
