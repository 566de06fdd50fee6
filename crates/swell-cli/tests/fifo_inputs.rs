//! Issue 37, class 2: no input can hang a run. A FIFO that no process writes to, given as the
//! scene, a heightmap or its sidecar, a water or foam texture, `--obj`, `--camera` or `--light`,
//! is refused at once naming it, and nothing on disk changes; a FIFO or pipe with a writer, and
//! `--scene -`, read as files do. The real binary, FIFOs made with mkfifo(1) in a temporary
//! directory that is removed with them.
#![cfg(unix)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::{files, stderr, SWELL};

/// Longest a refused run may take: it should take milliseconds; a run that blocks on a FIFO
/// would take forever.
const PROMPTLY: Duration = Duration::from_secs(30);

/// A small sea: 32 x 18 pixels render in milliseconds.
const SEA: &str = "version = 1\n[camera]\neye = [0.0, 6.0, 14.0]\ntarget = [0.0, 0.0, 0.0]\n\
                   [render]\nwidth = 32\nheight = 18\n[water]\nmodel = 'sines'\ncells = [16, 16]\n\
                   [[water.waves]]\namplitude = 0.3\nwavelength = 8.0\nspeed = 3.0\ndirection = [1.0, 0.0]\n";

/// A triangle facing +Z, and a camera looking at it (tests/render_obj.rs).
const OBJ: &str = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n";
const CAMERA: &str =
    r#"{"eye":[0,0,3],"target":[0,0,0],"up":[0,1,0],"fov_y_deg":60,"near":0.1,"far":10,"width":16,"height":12}"#;
const LIGHT: &str = r#"{"dir":[0,0,-1],"color":[0.6,0.6,0.6],"ambient":0.2}"#;

/// Makes a FIFO at `dir/name` with mkfifo(1); the temporary directory removes it.
fn fifo(dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(name);
    let status = Command::new("mkfifo").arg(&path).status().expect("mkfifo runs");
    assert!(status.success(), "mkfifo {}", path.display());
    path
}

/// A 4 x 4 8-bit grey PNG, a valid heightmap.
fn write_heightmap(path: &Path) {
    image::GrayImage::from_fn(4, 4, |x, y| image::Luma([(40 * x + 10 * y) as u8])).save(path).unwrap();
}

/// Runs `swell args` in `cwd` with `stdin` as its standard input (none if `None`), and kills it
/// and fails the test if it runs past [`PROMPTLY`].
fn run(cwd: &Path, args: &[&str], stdin: Option<Vec<u8>>) -> Output {
    let mut child = Command::new(SWELL)
        .args(args)
        .current_dir(cwd)
        .stdin(if stdin.is_some() { Stdio::piped() } else { Stdio::null() })
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    if let Some(bytes) = stdin {
        let mut pipe = child.stdin.take().unwrap();
        // Closing the pipe after the write is what ends the scene.
        std::thread::spawn(move || pipe.write_all(&bytes));
    }
    let pid = child.id() as libc::pid_t;
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || tx.send(child.wait_with_output().unwrap()));
    match rx.recv_timeout(PROMPTLY) {
        Ok(out) => out,
        Err(_) => {
            // SAFETY: kill(2) on the child's pid; the child is not yet reaped (wait is pending).
            unsafe { libc::kill(pid, libc::SIGKILL) };
            panic!("swell {} ran for over {PROMPTLY:?}: blocked on a FIFO?", args.join(" "));
        }
    }
}

/// `swell args` fails promptly with exit 1, its message names `fifo` and says no process writes
/// to it, and the files of `dir` are what they were.
fn refused_at_once(dir: &Path, args: &[&str], fifo: &Path) {
    let before = files_but_fifos(dir);
    let start = Instant::now();
    let out = run(dir, args, None);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "swell {}: {err}", args.join(" "));
    let expected = format!("{}: is a FIFO or pipe that no process writes to", fifo.display());
    assert!(err.starts_with("error: ") && err.contains(&expected), "swell {}: {err}", args.join(" "));
    assert!(!err.contains("panicked"), "{err}");
    assert!(start.elapsed() < PROMPTLY);
    assert_eq!(files_but_fifos(dir), before, "swell {} changed files", args.join(" "));
}

