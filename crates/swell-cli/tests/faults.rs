//! Faults during long jobs, through the real binary: SIGINT / SIGTERM during a bake or an
//! animation, a disk that refuses to grow a file (RLIMIT_FSIZE in the child, SIGXFSZ ignored, so
//! writes fail with EFBIG as on a full disk), and the output directory removed mid-bake. Each must
//! end with a non-zero exit and a clear message, leave no partial file under a final name (nor a
//! temporary one), and `--resume` must then complete the bake byte for byte like an uninterrupted
//! one.

use std::collections::BTreeMap;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

const SWELL: &str = env!("CARGO_BIN_EXE_swell");
const FRAMES: &str = "0..39";
const FRAME_COUNT: usize = 40;

/// The sea preset on a 96 x 96 grid, written to `dir/sea.toml`.
fn sea_scene(dir: &Path) -> PathBuf {
    let text = include_str!("../../swell/presets/sea.toml").replace("cells = [256, 256]", "cells = [96, 96]");
    assert!(text.contains("[96, 96]"));
    let path = dir.join("sea.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// `swell bake` of [`FRAMES`] into `out`, PNGs and compression making each frame slow enough to
/// interrupt mid-way.
fn bake(scene: &Path, out: &Path, resume: bool) -> Command {
    let mut c = Command::new(SWELL);
    c.args(["bake", "--scene"]).arg(scene);
    c.args(["--frames", FRAMES, "--png", "16", "--exr-compression", "zip", "--threads", "2", "--quiet", "--out"]);
    c.arg(out);
    if resume {
        c.arg("--resume");
    }
    c
}

/// Every file of `dir` and its bytes, temporaries (dot files) included.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .map(|e| (e.file_name().to_string_lossy().into_owned(), std::fs::read(e.path()).unwrap()))
        .collect()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Waits until `file` exists while `child` runs.
fn wait_for(child: &mut Child, file: &Path) {
    let start = Instant::now();
    while !file.exists() {
        assert!(start.elapsed() < Duration::from_secs(120), "the job never got to {}", file.display());
        assert!(child.try_wait().unwrap().is_none(), "the job ended before {} appeared", file.display());
        std::thread::sleep(Duration::from_millis(2));
    }
}

/// The files of an uninterrupted bake.
fn whole_bake(tmp: &Path, scene: &Path) -> BTreeMap<String, Vec<u8>> {
    let whole = tmp.join("whole");
    let o = bake(scene, &whole, false).output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let whole = files(&whole);
    // Per frame: disp and normal, EXR and PNG, and the frame's record check_NNNN.json.
    assert_eq!(whole.len(), 1 + FRAME_COUNT * 5);
    whole
}

/// What an interrupted bake left in `dir` is a subset of the whole bake, byte for byte, with no
/// temporary files; resuming then gives exactly the whole bake.
fn check_partial_then_resume(scene: &Path, dir: &Path, whole: &BTreeMap<String, Vec<u8>>, what: &str) {
    let partial = files(dir);
    for (name, bytes) in &partial {
        assert!(whole.get(name) == Some(bytes), "{what}: {name} is partial, temporary or differs");
    }
    assert!(partial.len() < whole.len(), "{what}: the bake finished before the fault");
    let o = bake(scene, dir, true).output().unwrap();
    assert!(o.status.success(), "{what}: resume failed: {}", stderr(&o));
    assert!(files(dir) == *whole, "{what}: the resumed bake differs from an uninterrupted one");
}

#[test]
fn sigint_or_sigterm_during_a_bake_stops_cleanly_and_resume_completes_it() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = sea_scene(tmp.path());
    let whole = whole_bake(tmp.path(), &scene);
    for (sig, name) in [(libc::SIGINT, "SIGINT"), (libc::SIGTERM, "SIGTERM")] {
        let dir = tmp.path().join(name);
        let mut child = bake(&scene, &dir, false).stderr(Stdio::piped()).spawn().unwrap();
        wait_for(&mut child, &dir.join("disp_0002.exr"));
        // SAFETY: kill(2) on our own child's pid, which has not been waited for yet.
        assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, sig) }, 0);
        let o = child.wait_with_output().unwrap();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{name}: {err}");
        assert!(err.starts_with(&format!("error: interrupted: stopped by {name}: ")), "{name}: {err}");
        assert!(err.contains("--resume") && err.contains("every file in"), "{name}: {err}");
        check_partial_then_resume(&scene, &dir, &whole, name);
    }
}

