//! Export and bake, end to end through the library: meshes re-read give back the same vertices,
//! baked EXR/PNG maps give back the model's fields, bakes do not depend on threads, and a looping
//! model's last frame flows into its first.

use std::collections::BTreeMap;
use std::path::Path;

use glam::{Quat, Vec2, Vec3};
use swell::export::{
    gltf_document, world_meshes, write_glb, write_gltf, write_obj, Bake, BakeManifest, BakeSettings, FrameRange,
};
use swell::math::GridSpec;
use swell::scene::Scene;
use swell::world::World;

/// A small Gerstner sea (two waves, 24 x 16 cells over 40 m x 30 m, off-centre).
const SEA: &str = r#"
version = 1
[camera]
eye = [3.0, 12.0, 40.0]
target = [0.0, 0.0, 5.0]
fov_y_deg = 50.0
near = 0.5
far = 900.0
[render]
width = 800
height = 600
[water]
model = "gerstner"
size = [40.0, 30.0]
cells = [24, 16]
center = [5.0, -2.0]
[[water.waves]]
amplitude = 0.5
wavelength = 12.0
speed = 4.3
direction = [1.0, 0.3]
steepness = 0.7
[[water.waves]]
amplitude = 0.2
wavelength = 5.0
speed = 2.8
direction = [-0.2, 1.0]
steepness = 0.5
"#;

fn world(text: &str, t: f64) -> World {
    let mut w = World::new(Scene::from_toml(text, "test").unwrap()).unwrap();
    w.update(t).unwrap();
    w
}

/// The water's patch as bakes and exports sample it.
fn mesh_of(w: &World) -> swell::mesh::SurfaceMesh {
    w.patch_mesh().unwrap().expect("the scene has water")
}

// ---------------------------------------------------------------- OBJ

struct ObjMesh {
    positions: Vec<Vec3>,
    uvs: Vec<Vec2>,
    normals: Vec<Vec3>,
    faces: Vec<[u32; 3]>,
}

/// A minimal OBJ reader: v, vt, vn and triangular f v/vt/vn faces (1-based), as we write them.
fn read_obj(path: &Path) -> ObjMesh {
    let text = std::fs::read_to_string(path).unwrap();
    let mut m = ObjMesh { positions: vec![], uvs: vec![], normals: vec![], faces: vec![] };
    let nums = |rest: &str| rest.split_whitespace().map(|s| s.parse::<f32>().unwrap()).collect::<Vec<_>>();
    for line in text.lines() {
        let (tag, rest) = line.split_once(' ').unwrap_or((line, ""));
        match tag {
            "v" => m.positions.push(Vec3::from_slice(&nums(rest))),
            "vt" => {
                let t = nums(rest);
                m.uvs.push(Vec2::new(t[0], 1.0 - t[1]));
            }
            "vn" => m.normals.push(Vec3::from_slice(&nums(rest))),
            "f" => {
                let idx: Vec<u32> = rest
                    .split_whitespace()
                    .map(|c| {
                        let parts: Vec<u32> = c.split('/').map(|p| p.parse().unwrap()).collect();
                        assert!(parts[0] == parts[1] && parts[1] == parts[2], "one index per corner: {c}");
                        parts[0] - 1
                    })
                    .collect();
                m.faces.push([idx[0], idx[1], idx[2]]);
            }
            _ => {}
        }
    }
    m
}

#[test]
fn obj_gives_back_the_same_vertices_normals_uvs_and_triangles() {
    let w = world(SEA, 1.7);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sea.obj");
    let patch = mesh_of(&w);
    write_obj(&path, &world_meshes(&w, Some(&patch))).unwrap();
    let back = read_obj(&path);
    let m = mesh_of(&w);
    // Shortest round-trip float text: positions and normals come back bit for bit.
    assert_eq!(back.positions, m.positions);
    assert_eq!(back.normals, m.normals);
    for (a, b) in back.uvs.iter().zip(&m.uvs) {
        assert!((*a - *b).abs().max_element() < 1e-6, "{a} vs {b}");
    }
    let tris: Vec<[u32; 3]> = m.indices.chunks(3).map(|t| [t[0], t[1], t[2]]).collect();
    assert_eq!(back.faces, tris);
}

// ---------------------------------------------------------------- glTF

