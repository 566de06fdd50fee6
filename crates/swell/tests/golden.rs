//! Golden images: small renders compared with stored PNGs within a tolerance, one per shading model
//! (with the water optics, overlays and supersampling switched on in some) and one per preset.
//!
//! Regenerate after an intended change with `SWELL_BLESS=1 cargo test -p swell --test golden`,
//! then LOOK at the images in `crates/swell/tests/golden/` before committing them.

use std::path::PathBuf;

use swell::export::write_png;
use swell::render::Renderer;
use swell::scene::Shading;
use swell::scene::{preset, Scene, PRESETS};
use swell::world::World;

const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;
/// Largest mean absolute difference over all channels, in 8-bit levels: small changes of
/// rounding pass, a changed look does not.
const MAX_MEAN_DIFF: f64 = 1.5;
/// Largest difference of any one channel of any pixel, in 8-bit levels: a few pixels may flip at
/// silhouettes, but no region may change colour.
const MAX_PIXEL_DIFF: u8 = 96;

fn golden_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden").join(format!("{name}.png"))
}

fn render(mut scene: Scene) -> Vec<u8> {
    scene.render.width = WIDTH;
    scene.render.height = HEIGHT;
    let encoding = scene.render.display_encoding();
    let mut world = World::new(scene).unwrap();
    world.update(1.5).unwrap();
    let mut rgba = Vec::new();
    Renderer::new().render(&world).encode_rgba8(&encoding, &mut rgba);
    rgba
}

fn check(name: &str, rgba: &[u8]) {
    let path = golden_path(name);
    if std::env::var_os("SWELL_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        write_png(&path, WIDTH, HEIGHT, rgba).unwrap();
        return;
    }
    let golden = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e}; run with SWELL_BLESS=1 to create it", path.display()))
        .to_rgba8();
    assert_eq!((golden.width(), golden.height()), (WIDTH, HEIGHT), "{name}: golden size");
    let (mut sum, mut max) = (0u64, 0u8);
    for (a, b) in rgba.iter().zip(golden.as_raw()) {
        let d = a.abs_diff(*b);
        sum += d as u64;
        max = max.max(d);
    }
    let mean = sum as f64 / rgba.len() as f64;
    assert!(
        mean <= MAX_MEAN_DIFF && max <= MAX_PIXEL_DIFF,
        "{name}: mean difference {mean:.3} (limit {MAX_MEAN_DIFF}), max {max} (limit {MAX_PIXEL_DIFF})"
    );
}

fn sea_with(shading: Shading) -> Scene {
    let mut scene = preset("sea").unwrap();
    let w = scene.water.as_mut().unwrap();
    w.material.shading = shading;
    w.surface.cells = [96, 96];
    scene
}

#[test]
fn flat_shading_matches_its_golden_image() {
    check("sea_flat", &render(sea_with(Shading::Flat)));
}

#[test]
fn gouraud_shading_matches_its_golden_image() {
    check("sea_gouraud", &render(sea_with(Shading::Gouraud)));
}

#[test]
fn phong_shading_with_a_shallow_bottom_and_texture_matches_its_golden_image() {
    let mut scene = sea_with(Shading::Phong);
    let m = &mut scene.water.as_mut().unwrap().material;
    m.bottom_depth = Some(3.0);
    m.texture = Some("procedural".into());
    m.texture_mix = 0.5;
    check("sea_phong_bottom_texture", &render(scene));
}

#[test]
fn blinn_phong_shading_with_overlays_and_supersampling_matches_its_golden_image() {
    let mut scene = sea_with(Shading::BlinnPhong);
    scene.water.as_mut().unwrap().surface.cells = [24, 24];
    scene.render.wireframe = true;
    scene.render.normals = true;
    scene.render.supersample = 2;
    check("sea_blinn_phong_overlays_ss2", &render(scene));
}

#[test]
fn every_preset_matches_its_golden_image() {
    for p in PRESETS {
        check(&format!("preset_{}", p.name), &render(preset(p.name).unwrap()));
    }
}
