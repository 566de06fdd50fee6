//! The promises of docs/baking.md for the FFT ocean, whose foam remembers earlier crests, through
//! the real binary: a killed and resumed bake, shards and a lone frame give the uninterrupted bake's
//! bytes, foam included; `--tile` only where the water repeats; scenes with only `[water]`; the
//! warning for a loop too short for the sea.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

mod common;
use common::{files, read_exr_y, stderr, swell, SWELL};

/// A water-only scene: a rough 128² FFT ocean with foam over its own 96 m patch.
const OCEAN: &str = "[water]\nmodel = \"fft\"\ngrid = 128\npatch_size = 96.0\nwind_speed = 20.0\n\
                     choppiness = 1.5\nsize = [96.0, 96.0]\ncells = [96, 96]\n";

fn write_scene(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn bake_args(scene: &Path, frames: &str, out: &Path, extra: &[&str]) -> Vec<String> {
    let mut args: Vec<String> = ["bake", "--scene", scene.to_str().unwrap(), "--frames", frames, "--quiet", "--out"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    args.push(out.to_str().unwrap().into());
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

#[test]
fn killed_resumed_sharded_and_single_frame_ocean_bakes_equal_the_whole_one_foam_included() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = write_scene(tmp.path(), "ocean.toml", OCEAN);
    let dir = |name: &str| tmp.path().join(name);
    let run = |args: Vec<String>| {
        let o = Command::new(SWELL).args(&args).output().unwrap();
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        o
    };
    // PNGs, compression and one thread make each frame slow enough to kill mid-way; the PNG range is
    // given because its default comes from the range's first frame, which the lone frame changes.
    let slow = ["--png", "16", "--png-range", "4", "--exr-compression", "zip", "--threads", "1"];
    run(bake_args(&scene, "0..59", &dir("whole"), &slow));
    let whole = files(&dir("whole"));
    assert_eq!(whole.len(), 1 + 60 * 7, "disp, normal and foam, EXR and PNG, and the record, per frame");

    let mut child = Command::new(SWELL).args(bake_args(&scene, "0..59", &dir("killed"), &slow)).spawn().unwrap();
    let start = Instant::now();
    while !dir("killed").join("foam_0005.png").exists() {
        assert!(start.elapsed() < Duration::from_secs(120), "the bake never got going");
        assert!(child.try_wait().unwrap().is_none(), "the bake ended before it could be killed");
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(!dir("killed").join("foam_0059.exr").exists(), "the bake finished before it was killed");
    let resumed = run([bake_args(&scene, "0..59", &dir("killed"), &slow), vec!["--resume".into()]].concat());
    assert!(stderr(&resumed).contains("already complete"), "{}", stderr(&resumed));

    for shard in ["3/4", "0/4", "2/4", "1/4"] {
        run([bake_args(&scene, "0..59", &dir("sharded"), &slow), vec!["--shard".into(), shard.into()]].concat());
    }
    run(bake_args(&scene, "42..42", &dir("single"), &slow));

    for (name, bytes) in &whole {
        if name == "bake.json" {
            continue;
        }
        assert!(files(&dir("killed"))[name] == *bytes, "{name} differs after kill + resume");
        assert!(files(&dir("sharded"))[name] == *bytes, "{name} differs in the shards");
    }
    let single = files(&dir("single"));
    for map in ["disp", "normal", "foam"] {
        for ext in ["exr", "png"] {
            let name = format!("{map}_0042.{ext}");
            assert!(single[&name] == whole[&name], "{name} of a one-frame bake differs");
        }
    }
}

#[test]
fn water_only_scenes_bake_export_and_give_stats() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = write_scene(tmp.path(), "ocean.toml", OCEAN);
    let s = scene.to_str().unwrap();
    let o =
        swell(&["bake", "--scene", s, "--frames", "0..1", "--quiet", "--out", tmp.path().join("b").to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(tmp.path().join("b/foam_0001.exr").is_file());
    let glb = tmp.path().join("o.glb");
    let o = swell(&["export", "--scene", s, "--out", glb.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(glb.is_file());
    let o = swell(&["stats", "--scene", s, "--time", "12"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stats: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(stats["surface_cells"], serde_json::json!([96, 96]));
    let foam = stats["foam_coverage"].as_f64().unwrap();
    assert!(foam > 1e-3 && foam < 0.5, "{foam}");
    // The stats' foam is the baked foam map's mean at that time (frame 288 at 24 fps).
    let o = swell(&[
        "bake",
        "--scene",
        s,
        "--frames",
        "288..288",
        "--quiet",
        "--out",
        tmp.path().join("c").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let map = read_exr_y(&tmp.path().join("c/foam_0288.exr"));
    let mean = map.iter().map(|&v| f64::from(v)).sum::<f64>() / map.len() as f64;
    assert!((mean - foam).abs() < 1e-6, "baked foam {mean} vs stats {foam}");

    // A scene with neither water nor terrain names what is missing, not `.`.
    let empty = write_scene(tmp.path(), "camera.toml", "[camera]\neye = [0.0, 5.0, 9.0]\ntarget = [0.0, 0.0, 0.0]\n");
    let o = swell(&[
        "bake",
        "--scene",
        empty.to_str().unwrap(),
        "--frames",
        "0..1",
        "--out",
        tmp.path().join("d").to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).starts_with("error: water: the scene has no [water]"), "{}", stderr(&o));
    let o = swell(&["stats", "--scene", empty.to_str().unwrap()]);
    assert!(stderr(&o).starts_with("error: water: the scene has no [water]"), "{}", stderr(&o));
}

#[test]
fn tile_is_refused_with_the_reason_where_the_water_does_not_repeat() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let tile = |scene: &Path| Command::new(SWELL).args(bake_args(scene, "0..0", &out, &["--tile"])).output().unwrap();
    let o = tile(&write_scene(tmp.path(), "ok.toml", OCEAN));
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::remove_dir_all(&out).unwrap();
    let cascades = write_scene(tmp.path(), "c.toml", &format!("{OCEAN}cascades = 2\n"));
    let o = tile(&cascades);
    assert!(stderr(&o).starts_with("error: --tile: this water does not repeat in space"), "{}", stderr(&o));
    let o = swell(&["bake", "--preset", "sea", "--frames", "0..0", "--tile", "--out", out.to_str().unwrap()]);
    assert!(stderr(&o).starts_with("error: --tile: this water does not repeat in space"), "{}", stderr(&o));
    let off = write_scene(tmp.path(), "off.toml", &OCEAN.replace("size = [96.0, 96.0]", "size = [100.0, 96.0]"));
    let o = tile(&off);
    assert!(stderr(&o).contains("repeats every 96 m but the bake's grid is 100 m along x"), "{}", stderr(&o));
    assert!(!out.exists(), "a refused bake writes nothing");
    let tiling = write_scene(tmp.path(), "t.toml", &format!("{OCEAN}cascades = 2\ntile_cascades = true\n"));
    let o = tile(&tiling);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_loop_too_short_for_the_sea_warns_on_stderr() {
    let tmp = tempfile::tempdir().unwrap();
    // Two bakes, so two directories: a directory holds one bake.
    let bake = |extra: &str| {
        let scene = write_scene(tmp.path(), "l.toml", &format!("{OCEAN}{extra}"));
        let out = tmp.path().join(format!("out-{}", extra.len()));
        Command::new(SWELL).args(bake_args(&scene, "0..0", &out, &[])).output().unwrap()
    };
    let o = bake("loop_period = 2.0\n");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).starts_with("warning: water.loop_period = 2 s is shorter than the sea's period"),
        "{}",
        stderr(&o)
    );
    let o = bake("loop_period = 400.0\n");
    assert!(o.status.success() && !stderr(&o).contains("warning"), "{}", stderr(&o));
}