/// Reads accessor `i` of a glTF document as f32 or u32 components (tightly packed, as we write).
fn accessor(doc: &serde_json::Value, bin: &[u8], i: usize) -> Vec<u32> {
    let acc = &doc["accessors"][i];
    let view = &doc["bufferViews"][acc["bufferView"].as_u64().unwrap() as usize];
    let width = match acc["type"].as_str().unwrap() {
        "SCALAR" => 1,
        "VEC2" => 2,
        "VEC3" => 3,
        t => panic!("unexpected accessor type {t}"),
    };
    let count = acc["count"].as_u64().unwrap() as usize;
    let start = view["byteOffset"].as_u64().unwrap() as usize;
    assert_eq!(view["byteLength"].as_u64().unwrap() as usize, 4 * width * count);
    bin[start..start + 4 * width * count].chunks(4).map(|b| u32::from_le_bytes(b.try_into().unwrap())).collect()
}

fn vec3s(raw: &[u32]) -> Vec<Vec3> {
    raw.chunks(3).map(|c| Vec3::new(f32::from_bits(c[0]), f32::from_bits(c[1]), f32::from_bits(c[2]))).collect()
}

fn check_gltf(doc: &serde_json::Value, bin: &[u8], w: &World) {
    let m = mesh_of(w);
    assert_eq!(doc["asset"]["version"], "2.0");
    let prim = &doc["meshes"][0]["primitives"][0];
    let attr = |name: &str| prim["attributes"][name].as_u64().unwrap() as usize;
    assert_eq!(vec3s(&accessor(doc, bin, attr("POSITION"))), m.positions);
    assert_eq!(vec3s(&accessor(doc, bin, attr("NORMAL"))), m.normals);
    let uv: Vec<Vec2> = accessor(doc, bin, attr("TEXCOORD_0"))
        .chunks(2)
        .map(|c| Vec2::new(f32::from_bits(c[0]), f32::from_bits(c[1])))
        .collect();
    assert_eq!(uv, m.uvs);
    assert_eq!(accessor(doc, bin, prim["indices"].as_u64().unwrap() as usize), m.indices);
    // POSITION min/max bound the vertices (the validator checks they are exact).
    let pos = &doc["accessors"][attr("POSITION")];
    let lo = Vec3::from_slice(&serde_json::from_value::<Vec<f32>>(pos["min"].clone()).unwrap());
    assert!(m.positions.iter().all(|p| p.cmpge(lo).all()));
    assert!(m.positions.iter().any(|p| p.x == lo.x));

    // The camera node sits at the eye and looks at the target down its local -Z, +Y up.
    let cam = &w.scene.camera;
    let node = doc["nodes"].as_array().unwrap().iter().find(|n| n.get("camera").is_some()).unwrap();
    let t = Vec3::from_slice(&serde_json::from_value::<Vec<f32>>(node["translation"].clone()).unwrap());
    let q = Quat::from_slice(&serde_json::from_value::<Vec<f32>>(node["rotation"].clone()).unwrap());
    assert!((t - cam.eye).length() < 1e-5);
    assert!((q.length() - 1.0).abs() < 1e-6);
    let forward = (cam.target - cam.eye).normalize();
    assert!((q * Vec3::NEG_Z - forward).length() < 1e-5, "camera looks along {}", q * Vec3::NEG_Z);
    assert!((q * Vec3::Y).dot(Vec3::Y) > 0.0 && (q * Vec3::X).y.abs() < 1e-5, "camera is level, +Y up");
    let p = &doc["cameras"][0]["perspective"];
    assert!((p["yfov"].as_f64().unwrap() - 50f64.to_radians()).abs() < 1e-6);
    assert!((p["aspectRatio"].as_f64().unwrap() - 800.0 / 600.0).abs() < 1e-6);
    assert_eq!(p["znear"].as_f64().unwrap(), 0.5);
    assert_eq!(p["zfar"].as_f64().unwrap(), 900.0);
}

#[test]
fn gltf_and_glb_give_back_the_same_vertices_and_the_scene_camera() {
    let w = world(SEA, 2.25);
    let dir = tempfile::tempdir().unwrap();
    let patch = mesh_of(&w);
    let meshes = world_meshes(&w, Some(&patch));
    let cam = &w.scene.camera;

    let gltf = dir.path().join("sea frame.gltf");
    write_gltf(&gltf, &meshes, cam, 800.0 / 600.0).unwrap();
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&gltf).unwrap()).unwrap();
    assert_eq!(doc["buffers"][0]["uri"], "sea%20frame.bin");
    let bin = std::fs::read(dir.path().join("sea frame.bin")).unwrap();
    assert_eq!(doc["buffers"][0]["byteLength"].as_u64().unwrap() as usize, bin.len());
    check_gltf(&doc, &bin, &w);

    let glb = dir.path().join("sea.glb");
    write_glb(&glb, &meshes, cam, 800.0 / 600.0).unwrap();
    let bytes = std::fs::read(&glb).unwrap();
    let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
    assert_eq!(&bytes[0..4], b"glTF");
    assert_eq!((word(4), word(8)), (2, bytes.len()));
    let json_len = word(12);
    assert_eq!(&bytes[16..20], b"JSON");
    let doc: serde_json::Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    let bin_at = 20 + json_len;
    assert_eq!(&bytes[bin_at + 4..bin_at + 8], b"BIN\0");
    let bin = &bytes[bin_at + 8..bin_at + 8 + word(bin_at)];
    assert!(doc["buffers"][0].get("uri").is_none());
    check_gltf(&doc, bin, &w);

    // The same document whichever way it is stored (compared after the same text round trip).
    let (a, _) = gltf_document(&meshes, cam, 800.0 / 600.0, None).unwrap();
    let a: serde_json::Value = serde_json::from_slice(&serde_json::to_vec(&a).unwrap()).unwrap();
    assert_eq!(a, doc);
}

