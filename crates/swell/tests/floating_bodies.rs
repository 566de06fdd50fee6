//! Issue 34 end to end through scenes: `[[body]]` read, written and refused; bodies riding the
//! world's water, resting on its terrain, drawn, and baked into `bodies.json` the same way
//! however the bake is run.

use std::collections::BTreeMap;
use std::path::Path;

use swell::export::{Bake, BakeSettings, BakedBodies, FrameRange, Shard};
use swell::render::Renderer;
use swell::scene::Scene;
use swell::world::World;

/// A sines sea with a crate, a buoy and a log.
const SEA: &str = r#"
version = 1
[camera]
eye = [0.0, 6.0, 14.0]
target = [0.0, 0.0, 0.0]
[[light]]
type = "directional"
direction = [0.3, -0.8, 0.2]
color = [1.0, 1.0, 1.0]
intensity = 1.0
[render]
width = 160
height = 100
[water]
model = "sines"
size = [40.0, 40.0]
cells = [32, 32]
density = 1000.0
[[water.waves]]
amplitude = 0.3
wavelength = 12.0
speed = 4.3
direction = [1.0, 0.2]
[[body]]
name = "crate"
shape = "box"
size = [1.0, 0.5, 2.0]
density = 500.0
position = [0.0, 0.3, 0.0]
rotation_deg = [20.0, 0.0, 0.0]
color = [0.8, 0.1, 0.1]
[[body]]
name = "buoy"
shape = "sphere"
size = [0.4]
mass = 40.0
position = [-4.0, 0.5, 2.0]
[[body]]
name = "log"
shape = "capsule"
size = [0.25, 2.0]
position = [3.0, 1.0, -1.0]
velocity = [0.0, -1.0, 0.0]
"#;

fn world(text: &str) -> World {
    World::new(Scene::from_toml(text, "test").unwrap()).unwrap()
}

#[test]
fn body_keys_round_trip_and_bad_values_name_the_key() {
    let scene = Scene::from_toml(SEA, "test").unwrap();
    assert_eq!(scene.bodies.len(), 3);
    assert_eq!(scene.water.as_ref().unwrap().density, 1000.0);
    let again = Scene::from_toml(&scene.to_toml(), "again").unwrap();
    assert_eq!(again, scene);
    for (from, to, key) in [
        ("shape = \"box\"", "shape = \"boat\"", "body[0].shape"),
        ("size = [1.0, 0.5, 2.0]", "size = [1.0, 0.5]", "body[0].size"),
        ("density = 500.0", "density = 0.0", "body[0].density"),
        ("mass = 40.0", "mass = -1.0", "body[1].mass"),
        ("density = 1000.0", "density = 5000.0", "water.density"),
        ("name = \"buoy\"", "name = \"crate\"", "body[1].name"),
        ("rotation_deg = [20.0, 0.0, 0.0]", "rotation_deg = [20.0, 0.0]", "body[0].rotation_deg"),
        ("velocity = [0.0, -1.0, 0.0]", "velocity = [0.0, -1.0, 0.0]\nspin = 3", "spin"),
    ] {
        let text = SEA.replace(from, to);
        let e = Scene::from_toml(&text, "test").unwrap_err().to_string();
        assert!(e.contains(key), "{to}: {e}");
    }
}

#[test]
fn bodies_ride_the_world_s_water_and_are_drawn() {
    let mut w = world(SEA);
    for k in 0..=240 {
        w.update(f64::from(k) / 60.0).unwrap();
    }
    let poses = w.body_poses().to_vec();
    assert_eq!(poses.len(), 3);
    for (b, p) in w.bodies.bodies().iter().zip(&poses) {
        assert!(p.position.is_finite() && p.rotation.is_finite(), "{}", b.name);
        let h = f64::from(w.water_height_at(p.position.x as f32, p.position.z as f32).unwrap());
        // Afloat: the centre within half a metre of the surface, neither sunk nor flung away.
        assert!((p.position.y - h).abs() < 0.5, "{} at {} over water at {h}", b.name, p.position);
    }
    // Drawn: the red crate shows in the image where it floats.
    let mut r = Renderer::new();
    let fb = r.render(&w);
    let reddish = fb.color.iter().filter(|c| c.x > 2.0 * c.y && c.x > 2.0 * c.z && c.x > 0.02).count();
    assert!(reddish > 20, "{reddish} red pixels");
    let mut without = Scene::from_toml(SEA, "test").unwrap();
    without.bodies.clear();
    let mut w2 = World::new(without).unwrap();
    w2.update(4.0).unwrap();
    let fb2 = Renderer::new().render(&w2).color.clone();
    let red2 = fb2.iter().filter(|c| c.x > 2.0 * c.y && c.x > 2.0 * c.z && c.x > 0.02).count();
    assert!(red2 < reddish / 4, "{red2} red pixels without bodies, {reddish} with");
}

