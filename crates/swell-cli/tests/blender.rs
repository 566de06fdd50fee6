//! The Blender round trip (issue 20): a bake imported by `tools/blender/swell_import_bake.py` in
//! headless Blender shows, at scene frame k, the surface `swell export` writes for time k / fps,
//! after Blender's axis change (X, Y, Z) = (x, -z, y); a looping bake wraps frames beyond its end.
//!
//! Needs `blender` on PATH (Debian's `blender` package; `.ci/run` installs it). Without it the
//! tests print that they skipped, unless `SWELL_REQUIRE_BLENDER=1` (set by `.ci/run`), which makes
//! a missing Blender a failure.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const SWELL: &str = env!("CARGO_BIN_EXE_swell");
const SCRIPT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tools/blender/swell_import_bake.py");

/// Largest allowed distance (m, per coordinate) between Blender's vertex and swell's.
const TOLERANCE_M: f64 = 1e-4;

/// Longest a Blender run may take before the test fails (it takes about a second).
const BLENDER_TIMEOUT: Duration = Duration::from_secs(300);

/// Whether Blender can run; prints why not (or fails under `SWELL_REQUIRE_BLENDER=1`).
fn blender_available() -> bool {
    let ok = Command::new("blender")
        .args(["--background", "--factory-startup", "--version"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !ok {
        assert!(
            std::env::var_os("SWELL_REQUIRE_BLENDER").is_none_or(|v| v != "1"),
            "SWELL_REQUIRE_BLENDER=1 but `blender --version` does not run: install Blender (apt-get install blender)"
        );
        eprintln!(
            "skipped: `blender` is not on PATH (apt-get install --no-install-recommends blender to run this test)"
        );
    }
    ok
}

fn swell(args: &[&str]) -> Output {
    let o = Command::new(SWELL).args(args).output().unwrap();
    assert!(o.status.success(), "swell {args:?}: {}", String::from_utf8_lossy(&o.stderr));
    o
}

/// A preset's text with `replacements` applied, each of which must match; written to `dir/name`.
fn scene(dir: &Path, name: &str, preset: &str, replacements: &[(&str, &str)]) -> PathBuf {
    let mut text = preset.to_string();
    for (from, to) in replacements {
        assert!(text.contains(from), "the preset no longer contains `{from}`");
        text = text.replacen(from, to, 1);
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Runs the import script headless at scene `frame` and returns its dump (frame, vertices).
fn blender_vertices(bake: &Path, frame: i64, out: &Path) -> serde_json::Value {
    let frame_s = frame.to_string();
    let mut child = Command::new("blender")
        .args(["--background", "--factory-startup", "--python", SCRIPT, "--"])
        .args(["--bake", bake.to_str().unwrap(), "--frame", &frame_s, "--dump-vertices", out.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > BLENDER_TIMEOUT {
            child.kill().unwrap();
            panic!("Blender took longer than {BLENDER_TIMEOUT:?}");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let o = child.wait_with_output().unwrap();
    let log = format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    assert!(o.status.success() && out.is_file(), "Blender failed:\n{log}");
    // Blender reports a failing Python script without a failing exit status.
    assert!(!log.contains("Traceback"), "the import script raised:\n{log}");
    serde_json::from_slice(&std::fs::read(out).unwrap()).unwrap()
}

/// The water's vertices of a `swell export --format obj` at `time` seconds, in swell's axes.
fn swell_vertices(scene: &Path, time: f64, out: &Path) -> Vec<[f64; 3]> {
    let time = time.to_string();
    swell(&[
        "export",
        "--scene",
        scene.to_str().unwrap(),
        "--format",
        "obj",
        "--time",
        &time,
        "--out",
        out.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(out).unwrap();
    let mut in_water = false;
    let mut verts = vec![];
    for line in text.lines() {
        if let Some(name) = line.strip_prefix("o ") {
            in_water = name.trim() == "water";
        } else if let (true, Some(v)) = (in_water, line.strip_prefix("v ")) {
            let c: Vec<f64> = v.split_whitespace().map(|x| x.parse().unwrap()).collect();
            verts.push([c[0], c[1], c[2]]);
        }
    }
    assert!(!verts.is_empty(), "no water vertices in {}", out.display());
    verts
}

/// Largest per-coordinate difference between Blender's world vertices and swell's, converted to
/// Blender's axes: (X, Y, Z) = (x, -z, y).
fn max_error(blender: &serde_json::Value, swell: &[[f64; 3]]) -> f64 {
    let verts = blender["vertices"].as_array().unwrap();
    assert_eq!(verts.len(), swell.len(), "Blender's grid and swell's differ in vertex count");
    verts
        .iter()
        .zip(swell)
        .map(|(b, s)| {
            let b: Vec<f64> = b.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
            let expected = [s[0], -s[2], s[1]];
            (0..3).map(|k| (b[k] - expected[k]).abs()).fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

#[test]
fn blender_shows_the_exported_surface_at_a_frame_of_a_gerstner_bake() {
    if !blender_available() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let sea = scene(
        d,
        "sea.toml",
        include_str!("../../swell/presets/sea.toml"),
        &[("cells = [256, 256]", "cells = [32, 32]")],
    );
    let bake = d.join("bake");
    swell(&["bake", "--scene", sea.to_str().unwrap(), "--frames", "0..5", "--quiet", "--out", bake.to_str().unwrap()]);

    let frame = 3;
    let got = blender_vertices(&bake, frame, &d.join("b3.json"));
    assert_eq!(got["frame"], frame);
    assert!(got["foam"].is_null(), "a Gerstner bake has no foam map: {}", got["foam"]);
    let want = swell_vertices(&sea, frame as f64 / 24.0, &d.join("s3.obj"));
    let err = max_error(&got, &want);
    eprintln!("sea, 33 x 33 vertices, frame {frame}: max |Blender - swell export| = {err:.3e} m");
    assert!(err < TOLERANCE_M, "frame {frame}: Blender is {err} m from swell's export");
    // The comparison can fail: frame 0's surface is far from frame 3's.
    let other = swell_vertices(&sea, 0.0, &d.join("s0.obj"));
    assert!(max_error(&got, &other) > 100.0 * TOLERANCE_M);
    // A directory that is not a bake: the script exits non-zero, naming the file.
    let o = Command::new("blender")
        .args(["--background", "--factory-startup", "--python", SCRIPT, "--", "--bake", d.to_str().unwrap()])
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && log.contains("bake.json does not exist"), "{log}");
    // Beyond a bake that is not a loop, Blender holds the last frame.
    let held = blender_vertices(&bake, 9, &d.join("b9.json"));
    let last = swell_vertices(&sea, 5.0 / 24.0, &d.join("s5.obj"));
    assert!(max_error(&held, &last) < TOLERANCE_M);
}

#[test]
fn blender_wraps_a_looping_tiled_fft_bake() {
    if !blender_available() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    // A 64 m patch on a 32² FFT grid, periodic over the patch (so --tile maps wrap), looping every
    // 8 s: at 2 fps the loop is 16 frames. (The period must be long against the slowest wave's,
    // here 6.4 s: a loop quantises frequencies to multiples of 2 pi / period, so a 1 s loop would
    // freeze every wave this grid resolves.)
    let ocean = scene(
        d,
        "ocean.toml",
        include_str!("../../swell/presets/ocean.toml"),
        &[
            ("size = [400.0, 400.0]", "size = [64.0, 64.0]"),
            ("cells = [400, 400]", "cells = [32, 32]"),
            ("grid = 256", "grid = 32"),
            ("patch_size = 256.0", "patch_size = 64.0\nloop_period = 8.0"),
        ],
    );
    let bake = d.join("bake");
    swell(&[
        "bake",
        "--scene",
        ocean.to_str().unwrap(),
        "--frames",
        "0..15",
        "--fps",
        "2",
        "--tile",
        "--normal-space",
        "tangent-gl",
        "--quiet",
        "--out",
        bake.to_str().unwrap(),
    ]);
    let manifest: serde_json::Value = serde_json::from_slice(&std::fs::read(bake.join("bake.json")).unwrap()).unwrap();
    assert_eq!(manifest["loop_frames"], 16);
    assert_eq!(manifest["grid"]["pixels"], serde_json::json!([32, 32]));
    assert!(bake.join("foam_0000.exr").is_file());

    // Scene frames 3, 19 (= 3 + 16) and -13 (= 3 - 16) all show bake frame 3, time 1.5 s.
    let want3 = swell_vertices(&ocean, 3.0 / 2.0, &d.join("s3.obj"));
    let last = swell_vertices(&ocean, 15.0 / 2.0, &d.join("s15.obj"));
    let first = swell_vertices(&ocean, 0.0, &d.join("s0.obj"));
    for frame in [3, 19, -13] {
        let got = blender_vertices(&bake, frame, &d.join(format!("b{frame}.json")));
        let foam = &got["foam"];
        assert!(foam["image"].as_str().unwrap().ends_with("foam_0000.exr") && foam["cyclic"] == true, "{foam}");
        let err = max_error(&got, &want3);
        eprintln!("fft loop, 33 x 33 vertices (tiled 32² maps), scene frame {frame}: max error {err:.3e} m");
        assert!(err < TOLERANCE_M, "scene frame {frame}: Blender is {err} m from swell's frame 3");
        // Held (not wrapped) sequences would show the last or first frame, which differ.
        assert!(max_error(&got, &last) > 100.0 * TOLERANCE_M && max_error(&got, &first) > 100.0 * TOLERANCE_M);
    }
    let got = blender_vertices(&bake, 29, &d.join("b29.json"));
    let err = max_error(&got, &swell_vertices(&ocean, 13.0 / 2.0, &d.join("s13.obj")));
    assert!(err < TOLERANCE_M, "scene frame 29: {err} m from swell's frame 13");
}
