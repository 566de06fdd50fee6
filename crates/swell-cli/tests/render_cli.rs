//! End-to-end tests of `swell render` and `swell presets`: the real binary in a temporary directory.

use std::path::Path;
use std::process::{Command, Output};

fn swell(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swell")).args(args).current_dir(dir).output().expect("run swell")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Files in `dir`, so tests can check that a failure left nothing behind (temporary files included).
fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

#[test]
fn renders_the_sea_preset_to_a_png_where_water_fills_most_of_the_frame() {
    let dir = tempfile::tempdir().unwrap();
    let o = swell(dir.path(), &["render", "--preset", "sea", "--out", "sea.png"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::open(dir.path().join("sea.png")).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (1280, 720));
    // Water is darker and bluer than the sky: count pixels whose blue exceeds red by a margin and
    // whose brightness is below the sky's.
    let water = img.pixels().filter(|p| p[2] as i32 - p[0] as i32 > 30 && p[2] < 200).count();
    let frac = water as f64 / (1280.0 * 720.0);
    assert!(frac > 0.5, "only {:.0}% of the frame looks like water", 100.0 * frac);
    // Shading follows the wave slopes: the water area is far from uniform.
    let lum: Vec<f64> = img.pixels().skip(1280 * 400).map(|p| p[0] as f64 + p[1] as f64 + p[2] as f64).collect();
    let mean = lum.iter().sum::<f64>() / lum.len() as f64;
    let var = lum.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / lum.len() as f64;
    assert!(var.sqrt() > 10.0, "water shading is flat (sd {:.1})", var.sqrt());
}

#[test]
fn renders_an_animated_gif_whose_frames_differ() {
    let dir = tempfile::tempdir().unwrap();
    let o = swell(dir.path(), &["render", "--preset", "sea", "--size", "160x90", "--frames", "6", "--out", "sea.gif"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let file = std::fs::File::open(dir.path().join("sea.gif")).unwrap();
    let decoder = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(file)).unwrap();
    let frames = image::AnimationDecoder::into_frames(decoder).collect_frames().unwrap();
    assert_eq!(frames.len(), 6);
    assert_eq!(frames[0].buffer().dimensions(), (160, 90));
    for pair in frames.windows(2) {
        assert_ne!(pair[0].buffer().as_raw(), pair[1].buffer().as_raw(), "consecutive frames are identical");
    }
}

#[test]
fn same_image_on_one_and_two_threads() {
    let dir = tempfile::tempdir().unwrap();
    for t in ["1", "2"] {
        let out = format!("t{t}.png");
        let o = swell(dir.path(), &["render", "--preset", "sea", "--size", "320x180", "--threads", t, "--out", &out]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let a = image::open(dir.path().join("t1.png")).unwrap();
    let b = image::open(dir.path().join("t2.png")).unwrap();
    assert_eq!(a.as_bytes(), b.as_bytes());
}

#[test]
fn presets_lists_one_line_per_preset() {
    let dir = tempfile::tempdir().unwrap();
    let o = swell(dir.path(), &["presets"]);
    assert!(o.status.success());
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.lines().any(|l| l.starts_with("sea ")), "{text}");
    assert_eq!(text.lines().count(), swell::scene::PRESETS.len());
}

/// Runs a failing command and checks: non-zero exit, `error: ` with `expect` on stderr, no panic,
/// and no file (not even a temporary one) left in the directory.
fn fails_cleanly(dir: &Path, args: &[&str], expect: &str) {
    let before = listing(dir);
    let o = swell(dir, args);
    let err = stderr(&o);
    assert!(!o.status.success(), "{args:?} succeeded");
    assert!(err.contains(expect), "{args:?}: stderr {err:?} lacks {expect:?}");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    assert_eq!(listing(dir), before, "{args:?} left files behind");
}

#[test]
fn bad_input_gives_a_clear_error_and_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("bad.toml"), "version = 1\n[camera\n").unwrap();
    std::fs::write(
        d.join("range.toml"),
        "version = 1\n[camera]\neye = [0.0, 5.0, 10.0]\ntarget = [0.0, 0.0, 0.0]\n[water]\nmodel = 'gerstner'\n\
         [[water.waves]]\namplitude = 1.0\nwavelength = 10.0\nspeed = 3.0\ndirection = [1.0, 0.0]\nsteepness = 0.5\n\
         [[water.waves]]\namplitude = 1.0\nwavelength = 10.0\nspeed = 3.0\ndirection = [1.0, 0.0]\nsteepness = 0.5\n\
         [[water.waves]]\namplitude = 1.0\nwavelength = 10.0\nspeed = 3.0\ndirection = [1.0, 0.0]\nsteepness = 1.7\n",
    )
    .unwrap();
    std::fs::write(d.join("binary.toml"), [0xff, 0xfe, 0x00, 0x80]).unwrap();
    fails_cleanly(d, &["render", "--preset", "tsunami", "--out", "x.png"], "unknown preset `tsunami`");
    fails_cleanly(d, &["render", "--scene", "bad.toml", "--out", "x.png"], "bad.toml: TOML parse error");
    fails_cleanly(
        d,
        &["render", "--scene", "range.toml", "--out", "x.png"],
        // issue 22: a validation error names the file, as a parse error does.
        "error: range.toml: water.waves[2].steepness = 1.7 is outside [0, 1]",
    );
    // A wrong type: one line, the key path once (toml's own `in `waves.speed`` line is dropped).
    std::fs::write(d.join("type.toml"), "[water]\nmodel = 'sines'\n[[water.waves]]\namplitude = 'x'\n").unwrap();
    let o = swell(d, &["render", "--scene", "type.toml", "--out", "x.png"]);
    let err = stderr(&o);
    assert!(err.starts_with("error: type.toml: water.waves[0].amplitude: invalid type"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    // A texture file that cannot be read is named with its key, beside the scene file.
    std::fs::create_dir(d.join("scenes")).unwrap();
    std::fs::write(d.join("scenes/tex.toml"), "[water]\nmodel = 'sines'\n[water.material]\ntexture = 'gone.png'\n")
        .unwrap();
    // Resolved to an absolute path (Scene::load), so that a scene saved elsewhere still finds it.
    let beside = std::path::absolute(d).unwrap().join("scenes/gone.png");
    fails_cleanly(
        d,
        &["render", "--scene", "scenes/tex.toml", "--out", "x.png"],
        &format!("water.material.texture: {}: ", beside.display()),
    );
    fails_cleanly(d, &["render", "--scene", "binary.toml", "--out", "x.png"], "not UTF-8");
    fails_cleanly(d, &["render", "--scene", "missing.toml", "--out", "x.png"], "missing.toml");
    fails_cleanly(d, &["render", "--preset", "sea", "--out", "no/such/dir/x.png"], "does not exist");
    fails_cleanly(d, &["render", "--preset", "sea", "--out", "x.jpg"], ".png");
    fails_cleanly(d, &["render", "--preset", "sea", "--size", "0x10", "--out", "x.png"], "--size width = 0 is outside");
    fails_cleanly(d, &["render", "--preset", "sea", "--size", "big", "--out", "x.png"], "WIDTHxHEIGHT");
    fails_cleanly(d, &["render", "--preset", "sea", "--frames", "0", "--out", "x.gif"], "--frames: 0 frames");
    fails_cleanly(d, &["render", "--preset", "sea", "--frames", "3", "--fps", "0", "--out", "x.gif"], "--fps");
    fails_cleanly(d, &["render", "--preset", "sea", "--out", "x.gif"], "--frames");
    fails_cleanly(d, &["render", "--preset", "sea", "--time", "nan", "--out", "x.png"], "--time");
    fails_cleanly(d, &["render", "--preset", "sea", "--threads", "100000", "--out", "x.png"], "--threads");
    fails_cleanly(d, &["render", "--out", "x.png"], "--preset");
}

#[cfg(target_os = "linux")]
#[test]
fn an_output_that_cannot_be_created_names_the_output_not_the_temporary_file() {
    // sysfs takes no regular files, even from root.
    let dir = tempfile::tempdir().unwrap();
    let o = swell(dir.path(), &["render", "--preset", "sea", "--size", "16x9", "--out", "/sys/swell-test.png"]);
    let err = stderr(&o);
    assert!(!o.status.success() && err.starts_with("error: /sys/swell-test.png: "), "{err}");
    assert!(!err.contains(".swell-"), "the temporary file is swell's business: {err}");
}

#[cfg(unix)]
#[test]
fn an_unwritable_directory_is_an_error_and_leaves_nothing() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let locked = dir.path().join("locked");
    std::fs::create_dir(&locked).unwrap();
    std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o555)).unwrap();
    // Root ignores permission bits; the check is only meaningful for other users.
    if std::fs::write(locked.join("probe"), b"x").is_ok() {
        std::fs::remove_file(locked.join("probe")).unwrap();
        eprintln!("running as root: checking a read-only path instead");
        fails_cleanly(
            dir.path(),
            &["render", "--preset", "sea", "--size", "32x18", "--out", "/proc/x.png"],
            "/proc/x.png",
        );
        return;
    }
    fails_cleanly(&locked, &["render", "--preset", "sea", "--size", "32x18", "--out", "x.png"], "x.png");
}

#[test]
fn an_existing_file_survives_a_failed_render() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("keep.png"), b"precious").unwrap();
    let o = swell(dir.path(), &["render", "--preset", "nope", "--out", "keep.png"]);
    assert!(!o.status.success());
    assert_eq!(std::fs::read(dir.path().join("keep.png")).unwrap(), b"precious");
}