/// A beach rising along +X: under water at x < 0, land above it beyond.
const BEACH: &str = r#"
version = 1
[terrain]
generator = "slope"
size = 65
extent = [80.0, 80.0]
start_height = -8.0
end_height = 8.0
[water]
model = "sines"
size = [80.0, 80.0]
cells = [16, 16]
[[water.waves]]
amplitude = 0.1
wavelength = 10.0
speed = 4.0
direction = [1.0, 0.0]
[[body]]
name = "on land"
shape = "box"
size = [1.0, 1.0, 1.0]
position = [30.0, 8.0, 0.0]
[[body]]
name = "sinker"
shape = "box"
size = [1.0, 1.0, 1.0]
density = 3000.0
position = [-20.0, 0.0, 0.0]
"#;

#[test]
fn bodies_rest_on_land_and_on_the_bed_instead_of_falling_through() {
    let mut w = world(BEACH);
    for k in 0..=600 {
        w.update(f64::from(k) / 60.0).unwrap();
    }
    let ground = |x: f64, z: f64| f64::from(w.terrain.as_ref().unwrap().ground_height(x as f32, z as f32).unwrap());
    for (b, p) in w.bodies.bodies().iter().zip(w.body_poses()) {
        let g = ground(p.position.x, p.position.z);
        // A unit cube resting on a gentle slope: its centre about half a metre above the ground.
        let above = p.position.y - g;
        assert!((0.35..0.75).contains(&above), "{}: centre {above} m above the ground", b.name);
        assert!(b.state.velocity.length() < 0.2, "{} still moving at {}", b.name, b.state.velocity);
    }
    // Starting inside the land is refused, naming the body.
    let e = Scene::from_toml(&BEACH.replace("position = [30.0, 8.0, 0.0]", "position = [30.0, 2.0, 0.0]"), "t")
        .and_then(World::new)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("body[0].position") && e.contains("inside the terrain"), "{e}");
}

fn bake(dir: &Path, frames: (u32, u32), shard: Option<&str>, resume: bool) {
    let mut w = world(SEA);
    let mut s = BakeSettings::new(FrameRange::new("f", frames.0, frames.1).unwrap());
    if let Some(sh) = shard {
        s.shard = Shard::parse("shard", sh).unwrap();
    }
    s.resume = resume;
    let bake = Bake::prepare(&mut w, dir, s).unwrap();
    bake.run(&mut w, &|_| {}).unwrap();
}

fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| !e.file_name().to_string_lossy().ends_with(".lock"))
        .map(|e| (e.file_name().to_string_lossy().into_owned(), std::fs::read(e.path()).unwrap()))
        .collect()
}

