//! End-to-end tests of `swell render --out FRAME.exr` (issue 32, HDR out): the frame's linear
//! scene radiance as float RGB, the same bytes on one and two threads, and the PNG of the same
//! frame is exactly these pixels through the exposure, the tone curve and the sRGB curve: with
//! the preset's EV100, and metered (`--auto-exposure`).

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

/// The byte of linear value `c` written out by hand: times `k`, Narkowicz's ACES fit at 0.6 x,
/// the sRGB curve, rounded.
fn by_hand(c: f32, k: f64) -> u8 {
    let y = 0.6 * f64::from(c) * k;
    let d = (y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14)).clamp(0.0, 1.0);
    let e = if d <= 0.0031308 { 12.92 * d } else { 1.055 * d.powf(1.0 / 2.4) - 0.055 };
    (e * 255.0 + 0.5) as u8
}

#[test]
fn the_exr_is_the_png_before_exposure_and_the_tone_curve() {
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
    fb.encode_rgba8(&render.display_encoding(), &mut rgba);
    let png = image::open(dir.path().join("frame.png")).unwrap().to_rgba8();
    assert_eq!(png.as_raw(), &rgba, "the PNG is not the EXR through exposure and the tone curve");
    // And by the formulas, apart from rounding at a byte's edge: the preset's EV100 13.5 exposes
    // 20,000 cd/m² by 20,000 / (1.2 × 2^13.5).
    let k = 20_000.0 / (1.2 * 2f64.powf(13.5));
    assert_eq!(render.ev100, Some(13.5));
    let mut off = 0;
    for (c, px) in radiance.iter().zip(png.pixels()) {
        for (v, b) in [c.x, c.y, c.z].into_iter().zip(px.0) {
            let want = by_hand(v, k);
            assert!(want.abs_diff(b) <= 1, "{v} gives {b}, by hand {want}");
            off += usize::from(want != b);
        }
    }
    assert!(off < radiance.len() / 100, "{off} channels a level off");

    // Metered: the frame's log-average luminance is exposed to 0.18.
    ok(
        dir.path(),
        &["render", "--out", "auto.png", "--auto-exposure", "--preset", "evening", "--size", "160x90", "--time", "1.5"],
    );
    let auto = image::open(dir.path().join("auto.png")).unwrap().to_rgba8();
    let samples: Vec<f64> = radiance
        .chunks(160)
        .step_by(4)
        .flat_map(|row| row.iter().step_by(4))
        .map(|c| f64::from(0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z).max(5e-6).log2())
        .collect();
    let average = (samples.iter().sum::<f64>() / samples.len() as f64).exp2();
    let k = 0.18 / average;
    let close = radiance.iter().zip(auto.pixels()).filter(|(c, px)| by_hand(c.y, k).abs_diff(px.0[1]) <= 1).count();
    assert!(close > radiance.len() * 99 / 100, "{close} of {} green bytes follow the metered exposure", radiance.len());
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

#[test]
fn exposure_flags_are_checked_and_a_stop_doubles_the_exposed_radiance() {
    let dir = tempfile::tempdir().unwrap();
    let o = swell(dir.path(), &["render", "--preset", "sea", "--ev100", "30", "--out", "x.png"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("--ev100 = 30 is outside [-6, 24]"), "{err}");
    let o = swell(dir.path(), &["render", "--preset", "sea", "--tone-curve", "filmic", "--out", "x.png"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("--tone-curve") && err.contains("aces, clip"), "{err}");
    assert!(files(dir.path()).is_empty(), "a refused run left files behind");
    // With the clip curve, EV100 13 exposes twice as much as 14: a dark pixel's linear value doubles.
    let size = ["--size", "64x36", "--tone-curve", "clip"];
    ok(dir.path(), &[&["render", "--preset", "sea", "--ev100", "14", "--out", "a.png"][..], &size].concat());
    ok(dir.path(), &[&["render", "--preset", "sea", "--ev100", "13", "--out", "b.png"][..], &size].concat());
    let lin = |p: &str| -> Vec<f64> {
        let img = image::open(dir.path().join(p)).unwrap().to_rgb8();
        img.as_raw()
            .iter()
            .map(|&b| {
                let e = f64::from(b) / 255.0;
                if e <= 0.04045 {
                    e / 12.92
                } else {
                    ((e + 0.055) / 1.055).powf(2.4)
                }
            })
            .collect()
    };
    let (a, b) = (lin("a.png"), lin("b.png"));
    let pairs: Vec<(f64, f64)> = a.into_iter().zip(b).filter(|(x, y)| *x > 0.05 && *y < 0.9).collect();
    assert!(pairs.len() > 500, "{} unclipped channels", pairs.len());
    let ratio = pairs.iter().map(|(x, y)| y / x).sum::<f64>() / pairs.len() as f64;
    assert!((ratio - 2.0).abs() < 0.05, "one stop gives {ratio}");
}
