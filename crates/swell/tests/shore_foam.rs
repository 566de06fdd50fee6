//! The coast's surf (issue 38, item 3): shallow water foams along the waterline and where its
//! crests reach the breaking height, nowhere in deep water from this cause, and the foam line
//! moves with the swell.

use glam::{Vec3, Vec4};
use swell::render::Renderer;
use swell::scene::{preset, Scene};
use swell::world::World;

const WIDTH: u32 = 320;
const HEIGHT: u32 = 180;

fn coast(shore_foam: f32) -> Scene {
    let mut scene = preset("coast").unwrap();
    scene.render.width = WIDTH;
    scene.render.height = HEIGHT;
    scene.water.as_mut().unwrap().material.shore_foam = shore_foam;
    scene
}

/// The frame at `t` as written (8-bit sRGB), and the world that drew it.
fn frame(scene: Scene, t: f64) -> (Vec<[u8; 3]>, World) {
    let mut world = World::new(scene.clone()).unwrap();
    world.update(t).unwrap();
    let mut rgba = Vec::new();
    Renderer::new().render(&world).encode_rgba8(&scene.render.display_encoding(), &mut rgba);
    (rgba.chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect(), world)
}

/// Pixels whose colour the shore foam changes at time `t` (more than 8 levels in some channel).
fn foamed(t: f64) -> (Vec<bool>, World) {
    let (with, world) = frame(coast(1.0), t);
    let (without, _) = frame(coast(0.0), t);
    let changed = with.iter().zip(&without).map(|(a, b)| a.iter().zip(b).any(|(p, q)| p.abs_diff(*q) > 8)).collect();
    (changed, world)
}

/// Depth of the water at rest (m, negative on land) where pixel `i`'s view ray meets y = 0, if
/// it does within the terrain's field.
fn rest_depth(world: &World, i: usize) -> Option<f32> {
    let camera = &world.scene.camera;
    let inverse = camera.clip_from_world(WIDTH as f32 / HEIGHT as f32).inverse();
    let (px, py) = ((i % WIDTH as usize) as f32 + 0.5, (i / WIDTH as usize) as f32 + 0.5);
    let ndc = (2.0 * px / WIDTH as f32 - 1.0, 1.0 - 2.0 * py / HEIGHT as f32);
    let unproject = |z: f32| {
        let p = inverse * Vec4::new(ndc.0, ndc.1, z, 1.0);
        p.truncate() / p.w
    };
    let (a, b) = (unproject(-1.0), unproject(1.0));
    let d: Vec3 = b - a;
    if d.y >= 0.0 {
        return None;
    }
    let hit = a + d * (-a.y / d.y);
    world.terrain.as_ref()?.ground_height(hit.x, hit.z).map(|h| -h)
}

#[test]
fn the_coast_foams_along_its_waterline_and_not_in_deep_water() {
    let (changed, world) = foamed(3.0);
    let depths: Vec<Option<f32>> = (0..changed.len()).map(|i| rest_depth(&world, i)).collect();
    let count = changed.iter().filter(|&&c| c).count();
    assert!(count > 300, "shore foam shows in only {count} pixels");
    // None in deep water: the deepest water it whitens is within the surf zone (crests 1.2 m
    // high break from about 2 x 1.2 / 0.78 = 3.1 m of water at rest; foam starts at 0.6 of it).
    let deepest = (0..changed.len()).filter(|&i| changed[i]).filter_map(|i| depths[i]).fold(f32::MIN, f32::max);
    assert!(deepest < 6.0, "shore foam over {deepest} m of water");
    // Along the waterline: a good share of the water a few decimetres deep at rest is foam at
    // any one time, under the crests (measured: 96 of 381 pixels; troughs stay clear).
    let edge: Vec<usize> = (0..changed.len()).filter(|&i| depths[i].is_some_and(|d| (0.3..0.8).contains(&d))).collect();
    let foamy = edge.iter().filter(|&&i| changed[i]).count();
    assert!(edge.len() > 50, "only {} pixels of water 0.3-0.8 m deep in view", edge.len());
    assert!(foamy * 5 > edge.len(), "{foamy} of {} pixels along the waterline foam", edge.len());
    // The foam line moves with the swell: two seconds later much of it lies elsewhere.
    let (later, _) = foamed(5.0);
    let both = changed.iter().zip(&later).filter(|(a, b)| **a && **b).count();
    let either = changed.iter().zip(&later).filter(|(a, b)| **a || **b).count();
    assert!((both as f32) < 0.8 * either as f32, "{both} of {either} foam pixels stayed put");
}