#[test]
fn a_bake_writes_the_same_poses_whole_sharded_threaded_or_resumed() {
    let whole = tempfile::tempdir().unwrap();
    bake(whole.path(), (0, 11), None, false);
    let poses: BakedBodies = serde_json::from_slice(&std::fs::read(whole.path().join("bodies.json")).unwrap()).unwrap();
    assert_eq!(poses.bodies.len(), 3);
    assert_eq!(poses.bodies[0].name, "crate");
    assert_eq!(poses.bodies[0].frames.len(), 12);
    let f = &poses.bodies[1].frames[5];
    assert_eq!(f.frame, 5);
    assert!((f.t - 5.0 / 24.0).abs() < 1e-12);
    let q = f.rotation;
    assert!(((q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt() - 1.0).abs() < 1e-9);
    // The poses are the world's at each frame's time.
    let mut w = world(SEA);
    w.update(5.0 / 24.0).unwrap();
    assert_eq!(f.position, w.body_poses()[1].position.to_array());
    let reference = files(whole.path());

    // Two shards, one on a single thread; then a resume after a frame's poses are damaged.
    let sharded = tempfile::tempdir().unwrap();
    bake(sharded.path(), (0, 11), Some("0/2"), false);
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| bake(sharded.path(), (0, 11), Some("1/2"), false));
    assert_eq!(files(sharded.path()), reference);
    std::fs::write(sharded.path().join("bodies_0007.json"), b"{}").unwrap();
    bake(sharded.path(), (0, 11), None, true);
    assert_eq!(files(sharded.path()), reference);
}

#[test]
fn a_body_dropped_into_a_running_world_replays_from_its_saved_scene() {
    let mut live = world(SEA);
    for k in 0..=90 {
        live.update(f64::from(k) / 60.0).unwrap();
    }
    let mut spec =
        swell::body::BodySpec::new(swell::body::BodyShape::Box, &[0.6, 0.6, 0.6], glam::Vec3::new(1.0, 2.0, 3.0));
    spec.density = Some(300.0);
    let k = live.add_body(spec).unwrap();
    assert_eq!(k, 3);
    assert_eq!(live.scene.bodies[3].name, "body3");
    assert!(live.scene.bodies[3].release_time > 1.5);
    for k in 91..=240 {
        live.update(f64::from(k) / 60.0).unwrap();
    }
    // Held until its release, then it fell onto the water and floats.
    let dropped = live.body_poses()[3];
    assert!(dropped.position.y < 0.5, "{}", dropped.position);
    // The scene as saved, run from t = 0 straight to the end: the same poses, bit for bit.
    let mut replay = World::new(Scene::from_toml(&live.scene.to_toml(), "saved").unwrap()).unwrap();
    replay.update(4.0).unwrap();
    assert_eq!(replay.body_poses(), live.body_poses());
    // A body inside another's name, or with a bad key, is refused naming it.
    let mut twin = swell::body::BodySpec::new(swell::body::BodyShape::Sphere, &[0.3], glam::Vec3::Y);
    twin.name = "crate".into();
    assert!(live.add_body(twin).unwrap_err().to_string().contains("body[4].name"));
    // Too light to step is refused naming the index it would have had, not body[0].
    let mut foam = swell::body::BodySpec::new(swell::body::BodyShape::Sphere, &[0.03], glam::Vec3::Y);
    foam.density = Some(20.0);
    let e = live.add_body(foam).unwrap_err().to_string();
    assert!(e.contains("body[4].mass"), "{e}");
    // A push moves a body; taking it away leaves it to the water.
    let before = live.body_poses()[0].position;
    live.bodies.bodies_mut()[0].thrust = glam::DVec3::new(2000.0, 0.0, 0.0);
    for k in 241..=300 {
        live.update(f64::from(k) / 60.0).unwrap();
    }
    assert!(live.body_poses()[0].position.x > before.x + 0.5, "{} -> {}", before, live.body_poses()[0].position);
}

#[test]
fn a_body_added_to_a_world_without_bodies_joins_at_the_world_s_time() {
    let mut without = Scene::from_toml(SEA, "test").unwrap();
    without.bodies.clear();
    let mut w = World::new(without).unwrap();
    for k in 0..=120 {
        w.update(f64::from(k) / 60.0).unwrap();
    }
    let spec = swell::body::BodySpec::new(swell::body::BodyShape::Sphere, &[0.3], glam::Vec3::new(0.0, 2.0, 0.0));
    w.add_body(spec).unwrap();
    // Released at the step after 2 s, and posed at once.
    assert!((w.scene.bodies[0].release_time - 241.0 / 120.0).abs() < 1e-12, "{}", w.scene.bodies[0].release_time);
    assert_eq!(w.body_poses().len(), 1);
    assert_eq!(w.body_poses()[0].position, glam::DVec3::new(0.0, 2.0, 0.0));
}
