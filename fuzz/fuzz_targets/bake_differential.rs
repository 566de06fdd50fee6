//! Differential bake (issue 37): from the input bytes, a small water-only scene (one of seven
//! models on a grid of at most 6 x 6 cells) and bake settings (a few frames anywhere in 0..45,
//! frame rate, PNGs, EXR compression, normal space, tiling). A bake in one go must equal, byte for
//! byte in every file (`bake.json`, maps and the frames' `check_NNNN.json` records):
//!
//! - the same bake as 2 to 4 shards, run one after the other in an input-chosen order into one
//!   directory;
//! - the same bake killed after some frame (the later frames' files gone) with one earlier frame
//!   damaged (a map emptied, truncated, changed in place or removed, or its record removed or
//!   swapped for another frame's), then resumed: the resume must bake exactly the lost and damaged
//!   frames again, and nothing else;
//!
//! and a one-frame bake of each frame must give that frame's maps (its `bake.json` and record
//! differ: they name another range). No lock or temporary file may be left behind. An input whose
//! bake is refused (a tile on water that does not repeat) must be refused again the same way.
#![no_main]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use libfuzzer_sys::fuzz_target;
use swell::export::{model_loop_period, Bake, BakeSettings, ExrCompression, FrameRange, NormalSpace, Shard};
use swell::scene::Scene;
use swell::world::World;

#[path = "common/input_bytes.rs"]
mod input_bytes;
use input_bytes::Bytes;

/// A water-only scene and whether it may tile (an FFT ocean over exactly its patch).
fn scene_text(b: &mut Bytes) -> (String, bool) {
    let cells = format!("cells = [{}, {}]\n", b.range(1, 6), b.range(1, 6));
    let seed = b.range(0, 255);
    let (body, tiles) = match b.byte() % 7 {
        0 => (format!("model = \"gerstner\"\nsize = [{s}.0, {s}.0]\n", s = b.pick(&[4, 20, 200])), false),
        1 => (
            format!(
                "model = \"noise\"\nsize = [20.0, 20.0]\namplitude = {}\nseed = {seed}\n",
                b.pick(&["0.1", "0.6", "2.0"])
            ),
            false,
        ),
        2 => {
            let patch = b.pick(&[16, 32, 96]);
            let looping = if b.byte() % 2 == 0 { "loop_period = 2.0\n" } else { "" };
            (
                format!(
                    "model = \"fft\"\nsize = [{patch}.0, {patch}.0]\ngrid = 16\npatch_size = {patch}.0\nwind_speed = {}\n\
                     choppiness = {}\nseed = {seed}\ncascades = 1\nfoam = true\nfoam_fade_s = {}\n{looping}",
                    b.pick(&["5.0", "15.0", "25.0"]),
                    b.pick(&["0.0", "1.0", "2.0"]),
                    b.pick(&["0.5", "2.0"]),
                ),
                true,
            )
        }
        3 => (format!("model = \"wave-set\"\nsize = [20.0, 20.0]\ncount = {}\nseed = {seed}\n", b.range(1, 6)), false),
        4 => ("model = \"radial\"\nsize = [2.0, 2.0]\n".to_string(), false),
        // Time-stepped: every shard and resume integrates from t = 0.
        5 => (
            "model = \"springs\"\nsize = [4.0, 4.0]\nlattice = [8, 8]\nspacing = 0.5\ntime_step = 0.4\nwarm_up = 1.0\n"
                .to_string(),
            false,
        ),
        _ => ("model = \"tessendorf\"\nsize = [20.0, 20.0]\nloop_period = 10.0\n".to_string(), false),
    };
    (format!("[water]\n{body}{cells}"), tiles)
}

/// Bakes `settings` of the scene `text` into `dir`; the frames it baked, or the error in words.
fn bake(text: &str, dir: &Path, settings: &BakeSettings) -> Result<Vec<u32>, String> {
    let scene = Scene::from_toml(text, "fuzz").map_err(|e| e.to_string())?;
    let mut world = World::new(scene).map_err(|e| e.to_string())?;
    let mut s = settings.clone();
    s.loop_period_s = model_loop_period(&world);
    let bake = Bake::prepare(&mut world, dir, s).map_err(|e| e.to_string())?;
    bake.run(&mut world, &|_| {}).map_err(|e| e.to_string())?;
    Ok(bake.frames_to_bake().to_vec())
}

/// Every file of `dir` with its bytes; a lock or temporary file left behind fails the input.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let e = e.unwrap();
        let name = e.file_name().to_string_lossy().into_owned();
        assert!(!name.starts_with('.') && !name.ends_with(".lock"), "{name} left in {}", dir.display());
        out.insert(name, std::fs::read(e.path()).unwrap());
    }
    out
}

/// A fresh scratch directory (removed by [`Scratch`]'s drop).
struct Scratch(PathBuf);

