//! End-to-end tests of `swell render --out FRAME.exr` (issue 32, HDR out): the frame's linear
//! scene radiance as float RGB, the same bytes on one and two threads, and the PNG of the same
//! frame is exactly these pixels through the renderer's exposure and sRGB curve.

use std::path::Path;
use std::process::{Command, Output};

use swell::raster::Framebuffer;

mod common;
use common::{files, read_exr_rgb};

fn swell(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swell")).args(args).current_dir(dir).output().expect("run swell")
}

fn ok(dir: &Path, args: &[&str]) {
    let o = swell(dir, args);
    assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
}

const FRAME: [&str; 6] = ["--preset", "evening", "--size", "160x90", "--time", "1.5"];

fn render(dir: &Path, out: &str, threads: &str) {
    let mut args = vec!["render", "--out", out, "--threads", threads];
    args.extend(FRAME);
    ok(dir, &args);
}

#[test]
fn the_exr_is_the_png_before_exposure_and_the_srgb_curve() {
    let dir = tempfile::tempdir().unwrap();
    render(dir.path(), "one.exr", "1");
    render(dir.path(), "two.exr", "2");
    render(dir.path(), "frame.png", "2");
    let written = files(dir.path());
    assert_eq!(written["one.exr"], written["two.exr"], "the EXR depends on the thread count");

    let radiance = read_exr_rgb(&dir.path().join("one.exr"));
    assert_eq!(radiance.len(), 160 * 90);
    assert!(radiance.iter().all(|c| c.is_finite() && c.min_element() >= 0.0), "radiance must be finite, >= 0");
    // Linear radiance, not display values: the evening sun's glitter and sky are not clipped to 1
    // or quantised to 1/255.
    let levels: std::collections::BTreeSet<u32> = radiance.iter().map(|c| c.x.to_bits()).collect();
    assert!(levels.len() > 2000, "only {} distinct red values: quantised?", levels.len());

    let render = swell::scene::preset("evening").unwrap().render;
    let mut fb = Framebuffer::new(160, 90);
    fb.color.copy_from_slice(&radiance);
    let mut rgba = Vec::new();
    fb.encode_rgba8(render.exposure, render.gamma, &mut rgba);
    let png = image::open(dir.path().join("frame.png")).unwrap().to_rgba8();
    assert_eq!(png.as_raw(), &rgba, "the PNG is not the EXR through exposure and the sRGB curve");
}

#[test]
fn an_exr_is_one_frame_and_a_refused_run_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let o = swell(dir.path(), &["render", "--preset", "sea", "--frames", "3", "--out", "clip.exr"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--out") && err.contains("clip.exr") && err.contains("one frame"), "{err}");
    assert!(files(dir.path()).is_empty(), "a refused run left files behind");
}
