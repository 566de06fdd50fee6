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

/// A river as a user writes it from docs/scene-format.md: a channel in the ground and the river
/// model with its length and rows, nothing else: no `[water.material]` (clear water, the default
/// texture), the model's default banks (swinging at 0.5 rad/s), flow and ripples.
const PLAIN_RIVER: &str = r#"
version = 1
[camera]
eye = [-0.9, 2.6, 13.5]
target = [-0.9, 0.0, 0.0]
[render]
width = 320
height = 180
[terrain]
generator = "channel"
size = 129
extent = [40.0, 160.0]
bed_height = -0.4
bank_height = 0.25
width = 3.4
bank_width = 1.5
direction = [0.0, 1.0]
meander_amplitude = 0.0
[terrain.transform]
translate = [-0.9, 0.0, 0.0]
# Dry ground everywhere, so that the frame drawn without the water (which finds the water
# pixels) draws the land exactly as the frames with it do.
[terrain.material]
wet_height = 0.0
[water]
model = "river"
size = [4.0, 96.0]
cells = [24, 768]
center = [0.0, -36.0]
"#;

/// The frame at time `t` as it is written: 8-bit sRGB, three bytes a pixel.
fn frame(scene: &Scene, t: f64) -> Vec<[u8; 3]> {
    let mut world = World::new(scene.clone()).unwrap();
    world.update(t).unwrap();
    let mut rgba = Vec::new();
    Renderer::new().render(&world).encode_rgba8(&scene.render.display_encoding(), &mut rgba);
    rgba.chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect()
}

/// Issue 38 item 4: the flow shows at the default material, in the normals and what they reflect.
#[test]
fn a_river_with_no_material_keys_flows_while_its_banks_barely_move() {
    let scene = Scene::from_toml(PLAIN_RIVER, "plain river").unwrap();
    let (t0, t1) = (0.0, 0.4);
    let (a, b) = (frame(&scene, t0), frame(&scene, t1));
    // Water pixels: those the frame without its water draws otherwise (the land is still).
    let dry = frame(&Scene { water: None, ..scene.clone() }, t0);
    // A change an eye sees: more than two levels of 255 in some channel of the written image.
    let differs = |x: [u8; 3], y: [u8; 3]| x.iter().zip(y).any(|(p, q)| p.abs_diff(q) > 2);
    let wet = |f: &[[u8; 3]], i: usize| differs(f[i], dry[i]);
    let n = a.len();
    let water: Vec<usize> = (0..n).filter(|&i| wet(&a, i) && wet(&b, i)).collect();
    let changed = water.iter().filter(|&&i| differs(a[i], b[i])).count();
    // The waterline's swing: pixels that are water in one frame and land in the other.
    let swept = (0..n).filter(|&i| wet(&a, i) != wet(&b, i)).count();
    assert!(water.len() > n / 10, "the river fills {} of {n} pixels", water.len());
    let share = changed as f32 / water.len() as f32;
    assert!(share > 0.3, "only {changed} of {} water pixels changed in {} s", water.len(), t1 - t0);
    assert!(swept < n / 100, "the banks swept {swept} of {n} pixels in {} s", t1 - t0);
    // Without the ripples only the clear water's hidden texture could move: next to nothing does.
    let mut flat = scene.clone();
    if let Some(WaterModelSpec::River(p)) = flat.water.as_mut().map(|w| &mut w.model) {
        p.ripple_amplitude = 0.0;
    }
    let (fa, fb) = (frame(&flat, t0), frame(&flat, t1));
    let flat_changed = water.iter().filter(|&&i| differs(fa[i], fb[i])).count();
    assert!(flat_changed * 5 < changed, "without ripples {flat_changed} changed, with them {changed}");
}

/// The ripples on the picture move downstream at `flow_speed` within 10 %: the image along the
/// river's centre, read at evenly spaced points of the water plane, is laid onto the later frame's
/// by the shift of least squared difference.
#[test]
fn the_rendered_ripples_move_downstream_at_flow_speed() {
    let scene = Scene::from_toml(PLAIN_RIVER, "plain river").unwrap();
    let p = river_params(&scene);
    let (w, h) = (scene.render.width as f32, scene.render.height as f32);
    let clip = scene.camera.clip_from_world(w / h);
    let luminance = |f: &[[u8; 3]], x: f32, z: f32| -> f32 {
        let c = clip * glam::Vec4::new(x, 0.0, z, 1.0);
        let (px, py) = ((c.x / c.w + 1.0) * 0.5 * w - 0.5, (1.0 - c.y / c.w) * 0.5 * h - 0.5);
        let (i, j, fx, fy) = (px.floor() as usize, py.floor() as usize, px.fract(), py.fract());
        let at = |i: usize, j: usize| {
            let [r, g, b] = f[j * w as usize + i].map(f32::from);
            0.2126 * r + 0.7152 * g + 0.0722 * b
        };
        let top = at(i, j) * (1.0 - fx) + at(i + 1, j) * fx;
        let bottom = at(i, j + 1) * (1.0 - fx) + at(i + 1, j + 1) * fx;
        top * (1.0 - fy) + bottom * fy
    };
    // From 5.5 m to 13.5 m ahead of the camera (z from 8 down to 0), every 1 cm, on three lines
    // along the stream inside its narrowest reach ([-1.5, -0.3] m across).
    let dz = 0.01;
    let zs: Vec<f32> = (0..=800).map(|k| k as f32 * dz).collect();
    // What does not move with the water (the sky's and the bed's gradients with distance, which
    // would pull the fit towards no shift) is taken out: each profile less its mean over 1 m.
    let window = (1.0 / dz) as usize;
    let profiles = |f: &[[u8; 3]]| -> Vec<Vec<f32>> {
        [-1.2, -0.9, -0.6]
            .iter()
            .map(|&x| {
                let line: Vec<f32> = zs.iter().map(|&z| luminance(f, x, z)).collect();
                (window / 2..line.len() - window / 2)
                    .map(|k| line[k] - line[k - window / 2..=k + window / 2].iter().sum::<f32>() / (window + 1) as f32)
                    .collect()
            })
            .collect()
    };
    let dt = 0.4;
    let (a, b) = (profiles(&frame(&scene, 1.0)), profiles(&frame(&scene, 1.0 + dt)));
    // Downstream is +Z: the later profile at z + s matches the earlier one at z.
    let misfit = |s: usize| -> f32 {
        let (mut sum, mut count) = (0.0, 0.0);
        for (pa, pb) in a.iter().zip(&b) {
            for (j, &v) in pa.iter().enumerate().take(pa.len() - s) {
                sum += (v - pb[j + s]).powi(2);
                count += 1.0;
            }
        }
        sum / count
    };
    let expected = p.flow_speed * dt as f32;
    let best = (0..(2.0 * expected / dz) as usize).min_by(|&i, &j| misfit(i).total_cmp(&misfit(j))).unwrap();
    let speed = best as f32 * dz / dt as f32;
    assert!((speed / p.flow_speed - 1.0).abs() < 0.1, "ripples move at {speed} m/s, flow_speed {}", p.flow_speed);
    // And the fit means something: the best shift lays the frames far closer than none does.
    assert!(misfit(best) * 4.0 < misfit(0), "misfit {} at the best shift, {} unshifted", misfit(best), misfit(0));
}
