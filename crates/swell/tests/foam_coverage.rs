//! The foam a rendered image shows covers what the simulation says it covers (issue 18): the FFT
//! ocean's whitecaps, seen straight down over one whole tile, cover the same fraction of the
//! image as the simulation's foam covers of the sea's area, and they read as foam (mostly solid
//! cells and lace), not a grey blend.
//!
//! The state metric is the foam coverage of the displaced surface's area seen from above: each
//! grid cell's mean vertex foam weighted by its area projected on the xz plane. That is the
//! vertices' mean (`swell stats`' `foam_coverage`, also checked here) corrected for the crests'
//! horizontal squeeze: foam sits where the surface folds (Jacobian below the threshold), so it
//! covers a little less area than its share of vertices.

use glam::Vec3;
use swell::render::Renderer;
use swell::scene::{preset, Light, Scene, WaterExtent};
use swell::world::{sea_stats, World};

/// Image side, pixels: 65 536 samples of a 256 m tile (1 m per pixel, the FFT's own spacing).
const SIDE: u32 = 256;
/// Side of the ocean's FFT tile, m (the `ocean` preset's `patch_size`).
const TILE_M: f32 = 256.0;
/// Time of the frame, s: long enough for foam to have built up and faded behind crests.
const T: f64 = 6.0;
/// Tolerance on the coverage, as a fraction of it: the pattern is a sample of cells, not the
/// tile mean, and the vertex foam is interpolated across pixels.
const RELATIVE_TOLERANCE: f64 = 0.15;

/// The `ocean` preset's sea as a single tile seen straight down, lit so that a pixel's linear
/// value is the foam covering it: black water, black sky, no glitter or scattering, white foam
/// under a white overhead sun and no ambient light. A coarse pattern (`foam_scale` 32 m) keeps
/// its cells larger than the 1 m pixels.
fn top_down_ocean() -> Scene {
    let mut scene = preset("ocean").unwrap();
    let half_fov = 30f32.to_radians();
    scene.camera.eye = Vec3::new(0.0, 0.5 * TILE_M / half_fov.tan(), 0.0);
    scene.camera.target = Vec3::ZERO;
    scene.camera.up = Vec3::new(0.0, 0.0, -1.0);
    scene.camera.fov_y_deg = 60.0;
    scene.camera.near = 1.0;
    scene.camera.far = 2000.0;
    scene.lights = vec![Light::Directional { direction: Vec3::new(0.0, -1.0, 0.0), color: Vec3::ONE, intensity: 1.0 }];
    scene.sky.zenith = Vec3::ZERO;
    scene.sky.horizon = Vec3::ZERO;
    scene.sky.ground = Vec3::ZERO;
    scene.sky.sun_size_deg = 0.0;
    scene.sky.haze_distance = 0.0;
    scene.render.ambient = Vec3::ZERO;
    scene.render.width = SIDE;
    scene.render.height = SIDE;
    let w = scene.water.as_mut().unwrap();
    w.surface.size = glam::Vec2::splat(TILE_M);
    w.surface.cells = [SIDE, SIDE];
    w.surface.extent = Some(WaterExtent::Patch);
    let m = &mut w.material;
    m.color = Vec3::ZERO;
    m.specular = 0.0;
    m.scatter_strength = 0.0;
    m.foam_color = Vec3::ONE;
    m.foam_scale = 32.0;
    scene
}

/// Foam coverage of the displaced surface's area seen from above (see the module doc).
fn area_coverage(world: &World) -> f64 {
    // The drawn surface: this scene's extent is the patch.
    let s = &world.water.as_ref().unwrap().surface;
    let (positions, foam) = (s.positions(), s.foam().expect("the ocean has foam"));
    let (mut foam_area, mut area) = (0.0f64, 0.0f64);
    for tri in s.indices().chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| tri[k] as usize);
        let (pa, pb, pc) = (positions[a], positions[b], positions[c]);
        let cross = (pb.x - pa.x) * (pc.z - pa.z) - (pb.z - pa.z) * (pc.x - pa.x);
        let t = 0.5 * f64::from(cross.abs());
        foam_area += t * f64::from(foam[a] + foam[b] + foam[c]) / 3.0;
        area += t;
    }
    foam_area / area
}

#[test]
fn the_image_shows_the_foam_coverage_of_the_simulation() {
    let scene = top_down_ocean();
    let stats = sea_stats(&scene, T).unwrap();
    let mut world = World::new(scene).unwrap();
    world.update(T).unwrap();
    let simulated = area_coverage(&world);
    // The area metric is the vertex mean (what `swell stats` reports) up to the crests' squeeze.
    assert!(stats.foam_coverage > 0.005, "the ocean has whitecaps: {}", stats.foam_coverage);
    assert!(
        simulated <= stats.foam_coverage && simulated > 0.7 * stats.foam_coverage,
        "area {simulated} vs vertices {}",
        stats.foam_coverage
    );

    let mut renderer = Renderer::new();
    let fb = renderer.render(&world);
    let pixels: Vec<f64> = fb.color.iter().map(|c| f64::from(c.x.min(c.y).min(c.z))).collect();
    let rendered = pixels.iter().sum::<f64>() / pixels.len() as f64;
    println!("foam: image {rendered:.4}, area {simulated:.4}, vertices (swell stats) {:.4}", stats.foam_coverage);
    assert!(
        (rendered - simulated).abs() <= RELATIVE_TOLERANCE * simulated,
        "foam in the image {rendered:.4}, simulated {simulated:.4} (vertex mean {:.4})",
        stats.foam_coverage
    );

    // Foam reads as foam: most of the foam in the image is in pixels that are mostly foam, not a
    // thin grey veil spread over the crests (the old blend put most of it below half).
    let solid: f64 = pixels.iter().filter(|&&v| v > 0.5).sum();
    assert!(solid > 0.6 * rendered * pixels.len() as f64, "solid foam {solid}, all {}", rendered * pixels.len() as f64);
}