// ---------------------------------------------------------------- bake

fn read_exr_rgb(path: &Path) -> (usize, usize, Vec<Vec3>) {
    let img = exr::prelude::read_first_rgba_layer_from_file(
        path,
        |res, _| (res.width(), res.height(), vec![Vec3::ZERO; res.width() * res.height()]),
        |(w, _, px), pos, (r, g, b, _a): (f32, f32, f32, f32)| px[pos.y() * *w + pos.x()] = Vec3::new(r, g, b),
    )
    .unwrap();
    img.layer_data.channel_data.pixels
}

fn read_exr_y(path: &Path) -> Vec<f32> {
    use exr::prelude::{ReadChannels, ReadLayers, ReadSpecificChannel};
    let img = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .specific_channels()
        .required("Y")
        .collect_pixels(
            |res, _| (res.width(), vec![0.0f32; res.width() * res.height()]),
            |(w, px), pos, (y,): (f32,)| px[pos.y() * *w + pos.x()] = y,
        )
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .unwrap();
    img.layer_data.channel_data.pixels.1
}

/// The model's own fields at time t on the grid, evaluated apart from the bake.
fn model_fields(text: &str, t: f64) -> (GridSpec, Vec<Vec3>, Vec<Vec3>) {
    let w = world(text, t);
    let m = mesh_of(&w);
    let g = m.grid;
    let disp = (0..g.vertex_count())
        .map(|v| {
            let r = g.rest_position(v % g.verts_x(), v / g.verts_x());
            m.positions[v] - Vec3::new(r.x, 0.0, r.y)
        })
        .collect();
    (g, disp, m.normals.clone())
}

fn bake(text: &str, dir: &Path, settings: BakeSettings) -> BakeManifest {
    let mut w = World::new(Scene::from_toml(text, "test").unwrap()).unwrap();
    let bake = Bake::prepare(&mut w, dir, settings).unwrap();
    bake.run(&mut w, &|_| {}).unwrap();
    bake.manifest().clone()
}

#[test]
fn baked_maps_read_back_as_the_models_fields() {
    let dir = tempfile::tempdir().unwrap();
    let mut s = BakeSettings::new(FrameRange::new("f", 3, 5).unwrap());
    s.fps = 10.0;
    s.png_bits = Some(16);
    let manifest = bake(SEA, dir.path(), s);
    assert_eq!(manifest.grid.pixels, [25, 17]);
    assert_eq!(manifest.model, "gerstner");
    let on_disk: BakeManifest = serde_json::from_slice(&std::fs::read(dir.path().join("bake.json")).unwrap()).unwrap();
    assert_eq!(on_disk, manifest);
    let range = manifest.png.as_ref().unwrap().displacement_range_m;
    for frame in 3..=5 {
        let (grid, disp, normals) = model_fields(SEA, frame as f64 / 10.0);
        let (w, h, got) = read_exr_rgb(&dir.path().join(format!("disp_{frame:04}.exr")));
        assert_eq!((w, h), (grid.verts_x(), grid.verts_z()));
        assert_eq!(got, disp, "frame {frame}: displacement");
        // Height is G, and it is the surface height the model reports at the displaced point.
        let v = 7 * w + 11;
        let r = grid.rest_position(11, 7);
        let p = Vec2::new(r.x + got[v].x, r.y + got[v].z);
        let h_model = world(SEA, frame as f64 / 10.0).water.unwrap().model.height_at(p.x, p.y, frame as f64 / 10.0);
        assert!((got[v].y - h_model).abs() < 1e-3, "G = {} vs height_at = {h_model}", got[v].y);
        let (_, _, n) = read_exr_rgb(&dir.path().join(format!("normal_{frame:04}.exr")));
        assert_eq!(n, normals, "frame {frame}: normals");
        assert!(!dir.path().join(format!("foam_{frame:04}.exr")).exists(), "Gerstner has no foam");

        // 16-bit PNG: within half a quantisation step of the float map.
        let png = image::open(dir.path().join(format!("disp_{frame:04}.png"))).unwrap().into_rgb16();
        assert_eq!(png.dimensions(), (w as u32, h as u32));
        for (px, d) in png.pixels().zip(&disp) {
            for c in 0..3 {
                let back = (2.0 * px[c] as f32 / 65535.0 - 1.0) * range;
                assert!((back - d[c]).abs() <= range / 65535.0 + 1e-6, "{back} vs {}", d[c]);
            }
        }
    }
}

