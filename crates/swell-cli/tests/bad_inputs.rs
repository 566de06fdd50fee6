//! Hostile and malformed inputs, run through the real `swell` binary: each must end with a non-zero
//! exit, an `error: ...` message naming the problem, no panic, and no output file.
//!
//! Every `*.toml` in `tests/bad-inputs/` (except heightmap sidecars, `*.png.toml`) is a scene; its
//! first line may be `# expect: TEXT`, text the error message must contain. Files without that line
//! (e.g. inputs found by the fuzzers, copied in as regressions) are checked for everything else.
//! `tests/bad-inputs/README.md` lists what each file exercises.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Longest any refusal may take: errors are found before any real work.
const TIMEOUT: Duration = Duration::from_secs(60);

fn bad_inputs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad-inputs")
}

/// Runs swell with `args`, killing it after [`TIMEOUT`]; returns (success, stderr).
fn run(args: &[&str]) -> (bool, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_swell"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run swell");
    let mut pipe = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        pipe.read_to_string(&mut s).ok();
        s
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > TIMEOUT {
            child.kill().ok();
            panic!("swell {args:?} still running after {TIMEOUT:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    (status.success(), reader.join().unwrap())
}

/// Checks one refusal; returns a description of what was wrong, if anything.
fn check(label: &str, args: &[&str], expect: Option<&str>, out_dir: &Path) -> Option<String> {
    let (ok, err) = run(args);
    let mut problems = Vec::new();
    if ok {
        problems.push("exited 0".to_string());
    }
    if err.contains("panicked") || err.contains("RUST_BACKTRACE") {
        problems.push("panicked".into());
    }
    if !err.starts_with("error: ") {
        problems.push("message does not start with `error: `".into());
    }
    if let Some(e) = expect {
        if !err.contains(e) {
            problems.push(format!("message does not contain `{e}`"));
        }
    }
    let left: Vec<_> = std::fs::read_dir(out_dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    if !left.is_empty() {
        problems.push(format!("left files {left:?}"));
    }
    (!problems.is_empty()).then(|| format!("{label}: {}\n    stderr: {}", problems.join("; "), err.trim_end()))
}

/// The `# expect: TEXT` of a scene file's first line, if any.
fn expectation(bytes: &[u8]) -> Option<String> {
    let line = bytes.split(|&b| b == b'\n').next()?;
    let line = std::str::from_utf8(line).ok()?;
    line.strip_prefix("# expect: ").map(|s| s.trim().to_string())
}

#[test]
fn every_bad_scene_is_refused_by_name_without_output() {
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(bad_inputs())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy();
            name.ends_with(".toml") && !name.ends_with(".png.toml")
        })
        .collect();
    scenes.sort();
    assert!(scenes.len() >= 40, "only {} bad scenes found", scenes.len());
    let out = tempfile::tempdir().unwrap();
    let png = out.path().join("out.png");
    let gif = out.path().join("out.gif");
    let mut failures = Vec::new();
    for scene in &scenes {
        let expect = expectation(&std::fs::read(scene).unwrap());
        let name = scene.file_name().unwrap().to_string_lossy().to_string();
        let s = scene.to_str().unwrap();
        let forms: [(&str, Vec<&str>); 2] = [
            ("png", vec!["render", "--scene", s, "--out", png.to_str().unwrap()]),
            ("gif", vec!["render", "--scene", s, "--out", gif.to_str().unwrap(), "--frames", "2"]),
        ];
        for (form, args) in forms {
            failures.extend(check(&format!("{name} ({form})"), &args, expect.as_deref(), out.path()));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} bad scenes misbehaved:\n{}",
        failures.len(),
        scenes.len(),
        failures.join("\n")
    );
}

#[test]
fn bad_command_lines_are_refused_by_name_without_output() {
    let out = tempfile::tempdir().unwrap();
    let png = out.path().join("t.png");
    let gif = out.path().join("t.gif");
    let (p, g) = (png.to_str().unwrap(), gif.to_str().unwrap());
    let cases: &[(&[&str], &str)] = &[
        (&["terrain", "--generator", "noise", "--size", "5000", "--out", p], "terrain.size = 5000"),
        (&["terrain", "--generator", "noise", "--size", "99999999999", "--out", p], "--size"),
        (&["terrain", "--generator", "diamond-square", "--size", "100", "--out", p], "2^n + 1"),
        (&["terrain", "--generator", "noise", "--size", "17", "--extent", "inf", "--out", p], "terrain.extent"),
        (&["terrain", "--generator", "noise", "--size", "17", "--extent", "nan", "--out", p], "terrain.extent"),
        (&["terrain", "--generator", "noise", "--size", "17", "--extent=-5", "--out", p], "terrain.extent"),
        (&["terrain", "--generator", "noise", "--size", "17", "--set", "octaves=1e300", "--out", p], "octaves"),
        (&["terrain", "--generator", "noise", "--size", "17", "--set", "amplitude=nan", "--out", p], "amplitude"),
        (&["terrain", "--generator", "noise", "--size", "17", "--set", "amplitude=inf", "--out", p], "amplitude"),
        (&["terrain", "--generator", "noise", "--size", "17", "--set", "nonsense=1", "--out", p], "nonsense"),
        (&["terrain", "--generator", "volcano", "--out", p], "volcano"),
        (&["terrain", "--generator", "heightmap", "--out", p], "heightmap"),
        (&["terrain", "--generator", "noise", "--size", "17", "--threads", "100000", "--out", p], "--threads"),
        (&["render", "--preset", "sea", "--size", "0x10", "--out", p], "--size width = 0"),
        (&["render", "--preset", "sea", "--size", "16384x16384", "--out", p], "memory budget"),
        (&["render", "--preset", "sea", "--size", "99999999999x2", "--out", p], "--size"),
        (&["render", "--preset", "sea", "--time", "nan", "--out", p], "--time"),
        (&["render", "--preset", "sea", "--time", "inf", "--out", p], "--time"),
        (&["render", "--preset", "sea", "--out", g, "--frames", "10001"], "--frames = 10001"),
        (&["render", "--preset", "sea", "--out", g, "--frames", "0"], "--frames = 0"),
        (&["render", "--preset", "sea", "--out", g, "--frames", "2", "--fps", "nan"], "--fps"),
        (&["render", "--preset", "sea", "--out", g, "--frames", "2", "--fps", "0"], "--fps"),
        (&["render", "--preset", "no-such-preset", "--out", p], "no-such-preset"),
        (&["render", "--scene", "/dev/null/x.toml", "--out", p], "/dev/null/x.toml"),
        (&["render", "--scene", "/nonexistent/scene.toml", "--out", p], "/nonexistent/scene.toml"),
        // An endless file is read only up to the scene-size limit.
        (&["render", "--scene", "/dev/zero", "--out", p], "MAX_SCENE_BYTES"),
    ];
    let mut failures = Vec::new();
    for (args, expect) in cases {
        // clap's own refusals say `error:` too and exit 2.
        failures.extend(check(&args.join(" "), args, Some(expect), out.path()));
    }
    // A scene directory given as the scene file.
    let dir = bad_inputs();
    failures.extend(check(
        "scene is a directory",
        &["render", "--scene", dir.to_str().unwrap(), "--out", p],
        None,
        out.path(),
    ));
    assert!(failures.is_empty(), "{} command lines misbehaved:\n{}", failures.len(), failures.join("\n"));
}