#[test]
fn a_full_disk_is_a_clear_error_and_resume_completes_the_bake() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = sea_scene(tmp.path());
    let whole = whole_bake(tmp.path(), &scene);
    let dir = tmp.path().join("full");
    // bake.json fits (about 4.3 KB since manifest_version 2); no map does (each is over 50 KB).
    let limit: libc::rlim_t = 16 << 10;
    let mut cmd = bake(&scene, &dir, false);
    // SAFETY: setrlimit and signal are async-signal-safe, as pre_exec requires.
    unsafe {
        cmd.pre_exec(move || {
            libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
            let rl = libc::rlimit { rlim_cur: limit, rlim_max: limit };
            if libc::setrlimit(libc::RLIMIT_FSIZE, &rl) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let o = cmd.output().unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.starts_with("error: ") && err.contains(dir.to_str().unwrap()), "{err}");
    assert!(err.contains("File too large"), "{err}");
    assert!(
        whole.values().all(|b| b.len() as u64 > limit || (b.len() as u64) < limit / 2),
        "the limit must fall between the files"
    );
    check_partial_then_resume(&scene, &dir, &whole, "full disk");
}

#[test]
fn an_output_directory_removed_mid_bake_is_a_clear_error_and_resume_completes_the_bake() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = sea_scene(tmp.path());
    let whole = whole_bake(tmp.path(), &scene);
    let dir = tmp.path().join("vanishing");
    let mut child = bake(&scene, &dir, false).stderr(Stdio::piped()).spawn().unwrap();
    wait_for(&mut child, &dir.join("disp_0002.exr"));
    // The bake may add a file while the directory is being emptied: retry until it is gone.
    let start = Instant::now();
    while dir.exists() && std::fs::remove_dir_all(&dir).is_err() {
        assert!(start.elapsed() < Duration::from_secs(10));
    }
    let o = child.wait_with_output().unwrap();
    let err = stderr(&o);
    if o.status.success() {
        // The bake wrote its last frame before the removal was complete: nothing to check.
        eprintln!("the bake finished before its directory was removed");
        return;
    }
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.starts_with("error: ") && err.contains(dir.to_str().unwrap()), "{err}");
    assert!(err.contains("No such file or directory"), "{err}");
    // The directory is not silently recreated with a partial bake in it.
    assert!(!dir.exists() || files(&dir).len() < whole.len());
    if !dir.exists() {
        std::fs::create_dir(&dir).unwrap();
    }
    check_partial_then_resume(&scene, &dir, &whole, "directory removed");
}

#[test]
fn sigterm_during_an_animation_leaves_no_gif_and_no_temporary_file() {
    let tmp = tempfile::tempdir().unwrap();
    let gif = tmp.path().join("anim.gif");
    let mut child = Command::new(SWELL)
        .args(["render", "--preset", "sea", "--size", "320x180", "--frames", "400", "--threads", "1", "--out"])
        .arg(&gif)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The GIF's temporary file appears with the first frame.
    let start = Instant::now();
    while files(tmp.path()).is_empty() {
        assert!(start.elapsed() < Duration::from_secs(120), "the animation never started writing");
        assert!(child.try_wait().unwrap().is_none(), "the animation ended early");
        std::thread::sleep(Duration::from_millis(2));
    }
    // SAFETY: kill(2) on our own child's pid, which has not been waited for yet.
    assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGTERM) }, 0);
    let o = child.wait_with_output().unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("stopped by SIGTERM") && err.contains("not written"), "{err}");
    assert!(files(tmp.path()).is_empty(), "left {:?}", files(tmp.path()).keys().collect::<Vec<_>>());
}
