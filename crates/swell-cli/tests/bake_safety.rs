//! Bakes that never lie (issue 37, class 3), through the real binary: `--resume` checks every
//! frame against its record and bakes damaged ones again; frame files without `bake.json` are
//! never adopted; a directory holds one bake, and a second bake into a directory in use is refused
//! naming the holder, while a lock left by a killed bake is found stale and replaced. A refused
//! run changes nothing on disk.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output};
use std::time::{Duration, Instant};

mod common;
use common::{files, stderr, SWELL};

/// The sea preset on a grid of `cells` x `cells`, written to `dir/NAME`.
fn sea_scene(dir: &Path, name: &str, cells: u32) -> PathBuf {
    let text = include_str!("../../swell/presets/sea.toml")
        .replace("cells = [256, 256]", &format!("cells = [{cells}, {cells}]"));
    assert!(text.contains(&format!("[{cells}, {cells}]")));
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// `swell bake --scene SCENE --frames FRAMES --quiet --out OUT EXTRA...`.
fn bake(scene: &Path, frames: &str, out: &Path, extra: &[&str]) -> Command {
    let mut c = Command::new(SWELL);
    c.args(["bake", "--scene"]).arg(scene).args(["--frames", frames, "--quiet", "--out"]).arg(out).args(extra);
    c
}

fn run(mut c: Command) -> Output {
    c.output().unwrap()
}

/// Every file of `dir`, dot files (temporaries) included, with its bytes: what a refused run must
/// leave exactly as it was.
fn everything(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .map(|e| (e.file_name().to_string_lossy().into_owned(), std::fs::read(e.path()).unwrap()))
        .collect()
}

/// Waits until every one of `names` exists in `dir` while `child` runs.
fn wait_for(child: &mut Child, dir: &Path, names: &[&str]) {
    let start = Instant::now();
    while !names.iter().all(|n| dir.join(n).exists()) {
        assert!(start.elapsed() < Duration::from_secs(120), "the bake never wrote {names:?}");
        assert!(child.try_wait().unwrap().is_none(), "the bake ended before {names:?} appeared");
        std::thread::sleep(Duration::from_millis(2));
    }
}

fn signal(child: &Child, sig: &str) {
    let ok = Command::new("kill").args([sig, &child.id().to_string()]).status().unwrap().success();
    assert!(ok, "kill {sig} {}", child.id());
}

/// Waits until `child` is stopped (state `T` in `/proc/PID/stat`): a signal is delivered a moment
/// after `kill` returns.
fn wait_stopped(child: &Child) {
    let start = Instant::now();
    loop {
        let stat = std::fs::read_to_string(format!("/proc/{}/stat", child.id())).unwrap();
        if stat[stat.rfind(')').unwrap() + 1..].split_whitespace().next() == Some("T") {
            return;
        }
        assert!(start.elapsed() < Duration::from_secs(10), "the bake did not stop: {stat}");
        std::thread::sleep(Duration::from_millis(1));
    }
}

/// The names of the files that differ between two snapshots, for messages.
fn changed(a: &BTreeMap<String, Vec<u8>>, b: &BTreeMap<String, Vec<u8>>) -> Vec<String> {
    let names: std::collections::BTreeSet<&String> = a.keys().chain(b.keys()).collect();
    names.into_iter().filter(|n| a.get(*n) != b.get(*n)).cloned().collect()
}

fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap().trim().to_string()
}