/// Every file under `dir` (one level of subdirectories) with its bytes, FIFOs by name only
/// (reading one would block the test).
fn files_but_fifos(dir: &Path) -> Vec<(String, Option<Vec<u8>>)> {
    use std::os::unix::fs::FileTypeExt;
    let mut all = Vec::new();
    for e in std::fs::read_dir(dir).unwrap().map(|e| e.unwrap()) {
        let name = e.file_name().to_string_lossy().into_owned();
        let kind = e.file_type().unwrap();
        if kind.is_fifo() {
            all.push((name, None));
        } else if kind.is_dir() {
            all.push((format!("{name}/"), None));
            all.extend(files_but_fifos(&e.path()).into_iter().map(|(n, b)| (format!("{name}/{n}"), b)));
        } else {
            all.push((name, Some(std::fs::read(e.path()).unwrap())));
        }
    }
    all.sort();
    all
}

#[test]
fn a_scene_fifo_without_a_writer_is_refused_at_once_by_every_command() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scene = fifo(d, "scene.toml");
    let s = scene.to_str().unwrap();
    refused_at_once(d, &["render", "--scene", s, "--out", "x.png"], &scene);
    refused_at_once(d, &["render", "--scene", s, "--out", "x.gif", "--frames", "2"], &scene);
    refused_at_once(d, &["export", "--scene", s, "--out", "x.obj"], &scene);
    refused_at_once(d, &["bake", "--scene", s, "--frames", "2", "--out", "bake"], &scene);
    refused_at_once(d, &["stats", "--scene", s], &scene);
    // A relative path is named as given.
    refused_at_once(d, &["render", "--scene", "scene.toml", "--out", "x.png"], Path::new("scene.toml"));
}

#[test]
fn files_a_scene_names_are_refused_at_once_when_they_are_fifos_without_a_writer() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let terrain =
        |path: &str| format!("{SEA}[terrain]\ngenerator = 'heightmap'\npath = '{path}'\nheight_scale = 2.0\n");
    // The heightmap image (no sidecar: the scene gives height_scale).
    let map = fifo(d, "map.png");
    std::fs::write(d.join("heightmap.toml"), terrain("map.png")).unwrap();
    refused_at_once(d, &["render", "--scene", "heightmap.toml", "--out", "x.png"], &d.join("map.png"));
    // Its sidecar, beside a real image.
    write_heightmap(&d.join("real.png"));
    let sidecar = fifo(d, "real.png.toml");
    std::fs::write(d.join("sidecar.toml"), terrain("real.png")).unwrap();
    refused_at_once(d, &["render", "--scene", "sidecar.toml", "--out", "x.png"], &sidecar);
    // The water's colour texture and its foam texture, each named with its key.
    let tex = fifo(d, "water.png");
    std::fs::write(d.join("tex.toml"), format!("{SEA}[water.material]\ntexture = 'water.png'\n")).unwrap();
    refused_at_once(d, &["render", "--scene", "tex.toml", "--out", "x.png"], &tex);
    let out = run(d, &["render", "--scene", "tex.toml", "--out", "x.png"], None);
    assert!(stderr(&out).contains("water.material.texture: "), "{}", stderr(&out));
    let foam = fifo(d, "foam.png");
    std::fs::write(d.join("foam.toml"), format!("{SEA}[water.material]\nfoam_texture = 'foam.png'\n")).unwrap();
    refused_at_once(d, &["render", "--scene", "foam.toml", "--out", "x.png"], &foam);
    // An export reads the heightmap too.
    refused_at_once(d, &["export", "--scene", "heightmap.toml", "--out", "x.obj"], &map);
}

#[test]
fn obj_camera_and_light_fifos_without_a_writer_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("t.obj"), OBJ).unwrap();
    std::fs::write(d.join("cam.json"), CAMERA).unwrap();
    std::fs::write(d.join("light.json"), LIGHT).unwrap();
    let obj = fifo(d, "mesh.obj");
    let cam = fifo(d, "cam-fifo.json");
    let light = fifo(d, "light-fifo.json");
    let render = |obj: &str, cam: &str, light: &str| {
        ["render", "--obj", obj, "--camera", cam, "--light", light, "--out", "m.png"].map(str::to_string)
    };
    let cases = [
        (render("mesh.obj", "cam.json", "light.json"), &obj),
        (render("t.obj", "cam-fifo.json", "light.json"), &cam),
        (render("t.obj", "cam.json", "light-fifo.json"), &light),
    ];
    for (args, fifo) in &cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused_at_once(d, &args, Path::new(fifo.file_name().unwrap()));
    }
    // The same files as regular files render: the refusals were the FIFOs'.
    let out =
        run(d, &["render", "--obj", "t.obj", "--camera", "cam.json", "--light", "light.json", "--out", "m.png"], None);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(d.join("m.png").is_file());
}

