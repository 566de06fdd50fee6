//! End-to-end checks of `swell stats`, `swell bench ocean` and rendering the `ocean` preset: the
//! real binary, run in a temporary directory.

use std::path::Path;
use std::process::{Command, Output};

fn swell(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swell")).args(args).current_dir(dir).output().expect("the swell binary runs")
}

fn json(out: &Output) -> serde_json::Value {
    assert!(out.status.success(), "failed: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("stdout is JSON")
}

#[test]
fn stats_prints_the_realised_sea_state_of_the_ocean_preset() {
    let dir = tempfile::tempdir().unwrap();
    let v = json(&swell(dir.path(), &["stats", "--preset", "ocean", "--time", "2.5"]));
    let (real, expected) = (v["hs_realised_m"].as_f64().unwrap(), v["hs_expected_m"].as_f64().unwrap());
    assert!(expected > 1.0 && (real / expected - 1.0).abs() < 0.2, "Hs {real} vs {expected}");
    let (lo, hi) = (v["min_height_m"].as_f64().unwrap(), v["max_height_m"].as_f64().unwrap());
    assert!(lo < 0.0 && hi > 0.0 && hi - lo > expected);
    assert!(v["peak_period_s"].as_f64().unwrap() > 3.0);
    assert!((0.0..=1.0).contains(&v["foam_coverage"].as_f64().unwrap()));
    assert_eq!(v["time_s"].as_f64(), Some(2.5));
}

#[test]
fn stats_of_the_blender_preset_reports_blenders_grid_and_scale() {
    let dir = tempfile::tempdir().unwrap();
    let v = json(&swell(dir.path(), &["stats", "--preset", "ocean-blender"]));
    // resolution 12 -> 144 -> 256, spatial_size 100, and the highest |height| at t = 0 is wave_scale.
    assert_eq!((v["grid"].as_u64(), v["patch_size_m"].as_f64()), (Some(256), Some(100.0)));
    let (lo, hi) = (v["min_height_m"].as_f64().unwrap(), v["max_height_m"].as_f64().unwrap());
    assert!((hi.max(-lo) - 1.5).abs() < 1e-4, "{lo} {hi}");
}

#[test]
fn stats_reads_scene_files_and_refuses_models_without_a_spectrum() {
    let dir = tempfile::tempdir().unwrap();
    let fft = "version = 1\n[camera]\neye = [0.0, 5.0, 10.0]\ntarget = [0.0, 0.0, 0.0]\n\
               [water]\nmodel = \"fft\"\ngrid = 32\npatch_size = 100.0\nspectrum = \"pierson-moskowitz\"\n";
    std::fs::write(dir.path().join("fft.toml"), fft).unwrap();
    let v = json(&swell(dir.path(), &["stats", "--scene", "fft.toml"]));
    assert_eq!(v["grid"].as_u64(), Some(32));
    let sines = "version = 1\n[camera]\neye = [0.0, 5.0, 10.0]\ntarget = [0.0, 0.0, 0.0]\n[water]\nmodel = \"sines\"\n";
    std::fs::write(dir.path().join("sines.toml"), sines).unwrap();
    let out = swell(dir.path(), &["stats", "--scene", "sines.toml"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("model = \"fft\""));
    let bad = fft.replace("grid = 32", "grid = 48");
    std::fs::write(dir.path().join("bad.toml"), bad).unwrap();
    let out = swell(dir.path(), &["stats", "--scene", "bad.toml"]);
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("water.grid = 48"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn bench_ocean_prints_the_median_and_stages_as_json() {
    let dir = tempfile::tempdir().unwrap();
    let v = json(&swell(dir.path(), &["bench", "ocean", "--grid", "32", "--steps", "3", "--json"]));
    assert_eq!(v["grid"].as_u64(), Some(32));
    assert!(v["median_ms"].as_f64().unwrap() > 0.0);
    for stage in ["evolve_ms", "fft_ms", "foam_ms", "mesh_ms"] {
        assert!(v["stages"][stage].as_f64().unwrap() >= 0.0, "{stage}");
    }
    let out = swell(dir.path(), &["bench", "ocean", "--grid", "100"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--grid = 100"));
}

#[test]
fn the_ocean_preset_renders() {
    let dir = tempfile::tempdir().unwrap();
    let out =
        swell(dir.path(), &["render", "--preset", "ocean", "--size", "160x90", "--time", "1.0", "--out", "o.png"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let img = image::open(dir.path().join("o.png")).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (160, 90));
    // The sea is darker than the sky above it.
    let lum = |y: u32| img.get_pixel(80, y).0.iter().map(|&c| u32::from(c)).sum::<u32>();
    assert!(lum(85) < lum(5));
}