#[test]
fn a_second_bake_into_a_directory_in_use_is_refused_naming_the_holder_until_the_holder_is_killed() {
    let tmp = tempfile::tempdir().unwrap();
    let sea = sea_scene(tmp.path(), "sea.toml", 96);
    let other = sea_scene(tmp.path(), "other.toml", 24);
    let out = tmp.path().join("out");
    // PNGs, compression and one thread: tens of milliseconds per frame, 60 frames.
    let slow = ["--png", "16", "--exr-compression", "zip", "--threads", "1"];
    let mut first = bake(&sea, "0..59", &out, &slow).spawn().unwrap();
    wait_for(&mut first, &out, &["bake.lock", "check_0001.json"]);
    // Frozen, so the directory holds still while the others try (the holder still runs).
    signal(&first, "-STOP");
    wait_stopped(&first);
    let before = everything(&out);
    assert!(!before.contains_key("check_0059.json"), "the bake finished before it was stopped");
    let lock: serde_json::Value = serde_json::from_slice(&before["bake.lock"]).unwrap();
    assert_eq!(lock["pid"], first.id());

    // Another scene, the same command again, and another scene as a shard: all refused, each
    // naming the holder (process id, host, start time, command) and leaving everything as it was.
    let holder_named = |o: &Output| {
        let e = stderr(o);
        assert!(!o.status.success(), "a second bake into a directory in use succeeded");
        assert!(e.contains(&format!("process {} on host {}", first.id(), host_name())), "{e}");
        assert!(e.contains(&format!("started {}", lock["started_utc"].as_str().unwrap())), "{e}");
        assert!(e.contains("bake --scene") && e.contains("sea.toml --frames 0..59"), "the command: {e}");
        assert!(e.contains(out.join("bake.lock").to_str().unwrap()), "{e}");
        e
    };
    let e = holder_named(&run(bake(&other, "0..3", &out, &[])));
    assert!(e.contains("in use by another bake"), "{e}");
    assert!(everything(&out) == before, "a refused bake changed {:?}", changed(&before, &everything(&out)));
    let e = holder_named(&run(bake(&sea, "0..59", &out, &[&slow[..], &["--resume"]].concat())));
    assert!(e.contains("this same bake"), "{e}");
    assert!(everything(&out) == before, "a refused bake changed {:?}", changed(&before, &everything(&out)));
    let e = holder_named(&run(bake(&other, "0..3", &out, &["--shard", "1/2"])));
    assert!(e.contains("in use by another bake"), "{e}");
    assert!(everything(&out) == before, "a refused shard changed {:?}", changed(&before, &everything(&out)));

    // SIGKILL: the holder is gone, its lock is left and found stale; resuming the same bake
    // replaces it, says so, and completes the bake as if nothing had happened.
    first.kill().unwrap();
    first.wait().unwrap();
    assert!(out.join("bake.lock").exists(), "SIGKILL cannot remove the lock");
    let o = run(bake(&sea, "0..59", &out, &[&slow[..], &["--resume"]].concat()));
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("removed the stale lock") && e.contains(&format!("process {} no longer runs", first.id())),
        "{e}"
    );
    assert!(!out.join("bake.lock").exists(), "the lock outlived its bake");
    let whole = tmp.path().join("whole");
    assert!(run(bake(&sea, "0..59", &whole, &slow)).status.success());
    // (`files` leaves out the temporaries SIGKILL left: docs/baking.md says to delete them.)
    assert!(files(&out) == files(&whole), "the resumed bake differs from an uninterrupted one");

    // Now idle, the directory still holds one bake: another scene is refused, naming the keys.
    let before = everything(&out);
    let o = run(bake(&other, "0..3", &out, &[]));
    let e = stderr(&o);
    assert!(
        !o.status.success() && e.contains("describes a different bake (") && e.contains("`model_params.cells`"),
        "{e}"
    );
    assert!(everything(&out) == before);
}

#[test]
fn shards_of_one_bake_share_a_directory_at_the_same_time() {
    let tmp = tempfile::tempdir().unwrap();
    let sea = sea_scene(tmp.path(), "sea.toml", 48);
    let (sharded, whole) = (tmp.path().join("sharded"), tmp.path().join("whole"));
    let extra = |shard: &'static str| ["--png", "8", "--threads", "1", "--shard", shard, "--resume"];
    let children: Vec<Child> =
        ["0/3", "1/3", "2/3"].iter().map(|s| bake(&sea, "0..29", &sharded, &extra(s)).spawn().unwrap()).collect();
    for c in children {
        let o = c.wait_with_output().unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
    }
    assert!(run(bake(&sea, "0..29", &whole, &["--png", "8"])).status.success());
    assert!(everything(&sharded) == everything(&whole), "three shards at once differ from the whole bake");
}

#[test]
fn resume_bakes_again_every_frame_that_is_empty_truncated_changed_or_unrecorded() {
    let tmp = tempfile::tempdir().unwrap();
    let sea = sea_scene(tmp.path(), "sea.toml", 16);
    let out = tmp.path().join("out");
    assert!(run(bake(&sea, "0..6", &out, &["--png", "8"])).status.success());
    let whole = files(&out);
    assert_eq!(whole.len(), 1 + 7 * 5);
    let path = |name: &str| out.join(name);
    std::fs::write(path("disp_0001.exr"), b"").unwrap(); // emptied
    let png = &whole["normal_0002.png"];
    std::fs::write(path("normal_0002.png"), &png[..png.len() / 2]).unwrap(); // truncated
    let mut exr = whole["disp_0003.exr"].clone();
    let at = exr.len() - 100;
    exr[at] ^= 0x40; // one bit flipped in the pixels: same size, same header
    std::fs::write(path("disp_0003.exr"), &exr).unwrap();
    std::fs::remove_file(path("check_0004.json")).unwrap(); // cut short before its record
    std::fs::remove_file(path("normal_0005.exr")).unwrap(); // a file lost
    std::fs::write(path("check_0006.json"), &whole["check_0000.json"]).unwrap(); // another frame's record
                                                                                 // A record of another bake: the same frame of a bake with other settings.
    let elsewhere = tmp.path().join("elsewhere");
    assert!(run(bake(&sea, "0..6", &elsewhere, &["--png", "8", "--fps", "30"])).status.success());
    std::fs::write(path("check_0000.json"), std::fs::read(elsewhere.join("check_0000.json")).unwrap()).unwrap();

    let o = run(bake(&sea, "0..6", &out, &["--png", "8", "--resume"]));
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(!e.contains("already complete"), "{e}");
    assert!(e.contains("7 frames failed their check and are baked again"), "{e}");
    for line in [
        "frame 0: check_0000.json belongs to another bake",
        "frame 1: disp_0001.exr is 0 bytes, its record says",
        "frame 2: normal_0002.png is",
        "frame 3: disp_0003.exr's checksum is",
        "frame 4: check_0004.json is missing",
        "frame 5: normal_0005.exr is missing",
        "frame 6: check_0006.json is the record of frame 0, not 6",
    ] {
        assert!(e.contains(line), "no `{line}` in: {e}");
    }
    assert!(files(&out) == whole, "the resumed bake differs from the original");
    // Nothing left to do now.
    let o = run(bake(&sea, "0..6", &out, &["--png", "8", "--resume"]));
    assert!(o.status.success() && stderr(&o).contains("7 frames already complete"), "{}", stderr(&o));
    assert!(!stderr(&o).contains("failed their check"), "{}", stderr(&o));
}