/// Renders `SEA` from a regular file in `dir` to `name`, and returns the image's bytes.
fn reference(dir: &Path, name: &str) -> Vec<u8> {
    std::fs::write(dir.join("ref.toml"), SEA).unwrap();
    let out = run(dir, &["render", "--scene", "ref.toml", "--out", name], None);
    assert!(out.status.success(), "{}", stderr(&out));
    std::fs::read(dir.join(name)).unwrap()
}

#[test]
fn a_scene_fifo_with_a_writer_renders_as_the_file_does() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let expected = reference(d, "ref.png");
    let scene = fifo(d, "scene.toml");
    // The writer has the FIFO open before swell reads it, as a shell's `<(...)` or a writer
    // started first has. Opening read-write never waits (Linux) and lets the write-only open
    // find a reader; once the read-write descriptor is closed, the writer is the only one.
    let rw = std::fs::OpenOptions::new().read(true).write(true).open(&scene).unwrap();
    let mut writer = std::fs::OpenOptions::new().write(true).open(&scene).unwrap();
    drop(rw);
    let feeder = std::thread::spawn(move || {
        // Until swell has opened the FIFO, a write fails (EPIPE) and writes nothing: retry.
        let deadline = Instant::now() + PROMPTLY;
        while let Err(e) = writer.write_all(SEA.as_bytes()) {
            assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "{e}");
            assert!(Instant::now() < deadline, "swell never opened the FIFO");
            std::thread::sleep(Duration::from_millis(5));
        }
        // Dropping the writer ends the scene.
    });
    let out = run(d, &["render", "--scene", "scene.toml", "--out", "fifo.png"], None);
    feeder.join().unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(std::fs::read(d.join("fifo.png")).unwrap(), expected);
}

#[test]
fn a_scene_on_standard_input_renders_as_the_file_does() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let expected = reference(d, "ref.png");
    // `-` and /dev/stdin (a pipe with a writer: the test's end of it).
    for (scene, name) in [("-", "dash.png"), ("/dev/stdin", "devstdin.png")] {
        let out = run(d, &["render", "--scene", scene, "--out", name], Some(SEA.as_bytes().to_vec()));
        assert!(out.status.success(), "--scene {scene}: {}", stderr(&out));
        assert_eq!(std::fs::read(d.join(name)).unwrap(), expected, "--scene {scene}");
    }
    // An empty standard input is an empty scene; /dev/stdin closed without data says why.
    let out = run(d, &["render", "--scene", "-", "--out", "e.png"], Some(Vec::new()));
    assert!(stderr(&out).starts_with("error: <stdin>: the scene is empty"), "{}", stderr(&out));
    let out = run(d, &["render", "--scene", "/dev/stdin", "--out", "e.png"], Some(Vec::new()));
    assert!(stderr(&out).contains("/dev/stdin: is a FIFO or pipe that no process writes to"), "{}", stderr(&out));
    assert!(!d.join("e.png").exists());
    // Other commands take `-` too.
    let out = run(d, &["export", "--scene", "-", "--out", "sea.obj"], Some(SEA.as_bytes().to_vec()));
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(d.join("sea.obj").is_file());
}

#[test]
fn relative_paths_in_a_scene_on_standard_input_resolve_against_the_current_directory() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_heightmap(&d.join("map.png"));
    let text = format!("{SEA}[terrain]\ngenerator = 'heightmap'\npath = 'map.png'\nheight_scale = 2.0\n");
    std::fs::write(d.join("island.toml"), &text).unwrap();
    let out = run(d, &["render", "--scene", "island.toml", "--out", "file.png"], None);
    assert!(out.status.success(), "{}", stderr(&out));
    let out = run(d, &["render", "--scene", "-", "--out", "stdin.png"], Some(text.clone().into_bytes()));
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(std::fs::read(d.join("stdin.png")).unwrap(), std::fs::read(d.join("file.png")).unwrap());
    // From another directory the same text looks for the map there, and says where.
    std::fs::create_dir(d.join("elsewhere")).unwrap();
    let out = run(&d.join("elsewhere"), &["render", "--scene", "-", "--out", "x.png"], Some(text.into_bytes()));
    let missing = std::path::absolute(d.join("elsewhere/map.png")).unwrap();
    assert!(stderr(&out).contains(&format!("{}: No such file", missing.display())), "{}", stderr(&out));
    assert_eq!(files(&d.join("elsewhere")).len(), 0);
}
