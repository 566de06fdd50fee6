//! End-to-end tests of issue 33's animation outputs through the real binary: the GIF (its own
//! median-cut quantiser and ordered dither) shows the same frames as the PNG sequence, up to the
//! palette; the PNG sequence is numbered by absolute frame, resumable and refuses bad patterns;
//! both are identical on one and two threads.

use std::os::unix::fs::MetadataExt;
use std::path::Path;
use std::process::{Command, Output};

fn swell(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swell")).args(args).current_dir(dir).output().expect("run swell")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn ok(dir: &Path, args: &[&str]) -> String {
    let o = swell(dir, args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    stderr(&o)
}

/// Every file under `dir`, recursively, temporary files included, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut v = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let e = e.unwrap();
        let name = e.file_name().to_string_lossy().into_owned();
        if e.file_type().unwrap().is_dir() {
            v.extend(listing(&e.path()).into_iter().map(|f| format!("{name}/{f}")));
        } else {
            v.push(name);
        }
    }
    v.sort();
    v
}

fn gif_frames(path: &Path) -> Vec<image::RgbaImage> {
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let decoder = image::codecs::gif::GifDecoder::new(file).unwrap();
    let frames = image::AnimationDecoder::into_frames(decoder).collect_frames().unwrap();
    frames.into_iter().map(|f| f.into_buffer()).collect()
}

fn png(path: &Path) -> image::RgbaImage {
    image::open(path).unwrap().to_rgba8()
}

/// Per-channel mean and largest absolute difference of two images' RGB, in 8-bit levels.
fn difference(a: &image::RgbaImage, b: &image::RgbaImage) -> (f64, u8) {
    assert_eq!(a.dimensions(), b.dimensions());
    let (mut sum, mut max, mut n) = (0u64, 0u8, 0u64);
    for (p, q) in a.pixels().zip(b.pixels()) {
        for c in 0..3 {
            let d = p[c].abs_diff(q[c]);
            sum += u64::from(d);
            max = max.max(d);
            n += 1;
        }
    }
    (sum as f64 / n as f64, max)
}

/// The GIF and the PNG sequence of the same frames: each GIF frame is its PNG frame through a
/// 256-colour palette and an ordered dither, so on average within 2 levels a channel (measured
/// 1.25 to 1.28 here: the dither's offsets average out, the palette's error in a sea's few hues
/// is about 1) and nowhere more than 24 (the dither's largest amplitude, peak to peak, plus the
/// palette's error; measured 7 to 8). The test is only worth its tolerance if another frame is
/// further off: checked against the next frame (half a second later) being at least twice as far.
#[test]
fn gif_frames_equal_the_png_sequence_up_to_the_palette() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("frames")).unwrap();
    let common = ["render", "--preset", "sea", "--size", "160x90", "--frames", "2..5", "--fps", "2"];
    ok(dir.path(), &[&common[..], &["--out", "sea.gif"]].concat());
    let log = ok(dir.path(), &[&common[..], &["--out", "frames/sea_%04d.png"]].concat());
    assert!(log.contains("wrote 4 frames to frames/sea_%04d.png"), "{log}");
    assert_eq!(listing(&dir.path().join("frames")), ["sea_0002.png", "sea_0003.png", "sea_0004.png", "sea_0005.png"]);
    let gif = gif_frames(&dir.path().join("sea.gif"));
    assert_eq!(gif.len(), 4);
    let pngs: Vec<_> = (2..=5).map(|k| png(&dir.path().join(format!("frames/sea_{k:04}.png")))).collect();
    for (k, (g, p)) in gif.iter().zip(&pngs).enumerate() {
        let (mean, max) = difference(g, p);
        assert!(mean <= 2.0 && max <= 24, "frame {}: mean {mean:.2}, max {max} levels", k + 2);
        let (other, _) = difference(g, &pngs[(k + 1) % pngs.len()]);
        assert!(other > 2.0 * mean.max(1.0), "frame {}: the next frame is as close ({other:.2} vs {mean:.2})", k + 2);
    }
}

#[test]
fn gif_and_png_sequence_are_the_same_on_one_and_two_threads() {
    let dir = tempfile::tempdir().unwrap();
    for t in ["1", "2"] {
        std::fs::create_dir(dir.path().join(format!("t{t}"))).unwrap();
        let args = ["render", "--preset", "sea", "--size", "200x120", "--frames", "5", "--threads", t];
        ok(dir.path(), &[&args[..], &["--out", &format!("t{t}.gif")]].concat());
        ok(dir.path(), &[&args[..], &["--out", &format!("t{t}/f_%d.png")]].concat());
    }
    let read = |p: &str| std::fs::read(dir.path().join(p)).unwrap();
    assert_eq!(read("t1.gif"), read("t2.gif"), "the GIF depends on --threads");
    for k in 0..5 {
        assert_eq!(read(&format!("t1/f_{k}.png")), read(&format!("t2/f_{k}.png")), "frame {k} depends on --threads");
    }
}