#[test]
fn frame_files_without_bake_json_are_never_adopted_nor_baked_over() {
    let tmp = tempfile::tempdir().unwrap();
    let sea = sea_scene(tmp.path(), "sea.toml", 16);
    let other = sea_scene(tmp.path(), "other.toml", 8);
    let out = tmp.path().join("out");
    assert!(run(bake(&sea, "0..4", &out, &[])).status.success());
    std::fs::remove_file(out.join("bake.json")).unwrap();
    let before = everything(&out);
    for (scene, extra) in [(&other, &["--resume"][..]), (&sea, &["--resume"][..]), (&other, &[][..])] {
        let o = run(bake(scene, "0..4", &out, extra));
        let e = stderr(&o);
        assert!(!o.status.success(), "{extra:?}: frame files without bake.json were taken: {e}");
        assert!(
            e.contains("holds frame files (check_0000.json, check_0001.json, check_0002.json, ... 15 files in all)"),
            "{e}"
        );
        assert!(e.contains("but no bake.json") && e.contains("bake into a new directory"), "{e}");
        assert!(everything(&out) == before, "{extra:?}: a refused bake changed the directory");
    }
    // Other files are the user's business: a directory with only those bakes.
    let notes = tmp.path().join("notes");
    std::fs::create_dir(&notes).unwrap();
    std::fs::write(notes.join("README.txt"), "my bakes").unwrap();
    assert!(run(bake(&sea, "0..1", &notes, &["--resume"])).status.success());
}

#[test]
fn a_directory_holds_one_bake_and_a_damaged_bake_json_is_named_by_its_cause() {
    let tmp = tempfile::tempdir().unwrap();
    let sea = sea_scene(tmp.path(), "sea.toml", 16);
    let other = sea_scene(tmp.path(), "other.toml", 8);
    let out = tmp.path().join("out");
    assert!(run(bake(&sea, "0..4", &out, &[])).status.success());
    let before = everything(&out);
    // Another bake, with or without --resume: refused, naming the keys; nothing changes.
    for extra in [&[][..], &["--resume"][..]] {
        let o = run(bake(&other, "0..1", &out, extra));
        let e = stderr(&o);
        assert!(!o.status.success(), "{extra:?}: a second bake was mixed into the first");
        assert!(e.contains("bake.json describes a different bake (`frames`, `grid.cells`"), "{e}");
        assert!(e.contains("`model_params.cells` differ)"), "{e}");
        assert!(e.contains("delete the old bake's files first"), "{e}");
        assert!(everything(&out) == before, "{extra:?}: a refused bake changed the directory");
    }
    // The same bake without --resume bakes every frame again, to the same bytes.
    let o = run(bake(&sea, "0..4", &out, &[]));
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(everything(&out) == before);

    // A bake.json that is empty, cut short or not JSON: the message says which.
    let manifest = before["bake.json"].clone();
    for (bytes, cause) in [
        (b"".to_vec(), "bake.json is empty (0 bytes)"),
        (manifest[..manifest.len() / 2].to_vec(), "bake.json is cut short: its JSON ends at line"),
        (b"not json\n".to_vec(), "bake.json is not JSON"),
        (b"{\"a\": 1}\n".to_vec(), "bake.json is not a bake manifest"),
    ] {
        std::fs::write(out.join("bake.json"), &bytes).unwrap();
        let damaged = everything(&out);
        for extra in [&[][..], &["--resume"][..]] {
            let o = run(bake(&sea, "0..4", &out, extra));
            let e = stderr(&o);
            assert!(!o.status.success() && e.contains(cause), "{cause}: {e}");
            assert!(!e.contains("another version"), "{cause}: {e}");
            assert!(everything(&out) == damaged, "{cause}: a refused bake changed the directory");
        }
    }
}
