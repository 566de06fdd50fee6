//! Airy linear waves with capillary-gravity dispersion (paper 000 eqs. 2-3).
//!
//! Run: `cargo run --release -p swell --example airy [OUT.png]` (default `airy.png`).

use std::path::PathBuf;

use glam::Vec2;
use swell::export::write_png;
use swell::render::Renderer;
use swell::scene::{preset, WaterModelSpec};
use swell::spectrum::Dispersion;
use swell::water::{AiryParams, AiryWave};
use swell::world::World;

fn main() -> swell::Result<()> {
    // Start from a preset for the camera, lights and sky, then set the model through the library.
    let mut scene = preset("airy")?;
    let water = scene.water.as_mut().expect("the preset has water");
    // Linear waves whose speeds follow the capillary-gravity dispersion relation.
    let wave = |amplitude, wavelength, x, z| AiryWave { amplitude, wavelength, direction: Vec2::new(x, z), phase: 0.0 };
    water.model = WaterModelSpec::Airy(AiryParams {
        waves: vec![wave(0.02, 1.5, 1.0, 0.0), wave(0.01, 0.7, 0.6, 0.8), wave(0.004, 0.3, -0.3, 1.0)],
        dispersion: Dispersion::Capillary { depth: 0.5 },
    });
    let (width, height) = (scene.render.width / 2, scene.render.height / 2);
    let mut world = World::new(scene)?;
    world.update(1.0)?;
    let mut rgba = Vec::new();
    Renderer::new().render_size(&world, width, height).encode_rgba8(&world.scene.render.display_encoding(), &mut rgba);
    let out = std::env::args().nth(1).map_or_else(|| PathBuf::from("airy.png"), PathBuf::from);
    write_png(&out, width, height, &rgba)?;
    println!("wrote {}", out.display());
    Ok(())
}