impl Scratch {
    fn new() -> Self {
        static COUNT: AtomicU64 = AtomicU64::new(0);
        let n = COUNT.fetch_add(1, Ordering::SeqCst);
        let dir = std::env::temp_dir().join(format!("swell-fuzz-bake-{}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }

    fn join(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fuzz_target!(|data: &[u8]| {
    let mut b = Bytes(data);
    let (text, tiles) = scene_text(&mut b);
    let first = b.range(0, 40);
    let last = first + b.range(0, 4);
    let mut s = BakeSettings::new(FrameRange::new("frames", first, last).unwrap());
    s.fps = b.pick(&[24.0, 30.0, 12.5, 60.0]);
    s.png_bits = b.pick(&[None, Some(8), Some(16)]);
    if s.png_bits.is_some() && b.byte() % 2 == 0 {
        s.png_range_m = Some(b.pick(&[0.5, 2.0]));
    }
    s.compression = b.pick(&[ExrCompression::None, ExrCompression::Rle, ExrCompression::Zip, ExrCompression::Piz]);
    s.normal_space = b.pick(&[NormalSpace::World, NormalSpace::TangentGl, NormalSpace::TangentDx]);
    // Mostly where it works; sometimes where it must be refused.
    s.tile = b.byte() % 4 == 0 && (tiles || b.byte() % 4 == 0);
    let frames: Vec<u32> = (first..=last).collect();
    let scratch = Scratch::new();

    // In one go.
    let whole_dir = scratch.join("whole");
    let whole = match bake(&text, &whole_dir, &s) {
        Ok(done) => {
            assert_eq!(done, frames);
            files(&whole_dir)
        }
        Err(e) => {
            // Refused (or failed): again the same way, whatever the directory.
            let again_dir = scratch.join("again");
            let again = bake(&text, &again_dir, &s).expect_err("a refused bake ran the second time");
            let (a, w) = (again_dir.to_string_lossy(), whole_dir.to_string_lossy());
            assert_eq!(e, again.replace(a.as_ref(), w.as_ref()));
            return;
        }
    };
    assert_eq!(whole.len(), 1 + frames.len() * files_per_frame(&whole, first));

    // Sharded into one directory, the shards in an input-chosen order.
    let count = b.range(2, 4);
    let start = b.range(0, count - 1);
    let sharded_dir = scratch.join("sharded");
    for k in 0..count {
        let shard = BakeSettings { shard: Shard { index: (start + k) % count, count }, ..s.clone() };
        bake(&text, &sharded_dir, &shard).expect("a shard of a bake that ran");
    }
    assert!(files(&sharded_dir) == whole, "{count} shards differ from the whole bake:\n{text}{s:?}");

    // Killed after frame `cut`, one frame at or before it damaged, then resumed.
    let resumed_dir = scratch.join("resumed");
    std::fs::create_dir(&resumed_dir).unwrap();
    for (name, bytes) in &whole {
        std::fs::write(resumed_dir.join(name), bytes).unwrap();
    }
    let cut = first + b.range(0, last - first);
    let frame_of = |name: &str| -> Option<u32> {
        let stem = name.rsplit_once('.')?.0;
        stem.rsplit_once('_')?.1.parse().ok()
    };
    for name in whole.keys() {
        if frame_of(name).is_some_and(|f| f > cut) {
            std::fs::remove_file(resumed_dir.join(name)).unwrap();
        }
    }
    let damaged = first + b.range(0, cut - first);
    let names: Vec<&String> = whole.keys().filter(|n| frame_of(n) == Some(damaged)).collect();
    let victim = resumed_dir.join(b.pick(&names));
    let len = std::fs::metadata(&victim).unwrap().len() as usize;
    let mut expect: Vec<u32> = frames.iter().copied().filter(|&f| f > cut).collect();
    let effective = match b.byte() % 5 {
        0 => std::fs::write(&victim, b"").map(|()| len > 0),
        1 => {
            let keep = usize::from(b.byte()) * len / 256;
            std::fs::write(&victim, &std::fs::read(&victim).unwrap()[..keep]).map(|()| keep < len)
        }
        2 => {
            let mut bytes = std::fs::read(&victim).unwrap();
            let at = (usize::from(b.byte()) << 8 | usize::from(b.byte())) % bytes.len().max(1);
            if let Some(x) = bytes.get_mut(at) {
                *x ^= 1 << (b.byte() % 8);
            }
            std::fs::write(&victim, &bytes).map(|()| !bytes.is_empty())
        }
        3 => std::fs::remove_file(&victim).map(|()| true),
        _ => {
            // Another frame's record in place of this one's (if there is another frame).
            let other = frames.iter().copied().find(|&f| f != damaged && f <= cut);
            let record = resumed_dir.join(format!("check_{damaged:04}.json"));
            match other {
                Some(o) => std::fs::copy(resumed_dir.join(format!("check_{o:04}.json")), &record).map(|_| true),
                None => std::fs::remove_file(&record).map(|()| true),
            }
        }
    }
    .unwrap();
    if effective {
        expect.push(damaged);
        expect.sort_unstable();
    }
    let resume = BakeSettings { resume: true, ..s.clone() };
    let done = bake(&text, &resumed_dir, &resume).expect("resuming a bake that ran");
    assert_eq!(done, expect, "resume baked other frames than the lost and damaged ones");
    assert!(files(&resumed_dir) == whole, "the resumed bake differs from the whole one:\n{text}{s:?}");

    // Each frame alone: the same maps (PNGs only with a given range: the automatic one comes from
    // the range's first frame).
    for &f in &frames {
        let dir = scratch.join(&format!("single-{f}"));
        let one = BakeSettings { frames: FrameRange::new("frames", f, f).unwrap(), ..s.clone() };
        assert_eq!(bake(&text, &dir, &one).expect("one frame of a bake that ran"), [f]);
        for (name, bytes) in files(&dir) {
            let map = !name.starts_with("check_") && name != "bake.json";
            if map && (name.ends_with(".exr") || s.png_range_m.is_some()) {
                assert!(whole[&name] == bytes, "{name} of a one-frame bake differs:\n{text}{s:?}");
            }
        }
    }
});

/// Files per frame: the maps of frame `first` (EXR and PNG) and its record.
fn files_per_frame(files: &BTreeMap<String, Vec<u8>>, first: u32) -> usize {
    let tag = format!("_{first:04}.");
    files.keys().filter(|n| n.contains(&tag)).count()
}
