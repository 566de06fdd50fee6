//! A Hooke spring lattice disturbed by drops at regular intervals (paper 003 §1.1.3).
//!
//! Run: `cargo run --release -p swell --example spring_mesh [OUT.png]` (default `spring_mesh.png`).

use std::path::PathBuf;

use swell::export::write_png;
use swell::render::Renderer;
use swell::scene::{preset, WaterModelSpec};
use swell::water::{DropSchedule, Edges, SpringMeshParams};
use swell::world::World;

fn main() -> swell::Result<()> {
    // Start from a preset for the camera, lights and sky, then set the model through the library.
    let mut scene = preset("springs")?;
    let water = scene.water.as_mut().expect("the preset has water");
    // Paper 003 defaults, free edges, a drop every 2 s; 30 s are simulated before the frame.
    water.model = WaterModelSpec::Springs(SpringMeshParams {
        edges: Edges::Free,
        warm_up: 30.0,
        drops: Some(DropSchedule { interval: 2.0, radius: 1.0, depth: 0.6, seed: 9 }),
        ..Default::default()
    });
    let (width, height) = (scene.render.width / 2, scene.render.height / 2);
    let mut world = World::new(scene)?;
    world.update(0.0)?;
    let mut rgba = Vec::new();
    Renderer::new().render_size(&world, width, height).encode_rgba8(&world.scene.render.display_encoding(), &mut rgba);
    let out = std::env::args().nth(1).map_or_else(|| PathBuf::from("spring_mesh.png"), PathBuf::from);
    write_png(&out, width, height, &rgba)?;
    println!("wrote {}", out.display());
    Ok(())
}
