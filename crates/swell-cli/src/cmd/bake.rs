//! `swell bake`: per-frame displacement, normal and foam maps into a directory (see docs/baking.md).

use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use swell::export::{
    model_loop_period, resolve_shard, Bake, BakeSettings, ExrCompression, FrameRange, NormalSpace, Shard,
};
use swell::world::World;
use swell::Result;

use super::{load_scene, thread_pool};
use crate::args::BakeArgs;

pub fn run(a: BakeArgs) -> Result<()> {
    // Every option is checked before the scene is loaded or anything is written.
    let mut settings = BakeSettings::new(FrameRange::parse("--frames", &a.frames)?);
    settings.fps = a.fps;
    settings.shard = match &a.shard {
        Some(s) => {
            // `auto` reads the batch system's array-job variables; I/N reads nothing.
            let env = |name: &str| std::env::var_os(name).map(|v| v.to_string_lossy().into_owned());
            let resolved = resolve_shard("--shard", s, &env)?;
            if let Some(source) = &resolved.source {
                eprintln!("--shard {}: {source}", s.trim());
            }
            resolved.shard
        }
        None => Shard::WHOLE,
    };
    settings.resume = a.resume;
    settings.png_bits = a.png;
    settings.png_range_m = a.png_range;
    settings.tile = a.tile;
    settings.compression = ExrCompression::parse("--exr-compression", &a.exr_compression)?;
    settings.normal_space = NormalSpace::parse("--normal-space", &a.normal_space)?;
    settings.validate()?;
    let scene = load_scene(&a.source)?;
    super::check_steps(
        &scene,
        "--frames / --fps (the last frame's time)",
        f64::from(settings.frames.last) / settings.fps,
    )?;
    let pool = thread_pool(a.threads)?;
    pool.install(|| {
        let mut world = World::new(scene)?;
        super::advance_with_progress(&mut world, f64::from(settings.frames.first) / settings.fps, World::advance)?;
        settings.loop_period_s = model_loop_period(&world);
        // Takes the directory's lock for this shard (held until `bake` is dropped, also when a
        // signal unwinds out of it) and refuses a directory that holds or bakes something else.
        let bake = Bake::prepare(&mut world, &a.out, settings)?;
        for note in bake.notes() {
            eprintln!("note: {}", swell::error::printable(note));
        }
        let todo = bake.frames_to_bake().len();
        if bake.skipped() > 0 {
            eprintln!("{} frames already complete in {}, skipped", bake.skipped(), a.out.display());
        }
        report_damaged(bake.damaged());
        let bar = if a.quiet { ProgressBar::hidden() } else { progress_bar(todo as u64, "baking") };
        let start = Instant::now();
        // issue 10: SIGINT/SIGTERM stop the bake after the frames in flight; --resume finishes it.
        let interrupt = crate::interrupt::Interrupt::install()?;
        let done = std::sync::atomic::AtomicUsize::new(0);
        let on_frame = |_| {
            bar.inc(1);
            done.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
            interrupt.stop_here();
        };
        let result = interrupt.catch(
            || bake.run(&mut world, &on_frame),
            || {
                interrupt.error(format_args!(
                    "{} of {todo} frames baked, every file in {} is complete; run the same command with --resume \
                     to bake the rest",
                    done.load(std::sync::atomic::Ordering::SeqCst),
                    a.out.display()
                ))
            },
        );
        bar.finish_and_clear();
        result?;
        let secs = start.elapsed().as_secs_f64();
        eprintln!(
            "baked {todo} frames into {} in {secs:.2} s ({:.1} frames/s)",
            a.out.display(),
            todo as f64 / secs.max(1e-9)
        );
        Ok(())
    })
}

/// Most damaged frames named one per line; the rest are counted.
const DAMAGED_LINES: usize = 10;

/// Tells which frames `--resume` found damaged and bakes again, and why.
fn report_damaged(damaged: &[(u32, String)]) {
    if damaged.is_empty() {
        return;
    }
    eprintln!("{} frames failed their check and are baked again:", damaged.len());
    for (frame, why) in damaged.iter().take(DAMAGED_LINES) {
        eprintln!("  frame {frame}: {}", swell::error::printable(why));
    }
    if damaged.len() > DAMAGED_LINES {
        eprintln!("  ... and {} more", damaged.len() - DAMAGED_LINES);
    }
}

/// A progress bar on stderr with elapsed time and ETA (drawn only when stderr is a terminal).
pub(super) fn progress_bar(len: u64, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(len).with_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} frames, {per_sec}, {elapsed} elapsed, ETA {eta}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    bar
}