#[test]
fn one_channel_foam_exr_reads_back_exactly() {
    // No model in this build reports foam; the EXR writer for it is checked directly.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("foam.exr");
    let foam: Vec<f32> = (0..12).map(|i| i as f32 / 11.0).collect();
    swell::export::write_exr_gray(&path, 4, 3, &foam, swell::export::ExrCompression::Zip).unwrap();
    assert_eq!(read_exr_y(&path), foam);
}

#[test]
fn bakes_are_byte_identical_on_1_and_2_threads_and_with_any_compression() {
    let run = |threads: usize, compression| {
        let dir = tempfile::tempdir().unwrap();
        let mut s = BakeSettings::new(FrameRange::new("f", 0, 6).unwrap());
        s.compression = compression;
        s.png_bits = Some(8);
        rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| bake(SEA, dir.path(), s));
        let mut files = BTreeMap::new();
        for e in std::fs::read_dir(dir.path()).unwrap() {
            let e = e.unwrap();
            files.insert(e.file_name(), std::fs::read(e.path()).unwrap());
        }
        files
    };
    use swell::export::ExrCompression::*;
    for c in [None, Zip, Piz] {
        let one = run(1, c);
        assert_eq!(one.len(), 1 + 7 * 5, "bake.json; per frame 2 EXR, 2 PNG and the record");
        assert!(one == run(2, c), "{c:?}: thread count changed the bytes");
    }
}

// ---------------------------------------------------------------- loops

/// Sines whose periods (wavelength / speed = 4 s, 2 s, 1 s) all divide a 4 s loop.
const LOOPING_SINES: &str = r#"
version = 1
[camera]
eye = [0.0, 10.0, 30.0]
target = [0.0, 0.0, 0.0]
[water]
model = "sines"
size = [24.0, 24.0]
cells = [24, 24]
[[water.waves]]
amplitude = 0.4
wavelength = 8.0
speed = 2.0
direction = [1.0, 0.0]
[[water.waves]]
amplitude = 0.2
wavelength = 6.0
speed = 3.0
direction = [0.6, 0.8]
[[water.waves]]
amplitude = 0.1
wavelength = 3.0
speed = 3.0
direction = [-0.3, 1.0]
"#;

#[test]
fn a_looping_bake_flows_from_its_last_frame_into_its_first() {
    // With a 4 s period at 6 fps the loop is 24 frames: bake 0..23; frame 24 would be frame 0.
    let dir = tempfile::tempdir().unwrap();
    let mut s = BakeSettings::new(FrameRange::new("f", 0, 23).unwrap());
    s.fps = 6.0;
    s.loop_period_s = Some(4.0);
    let manifest = bake(LOOPING_SINES, dir.path(), s);
    assert_eq!(manifest.loop_frames, Some(24));
    let frames: Vec<Vec<Vec3>> =
        (0..24).map(|k| read_exr_rgb(&dir.path().join(format!("disp_{k:04}.exr"))).2).collect();
    let step = |a: &[Vec3], b: &[Vec3]| a.iter().zip(b).map(|(p, q)| (*p - *q).length()).fold(0.0f32, f32::max);

    // One period on, the model is where it started...
    let (_, one_period_on, _) = model_fields(LOOPING_SINES, 4.0);
    assert!(step(&one_period_on, &frames[0]) < 1e-4, "the model does not repeat after 4 s");
    // ...so the wrap-around step (23 -> 0) is an ordinary step: as large as the others, not a jump
    // and not a stall.
    let steps: Vec<f32> = (0..23).map(|k| step(&frames[k], &frames[k + 1])).collect();
    let wrap = step(&frames[23], &frames[0]);
    let (lo, hi) = steps.iter().fold((f32::MAX, 0.0f32), |(lo, hi), &s| (lo.min(s), hi.max(s)));
    assert!(wrap >= 0.9 * lo && wrap <= 1.1 * hi, "wrap step {wrap} outside the other steps' [{lo}, {hi}]");
    assert!((wrap - step(&one_period_on, &frames[23])).abs() < 1e-4);
}