#[test]
fn resume_skips_complete_frames_and_renders_missing_truncated_and_wrong_sized_ones() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("seq")).unwrap();
    let args = ["render", "--preset", "sea", "--size", "96x54", "--frames", "10..15", "--out", "seq/s_%03d.png"];
    ok(dir.path(), &args);
    let path = |k: u32| dir.path().join(format!("seq/s_{k:03}.png"));
    let originals: Vec<Vec<u8>> = (10..=15).map(|k| std::fs::read(path(k)).unwrap()).collect();
    // Frame 11 cut short (as a killed non-atomic writer would leave it), 13 gone, 14 another size.
    let f11 = &originals[1];
    std::fs::write(path(11), &f11[..f11.len() / 2]).unwrap();
    std::fs::remove_file(path(13)).unwrap();
    ok(dir.path(), &["render", "--preset", "sea", "--size", "48x27", "--time", "0.5", "--out", "seq/s_014.png"]);
    let inode = |k: u32| std::fs::metadata(path(k)).unwrap().ino();
    let before: Vec<u64> = [10, 11, 12, 14, 15].iter().map(|&k| inode(k)).collect();
    let log = ok(dir.path(), &[&args[..], &["--resume"]].concat());
    assert!(log.contains("wrote 3 frames to seq/s_%03d.png (3 already complete, skipped)"), "{log}");
    // Skipped frames are the same files (an atomic rewrite would give a new inode); the others
    // were written again, identical to the first run's.
    assert_eq!([inode(10), inode(12), inode(15)], [before[0], before[2], before[4]]);
    assert_ne!(inode(11), before[1]);
    assert_ne!(inode(14), before[3]);
    for (k, bytes) in (10..=15).zip(&originals) {
        assert_eq!(&std::fs::read(path(k)).unwrap(), bytes, "frame {k}");
    }
    let log = ok(dir.path(), &[&args[..], &["--resume"]].concat());
    assert!(log.contains("wrote 0 frames to seq/s_%03d.png (6 already complete, skipped)"), "{log}");
    assert_eq!(listing(&dir.path().join("seq")).len(), 6, "no temporary files left");
}

/// Runs a failing command: non-zero exit, every `expect` in the message, nothing written.
fn refused(args: &[&str], expect: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("frames")).unwrap();
    let base = ["render", "--preset", "sea", "--size", "32x18"];
    let o = swell(dir.path(), &[&base[..], args].concat());
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
    assert!(err.starts_with("error: "), "{args:?}: {err}");
    for e in expect {
        assert!(err.contains(e), "{args:?}: `{e}` not in: {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
    assert!(listing(dir.path()).is_empty(), "{args:?} left {:?}", listing(dir.path()));
}

#[test]
fn bad_patterns_are_refused_with_the_flag_the_value_and_what_is_valid() {
    let valid = "valid: one %d or %0Nd (N in [1, 9]) in the file name";
    refused(
        &["--frames", "3", "--out", "frames/a_%d_%d.png"],
        &["--out: ", "`frames/a_%d_%d.png`", "two frame-number directives", valid],
    );
    refused(
        &["--frames", "3", "--out", "frames/a_%s.png"],
        &["--out: ", "`%s` is not a frame-number directive", valid],
    );
    refused(&["--frames", "3", "--out", "frames/a_%4d.png"], &["--out: ", "pad with zeros", valid]);
    refused(&["--frames", "3", "--out", "frames/a_%012d.png"], &["--out: ", "outside [1, 9]", valid]);
    refused(&["--frames", "3", "--out", "frames/100%%.png"], &["--out: ", "no frame-number directive", valid]);
    refused(&["--out", "frames/a_%04d.png"], &["--out: ", "`frames/a_%04d.png` is a PNG sequence pattern", "--frames"]);
    refused(
        &["--frames", "3", "--out", "missing/a_%04d.png"],
        &["--out: ", "directory missing of the sequence `missing/a_%04d.png` does not exist"],
    );
    refused(&["--frames", "3", "--out", "a.png"], &["--out: ", "`a.png` is one file", "frames/sea_%04d.png"]);
    refused(&["--frames", "3", "--out", "a.gif", "--resume"], &["--resume: ", "applies to a PNG sequence"]);
    refused(&["--out", "a.png", "--resume"], &["--resume: ", "applies to a PNG sequence"]);
}

#[test]
fn verbose_reports_the_rendering_time_and_the_whole_command() {
    let dir = tempfile::tempdir().unwrap();
    let log = ok(
        dir.path(),
        &["render", "--preset", "sea", "--size", "64x36", "--frames", "3", "--verbose", "--out", "a.gif"],
    );
    assert!(log.contains("rendered 3 frames in "), "{log}");
    assert!(log.contains("the whole command took "), "{log}");
}
