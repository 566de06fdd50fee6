//! End-to-end tests of `swell bench`: the real binary, one timed run per row (hidden `--runs 1`).

use std::path::Path;
use std::process::{Command, Output};

fn swell(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swell")).args(args).current_dir(dir).output().expect("run swell")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Checks that `dir` holds NAME.md, NAME.json and a readable NAME.png, and returns the md and json.
fn results(dir: &Path, name: &str) -> (String, serde_json::Value) {
    let md = std::fs::read_to_string(dir.join(format!("{name}.md"))).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join(format!("{name}.json"))).unwrap()).unwrap();
    let png = image::open(dir.join(format!("{name}.png"))).unwrap().to_rgb8();
    let (w, h) = png.dimensions();
    assert!(w >= 400 && h >= 300, "plot is {w}x{h}");
    // Something was drawn: the plot is not a blank page (curves and text are dark or coloured).
    let inked = png.pixels().filter(|p| p.0.iter().any(|&c| c < 200)).count();
    assert!(inked > (w * h / 100) as usize, "plot looks blank ({inked} inked pixels)");
    assert_eq!(json["experiment"], name);
    (md, json)
}

#[test]
fn grid_size_writes_the_papers_figures_beside_swells() {
    let dir = tempfile::tempdir().unwrap();
    let o = swell(dir.path(), &["bench", "grid-size", "--runs", "1", "--out", "res"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = dir.path().join("res");
    let (md, json) = results(&out, "grid-size");
    // Paper 000 table 4.1, first and last rows, in ticks, with the growth columns.
    assert!(md.contains("| 100x100 |") && md.contains("| 42782 |"), "{md}");
    assert!(md.contains("| 800x800 |") && md.contains("| 56732 |"), "{md}");
    assert!(md.contains("growth ratio") && md.contains("ticks"), "{md}");
    let points = json["series"][0]["points"].as_array().unwrap();
    assert_eq!(points.len(), 8);
    for p in points {
        let median = p["swell"]["median_ms"].as_f64().unwrap();
        assert!(median > 0.0 && median.is_finite(), "{p}");
        assert_eq!(p["swell"]["runs"], 1);
    }
    assert_eq!(json["paper_unit"], "ticks");
    assert!(json["machine"]["logical_cores"].as_u64().unwrap() >= 1);
    // The table also goes to stdout, and nothing else is left in the directory.
    assert!(String::from_utf8_lossy(&o.stdout).contains("| 42782 |"));
    let mut names: Vec<_> =
        std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    names.sort();
    assert_eq!(names, ["grid-size.json", "grid-size.md", "grid-size.png"]);
}

#[test]
fn realtime_reports_frames_per_second_of_every_preset() {
    let dir = tempfile::tempdir().unwrap();
    let o = swell(dir.path(), &["bench", "realtime", "--runs", "1", "--out", "."]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (md, json) = results(dir.path(), "realtime");
    assert!(md.contains("frames per second") && md.contains("| sea |"), "{md}");
    assert_eq!(json["plot"], "fps");
}

#[test]
fn unknown_experiments_and_bad_run_counts_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let o = swell(dir.path(), &["bench", "tsunami", "--out", "res"]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(e.contains("unknown experiment `tsunami`") && e.contains("grid-size") && e.contains("all"), "{e}");
    let o = swell(dir.path(), &["bench", "realtime", "--runs", "0", "--out", "res"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--runs"), "{}", stderr(&o));
    assert!(!dir.path().join("res").exists(), "a refused run created its output directory");
}

#[test]
fn ocean_writes_each_stage_per_grid_and_keeps_its_stdout_form() {
    let dir = tempfile::tempdir().unwrap();
    let o = swell(dir.path(), &["bench", "ocean", "--runs", "1", "--out", "res"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (md, json) = results(&dir.path().join("res"), "ocean");
    assert!(md.contains("| 64x64 |") && md.contains("| 1024x1024 |"), "{md}");
    let series = json["series"].as_array().unwrap();
    let names: Vec<&str> = series.iter().map(|s| s["name"].as_str().unwrap()).collect();
    assert!(names.iter().any(|n| n.starts_with("evolve")) && names.iter().any(|n| n.starts_with("FFTs")), "{names:?}");
    assert!(names.iter().any(|n| n.starts_with("foam")) && names.iter().any(|n| n.starts_with("displaced mesh")));
    for s in series {
        let points = s["points"].as_array().unwrap();
        assert_eq!(points.len(), 5, "{s}");
        for p in points {
            let (median, min, max) = (
                p["swell"]["median_ms"].as_f64().unwrap(),
                p["swell"]["min_ms"].as_f64().unwrap(),
                p["swell"]["max_ms"].as_f64().unwrap(),
            );
            assert!(median.is_finite() && min <= median && median <= max, "{p}");
        }
    }
    // The stages are parts of the simulation: their medians cannot add up to much more than it.
    let median = |s: usize, row: usize| series[s]["points"][row]["swell"]["median_ms"].as_f64().unwrap();
    let sim = median(0, 4);
    let parts: f64 = (1..4).map(|s| median(s, 4)).sum();
    assert!(parts <= 1.5 * sim + 0.5, "stages {parts} ms against the simulation's {sim} ms");
    // `--grid N --json` still prints one JSON object and writes nothing.
    let o = swell(dir.path(), &["bench", "ocean", "--grid", "16", "--steps", "2", "--json", "--out", "none"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["grid"], 16);
    assert!(v["median_ms"].as_f64().unwrap() > 0.0 && v["stages"]["fft_ms"].is_number());
    assert!(!dir.path().join("none").exists());
}
