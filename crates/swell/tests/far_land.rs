//! Issue 18's land to the horizon: the terrain presets show land (or sea) under every pixel below
//! the horizon for low, middle and high cameras and several headings; the far land meets the
//! field without a crack (its first ring is the field's border, bit for bit, after the transform);
//! the river runs in a valley whose land reaches the image's edges; and frames are the same on
//! one and two threads.
//!
//! (The far land's mesh is tested for watertightness and winding in `terrain/far_land.rs`, its
//! skyline in `world/terrain_far_land.rs`.)

use glam::{Vec2, Vec3};
use swell::math::Transform;
use swell::raster::Framebuffer;
use swell::render::Renderer;
use swell::scene::{preset, Scene};
use swell::world::World;

const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;

fn render(scene: &Scene) -> Framebuffer {
    let mut scene = scene.clone();
    scene.render.width = WIDTH;
    scene.render.height = HEIGHT;
    let mut world = World::new(scene).unwrap();
    world.update(1.0).unwrap();
    let fb = Renderer::new().render(&world).clone();
    assert!(fb.color.iter().all(|c| c.is_finite()), "a pixel is not finite");
    fb
}

fn rgba(fb: &Framebuffer, scene: &Scene) -> Vec<u8> {
    let mut out = Vec::new();
    fb.encode_rgba8(&scene.render.display_encoding(), &mut out);
    out
}

/// `scene` with its camera `height` m above the ground at (`x`, `z`) (or above the water at rest,
/// whichever is higher), looking along `heading_deg` (0 = −Z, 90 = +X) and `pitch_deg` down.
fn aimed(scene: &Scene, x: f32, z: f32, height: f32, heading_deg: f32, pitch_deg: f32) -> Scene {
    let world = World::new(scene.clone()).unwrap();
    let ground = world.terrain.as_ref().and_then(|t| t.ground_height(x, z)).unwrap_or(0.0).max(0.0);
    let mut scene = scene.clone();
    let (h, p) = (heading_deg.to_radians(), pitch_deg.to_radians());
    let eye = Vec3::new(x, ground + height, z);
    scene.camera.eye = eye;
    scene.camera.target = eye + Vec3::new(h.sin() * p.cos(), -p.sin(), -h.cos() * p.cos()) * 10.0;
    scene
}

/// Coverage: with two very different sky `ground` colours (magenta, green) the images must be
/// identical; the sky shows its ground colour below the horizon wherever nothing was drawn, so a
/// void would differ. Low, middle and high cameras, four headings, inside the field and near its
/// edge.
#[test]
fn land_or_sea_covers_every_pixel_below_the_horizon() {
    for name in ["coast", "valley-lake", "terrain", "river"] {
        let scene = preset(name).unwrap();
        let half = scene.terrain.as_ref().unwrap().extent.unwrap() * 0.5;
        for (height, pitch) in [(2.0f32, 2.0f32), (40.0, 10.0), (600.0, 30.0)] {
            for (k, heading) in [0.0f32, 90.0, 200.0, 305.0].into_iter().enumerate() {
                // Alternately near the centre and near a corner of the field.
                let at = if k % 2 == 0 { half * 0.1 } else { half * Vec2::new(0.8, -0.7) };
                let mut a = aimed(&scene, at.x, at.y, height, heading, pitch);
                a.sky.ground = Vec3::new(1.0, 0.0, 1.0);
                let mut b = a.clone();
                b.sky.ground = Vec3::new(0.0, 1.0, 0.0);
                let (ia, ib) = (rgba(&render(&a), &a), rgba(&render(&b), &b));
                let differ = ia.chunks(4).zip(ib.chunks(4)).filter(|(p, q)| p != q).count();
                assert_eq!(differ, 0, "{name}, camera {height} m, heading {heading}°: {differ} pixels show the ground");
            }
        }
    }
}