// ---------------------------------------------------------------- foam

/// A model with foam, to check the foam maps: the sines above, with foam coverage
/// `0.5 + 0.5 sin(x / 3 + t)` at each vertex's rest position.
struct FoamySines {
    waves: swell::water::SumOfSines,
    t: f64,
}

impl swell::water::WaveModel for FoamySines {
    fn slope_components(&self, _out: &mut Vec<(f32, f32)>) {}

    fn evaluate(&self, grid: &GridSpec, t: f64, positions: &mut [Vec3], normals: &mut [Vec3]) {
        self.waves.evaluate(grid, t, positions, normals)
    }
    fn height_at(&self, x: f32, z: f32, t: f64) -> f32 {
        self.waves.height_at(x, z, t)
    }
    fn advance(&mut self, t: f64) -> swell::Result<()> {
        self.t = t;
        Ok(())
    }
    fn foam(&self, grid: &GridSpec, out: &mut [f32]) -> bool {
        for (v, f) in out.iter_mut().enumerate() {
            *f = foam_at(grid, v, self.t);
        }
        true
    }
}

fn foam_at(grid: &GridSpec, v: usize, t: f64) -> f32 {
    let r = grid.rest_position(v % grid.verts_x(), v / grid.verts_x());
    0.5 + 0.5 * (r.x / 3.0 + t as f32).sin()
}

#[test]
fn models_with_foam_get_foam_maps() {
    let mut w = World::new(Scene::from_toml(LOOPING_SINES, "test").unwrap()).unwrap();
    let sines = match &w.scene.water.as_ref().unwrap().model {
        swell::scene::WaterModelSpec::Sines(s) => swell::water::SumOfSines::new(s.waves.clone()).unwrap(),
        _ => unreachable!(),
    };
    w.water.as_mut().unwrap().model = Box::new(FoamySines { waves: sines, t: 0.0 });
    let dir = tempfile::tempdir().unwrap();
    let mut s = BakeSettings::new(FrameRange::new("f", 1, 2).unwrap());
    s.png_bits = Some(8);
    let bake = Bake::prepare(&mut w, dir.path(), s).unwrap();
    bake.run(&mut w, &|_| {}).unwrap();
    let names: Vec<&str> = bake.manifest().maps.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["disp", "normal", "foam"]);
    let foam = bake.manifest().foam.as_ref().expect("a bake with a foam map says what foam is");
    assert_eq!((foam.quantity.as_str(), foam.range), ("coverage", [0.0, 1.0]));
    let grid = w.water.as_ref().unwrap().patch_grid;
    for frame in 1..=2 {
        let t = frame as f64 / 24.0;
        let foam = read_exr_y(&dir.path().join(format!("foam_{frame:04}.exr")));
        let expected: Vec<f32> = (0..grid.vertex_count()).map(|v| foam_at(&grid, v, t)).collect();
        assert_eq!(foam, expected, "frame {frame}");
        let png = image::open(dir.path().join(format!("foam_{frame:04}.png"))).unwrap().into_luma8();
        for (p, f) in png.pixels().zip(&expected) {
            assert!((p[0] as f32 / 255.0 - f).abs() <= 0.5 / 255.0 + 1e-6);
        }
    }
}

/// A water-only scene (no camera, no lights): a rough FFT ocean with foam whose 48 m grid of 48
/// cells is exactly its patch, so its maps can tile.
const FOAMY_OCEAN: &str = r#"
[water]
model = "fft"
grid = 64
patch_size = 48.0
wind_speed = 20.0
choppiness = 1.5
size = [48.0, 48.0]
cells = [48, 48]
"#;

// ---------------------------------------------------------------- normal spaces

