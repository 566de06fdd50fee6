//! `swell bake` and `swell export` through the real binary in a temporary directory: kill and
//! resume, shards, bad input, and the files the commands promise.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

mod common;
use common::{files, stderr, swell, SWELL};

/// The sea preset on a grid of `cells` x `cells`, written to `dir/sea.toml`.
fn sea_scene(dir: &Path, cells: u32) -> PathBuf {
    let text = include_str!("../../swell/presets/sea.toml")
        .replace("cells = [256, 256]", &format!("cells = [{cells}, {cells}]"));
    assert!(text.contains(&format!("[{cells}, {cells}]")));
    let path = dir.join("sea.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_killed_bake_resumed_equals_an_uninterrupted_one_byte_for_byte() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = sea_scene(tmp.path(), 128);
    let scene = scene.to_str().unwrap();
    let (killed, whole) = (tmp.path().join("killed"), tmp.path().join("whole"));
    // PNGs and compression make each frame slow enough (tens of ms on one thread) to kill mid-way.
    let args = |out: &Path| -> Vec<String> {
        [
            "bake",
            "--scene",
            scene,
            "--frames",
            "0..79",
            "--png",
            "16",
            "--exr-compression",
            "zip",
            "--threads",
            "1",
            "--quiet",
            "--out",
        ]
        .iter()
        .map(|s| s.to_string())
        .chain([out.to_str().unwrap().to_string()])
        .collect()
    };
    let mut child = Command::new(SWELL).args(args(&killed)).spawn().unwrap();
    let start = Instant::now();
    while !killed.join("disp_0003.png").exists() {
        assert!(start.elapsed() < Duration::from_secs(60), "the bake never got going");
        assert!(child.try_wait().unwrap().is_none(), "the bake ended before it could be killed");
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let mut partial = files(&killed);
    assert!(!partial.contains_key("disp_0079.exr"), "the bake finished before it was killed");
    // SIGKILL leaves the killed bake's lock; its process is gone, so the resume removes it.
    assert!(partial.remove("bake.lock").is_some(), "no lock while baking: {:?}", partial.keys());

    let mut resume = args(&killed);
    resume.push("--resume".into());
    let o = Command::new(SWELL).args(&resume).output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("already complete"), "{}", stderr(&o));
    assert!(stderr(&o).contains("removed the stale lock"), "{}", stderr(&o));
    let o = Command::new(SWELL).args(args(&whole)).output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));

    let (resumed, whole) = (files(&killed), files(&whole));
    assert_eq!(whole.len(), 1 + 80 * 5, "bake.json; per frame 2 EXR, 2 PNG and the record");
    assert_eq!(resumed.keys().collect::<Vec<_>>(), whole.keys().collect::<Vec<_>>());
    for (name, bytes) in &whole {
        assert!(&resumed[name] == bytes, "{name} differs after kill + resume");
    }
    // Complete frames from before the kill were kept, not rewritten with other bytes.
    for (name, bytes) in &partial {
        assert!(&whole[name] == bytes, "{name} written before the kill differs");
    }
}