/// The seam: the far land's first ring is the terrain mesh's border, the same world positions bit
/// for bit, under a transform that moves, turns and scales the land; and nothing of the far land
/// lies inside the field.
#[test]
fn the_far_land_meets_the_field_without_a_crack() {
    for name in ["coast", "valley-lake", "terrain", "river"] {
        let mut scene = preset(name).unwrap();
        let t = scene.terrain.as_mut().unwrap();
        t.transform = Transform {
            translate: Vec3::new(3.0, -1.5, 7.0),
            rotate_deg: Vec3::new(0.0, 33.0, 0.0),
            scale: Vec3::new(1.5, 1.2, 0.8),
        };
        let world = World::new(scene).unwrap();
        let terrain = world.terrain.as_ref().unwrap();
        let far = terrain.far_land.as_ref().expect("the preset has far land");
        let (cols, rows) = (terrain.field.cols(), terrain.field.rows());
        let border: Vec<Vec3> = (0..cols - 1)
            .map(|i| (i, 0))
            .chain((0..rows - 1).map(|j| (cols - 1, j)))
            .chain((0..cols - 1).map(|i| (cols - 1 - i, rows - 1)))
            .chain((0..rows - 1).map(|j| (0, rows - 1 - j)))
            .map(|(i, j)| terrain.mesh.positions[j * cols + i])
            .collect();
        for (k, p) in border.iter().enumerate() {
            assert_eq!(p.to_array().map(f32::to_bits), far.positions[k].to_array().map(f32::to_bits), "{name} {k}");
        }
        // Every other far vertex lies outside the field (the ground query answers only inside).
        for p in &far.positions[border.len()..] {
            assert!(terrain.ground_height(p.x, p.z).is_none(), "{name}: far vertex {p} inside the field");
        }
    }
}

/// The river runs in a valley: across it the ground falls to the bed and rises on both sides to
/// well above the water, beyond the field too, and in the image the land reaches both edges.
#[test]
fn the_river_runs_in_a_valley_whose_land_reaches_the_image_edges() {
    let scene = preset("river").unwrap();
    let world = World::new(scene.clone()).unwrap();
    let terrain = world.terrain.as_ref().unwrap();
    for z in [-15.0f32, 0.0, 15.0] {
        let bed = terrain.ground_height(0.0, z).unwrap();
        assert!(bed < -0.3, "the bed is under the water at z = {z}: {bed}");
        for side in [-1.0f32, 1.0] {
            let mut last = bed;
            for k in 1..=19 {
                let h = terrain.ground_height(side * k as f32, z).unwrap();
                assert!(h >= last - 1e-4, "the valley side falls at x = {}, z = {z}", side * k as f32);
                last = h;
            }
            assert!(last > 4.0, "the valley side at x = {} rises only to {last}", side * 19.0);
        }
    }
    // Beyond the field, land on both sides stays above the river's banks.
    let far = terrain.far_land.as_ref().unwrap();
    for side in [-1.0f32, 1.0] {
        let beside = far.positions.iter().filter(|p| p.x * side > 25.0 && p.z.abs() < 20.0).collect::<Vec<_>>();
        assert!(!beside.is_empty() && beside.iter().all(|p| p.y > 4.0), "side {side}: {beside:?}");
    }
    // In the image: the columns at the left and right edges are land from the bottom up to
    // above the middle row (the valley sides rise above the eye), never sky.
    let fb = render(&scene);
    let w = WIDTH as usize;
    for x in [0, w - 1] {
        for y in HEIGHT as usize / 2..HEIGHT as usize {
            assert!(fb.depth[y * w + x] < 1.0, "column {x}, row {y} shows the sky");
        }
    }
}

#[test]
fn frames_with_far_land_are_the_same_on_one_and_two_threads() {
    for name in ["coast", "river", "terrain"] {
        let scene = preset(name).unwrap();
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| rgba(&render(&scene), &scene))
        };
        assert!(run(1) == run(2), "{name}");
    }
}