#[test]
fn tangent_normal_maps_give_back_the_world_normal_on_the_flat_plane() {
    use swell::export::NormalSpace;
    let bake_in = |space: NormalSpace| {
        let dir = tempfile::tempdir().unwrap();
        let mut s = BakeSettings::new(FrameRange::new("f", 4, 4).unwrap());
        s.normal_space = space;
        s.png_bits = Some(16);
        let m = bake(SEA, dir.path(), s);
        (dir, m)
    };
    let (world_dir, world_m) = bake_in(NormalSpace::World);
    let (gl_dir, gl_m) = bake_in(NormalSpace::TangentGl);
    let (dx_dir, dx_m) = bake_in(NormalSpace::TangentDx);
    let normals = |d: &Path| read_exr_rgb(&d.join("normal_0004.exr"));
    let (w, h, world_n) = normals(world_dir.path());
    let (_, _, gl) = normals(gl_dir.path());
    let (_, _, dx) = normals(dx_dir.path());
    // The frame of the flat plane: T = +X, N = +Y, B = -Z (OpenGL, green to the image's top) or
    // +Z (DirectX). T * R + B * G + N * B(lue) is the world normal again, exactly.
    for v in 0..w * h {
        let back_gl = Vec3::X * gl[v].x + Vec3::NEG_Z * gl[v].y + Vec3::Y * gl[v].z;
        let back_dx = Vec3::X * dx[v].x + Vec3::Z * dx[v].y + Vec3::Y * dx[v].z;
        assert_eq!(back_gl, world_n[v], "pixel {v}");
        assert_eq!(back_dx, world_n[v], "pixel {v}");
    }
    // Independently of the formula: where the displaced surface rises towards the image's top
    // (from row j + 1 to row j - 1, i.e. towards -Z), the OpenGL green is negative and the
    // DirectX green positive. The slope is a central difference of the displaced grid, so a
    // few vertices near crests may disagree; nearly all must agree.
    let (_, _, disp) = read_exr_rgb(&world_dir.path().join("disp_0004.exr"));
    let spacing_z = world_m.grid.spacing_m[1];
    let (mut agree, mut total) = (0, 0);
    for j in 1..h - 1 {
        for i in 0..w {
            // Displaced position of row j + 1 minus that of row j - 1 (along +Z).
            let e = disp[(j + 1) * w + i] - disp[(j - 1) * w + i] + Vec3::new(0.0, 0.0, 2.0 * spacing_z);
            let slope_towards_top = -e.y / e.z;
            if slope_towards_top.abs() > 0.1 {
                total += 1;
                let v = j * w + i;
                let rises = slope_towards_top > 0.0;
                if (gl[v].y < 0.0) == rises && (dx[v].y > 0.0) == rises {
                    agree += 1;
                }
            }
        }
    }
    assert!(total > 20 && agree as f64 >= 0.95 * total as f64, "{agree} of {total} slopes agree");
    // Flat water is blue in both tangent spaces; PNGs encode (n + 1) / 2.
    let png = image::open(gl_dir.path().join("normal_0004.png")).unwrap().into_rgb16();
    for (px, n) in png.pixels().zip(&gl) {
        for c in 0..3 {
            let back = 2.0 * px[c] as f32 / 65535.0 - 1.0;
            assert!((back - n[c]).abs() <= 1.0 / 65535.0 + 1e-6);
        }
        assert!(px[2] > 32768, "tangent-space blue (N = +Y) of a sea is positive");
    }
    // Displacement does not depend on the normal space; the manifest says which space it is.
    assert_eq!(
        std::fs::read(world_dir.path().join("disp_0004.exr")).unwrap(),
        std::fs::read(gl_dir.path().join("disp_0004.exr")).unwrap()
    );
    assert_eq!(
        (world_m.normal_space, gl_m.normal_space, dx_m.normal_space),
        (NormalSpace::World, NormalSpace::TangentGl, NormalSpace::TangentDx)
    );
    assert!(gl_m.maps[1].channels.contains("OpenGL") && dx_m.maps[1].channels.contains("DirectX"));
    let text = std::fs::read_to_string(gl_dir.path().join("bake.json")).unwrap();
    assert!(text.contains("\"normal_space\": \"tangent-gl\""), "{text}");
}

#[test]
fn the_manifest_states_units_axes_and_its_version() {
    let dir = tempfile::tempdir().unwrap();
    let m = bake(SEA, dir.path(), BakeSettings::new(FrameRange::new("f", 0, 0).unwrap()));
    assert_eq!(m.manifest_version, swell::export::BAKE_MANIFEST_VERSION);
    assert_eq!((m.units.length.as_str(), m.units.time.as_str()), ("metre", "second"));
    assert!(m.foam.is_none(), "Gerstner has no foam");
    // The Blender matrix is a +90 degree rotation about X: swell's up (+Y) is Blender's +Z, and
    // swell's +Z (towards the viewer of the maps' bottom) is Blender's -Y.
    let mul = |m: [[i8; 3]; 3], v: [i8; 3]| -> [i8; 3] { [0, 1, 2].map(|r| (0..3).map(|c| m[r][c] * v[c]).sum()) };
    let b = m.axes.to_blender.matrix;
    assert_eq!(mul(b, [0, 1, 0]), [0, 0, 1]);
    assert_eq!(mul(b, [0, 0, 1]), [0, -1, 0]);
    assert_eq!(mul(b, [1, 0, 0]), [1, 0, 0]);
    let r = glam::Mat3::from_rotation_x(std::f32::consts::FRAC_PI_2);
    for v in [Vec3::X, Vec3::Y, Vec3::Z, Vec3::new(0.3, -1.2, 2.0)] {
        let by_matrix = Vec3::from_array([0, 1, 2].map(|k| (0..3).map(|c| f32::from(b[k][c]) * v[c]).sum::<f32>()));
        assert!((r * v - by_matrix).length() < 1e-6, "{v}");
    }
    assert_eq!(m.axes.to_gltf.matrix, [[1, 0, 0], [0, 1, 0], [0, 0, 1]]);
}

