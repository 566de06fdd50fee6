//! Paper 004's river flows (issue 18): its texture slides downstream at `flow_speed`, one repeat per
//! `texture_length`, so pixels on the water change between frames while the banks stay put; the
//! physical sky renders the same on one and two threads.

use glam::Vec2;
use swell::render::Renderer;
use swell::scene::WaterModelSpec;
use swell::scene::{preset, Scene, SkyModel};
use swell::shading::{NoBottom, WaterLook};
use swell::water::{River, RiverParams};
use swell::world::World;

/// The river preset with still banks and no ripples, so that only the texture can move.
fn still_river() -> Scene {
    let mut scene = preset("river").unwrap();
    scene.render.width = 320;
    scene.render.height = 180;
    let w = scene.water.as_mut().unwrap();
    match &mut w.model {
        WaterModelSpec::River(p) => (p.bank_rate, p.ripple_amplitude) = (0.0, 0.0),
        other => panic!("not a river: {other:?}"),
    }
    scene
}

fn river_params(scene: &Scene) -> RiverParams {
    match &scene.water.as_ref().unwrap().model {
        WaterModelSpec::River(p) => *p,
        other => panic!("not a river: {other:?}"),
    }
}

#[test]
fn the_texture_offset_between_frames_is_flow_speed_times_dt_over_texture_length() {
    let scene = still_river();
    let p = river_params(&scene);
    let world = World::new(scene).unwrap();
    let water = world.water.as_ref().unwrap();
    assert_eq!(water.material.texture.as_deref(), Some("streaks"), "a river has a texture by default");
    assert!(water.texture.is_some());
    let river = River::new(p).unwrap();
    for (t0, t1) in [(0.0, 0.5), (1.25, 1.5), (3600.0, 3600.1)] {
        let at = |t: f64| WaterLook::new(&water.material, &NoBottom, water.texture.as_ref(), t).texture_offset;
        let (a, b) = (at(t0), at(t1));
        // Along the river (v), in repeats: the sampling coordinate v = z / length + offset falls by
        // flow_speed dt / texture_length, so the pattern moves downstream (+Z).
        let expected = (p.flow_speed as f64 * (t1 - t0) / p.texture_length as f64) as f32;
        let dv = (a.y - b.y).rem_euclid(1.0);
        assert!((dv - expected.rem_euclid(1.0)).abs() < 1e-4, "{t0}..{t1}: {dv} vs {expected}");
        assert_eq!(a.x, b.x, "no motion across the river");
        // The same offset the model reports for the renderer (River::uv_offset).
        let uv = (river.uv_offset(t1) - river.uv_offset(t0)).rem_euclid(1.0);
        assert!((uv - dv).abs() < 1e-4, "{uv} vs {dv}");
    }
}

#[test]
fn pixels_of_the_river_change_between_frames_while_the_banks_stay() {
    let mut world = World::new(still_river()).unwrap();
    let mut renderer = Renderer::new();
    world.update(0.0).unwrap();
    let before_mesh = world.water.as_ref().unwrap().surface.positions().to_vec();
    let before = renderer.render(&world).color.clone();
    world.update(0.6).unwrap();
    let after_mesh = world.water.as_ref().unwrap().surface.positions().to_vec();
    let after = renderer.render(&world).color.clone();
    assert_eq!(before_mesh, after_mesh, "the banks' geometry is as before");
    // Pixels whose colour moved by more than 1 % of white: the river's, and only where water is.
    let changed = before.iter().zip(&after).filter(|(a, b)| (**a - **b).abs().max_element() > 0.01).count();
    assert!(changed > before.len() / 50, "only {changed} of {} pixels changed", before.len());
    // Without a flow nothing moves.
    let mut still = still_river();
    if let Some(WaterModelSpec::River(p)) = still.water.as_mut().map(|w| &mut w.model) {
        p.flow_speed = 0.0;
    }
    let mut world = World::new(still).unwrap();
    let a = renderer.render(&world).color.clone();
    world.update(0.6).unwrap();
    assert_eq!(a, renderer.render(&world).color, "a river with flow_speed 0 renders the same at any time");
}

#[test]
fn a_river_texture_file_that_cannot_be_read_names_its_key_and_file() {
    let mut scene = still_river();
    scene.water.as_mut().unwrap().material.texture = Some("/nonexistent/river-water.png".into());
    let e = World::new(scene).err().unwrap().to_string();
    assert!(e.contains("water.material.texture") && e.contains("/nonexistent/river-water.png"), "{e}");
}

#[test]
fn a_turned_river_slides_its_texture_along_its_own_axis() {
    let mut scene = still_river();
    scene.water.as_mut().unwrap().surface.yaw_deg = 90.0;
    let p = river_params(&scene);
    let world = World::new(scene).unwrap();
    // Ry(90°) carries local +Z to world +X.
    let v = world.water.as_ref().unwrap().material.flow_velocity;
    assert!((v - Vec2::new(p.flow_speed, 0.0)).length() < 1e-5, "{v}");
}

#[test]
fn the_physical_sky_renders_identically_on_one_and_two_threads() {
    for name in ["noon", "evening", "hazy"] {
        let mut scene = preset(name).unwrap();
        assert_eq!(scene.sky.model, SkyModel::Preetham);
        scene.render.width = 192;
        scene.render.height = 108;
        scene.water.as_mut().unwrap().surface.cells = [64, 64];
        let world = World::new(scene).unwrap();
        let image = |n: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
            pool.install(|| Renderer::new().render(&world).color.clone())
        };
        let one = image(1);
        assert!(one.iter().all(|c| c.is_finite()), "{name}");
        assert!(one == image(2), "{name} differs on two threads");
    }
}
