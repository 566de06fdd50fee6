//! `swell terrain` end to end: the real binary in a temporary directory.

use std::path::Path;
use std::process::{Command, Output};

fn swell(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swell")).current_dir(dir).args(args).output().expect("the swell binary runs")
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

#[test]
fn writes_a_16_bit_heightmap_that_a_scene_renders() {
    let dir = tempfile::tempdir().unwrap();
    let out = swell(
        dir.path(),
        &[
            "terrain",
            "--generator",
            "diamond-square",
            "--size",
            "65",
            "--seed",
            "5",
            "--extent",
            "120x100",
            "--set",
            "amplitude=30",
            "--set",
            "corners=[0, 0, 10, 10]",
            "--out",
            "map.png",
        ],
    );
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(files_in(dir.path()), ["map.png", "map.png.toml"]);
    let img = image::open(dir.path().join("map.png")).unwrap();
    assert_eq!(img.color(), image::ColorType::L16);
    assert_eq!((img.width(), img.height()), (65, 65));
    let grey = img.to_luma16();
    // Scaled to the full 16-bit range: the lowest height is 0, the highest 65535.
    assert_eq!(grey.pixels().map(|p| p.0[0]).min(), Some(0));
    assert_eq!(grey.pixels().map(|p| p.0[0]).max(), Some(65535));
    let sidecar = std::fs::read_to_string(dir.path().join("map.png.toml")).unwrap();
    assert!(sidecar.contains("extent = [120.0, 100.0]"), "{sidecar}");

    // The same seed gives the same file.
    let again = swell(
        dir.path(),
        &[
            "terrain",
            "--generator",
            "diamond-square",
            "--size",
            "65",
            "--seed",
            "5",
            "--extent",
            "120x100",
            "--set",
            "amplitude=30",
            "--set",
            "corners=[0, 0, 10, 10]",
            "--out",
            "again.png",
            "--threads",
            "1",
        ],
    );
    assert!(again.status.success());
    assert_eq!(
        std::fs::read(dir.path().join("map.png")).unwrap(),
        std::fs::read(dir.path().join("again.png")).unwrap()
    );

    // A scene in a subdirectory loads it by a path relative to the scene file, and shows it.
    std::fs::create_dir(dir.path().join("scenes")).unwrap();
    let scene = |terrain: &str| {
        format!(
            "version = 1\n[camera]\neye = [0.0, 90.0, 110.0]\ntarget = [0.0, 0.0, 0.0]\n\
             [[light]]\ntype = 'directional'\ndirection = [0.0, -1.0, 0.0]\n[render]\nwidth = 96\nheight = 64\n{terrain}"
        )
    };
    std::fs::write(
        dir.path().join("scenes/land.toml"),
        scene("[terrain]\ngenerator = 'heightmap'\npath = '../map.png'\n"),
    )
    .unwrap();
    std::fs::write(dir.path().join("scenes/empty.toml"), scene("")).unwrap();
    for name in ["land", "empty"] {
        let r =
            swell(dir.path(), &["render", "--scene", &format!("scenes/{name}.toml"), "--out", &format!("{name}.png")]);
        assert!(r.status.success(), "{name}: {}", String::from_utf8_lossy(&r.stderr));
    }
    let land = image::open(dir.path().join("land.png")).unwrap().to_rgb8();
    let empty = image::open(dir.path().join("empty.png")).unwrap().to_rgb8();
    // The terrain covers the image centre, where the empty scene shows only the sky's ground colour.
    assert_ne!(land.get_pixel(48, 32), empty.get_pixel(48, 32));
    let differing = land.pixels().zip(empty.pixels()).filter(|(a, b)| a != b).count();
    assert!(differing > 96 * 64 / 4, "only {differing} pixels show terrain");
}

#[test]
fn bad_input_fails_clearly_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&[&str], &str); 9] = [
        (&["--generator", "diamond-square", "--size", "100"], "2^n + 1"),
        (
            &["--generator", "volcano"],
            "valid: diamond-square, random-average, noise, hills, flat, slope, heightmap, channel",
        ),
        (&["--generator", "noise", "--set", "octaves=99"], "terrain.octaves = 99 is outside [1, 16]"),
        (&["--generator", "hills", "--extent=-5"], "terrain.extent[0] = -5"),
        (&["--generator", "heightmap"], "heightmap"),
        // Issue 37: --set never beats a flag, nor carries a second key.
        (&["--generator", "flat", "--size", "33", "--set", "size=65"], "`size` has a flag of its own: give --size"),
        (&["--generator", "flat", "--set", "generator=noise"], "give --generator instead"),
        (&["--generator", "noise", "--set", "octaves=3\n[water]\nmodel='fft'"], "--set octaves: the value spans lines"),
        (&["--generator", "noise", "--set", "octaves=3, roughness = 1"], "octaves"),
    ];
    for (args, expected) in cases {
        let mut full = vec!["terrain"];
        full.extend_from_slice(args);
        full.extend_from_slice(&["--out", "map.png"]);
        let out = swell(dir.path(), &full);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
        assert!(files_in(dir.path()).is_empty(), "{args:?} left {:?}", files_in(dir.path()));
    }
    // The sidecar cannot be written (a directory holds its name): the heightmap is not left behind.
    std::fs::create_dir(dir.path().join("map.png.toml")).unwrap();
    let out = swell(dir.path(), &["terrain", "--generator", "flat", "--size", "9", "--out", "map.png"]);
    assert!(!out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(!dir.path().join("map.png").exists(), "the heightmap was left behind without its sidecar");
    std::fs::remove_dir(dir.path().join("map.png.toml")).unwrap();
    // An output under a file names the file, not a missing directory.
    std::fs::write(dir.path().join("plain"), "x").unwrap();
    let out = swell(dir.path(), &["terrain", "--generator", "flat", "--out", "plain/map.png"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("plain is a file, not a directory"), "{err}");
    std::fs::remove_file(dir.path().join("plain")).unwrap();
    let out = swell(dir.path(), &["terrain", "--generator", "flat", "--out", "map.jpg"]);
    assert!(!out.status.success() && String::from_utf8_lossy(&out.stderr).contains(".png"));
    assert!(files_in(dir.path()).is_empty());
}

#[test]
fn exr_heightmaps_hold_the_same_heights_in_metres() {
    let dir = tempfile::tempdir().unwrap();
    let common = ["terrain", "--generator", "noise", "--size", "33", "--seed", "3", "--extent", "80x60"];
    let run = |extra: &[&str]| {
        let mut args = common.to_vec();
        args.extend_from_slice(extra);
        let out = swell(dir.path(), &args);
        assert!(out.status.success(), "{extra:?}: {}", String::from_utf8_lossy(&out.stderr));
    };
    run(&["--out", "map.png"]);
    run(&["--out", "map.exr"]);
    // --format wins over an extension that names no format.
    run(&["--format", "exr", "--out", "map.bin"]);
    assert_eq!(files_in(dir.path()), ["map.bin", "map.bin.toml", "map.exr", "map.exr.toml", "map.png", "map.png.toml"]);
    assert_eq!(std::fs::read(dir.path().join("map.exr")).unwrap(), std::fs::read(dir.path().join("map.bin")).unwrap());

    let image = exr::prelude::read_first_flat_layer_from_file(dir.path().join("map.exr")).unwrap();
    assert_eq!((image.layer_data.size.width(), image.layer_data.size.height()), (33, 33));
    let metres: Vec<f32> = image.layer_data.channel_data.list[0].sample_data.values_as_f32().collect();
    let side: toml::Table = std::fs::read_to_string(dir.path().join("map.png.toml")).unwrap().parse().unwrap();
    let (scale, offset) = (side["height_scale"].as_float().unwrap(), side["height_offset"].as_float().unwrap());
    let grey = image::open(dir.path().join("map.png")).unwrap().to_luma16();
    // The PNG quantises the same heights: each EXR height is within half a grey level of it.
    for (m, g) in metres.iter().zip(grey.pixels()) {
        let from_png = offset + scale * f64::from(g.0[0]) / 65535.0;
        assert!((f64::from(*m) - from_png).abs() <= 0.5 * scale / 65535.0 + 1e-5, "{m} vs {from_png}");
    }
    // The PNG's offset is the lowest height: the EXR holds that very value.
    let lowest = metres.iter().copied().fold(f32::INFINITY, f32::min);
    assert_eq!(lowest, offset as f32, "the sidecar prints the shortest f32 decimal");
    let exr_side = std::fs::read_to_string(dir.path().join("map.exr.toml")).unwrap();
    assert!(exr_side.contains("height_scale = 1.0") && exr_side.contains("extent = [80.0, 60.0]"), "{exr_side}");

    // A format that disagrees with the extension is refused before anything is written.
    let mut args = common.to_vec();
    args.extend_from_slice(&["--format", "exr", "--out", "other.png"]);
    let out = swell(dir.path(), &args);
    assert!(!out.status.success() && String::from_utf8_lossy(&out.stderr).contains("--format exr"));
    assert!(!dir.path().join("other.png").exists());
}
