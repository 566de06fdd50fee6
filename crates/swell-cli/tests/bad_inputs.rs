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
    let mesh = out.path().join("t.obj");
    let (p, g, m) = (png.to_str().unwrap(), gif.to_str().unwrap(), mesh.to_str().unwrap());
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
        (&["render", "--preset", "sea", "--out", g, "--frames", "0"], "--frames: 0 frames"),
        // issue 22: one meaning per flag, no flag ignored, times in a documented range.
        (&["render", "--preset", "sea", "--out", g, "--frames", "0..x"], "--frames: `0..x` is not a frame count"),
        (&["render", "--preset", "sea", "--out", g, "--frames", "4", "--fps", "60"], "(0, 50] for a GIF"),
        (
            &["render", "--preset", "sea", "--out", g, "--frames", "4", "--fps", "1001"],
            "--fps = 1001 is outside (0, 1000]",
        ),
        (&["render", "--preset", "sea", "--time", "1e300", "--out", p], "--time = 1e300 is outside [-1e7, 1e7]"),
        (&["render", "--preset", "sea", "--time=-2e7", "--out", p], "--time = -20000000 is outside"),
        (&["render", "--preset", "springs", "--time", "1e6", "--out", p], "it would need 2,500,149 steps"),
        (&["render", "--preset", "sea", "--camera", "/nonexistent.json", "--out", p], "--camera: belongs to the --obj"),
        (&["render", "--preset", "sea", "--light", "/nonexistent.json", "--out", p], "--light: belongs to the --obj"),
        (&["render", "--preset", "sea", "--repeat", "3", "--out", p], "--repeat: belongs to the --obj"),
        (&["bake", "--preset", "sea", "--frames", "2", "--png-range", "3", "--out", p], "--png-range: sets the range"),
        (&["bake", "--preset", "sea", "--frames", "0..9999999", "--fps", "0.5", "--out", p], "the last frame's time"),
        (&["export", "--preset", "sea", "--time", "1e300", "--out", m], "--time = 1e300"),
        (&["export", "--preset", "sea", "--frames", "0", "--out", m], "--frames: 0 frames"),
        (&["stats", "--preset", "ocean", "--time", "1e300"], "--time = 1e300"),
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

#[test]
fn bad_obj_camera_and_light_files_are_refused_by_name_without_output() {
    let out = tempfile::tempdir().unwrap();
    let png = out.path().join("m.png");
    let p = png.to_str().unwrap();
    let dir = bad_inputs();
    let f = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let (good_obj, good_cam) = (f("mesh-good.obj"), f("camera-good.json"));
    let mut failures = Vec::new();
    let objs: &[(&str, &str)] = &[
        // issue 22: a JSON file given as the mesh renders nothing, so it is refused.
        ("camera-good.json", "no triangles"),
        ("obj-index-out-of-range.obj", "vertex index 4 is outside [1, 3]"),
        ("obj-negative-index-out-of-range.obj", "vertex index -4 is outside"),
        ("obj-huge-index.obj", "is not a vertex index"),
        ("obj-nan-vertex.obj", "three finite numbers"),
        ("obj-overflowing-vertex.obj", "three finite numbers"),
        ("obj-two-corner-face.obj", "at least 3 vertices"),
        ("obj-missing-normal.obj", "normal index 1 is outside [1, 0]"),
        ("obj-non-utf8.obj", "not UTF-8"),
        ("obj-truncated.obj", "line 2"),
        ("/dev/zero", "MAX_OBJ_BYTES"),
    ];
    for (obj, expect) in objs {
        let obj = if obj.starts_with('/') { obj.to_string() } else { f(obj) };
        let args = ["render", "--obj", &obj, "--camera", &good_cam, "--out", p];
        failures.extend(check(&obj, &args, Some(expect), out.path()));
    }
    let cameras: &[(&str, &str)] = &[
        ("camera-missing-height.json", "height is missing"),
        ("camera-too-wide.json", "camera.width = 20000 is outside [1, 16384]"),
        ("camera-eye-is-target.json", "must differ from camera.eye"),
        ("camera-overflowing-distance.json", "too far from camera.eye"),
        ("camera-fov-180.json", "camera.fov_y_deg = 180"),
        ("camera-unknown-key.json", "unknown key `zoom`"),
        ("camera-truncated.json", "EOF"),
        ("light-deep-nesting.json", "recursion limit"),
        ("/dev/zero", "MAX_VIEW_JSON_BYTES"),
    ];
    for (cam, expect) in cameras {
        let cam = if cam.starts_with('/') { cam.to_string() } else { f(cam) };
        let args = ["render", "--obj", &good_obj, "--camera", &cam, "--out", p];
        failures.extend(check(&cam, &args, Some(expect), out.path()));
    }
    let lights: &[(&str, &str)] = &[
        ("light-zero-dir.json", "light.dir"),
        ("light-negative-color.json", "light.color[1] = -1"),
        ("light-wrong-type.json", "ambient must be [x, y, z] or a number"),
        ("light-overflowing-color.json", "light.color[0] = inf"),
        ("light-deep-nesting.json", "recursion limit"),
        ("camera-good.json", "unknown key `eye`"),
    ];
    for (light, expect) in lights {
        let light = f(light);
        let args = ["render", "--obj", &good_obj, "--camera", &good_cam, "--light", &light, "--out", p];
        failures.extend(check(&light, &args, Some(expect), out.path()));
    }
    assert!(failures.is_empty(), "{} OBJ/camera/light files misbehaved:\n{}", failures.len(), failures.join("\n"));
}
