//! The `--obj` comparison mode, run as a user would: real binary, files in a temporary directory.

use std::process::Command;

fn swell() -> Command {
    Command::new(env!("CARGO_BIN_EXE_swell"))
}

#[test]
fn a_lit_triangle_is_written_without_gamma_and_timed() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    // A triangle in the z = 0 plane facing +Z, straight in front of the camera.
    std::fs::write(p("t.obj"), "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n").unwrap();
    std::fs::write(
        p("cam.json"),
        r#"{"eye":[0,0,3],"target":[0,0,0],"up":[0,1,0],"fov_y_deg":60,"near":0.1,"far":10,"width":64,"height":48}"#,
    )
    .unwrap();
    // N.L = cos 60° = 0.5 for this light: 0.5 * (0.2 + 0.6 * 0.5) = 0.25 -> 64 (no sRGB curve).
    std::fs::write(
        p("light.json"),
        r#"{"dir":[0,-0.8660254,-0.5],"color":[0.6,0.6,0.6],"ambient":0.2,"base_color":[0.5,0.5,0.5],"background":[1,0,0]}"#,
    )
    .unwrap();
    let out = swell()
        .args(["render", "--obj"])
        .arg(p("t.obj"))
        .arg("--camera")
        .arg(p("cam.json"))
        .arg("--light")
        .arg(p("light.json"))
        .args(["--shading", "flat", "--repeat", "3", "--out"])
        .arg(p("t.png"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(json["median_ms"].as_f64().unwrap() >= 0.0);
    let img = image::open(p("t.png")).unwrap().to_rgba8();
    assert_eq!(img.dimensions(), (64, 48));
    assert_eq!(img.get_pixel(32, 24).0, [64, 64, 64, 255]);
    assert_eq!(img.get_pixel(1, 1).0, [255, 0, 0, 255]);
}

#[test]
fn out_of_range_indices_are_errors_naming_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    std::fs::write(p("bad.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n").unwrap();
    std::fs::write(p("cam.json"), r#"{"eye":[0,0,3],"target":[0,0,0],"width":8,"height":8}"#).unwrap();
    let out = swell()
        .args(["render", "--obj"])
        .arg(p("bad.obj"))
        .arg("--camera")
        .arg(p("cam.json"))
        .arg("--out")
        .arg(p("x.png"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("line 4") && err.contains("4 is outside [1, 3]"), "{err}");
    assert!(!p("x.png").exists());
}
