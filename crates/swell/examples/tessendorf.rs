//! Gerstner waves in Tessendorf's form with finite-depth dispersion and a looping period (paper 003).
//!
//! Run: `cargo run --release -p swell --example tessendorf [OUT.png]` (default `tessendorf.png`).

use std::path::PathBuf;

use glam::Vec2;
use swell::export::write_png;
use swell::render::Renderer;
use swell::scene::{preset, WaterModelSpec};
use swell::spectrum::Dispersion;
use swell::water::{TessendorfParams, TessendorfWave};
use swell::world::World;

fn main() -> swell::Result<()> {
    // Start from a preset for the camera, lights and sky, then set the model through the library.
    let mut scene = preset("tessendorf")?;
    let water = scene.water.as_mut().expect("the preset has water");
    // Three waves over 8 m of water; the animation repeats exactly every 40 s.
    let wave =
        |amplitude, wavelength, x, z| TessendorfWave { amplitude, wavelength, direction: Vec2::new(x, z), phase: 0.0 };
    water.model = WaterModelSpec::Tessendorf(TessendorfParams {
        waves: vec![wave(1.2, 40.0, 1.0, 0.2), wave(0.5, 17.0, 0.8, -0.5), wave(0.2, 8.0, 0.5, 1.0)],
        dispersion: Dispersion::FiniteDepth { depth: 8.0 },
        loop_period: Some(40.0),
    });
    let (width, height) = (scene.render.width / 2, scene.render.height / 2);
    let mut world = World::new(scene)?;
    world.update(5.0)?;
    let mut rgba = Vec::new();
    Renderer::new().render_size(&world, width, height).encode_rgba8(&world.scene.render.display_encoding(), &mut rgba);
    let out = std::env::args().nth(1).map_or_else(|| PathBuf::from("tessendorf.png"), PathBuf::from);
    write_png(&out, width, height, &rgba)?;
    println!("wrote {}", out.display());
    Ok(())
}
