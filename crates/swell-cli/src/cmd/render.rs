//! `swell render`: one frame to PNG, or `--frames N` to an animated GIF.

use std::path::Path;

use indicatif::{ProgressBar, ProgressStyle};
use swell::export::{write_gif, write_png};
use swell::render::Renderer;
use swell::scene::{World, MAX_IMAGE_SIDE};
use swell::{Error, Result};

use super::{load_scene, thread_pool};
use crate::args::RenderArgs;

/// Most frames one animation may have: see `swell::limits`.
use swell::limits::MAX_FRAMES;

enum Output {
    Png,
    Gif { frames: u32 },
}

pub fn run(a: RenderArgs) -> Result<()> {
    let output = resolve_output(&a)?;
    if !a.time.is_finite() {
        return Err(Error::out_of_range("--time", a.time, "finite seconds"));
    }
    let mut scene = load_scene(&a.source)?;
    if let Some(size) = &a.size {
        let (w, h) = parse_size(size)?;
        scene.render.width = w;
        scene.render.height = h;
    }
    let threads = a.threads.unwrap_or(scene.render.threads);
    let pool = thread_pool(threads)?;
    let (width, height) = (scene.render.width, scene.render.height);
    let (exposure, gamma) = (scene.render.exposure, scene.render.gamma);
    let mut world = World::new(scene)?;
    let mut renderer = Renderer::new();
    pool.install(|| match output {
        Output::Png => {
            world.update(a.time)?;
            let mut rgba = Vec::new();
            renderer.render(&world).encode_rgba8(exposure, gamma, &mut rgba);
            write_png(&a.out, width, height, &rgba)
        }
        Output::Gif { frames } => {
            let bar = ProgressBar::new(frames as u64).with_style(
                ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} frames, {elapsed} elapsed, ETA {eta}")
                    .expect("valid template")
                    .progress_chars("=> "),
            );
            bar.set_message(format!("rendering {}", a.out.display()));
            let delay_cs = (100.0 / a.fps).round().clamp(1.0, 65535.0) as u16;
            let result = write_gif(
                &a.out,
                width as u16,
                height as u16,
                frames as usize,
                delay_cs,
                |k, rgba| {
                    world.update(a.time + k as f64 / a.fps)?;
                    renderer.render(&world).encode_rgba8(exposure, gamma, rgba);
                    Ok(())
                },
                || bar.inc(1),
            );
            bar.finish_and_clear();
            result
        }
    })?;
    eprintln!("wrote {}", a.out.display());
    Ok(())
}

/// Decides PNG or GIF from the extension and checks everything about the output before any work.
fn resolve_output(a: &RenderArgs) -> Result<Output> {
    let ext = a.out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let output = match (ext.as_deref(), a.frames) {
        (Some("png"), None) => Output::Png,
        (Some("png"), Some(_)) => {
            return Err(Error::invalid("--out", "--frames writes an animation: give a .gif output"))
        }
        (Some("gif"), Some(n)) => {
            if !(1..=MAX_FRAMES).contains(&n) {
                return Err(Error::out_of_range("--frames", n, format!("[1, {MAX_FRAMES}]")));
            }
            if !(a.fps.is_finite() && a.fps > 0.0 && a.fps <= 100.0) {
                return Err(Error::out_of_range("--fps", a.fps, "(0, 100]"));
            }
            Output::Gif { frames: n }
        }
        (Some("gif"), None) => {
            return Err(Error::invalid("--frames", "a .gif output needs --frames N (the number of frames)"))
        }
        _ => {
            return Err(Error::invalid(
                "--out",
                format!("{} must end in .png (one frame) or .gif (an animation)", a.out.display()),
            ))
        }
    };
    check_output_dir(&a.out)?;
    Ok(output)
}

/// Fails early, before rendering, if the output's directory does not exist.
fn check_output_dir(out: &Path) -> Result<()> {
    let dir = match out.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if dir.is_dir() {
        Ok(())
    } else {
        Err(Error::invalid("--out", format!("directory {} does not exist", dir.display())))
    }
}

/// Parses `WIDTHxHEIGHT`, each side in [1, MAX_IMAGE_SIDE].
fn parse_size(s: &str) -> Result<(u32, u32)> {
    let bad = || Error::invalid("--size", format!("`{s}` is not WIDTHxHEIGHT (e.g. 1280x720)"));
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    for (name, v) in [("--size width", w), ("--size height", h)] {
        if !(1..=MAX_IMAGE_SIDE).contains(&v) {
            return Err(Error::out_of_range(name, v, format!("[1, {MAX_IMAGE_SIDE}]")));
        }
    }
    Ok((w, h))
}
