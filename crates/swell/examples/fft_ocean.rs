//! The FFT ocean embedded through the query API ([`swell::Water`]): per frame, the displaced mesh
//! (positions and normals for your renderer) and the height under a floating object, at the same
//! time, so one spectral synthesis serves both.
//!
//! `cargo run --release -p swell --example fft_ocean`

use glam::{Vec2, Vec3};
use swell::Water;

/// A JONSWAP sea under a 12 m/s wind: a 128² FFT over a 128 m patch, drawn on a 128-cell mesh.
const SCENE: &str = "
version = 1
[camera]
eye = [0.0, 12.0, 60.0]
target = [0.0, 0.0, 0.0]

[water]
model = 'fft'
size = [128.0, 128.0]
cells = [128, 128]
grid = 128
patch_size = 128.0
spectrum = 'jonswap'
wind_speed = 12.0
choppiness = 1.0
foam = true
seed = 7
";

fn main() -> swell::Result<()> {
    let mut water = Water::from_toml(SCENE, "fft_ocean example")?;
    let n = water.vertex_count();
    let (mut positions, mut normals, mut foam) = (vec![Vec3::ZERO; n], vec![Vec3::ZERO; n], vec![0.0f32; n]);
    // A buoy's hull: four points 1 m apart around (10, -4).
    let hull = [Vec2::new(9.5, -4.5), Vec2::new(10.5, -4.5), Vec2::new(9.5, -3.5), Vec2::new(10.5, -3.5)];
    let mut heights = [0.0f32; 4];
    for frame in 0..4 {
        let t = frame as f64 / 24.0;
        water.displace(t, &mut positions, &mut normals)?; // synthesises time t once ...
        water.foam(t, &mut foam)?; // ... and these reuse it
        water.heights_at(t, &hull, &mut heights)?;
        let draft = heights.iter().sum::<f32>() / 4.0;
        let whitecaps = foam.iter().filter(|f| **f > 0.5).count() as f32 / n as f32;
        println!(
            "t = {t:.3} s: buoy waterline {draft:+.3} m, highest vertex {:+.2} m, whitecaps {:.1} %",
            positions.iter().map(|p| p.y).fold(f32::MIN, f32::max),
            100.0 * whitecaps
        );
    }
    Ok(())
}