#[test]
fn tiled_maps_leave_out_the_repeated_last_column_and_row() {
    let (full, tiled) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let s = BakeSettings::new(FrameRange::new("f", 2, 2).unwrap());
    bake(FOAMY_OCEAN, full.path(), s.clone());
    let m = bake(FOAMY_OCEAN, tiled.path(), BakeSettings { tile: true, ..s });
    assert_eq!((m.grid.pixels, m.grid.tile), ([48, 48], true));
    for map in ["disp", "normal"] {
        let (w, h, a) = read_exr_rgb(&full.path().join(format!("{map}_0002.exr")));
        let (tw, th, b) = read_exr_rgb(&tiled.path().join(format!("{map}_0002.exr")));
        assert_eq!((w - 1, h - 1), (tw, th));
        let cropped: Vec<Vec3> = (0..th).flat_map(|j| a[j * w..j * w + tw].to_vec()).collect();
        assert_eq!(cropped, b, "{map}");
        // The dropped last column and row repeat the first: the tile is seamless.
        for j in 0..h {
            assert!((a[j * w + w - 1] - a[j * w]).length() < 1e-5, "{map} row {j}");
        }
    }
}

#[test]
fn tile_is_refused_for_water_that_does_not_repeat_over_the_bake() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (SEA.to_string(), "does not repeat in space"),
        (FOAMY_OCEAN.replace("size = [48.0, 48.0]", "size = [40.0, 48.0]"), "40 m along x"),
        (format!("{FOAMY_OCEAN}cascades = 2\n"), "does not repeat in space"),
    ];
    for (text, reason) in cases {
        let mut w = World::new(Scene::from_toml(&text, "test").unwrap()).unwrap();
        let s = BakeSettings { tile: true, ..BakeSettings::new(FrameRange::new("f", 0, 1).unwrap()) };
        let e = Bake::prepare(&mut w, dir.path(), s).err().unwrap().to_string();
        assert!(e.starts_with("--tile") && e.contains(reason), "{e}");
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "nothing written");
    // Cascades whose patches divide the first tile when asked to.
    let tiling = format!("{FOAMY_OCEAN}cascades = 3\ntile_cascades = true\n");
    let m = bake(
        &tiling,
        dir.path(),
        BakeSettings { tile: true, ..BakeSettings::new(FrameRange::new("f", 0, 0).unwrap()) },
    );
    assert_eq!(m.grid.pixels, [48, 48]);
    let (w, h, a) = read_exr_rgb(&dir.path().join("disp_0000.exr"));
    assert_eq!((w, h), (48, 48));
    assert!(a.iter().all(|d| d.is_finite()));
}

/// Every map file of `frame` in `dir`, as bytes.
fn frame_bytes(dir: &Path, frame: u32) -> Vec<(String, Vec<u8>)> {
    ["disp", "normal", "foam"]
        .iter()
        .map(|m| {
            let name = format!("{m}_{frame:04}.exr");
            let bytes = std::fs::read(dir.join(&name)).unwrap_or_else(|e| panic!("{name}: {e}"));
            (name, bytes)
        })
        .collect()
}

