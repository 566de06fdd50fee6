//! Golden image: the `sea` preset rendered small, compared with a committed PNG within a tolerance.
//!
//! Regenerate after an intended change with `SWELL_BLESS=1 cargo test -p swell --test golden_sea`
//! and look at the new image before committing it.

use std::path::PathBuf;

use swell::render::Renderer;
use swell::scene::preset;
use swell::world::World;

const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;

fn render(name: &str, t: f64) -> Vec<u8> {
    let mut scene = preset(name).unwrap();
    scene.render.width = WIDTH;
    scene.render.height = HEIGHT;
    let mut world = World::new(scene).unwrap();
    world.update(t).unwrap();
    let mut rgba = Vec::new();
    let r = world.scene.render;
    Renderer::new().render(&world).encode_rgba8(&r.display_encoding(), &mut rgba);
    rgba
}

/// Compares with the golden file: mean absolute difference under 1 level and no pixel channel more
/// than 40 levels off (a few edge pixels may flip between triangles under a different libm).
fn check(name: &str, rgba: &[u8]) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("tests/golden/{name}-{WIDTH}x{HEIGHT}.png"));
    if std::env::var_os("SWELL_BLESS").is_some() {
        swell::export::write_png(&path, WIDTH, HEIGHT, rgba).unwrap();
        return;
    }
    let golden = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (run with SWELL_BLESS=1 to create it)", path.display()))
        .to_rgba8();
    assert_eq!(golden.dimensions(), (WIDTH, HEIGHT));
    let diffs: Vec<i32> = golden.as_raw().iter().zip(rgba).map(|(&a, &b)| (a as i32 - b as i32).abs()).collect();
    let mean = diffs.iter().sum::<i32>() as f64 / diffs.len() as f64;
    let max = *diffs.iter().max().unwrap();
    assert!(mean < 1.0 && max <= 40, "{name}: mean diff {mean:.3}, max {max} against {}", path.display());
}

#[test]
fn sea_matches_its_golden_image() {
    check("sea", &render("sea", 1.5));
}

#[test]
fn the_golden_comparison_can_fail() {
    // A different time must not pass as the same picture.
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("tests/golden/sea-{WIDTH}x{HEIGHT}.png"));
    if std::env::var_os("SWELL_BLESS").is_some() || !path.exists() {
        return;
    }
    let golden = image::open(&path).unwrap().to_rgba8();
    let other = render("sea", 4.0);
    let mean = golden.as_raw().iter().zip(&other).map(|(&a, &b)| (a as i32 - b as i32).abs()).sum::<i32>() as f64
        / other.len() as f64;
    assert!(mean >= 1.0, "a frame 2.5 s later is within tolerance (mean {mean:.3}): the check is too loose");
}
