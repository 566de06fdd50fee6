//! Issue 36 end to end: the example measured sea (docs/examples/measured-sea: a CSV table beside
//! its scene) through `swell stats`, `render`, `export` and `bake`, a copy of it moved elsewhere
//! (the table is found beside the scene), and a bad table refused naming file, line and field.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn swell(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swell")).args(args).current_dir(dir).output().expect("the swell binary runs")
}

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/examples/measured-sea").join(name)
}

/// The example scene made small and cheap, written with its table into `dir`.
fn small_copy(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(example("buoy.toml")).unwrap();
    let text = text
        .replace("cells = [300, 300]", "cells = [60, 60]")
        .replace("width = 1280", "width = 160")
        .replace("height = 720", "height = 90")
        .replace("grid = 256", "grid = 128");
    std::fs::write(dir.join("buoy.toml"), text).unwrap();
    std::fs::copy(example("buoy.csv"), dir.join("buoy.csv")).unwrap();
    dir.join("buoy.toml")
}

#[test]
fn stats_of_the_example_report_the_input_and_the_realised_sea() {
    let dir = tempfile::tempdir().unwrap();
    let scene = example("buoy.toml");
    let out = swell(dir.path(), &["stats", "--scene", scene.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let f = |k: &str| v[k].as_f64().unwrap_or_else(|| panic!("{k} in {v}"));
    // The table's own values, by wavespectra 4.9 (printed when the file was made): Hs 2.3324 m,
    // Tp 13.326 s, Dpm 320°, Dspr 34.63°.
    assert!((f("hs_expected_m") - 2.3324).abs() < 1e-3, "{v}");
    assert!((f("tp_expected_s") - 13.326).abs() < 1e-2, "{v}");
    assert!((f("dpm_expected_deg") - 320.0).abs() < 1e-3, "{v}");
    assert!((f("dspr_expected_deg") - 34.63).abs() < 1e-2, "{v}");
    // The realised sea within its sampling scatter (docs/embedding.md states it).
    assert!((f("hs_realised_m") / f("hs_expected_m") - 1.0).abs() < 0.15, "{v}");
    assert!((f("tp_realised_s") / f("tp_expected_s") - 1.0).abs() < 0.12, "{v}");
    assert!((f("dpm_realised_deg") - f("dpm_expected_deg")).abs() < 12.0, "{v}");
    assert!((f("dspr_realised_deg") - f("dspr_expected_deg")).abs() < 4.0, "{v}");
}

#[test]
fn the_example_renders_exports_and_bakes_from_a_copy_elsewhere() {
    let dir = tempfile::tempdir().unwrap();
    let scene = small_copy(dir.path());
    let s = scene.to_str().unwrap();
    for args in [
        vec!["render", "--scene", s, "--out", "buoy.png"],
        vec!["export", "--scene", s, "--out", "buoy.glb"],
        vec!["bake", "--scene", s, "--frames", "2", "--out", "bake"],
    ] {
        let out = swell(dir.path(), &args);
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    }
    assert!(dir.path().join("buoy.png").metadata().unwrap().len() > 1000);
    assert!(dir.path().join("buoy.glb").metadata().unwrap().len() > 1000);
    assert!(dir.path().join("bake/bake.json").exists());
}

#[test]
fn a_bad_table_is_refused_naming_the_file_the_line_and_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let scene = small_copy(dir.path());
    let csv = std::fs::read_to_string(dir.path().join("buoy.csv")).unwrap();
    let cases = [
        (
            csv.replacen("freq_hz,dir_deg,efth", "freq,dir,efth", 1),
            "buoy.csv: line 3: the first column `freq` names no unit",
        ),
        (csv.lines().take(500).collect::<Vec<_>>().join("\n"), "buoy.csv: no row for (freq_hz = "),
        (csv.replacen("0.035,15,", "0.035,15,-", 1), "buoy.csv: efth[0][1] = -"),
        (format!("{csv}0.035,15,1\n"), "is repeated"),
    ];
    for (text, expected) in cases {
        std::fs::write(dir.path().join("buoy.csv"), &text).unwrap();
        let out = swell(dir.path(), &["stats", "--scene", scene.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(expected), "{expected}: {err}");
    }
}
