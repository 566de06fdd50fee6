//! Issue 37, class 5: an output's format and extension agree, and a refused output names its real
//! cause, with nothing written.

mod common;

use common::{files, stderr, swell};

#[test]
fn export_refuses_a_format_its_extension_contradicts() {
    let dir = tempfile::tempdir().unwrap();
    for (format, out, ext) in [("obj", "x.glb", "glb"), ("glb", "x.obj", "obj"), ("gltf", "x.GLB", "GLB")] {
        let path = dir.path().join(out);
        let o = swell(&["export", "--preset", "pool", "--format", format, "--out", path.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(1), "--format {format} --out {out}");
        let err = stderr(&o);
        assert!(err.contains(&format!("ends in .{} but --format is {format}", ext.to_ascii_lowercase())), "{err}");
        assert!(files(dir.path()).is_empty(), "{:?}", files(dir.path()).keys());
    }
    // Agreeing, or without an extension, the format is taken.
    let o =
        swell(&["export", "--preset", "pool", "--format", "OBJ", "--out", dir.path().join("x.obj").to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o =
        swell(&["export", "--preset", "pool", "--format", "obj", "--out", dir.path().join("mesh").to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::read_to_string(dir.path().join("mesh")).unwrap().contains("\nv "));
    // An extension that names no format leaves the choice to --format.
    let o =
        swell(&["export", "--preset", "pool", "--format", "glb", "--out", dir.path().join("x.mesh").to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(&std::fs::read(dir.path().join("x.mesh")).unwrap()[..4], b"glTF");
}

#[test]
fn an_output_under_a_file_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("taken");
    std::fs::write(&file, "x").unwrap();
    let under = file.join("deeper/out");
    for args in [
        vec!["render", "--preset", "pool", "--out", &format!("{}.png", under.display())],
        vec!["export", "--preset", "pool", "--out", &format!("{}.obj", under.display())],
    ] {
        let args: Vec<&str> = args.iter().map(|s| s.as_ref()).collect();
        let o = swell(&args);
        assert_eq!(o.status.code(), Some(1));
        let err = stderr(&o);
        assert!(err.contains(&format!("{} is a file, not a directory", file.display())), "{err}");
    }
    assert_eq!(std::fs::read(&file).unwrap(), b"x");
}
