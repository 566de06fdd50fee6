//! Embedding swell: a displaced grid with normals for time t, and the water height at a point,
//! without the renderer. Shown in the README.

use glam::Vec2;
use swell::math::GridSpec;
use swell::mesh::SurfaceMesh;
use swell::water::{Gerstner, GerstnerWave, WaveModel};

fn main() -> swell::Result<()> {
    // Two waves, 30 m and 12 m long, over a 100 m square patch sampled by 128 x 128 cells.
    let waves = vec![
        GerstnerWave { amplitude: 0.4, wavelength: 30.0, speed: 6.8, direction: Vec2::new(1.0, 0.3), steepness: 0.6 },
        GerstnerWave { amplitude: 0.15, wavelength: 12.0, speed: 4.3, direction: Vec2::new(0.2, 1.0), steepness: 0.6 },
    ];
    let model = Gerstner::new(waves)?; // validated: errors name the wave, the key and the range
    let mut mesh = SurfaceMesh::new(GridSpec::centered(Vec2::splat(100.0), 128, 128)?);
    for frame in 0..4 {
        let t = frame as f64 * 0.5;
        mesh.displace(&model, t); // positions + analytic normals, in parallel, no allocation
        let h = model.height_at(10.0, -4.0, t); // the water height above one world point
        println!("t = {t:.3} s: height at (10, -4) = {h:.3} m, first vertex {}", mesh.positions[0]);
    }
    Ok(())
}