#[test]
fn shards_resumes_single_frames_and_stills_give_the_sequential_bake_foam_included() {
    let range = || FrameRange::new("f", 0, 60).unwrap();
    let sequential = tempfile::tempdir().unwrap();
    let m = bake(FOAMY_OCEAN, sequential.path(), BakeSettings::new(range()));
    assert_eq!(m.maps.len(), 3, "the ocean has foam");
    let foam = read_exr_y(&sequential.path().join("foam_0060.exr"));
    assert!(foam.iter().sum::<f32>() / foam.len() as f32 > 1e-3, "the case must have foam");

    // Shards into one directory.
    let sharded = tempfile::tempdir().unwrap();
    for i in [2, 0, 1] {
        let shard = swell::export::Shard::parse("shard", &format!("{i}/3")).unwrap();
        bake(FOAMY_OCEAN, sharded.path(), BakeSettings { shard, ..BakeSettings::new(range()) });
    }
    // A bake interrupted after frame 20 (the later frames' files lost), then resumed.
    let resumed = tempfile::tempdir().unwrap();
    bake(FOAMY_OCEAN, resumed.path(), BakeSettings::new(range()));
    for frame in 21..=60u32 {
        for (name, _) in frame_bytes(resumed.path(), frame) {
            std::fs::remove_file(resumed.path().join(name)).unwrap();
        }
    }
    bake(FOAMY_OCEAN, resumed.path(), BakeSettings { resume: true, ..BakeSettings::new(range()) });
    // One frame alone, and a bake that starts mid-range.
    let single = tempfile::tempdir().unwrap();
    bake(FOAMY_OCEAN, single.path(), BakeSettings::new(FrameRange::new("f", 47, 47).unwrap()));
    let mid = tempfile::tempdir().unwrap();
    bake(FOAMY_OCEAN, mid.path(), BakeSettings::new(FrameRange::new("f", 40, 60).unwrap()));
    for frame in [0, 1, 21, 40, 47, 59, 60] {
        let want = frame_bytes(sequential.path(), frame);
        assert!(frame_bytes(sharded.path(), frame) == want, "shards, frame {frame}");
        assert!(frame_bytes(resumed.path(), frame) == want, "resumed, frame {frame}");
        if frame == 47 {
            assert!(frame_bytes(single.path(), frame) == want, "single frame {frame}");
        }
        if frame >= 40 {
            assert!(frame_bytes(mid.path(), frame) == want, "mid-range, frame {frame}");
        }
    }
    // A still (a world built and moved straight to the frame's time) has the baked foam.
    let still = world(FOAMY_OCEAN, 47.0 / 24.0);
    assert_eq!(mesh_of(&still).foam, read_exr_y(&sequential.path().join("foam_0047.exr")));
}

#[test]
fn an_fft_loop_closes_in_every_map_foam_included() {
    // A 2 s loop at 24 fps: frame 48 is frame 0 again, byte for byte.
    let looping = format!("{FOAMY_OCEAN}loop_period = 2.0\n");
    let dir = tempfile::tempdir().unwrap();
    let mut s = BakeSettings::new(FrameRange::new("f", 0, 48).unwrap());
    s.loop_period_s = Some(2.0);
    let m = bake(&looping, dir.path(), s);
    assert_eq!(m.loop_frames, Some(48));
    for ((name, a), (_, b)) in frame_bytes(dir.path(), 48).into_iter().zip(frame_bytes(dir.path(), 0)) {
        assert!(a == b, "{name} differs from frame 0's");
    }
    let bytes = |frame| frame_bytes(dir.path(), frame).into_iter().map(|(_, b)| b).collect::<Vec<_>>();
    assert!(bytes(24)[2] != bytes(0)[2], "half a loop on, the foam differs");
}

#[test]
fn a_short_loop_keeps_the_long_waves_moving() {
    // Paper 003's floor() froze every wave longer than the loop: a 2 s loop on this 20 m/s sea
    // (peak period about 11 s) stood nearly still. Rounded to the nearest non-zero multiple, the
    // sea moves from frame to frame about as much as the sea without a loop.
    let change = |text: &str| {
        let (_, a, _) = model_fields(text, 3.0);
        let (_, b, _) = model_fields(text, 3.0 + 1.0 / 24.0);
        (a.iter().zip(&b).map(|(p, q)| f64::from(p.y - q.y).powi(2)).sum::<f64>() / a.len() as f64).sqrt()
    };
    let unlooped = change(FOAMY_OCEAN);
    let looped = change(&format!("{FOAMY_OCEAN}loop_period = 2.0\n"));
    // Comparable, not equal: at 2 s every frequency is a multiple of π rad/s, and this small
    // patch's waves (periods up to 5.5 s) all speed up to at least that.
    assert!(looped > 0.5 * unlooped && looped < 3.0 * unlooped, "{looped} vs {unlooped}");
}

#[test]
fn a_turned_or_scaled_patch_is_refused_by_bake_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    for key in ["yaw_deg = 30.0", "uniform_scale = 2.0"] {
        let text = SEA.replace("center = [5.0, -2.0]", &format!("center = [5.0, -2.0]\n{key}"));
        let mut w = World::new(Scene::from_toml(&text, "test").unwrap()).unwrap();
        let s = BakeSettings::new(FrameRange::new("f", 0, 1).unwrap());
        let e = Bake::prepare(&mut w, dir.path(), s).err().unwrap().to_string();
        assert!(e.starts_with("water.yaw_deg") && e.contains("uniform_scale = 1"), "{e}");
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "nothing written");
}
