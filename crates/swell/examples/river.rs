//! Paper 004's river between oscillating banks, with its sliding-texture offset.
//!
//! Run: `cargo run --release -p swell --example river [OUT.png]` (default `river.png`).

use std::path::PathBuf;

use swell::export::write_png;
use swell::render::Renderer;
use swell::scene::{preset, WaterModelSpec};
use swell::water::{River, RiverParams};
use swell::world::World;

fn main() -> swell::Result<()> {
    // Start from a preset for the camera, lights and sky, then set the model through the library.
    let mut scene = preset("river")?;
    let water = scene.water.as_mut().expect("the preset has water");
    // Wider swings and stronger ripples; the renderer slides the water texture by River::uv_offset(t).
    let params = RiverParams {
        left_amplitude: 0.7,
        right_amplitude: 0.6,
        bank_phase: 1.0,
        ripple_amplitude: 0.01,
        ..Default::default()
    };
    println!("texture offset at t = 2 s: {:.3}", River::new(params)?.uv_offset(2.0));
    water.model = WaterModelSpec::River(params);
    let (width, height) = (scene.render.width / 2, scene.render.height / 2);
    let mut world = World::new(scene)?;
    world.update(2.0)?;
    let mut rgba = Vec::new();
    Renderer::new().render_size(&world, width, height).encode_rgba8(&world.scene.render.display_encoding(), &mut rgba);
    let out = std::env::args().nth(1).map_or_else(|| PathBuf::from("river.png"), PathBuf::from);
    write_png(&out, width, height, &rgba)?;
    println!("wrote {}", out.display());
    Ok(())
}