#[test]
fn three_shards_together_equal_the_whole_bake() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = sea_scene(tmp.path(), 24);
    let scene = scene.to_str().unwrap();
    let (sharded, whole) = (tmp.path().join("sharded"), tmp.path().join("whole"));
    for shard in ["2/3", "0/3", "1/3"] {
        let o = swell(&[
            "bake",
            "--scene",
            scene,
            "--frames",
            "5..14",
            "--fps",
            "30",
            "--shard",
            shard,
            "--out",
            sharded.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let o = swell(&["bake", "--scene", scene, "--frames", "5..14", "--fps", "30", "--out", whole.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (sharded, whole) = (files(&sharded), files(&whole));
    assert_eq!(whole.len(), 1 + 10 * 3, "bake.json; per frame 2 EXR and the record");
    assert!(sharded == whole, "shards differ from the whole bake");
}

#[test]
fn bad_frame_ranges_and_unwritable_outputs_are_clear_errors_and_write_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = sea_scene(tmp.path(), 8);
    let scene = scene.to_str().unwrap();
    let out = tmp.path().join("out");
    let out_s = out.to_str().unwrap();
    for (frames, expect) in [
        ("9..3", "ends before it starts"),
        ("abc", "or a range A..B"),
        ("-2..5", "or a range A..B"),
        ("2..", "or a range A..B"),
        ("1.5..3", "or a range A..B"),
        ("0", "0 frames"),
        ("0..99999999999", "is outside"),
    ] {
        let o = swell(&["bake", "--scene", scene, "--frames", frames, "--out", out_s]);
        assert!(!o.status.success(), "--frames {frames} was accepted");
        let e = stderr(&o);
        assert!(e.contains("--frames") && e.contains(expect), "--frames {frames}: {e}");
        assert!(!out.exists(), "--frames {frames} left output behind");
    }
    for (args, expect) in [
        (vec!["--shard", "3/3"], "--shard index = 3 is outside [0, 2]"),
        (vec!["--fps", "0"], "--fps = 0 is outside"),
        (vec!["--png", "12"], "--png"),
        (vec!["--exr-compression", "lzw"], "--exr-compression"),
    ] {
        let mut a = vec!["bake", "--scene", scene, "--frames", "0..2", "--out", out_s];
        a.extend(args.iter());
        let o = swell(&a);
        assert!(!o.status.success() && stderr(&o).contains(expect), "{args:?}: {}", stderr(&o));
        assert!(!out.exists());
    }
    // A directory that cannot be created (its parent is a file): the error names the path.
    let file = tmp.path().join("a-file");
    std::fs::write(&file, "x").unwrap();
    let under_file = file.join("bake");
    let o = swell(&["bake", "--scene", scene, "--frames", "0..2", "--out", under_file.to_str().unwrap()]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains(under_file.to_str().unwrap()), "{}", stderr(&o));
    let o = swell(&["bake", "--scene", scene, "--frames", "0..2", "--out", file.to_str().unwrap()]);
    assert!(!o.status.success() && stderr(&o).contains("not a directory"), "{}", stderr(&o));
    let o = swell(&["export", "--scene", scene, "--out", under_file.join("x.glb").to_str().unwrap()]);
    assert!(!o.status.success() && stderr(&o).contains("is a file, not a directory"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&file).unwrap(), b"x");
}

#[test]
fn resume_refuses_a_directory_baked_with_other_settings() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = sea_scene(tmp.path(), 8);
    let scene = scene.to_str().unwrap();
    let out = tmp.path().join("out");
    let out_s = out.to_str().unwrap();
    assert!(swell(&["bake", "--scene", scene, "--frames", "0..3", "--out", out_s]).status.success());
    let before = files(&out);
    let o = swell(&["bake", "--scene", scene, "--frames", "0..3", "--fps", "30", "--resume", "--out", out_s]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("`fps` differs"), "{}", stderr(&o));
    assert!(files(&out) == before, "a refused resume changed the bake");
    let o = swell(&["bake", "--scene", scene, "--frames", "0..3", "--resume", "--out", out_s]);
    assert!(o.status.success() && stderr(&o).contains("4 frames already complete"), "{}", stderr(&o));
}

#[test]
fn export_writes_every_format_and_one_file_per_frame() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = sea_scene(tmp.path(), 16);
    let scene = scene.to_str().unwrap();
    let d = tmp.path();
    let p = |name: &str| d.join(name).to_str().unwrap().to_string();
    for (out, format) in [("a.obj", None), ("b.gltf", None), ("c.glb", None), ("d.mesh", Some("glb"))] {
        let mut a = vec!["export", "--scene", scene, "--time", "1.5", "--out"];
        let out_path = p(out);
        a.push(&out_path);
        if let Some(f) = format {
            a.extend(["--format", f]);
        }
        let o = swell(&a);
        assert!(o.status.success(), "{out}: {}", stderr(&o));
    }
    let obj = std::fs::read_to_string(d.join("a.obj")).unwrap();
    assert_eq!(obj.lines().filter(|l| l.starts_with("v ")).count(), 17 * 17);
    assert_eq!(obj.lines().filter(|l| l.starts_with("f ")).count(), 2 * 16 * 16);
    assert!(d.join("b.bin").is_file());
    assert_eq!(&std::fs::read(d.join("d.mesh")).unwrap()[..4], b"glTF");
    assert_eq!(std::fs::read(d.join("c.glb")).unwrap(), std::fs::read(d.join("d.mesh")).unwrap());

    let o = swell(&["export", "--scene", scene, "--frames", "8..10", "--fps", "12", "--out", &p("seq.gltf")]);
    assert!(o.status.success(), "{}", stderr(&o));
    for k in 8..=10 {
        assert!(d.join(format!("seq_{k:04}.gltf")).is_file() && d.join(format!("seq_{k:04}.bin")).is_file());
    }
    // Frame 9 at 12 fps is time 0.75 s: the same bytes as a single export at --time 0.75.
    let o = swell(&["export", "--scene", scene, "--time", "0.75", "--out", &p("single.gltf")]);
    assert!(o.status.success());
    assert_eq!(std::fs::read(d.join("seq_0009.bin")).unwrap(), std::fs::read(d.join("single.bin")).unwrap());

    for (args, expect) in [
        (vec!["--out", "x.stl"], "--out"),
        (vec!["--out", "x.obj", "--format", "fbx"], "--format"),
        (vec!["--out", "x.obj", "--frames", "3..1"], "--frames"),
    ] {
        let mut a = vec!["export", "--scene", scene];
        a.extend(args.iter());
        let o = swell(&a);
        assert!(!o.status.success() && stderr(&o).contains(expect), "{args:?}: {}", stderr(&o));
    }
}

/// Every variable `--shard auto` reads, removed so the test's own environment cannot leak in.
const ARRAY_JOB_VARS: [&str; 9] = [
    "SLURM_ARRAY_TASK_ID",
    "SLURM_ARRAY_TASK_MIN",
    "SLURM_ARRAY_TASK_STEP",
    "SLURM_ARRAY_TASK_COUNT",
    "JOB_COMPLETION_INDEX",
    "AWS_BATCH_JOB_ARRAY_INDEX",
    "AWS_BATCH_JOB_ARRAY_SIZE",
    "SWELL_SHARD_COUNT",
    "SLURM_ARRAY_TASK_MAX",
];

/// `swell args` with exactly the array-job variables `vars` set.
fn swell_in_job(args: &[&str], vars: &[(&str, &str)]) -> Output {
    let mut c = Command::new(SWELL);
    c.args(args);
    for v in ARRAY_JOB_VARS {
        c.env_remove(v);
    }
    c.envs(vars.iter().copied());
    c.output().unwrap()
}

#[test]
fn shard_auto_takes_the_slurm_array_tasks_and_says_so() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = sea_scene(tmp.path(), 12);
    let scene = scene.to_str().unwrap();
    let (farm, whole) = (tmp.path().join("farm"), tmp.path().join("whole"));
    let args = |out: &Path| -> Vec<String> {
        ["bake", "--scene", scene, "--frames", "2..9", "--shard", "auto", "--quiet", "--out"]
            .iter()
            .map(|s| s.to_string())
            .chain([out.to_str().unwrap().to_string()])
            .collect()
    };
    // sbatch --array=1-3: task ids 1, 2, 3 are shards 0, 1, 2.
    for id in ["3", "1", "2"] {
        let a = args(&farm);
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        let o = swell_in_job(
            &a,
            &[
                ("SLURM_ARRAY_TASK_ID", id),
                ("SLURM_ARRAY_TASK_MIN", "1"),
                ("SLURM_ARRAY_TASK_MAX", "3"),
                ("SLURM_ARRAY_TASK_COUNT", "3"),
            ],
        );
        assert!(o.status.success(), "{}", stderr(&o));
        let shard = id.parse::<u32>().unwrap() - 1;
        let e = stderr(&o);
        assert!(e.contains(&format!("shard {shard}/3 from the Slurm job array")), "{e}");
        assert!(e.contains(&format!("SLURM_ARRAY_TASK_ID = {id}")) && e.contains("SLURM_ARRAY_TASK_COUNT = 3"), "{e}");
    }
    let o = swell(&["bake", "--scene", scene, "--frames", "2..9", "--quiet", "--out", whole.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (farm, whole) = (files(&farm), files(&whole));
    assert_eq!(whole.len(), 1 + 8 * 3, "bake.json; per frame 2 EXR and the record");
    assert!(farm == whole, "the three array tasks differ from the whole bake");

    // Kubernetes: the index, with the count from auto/N or SWELL_SHARD_COUNT.
    let k8s = tmp.path().join("k8s");
    let k8s_s = k8s.to_str().unwrap();
    for (index, shard, vars) in [("0", "auto/2", vec![]), ("1", "auto", vec![("SWELL_SHARD_COUNT", "2")])] {
        let mut v = vars.clone();
        v.push(("JOB_COMPLETION_INDEX", index));
        let o = swell_in_job(
            &["bake", "--scene", scene, "--frames", "2..9", "--shard", shard, "--quiet", "--out", k8s_s],
            &v,
        );
        assert!(o.status.success() && stderr(&o).contains("Kubernetes indexed job"), "{}", stderr(&o));
    }
    assert!(files(&k8s) == whole, "the two Kubernetes pods differ from the whole bake");
}

#[test]
fn shard_auto_errors_name_the_variable_value_and_range_and_write_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = sea_scene(tmp.path(), 8);
    let scene = scene.to_str().unwrap();
    let out = tmp.path().join("out");
    let out_s = out.to_str().unwrap();
    for (shard, vars, expect) in [
        ("auto", vec![], "no array-job variable is set"),
        ("auto", vec![("JOB_COMPLETION_INDEX", "3")], "JOB_COMPLETION_INDEX = 3) but it does not say how many tasks"),
        ("auto/4", vec![("JOB_COMPLETION_INDEX", "4")], "--shard auto: JOB_COMPLETION_INDEX = 4 is outside [0, 3]"),
        (
            "auto",
            vec![("SLURM_ARRAY_TASK_ID", "17"), ("SLURM_ARRAY_TASK_MIN", "1"), ("SLURM_ARRAY_TASK_COUNT", "16")],
            "--shard auto: SLURM_ARRAY_TASK_ID = 17 is outside [1, 16]",
        ),
        (
            "auto",
            vec![("AWS_BATCH_JOB_ARRAY_INDEX", "two"), ("AWS_BATCH_JOB_ARRAY_SIZE", "4")],
            "AWS_BATCH_JOB_ARRAY_INDEX: `two`",
        ),
        ("auto", vec![("AWS_BATCH_JOB_ARRAY_INDEX", "1")], "AWS_BATCH_JOB_ARRAY_SIZE is not set"),
        ("auto/x", vec![("JOB_COMPLETION_INDEX", "1")], "--shard auto/N: `x` is not a whole number"),
    ] {
        let o = swell_in_job(&["bake", "--scene", scene, "--frames", "0..3", "--shard", shard, "--out", out_s], &vars);
        assert!(!o.status.success(), "{shard} {vars:?} was accepted");
        assert!(stderr(&o).contains(expect), "{shard} {vars:?}: {}", stderr(&o));
        assert!(!out.exists(), "{shard} {vars:?} left output behind");
    }
}

#[test]
fn normal_space_is_checked_recorded_and_part_of_what_resume_compares() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = sea_scene(tmp.path(), 8);
    let scene = scene.to_str().unwrap();
    let out = tmp.path().join("out");
    let out_s = out.to_str().unwrap();
    let o = swell(&["bake", "--scene", scene, "--frames", "0..1", "--normal-space", "tangent", "--out", out_s]);
    assert!(!o.status.success(), "--normal-space tangent was accepted");
    assert!(
        stderr(&o).contains("--normal-space: `tangent` is not a normal space; valid: world, tangent-gl, tangent-dx")
    );
    assert!(!out.exists());

    let o = swell(&["bake", "--scene", scene, "--frames", "0..1", "--normal-space", "tangent-dx", "--out", out_s]);
    assert!(o.status.success(), "{}", stderr(&o));
    let manifest: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("bake.json")).unwrap()).unwrap();
    assert_eq!(manifest["normal_space"], "tangent-dx");
    assert_eq!(manifest["manifest_version"], 2);
    assert_eq!(manifest["axes"]["to_blender"]["matrix"], serde_json::json!([[1, 0, 0], [0, 0, -1], [0, 1, 0]]));
    assert_eq!(manifest["units"]["length"], "metre");
    let before = files(&out);
    // Resuming with another normal space is refused, naming the key.
    let o = swell(&["bake", "--scene", scene, "--frames", "0..1", "--resume", "--out", out_s]);
    assert!(!o.status.success() && stderr(&o).contains("`normal_space`"), "{}", stderr(&o));
    assert!(files(&out) == before);
    // The same options resume.
    let resume_dx = || {
        swell(&[
            "bake",
            "--scene",
            scene,
            "--frames",
            "0..1",
            "--normal-space",
            "tangent-dx",
            "--resume",
            "--out",
            out_s,
        ])
    };
    let o = resume_dx();
    assert!(o.status.success() && stderr(&o).contains("2 frames already complete"), "{}", stderr(&o));

    // A directory baked by a swell before manifest_version 2 is refused with the reason.
    let mut old = manifest.clone();
    old.as_object_mut().unwrap().remove("manifest_version");
    std::fs::write(out.join("bake.json"), serde_json::to_vec_pretty(&old).unwrap()).unwrap();
    let o = resume_dx();
    assert!(!o.status.success(), "an old manifest was resumed");
    assert!(stderr(&o).contains("has manifest_version 1, this swell writes 2"), "{}", stderr(&o));
}
