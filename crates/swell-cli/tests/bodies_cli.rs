//! Issue 34 through the real binary: a boat hull read from an OBJ floats at its draft in a bake's
//! `bodies.json`, a render draws the bodies, and an export writes the bodies' motion as a glTF
//! node animation.

use std::path::Path;

mod common;
use common::{stderr, swell};

/// The example hull (docs/examples/floating/hull.obj): a pentagonal prism 0.8 m high whose volume
/// is 5.12 m³.
const HULL: &str = include_str!("../../../docs/examples/floating/hull.obj");

/// Still water (a sines sea with no waves) and the hull, at density 300, released 0.2 m above
/// its equilibrium; the hull's path relative to the scene file.
fn still_water_boat(dir: &Path) -> String {
    std::fs::write(dir.join("hull.obj"), HULL).unwrap();
    let scene = "version = 1\n\
        [water]\nmodel = 'sines'\nsize = [20.0, 20.0]\ncells = [8, 8]\n\
        [[body]]\nname = 'boat'\nshape = 'mesh'\npath = 'hull.obj'\ndensity = 300.0\n\
        position = [0.0, 0.37, 0.0]\n";
    let path = dir.join("boat.toml");
    std::fs::write(&path, scene).unwrap();
    path.to_str().unwrap().to_string()
}

#[test]
fn an_obj_hull_floats_at_its_draft_in_a_bake() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = still_water_boat(tmp.path());
    let out = tmp.path().join("bake");
    let o = swell(&["bake", "--scene", &scene, "--frames", "0..180", "--fps", "3", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("bodies.json")).unwrap()).unwrap();
    let boat = &json["bodies"][0];
    assert_eq!(boat["name"], "boat");
    let frames = boat["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 181);
    // Its centre of mass (mid-height) settles where 300/1025 of its 0.8 m height is under water:
    // y = 0.4 - 0.8 * 300 / 1025. The last 20 s average out what heave is left.
    let tail: Vec<f64> = frames[120..].iter().map(|f| f["position"][1].as_f64().unwrap()).collect();
    let y = tail.iter().sum::<f64>() / tail.len() as f64;
    let expected = 0.4 - 0.8 * 300.0 / 1025.0;
    assert!((y - expected).abs() < 0.01 * 0.8, "settled at {y} m, expected {expected} m");
    // The hull in the bake's manifest, so a resume with another hull is another bake.
    let manifest = std::fs::read_to_string(out.join("bake.json")).unwrap();
    assert!(manifest.contains("\"bodies\"") && manifest.contains("hull.obj"), "{manifest}");
}

#[test]
fn an_export_writes_the_bodies_and_their_motion() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = still_water_boat(tmp.path());
    let glb = tmp.path().join("boat.glb");
    let o = swell(&["export", "--scene", &scene, "--frames", "0..11", "--fps", "12", "--out", glb.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Each frame's file holds the boat placed at its pose; the animation file its motion.
    let bytes = std::fs::read(tmp.path().join("boat_bodies.glb")).unwrap();
    assert_eq!(&bytes[..4], b"glTF");
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let doc: serde_json::Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    assert_eq!(doc["nodes"][0]["name"], "boat");
    let animation = &doc["animations"][0];
    assert_eq!(animation["channels"].as_array().unwrap().len(), 2);
    let input = animation["samplers"][0]["input"].as_u64().unwrap() as usize;
    assert_eq!(doc["accessors"][input]["count"], 12);
    assert!((doc["accessors"][input]["max"][0].as_f64().unwrap() - 11.0 / 12.0).abs() < 1e-6);
    let frame = std::fs::read(tmp.path().join("boat_0005.glb")).unwrap();
    let len = u32::from_le_bytes(frame[12..16].try_into().unwrap()) as usize;
    let doc: serde_json::Value = serde_json::from_slice(&frame[20..20 + len]).unwrap();
    let names: Vec<&str> = doc["nodes"].as_array().unwrap().iter().filter_map(|n| n["name"].as_str()).collect();
    assert!(names.contains(&"water") && names.contains(&"boat"), "{names:?}");
    // An OBJ per frame has the boat's triangles after the water's.
    let obj = tmp.path().join("boat.obj");
    let o = swell(&["export", "--scene", &scene, "--time", "1.0", "--out", obj.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&obj).unwrap();
    assert!(text.contains("boat"), "no boat object in the OBJ");
}

#[test]
fn bad_bodies_are_refused_naming_the_key_and_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = still_water_boat(tmp.path());
    let open = HULL.lines().filter(|l| !l.starts_with("f 1 2 3")).collect::<Vec<_>>().join("\n");
    std::fs::write(tmp.path().join("hull.obj"), open).unwrap();
    let o = swell(&["render", "--scene", &scene, "--out", tmp.path().join("x.png").to_str().unwrap()]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(e.contains("body[0].path") && e.contains("hull.obj") && e.contains("closed"), "{e}");
}
