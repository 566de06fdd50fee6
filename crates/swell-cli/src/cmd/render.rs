//! `swell render`: one frame to PNG (or to EXR, its linear radiance), or `--frames N` to an
//! animated GIF or a PNG sequence (`--out 'frames/sea_%04d.png'`); or, with `--obj`, one mesh seen by one camera, for comparison
//! with an OpenGL renderer.

use std::cell::Cell;
use std::path::Path;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};
use swell::export::{
    pending_frames, write_exr_rgb, write_gif, write_png, write_png_sequence, ExrCompression, FramePattern, FrameRange,
    MAX_FPS, MAX_GIF_FPS,
};
use swell::math::{ev100_of_exposure, DisplayEncoding, ToneCurve};
use swell::mesh::parse_obj;
use swell::render::{parse_camera_json, parse_light_json, MeshLight, MeshRenderer, Renderer, MAX_VIEW_JSON_BYTES};
use swell::scene::Shading;
use swell::scene::{Camera, Scene, MAX_IMAGE_SIDE};
use swell::world::World;
use swell::{Error, Result};

use super::{load_scene, thread_pool};
use crate::args::RenderArgs;

/// Most frames one animation may have: see `swell::limits`.
use swell::limits::MAX_FRAMES;

enum Output {
    Png,
    /// One frame's linear scene radiance: the framebuffer before exposure and the tone curve.
    Exr,
    Gif {
        frames: FrameRange,
    },
    PngSequence {
        frames: FrameRange,
        pattern: FramePattern,
    },
}

impl Output {
    fn frames(&self) -> Option<FrameRange> {
        match self {
            Output::Png | Output::Exr => None,
            Output::Gif { frames } | Output::PngSequence { frames, .. } => Some(*frames),
        }
    }
}

pub fn run(a: RenderArgs) -> Result<()> {
    let started = Instant::now();
    if a.obj.is_some() {
        return run_mesh(&a);
    }
    refuse_mesh_flags(&a)?;
    let output = resolve_output(&a)?;
    let time = a.time.unwrap_or(0.0);
    swell::limits::check_time("--time", time)?;
    // The latest time the command simulates: the frame's, or the animation's last frame's.
    let last_time = match output.frames() {
        None => time,
        Some(frames) => time + f64::from(frames.last) / a.fps,
    };
    swell::limits::check_time("--time + last frame / --fps", last_time)?;
    let scene = scene_with_flags(&a, last_time)?;
    let threads = a.threads.unwrap_or(scene.render.threads);
    let pool = thread_pool(threads)?;
    let (width, height) = (scene.render.width, scene.render.height);
    let encoding = scene.render.display_encoding();
    let mut world = World::new(scene)?;
    let mut renderer = Renderer::new();
    if let Output::Exr = output {
        pool.install(|| write_radiance(&a.out, &mut world, &mut renderer, time))?;
        eprintln!("wrote {}", a.out.display());
        return Ok(());
    }
    // Time spent rendering frames (simulation, rendering, sRGB encoding; not the advance to the
    // first frame), for --verbose: the writers call `render` between their batches of encoding,
    // never during them, so this is the time the frames alone take.
    let mut render_time = Duration::ZERO;
    let mut rendered = 0u32;
    // The metered exposures of the frames (EV100), lowest and highest, for --verbose.
    let mut metered = (f32::INFINITY, f32::NEG_INFINITY);
    let mut render_frame = |world: &mut World, t: f64, rgba: &mut Vec<u8>| -> Result<()> {
        let start = Instant::now();
        world.update(t)?;
        let used = renderer.render(world).encode_rgba8(&encoding, rgba);
        if encoding.auto_exposure {
            let ev = ev100_of_exposure(used.exposure / encoding.exposure);
            metered = (metered.0.min(ev), metered.1.max(ev));
        }
        render_time += start.elapsed();
        rendered += 1;
        Ok(())
    };
    let frame_time = |k: u32| time + f64::from(k) / a.fps;
    let bar = |len: usize, what: &str| {
        let bar = ProgressBar::new(len as u64).with_style(
            ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} frames, {elapsed} elapsed, ETA {eta}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        bar.set_message(format!("rendering {what}"));
        bar
    };
    let mut wrote = a.out.display().to_string();
    pool.install(|| match &output {
        Output::Exr => unreachable!("written above"),
        Output::Png => {
            super::advance_with_progress(&mut world, time, World::update)?;
            let mut rgba = Vec::new();
            render_frame(&mut world, time, &mut rgba)?;
            write_png(&a.out, width, height, &rgba)
        }
        Output::Gif { frames } => {
            let bar = bar(frames.len() as usize, &wrote);
            super::advance_with_progress(&mut world, frame_time(frames.first), World::update)?;
            // issue 10: SIGINT/SIGTERM abandon the animation between frames; the GIF is written
            // atomically, so nothing is left under its name.
            let interrupt = crate::interrupt::Interrupt::install()?;
            let result = write_gif(
                &a.out,
                width as u16,
                height as u16,
                frames.len() as usize,
                a.fps,
                |k, rgba| {
                    interrupt.check(format_args!("{} not written", a.out.display()))?;
                    render_frame(&mut world, frame_time(frames.first + k as u32), rgba)
                },
                || bar.inc(1),
            );
            bar.finish_and_clear();
            result
        }
        Output::PngSequence { frames, pattern } => {
            let todo = pending_frames(pattern, *frames, width, height, a.resume);
            let skipped = frames.len() as usize - todo.len();
            wrote = format!("{} frames to {}", todo.len(), a.out.display());
            if skipped > 0 {
                wrote += &format!(" ({skipped} already complete, skipped)");
            }
            let Some(&first) = todo.first() else { return Ok(()) };
            let bar = bar(todo.len(), &a.out.display().to_string());
            super::advance_with_progress(&mut world, frame_time(first), World::update)?;
            // Each frame is its own atomic file: an interrupted sequence keeps its whole frames, and
            // --resume continues from them.
            let interrupt = crate::interrupt::Interrupt::install()?;
            let written = Cell::new(0usize);
            let result = write_png_sequence(
                pattern,
                &todo,
                width,
                height,
                |k, rgba| {
                    interrupt.check(format_args!(
                        "{} of {} frames written, each complete; the others not written (--resume continues)",
                        written.get(),
                        todo.len(),
                    ))?;
                    render_frame(&mut world, frame_time(k), rgba)
                },
                || {
                    written.set(written.get() + 1);
                    bar.inc(1);
                },
            );
            bar.finish_and_clear();
            result
        }
    })?;
    eprintln!("wrote {wrote}");
    if a.verbose {
        let (render, total) = (render_time.as_secs_f64(), started.elapsed().as_secs_f64());
        eprintln!(
            "rendered {rendered} frames in {render:.3} s ({:.1} ms a frame); the whole command took {total:.3} s, \
             {:.2} x the rendering",
            1e3 * render / f64::from(rendered.max(1)),
            total / render.max(1e-9),
        );
        if encoding.auto_exposure {
            eprintln!("metered EV100 {:.2} to {:.2}", metered.0, metered.1);
        }
    }
    Ok(())
}

/// `--out FRAME.exr`: the frame at `time` (s) as linear scene radiance, float RGB in the
/// renderer's units, top row first; the PNG of the same frame is these pixels through
/// [`swell::raster::Framebuffer::encode_rgba8`] (exposure, then the sRGB curve). ZIP-compressed
/// (lossless; a sky compresses well). Identical bytes for any thread count, like the PNG.
fn write_radiance(out: &Path, world: &mut World, renderer: &mut Renderer, time: f64) -> Result<()> {
    super::advance_with_progress(world, time, World::update)?;
    let fb = renderer.render(world);
    write_exr_rgb(out, fb.width() as usize, fb.height() as usize, &fb.color, ExrCompression::Zip)
}

/// Refuses the comparison mode's own flags without `--obj`: they would be ignored otherwise.
fn refuse_mesh_flags(a: &RenderArgs) -> Result<()> {
    for (flag, given) in
        [("--camera", a.camera.is_some()), ("--light", a.light.is_some()), ("--repeat", a.repeat.is_some())]
    {
        if given {
            return Err(Error::invalid(
                flag,
                "belongs to the --obj comparison mode; a scene has its own [camera] and [[light]]",
            ));
        }
    }
    Ok(())
}

/// The scene of `--scene`/`--preset` with the flags that override its keys (`--size`,
/// `--shading`, `--wireframe`, `--normals`, `--supersample`) applied and checked, after checking
/// that a time-stepped model can reach `last_time` (s).
fn scene_with_flags(a: &RenderArgs, last_time: f64) -> Result<Scene> {
    let mut scene = load_scene(&a.source)?;
    super::check_steps(&scene, "--time", last_time)?;
    if let Some(size) = &a.size {
        let (w, h) = parse_size(size)?;
        scene.render.width = w;
        scene.render.height = h;
    }
    if let Some(name) = &a.shading {
        let shading = Shading::parse("--shading", name)?;
        if let Some(w) = &mut scene.water {
            w.material.shading = shading;
        }
    }
    scene.render.wireframe |= a.wireframe;
    scene.render.normals |= a.normals;
    if let Some(ev) = a.ev100 {
        scene.render.ev100 = Some(ev);
        scene.render.auto_exposure = false;
    }
    if a.auto_exposure {
        scene.render.auto_exposure = true;
        scene.render.ev100 = None;
    }
    if let Some(name) = &a.tone_curve {
        scene.render.tone_curve = ToneCurve::parse("--tone-curve", name)?;
    }
    if let Some(n) = a.supersample {
        scene.render.supersample = n;
    }
    // One check of the settings the flags changed; a value a flag gave is named by its flag.
    scene.render.validate("render").map_err(|e| match e {
        Error::OutOfRange { key, value, range } => {
            let flag = match key.as_str() {
                "render.ev100" if a.ev100.is_some() => "--ev100",
                "render.supersample" if a.supersample.is_some() => "--supersample",
                _ => return Error::OutOfRange { key, value, range },
            };
            Error::OutOfRange { key: flag.into(), value, range }
        }
        other => other,
    })?;
    Ok(scene)
}

/// Decides PNG, GIF or PNG sequence from the extension and a `%` pattern, and checks everything
/// about the output before any work.
fn resolve_output(a: &RenderArgs) -> Result<Output> {
    let ext = a.out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let frames = a.frames.as_deref().map(|f| FrameRange::parse("--frames", f)).transpose()?;
    if !(a.fps.is_finite() && a.fps > 0.0 && a.fps <= MAX_FPS) {
        return Err(Error::out_of_range("--fps", a.fps, format!("(0, {MAX_FPS}]")));
    }
    let is_pattern = FramePattern::is_pattern(&a.out);
    let output = match (ext.as_deref(), frames) {
        (Some("png"), None) => {
            // A name such as `sea_%04d.png` was meant for a sequence; another `%` is just a character.
            if is_pattern && FramePattern::parse("--out", &a.out).is_ok() {
                return Err(Error::invalid(
                    "--out",
                    format!(
                        "`{}` is a PNG sequence pattern: it needs --frames N (frames 0 to N-1) or A..B",
                        a.out.display()
                    ),
                ));
            }
            Output::Png
        }
        (Some("png"), Some(frames)) => {
            if !is_pattern {
                return Err(Error::invalid(
                    "--out",
                    format!(
                        "`{}` is one file, but --frames writes an animation: give a .gif output, or a PNG \
                         sequence pattern with the frame number as %04d (e.g. frames/sea_%04d.png)",
                        a.out.display()
                    ),
                ));
            }
            let pattern = FramePattern::parse("--out", &a.out)?;
            check_frame_count(frames)?;
            Output::PngSequence { frames, pattern }
        }
        (Some("gif"), Some(frames)) => {
            check_frame_count(frames)?;
            if a.fps > MAX_GIF_FPS {
                return Err(Error::out_of_range(
                    "--fps",
                    a.fps,
                    format!(
                        "(0, {MAX_GIF_FPS}] for a GIF: its delays are whole hundredths of a second and players \
                         slow down delays under 2/100 s (export or bake frames for higher rates)"
                    ),
                ));
            }
            Output::Gif { frames }
        }
        (Some("gif"), None) => {
            return Err(Error::invalid("--frames", "a .gif output needs --frames N (frames 0 to N-1) or A..B"))
        }
        (Some("exr"), None) => Output::Exr,
        (Some("exr"), Some(_)) => {
            return Err(Error::invalid(
                "--out",
                format!(
                    "{} is one frame's linear radiance; --frames writes an animation (.gif) or a PNG sequence \
                     (frames/sea_%04d.png): render one .exr per --time instead",
                    a.out.display()
                ),
            ))
        }
        _ => {
            return Err(Error::invalid(
                "--out",
                format!(
                    "{} must end in .png (one frame, or with --frames a sequence pattern such as \
                     frames/sea_%04d.png), .exr (one frame's linear radiance) or .gif (an animation)",
                    a.out.display()
                ),
            ))
        }
    };
    if a.resume && !matches!(output, Output::PngSequence { .. }) {
        return Err(Error::invalid(
            "--resume",
            "applies to a PNG sequence (--frames with --out such as frames/sea_%04d.png); a PNG or GIF is \
             written whole",
        ));
    }
    if let Output::PngSequence { pattern, .. } = &output {
        if !pattern.dir().is_dir() {
            return Err(Error::invalid(
                "--out",
                format!(
                    "directory {} of the sequence `{}` does not exist (create it first)",
                    pattern.dir().display(),
                    a.out.display()
                ),
            ));
        }
    } else {
        super::check_output_dir(&a.out)?;
    }
    Ok(output)
}

/// Refuses more frames than one command renders ([`MAX_FRAMES`]).
fn check_frame_count(frames: FrameRange) -> Result<()> {
    if frames.len() > MAX_FRAMES {
        return Err(Error::out_of_range(
            "--frames",
            format!("{} frames", frames.len()),
            format!("[1, {MAX_FRAMES}] frames"),
        ));
    }
    Ok(())
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

/// `--obj MESH --camera CAMERA.json [--light LIGHT.json] [--shading M] [--repeat N]`.
fn run_mesh(a: &RenderArgs) -> Result<()> {
    let obj = a.obj.as_deref().expect("checked by the caller");
    let camera_path =
        a.camera.as_deref().ok_or_else(|| Error::invalid("--camera", "--obj needs --camera CAMERA.json"))?;
    let scene_only = "does not apply to the --obj comparison mode";
    for (flag, given, why) in [
        ("--preset", a.source.preset.is_some(), scene_only),
        ("--scene", a.source.scene.is_some(), scene_only),
        ("--frames", a.frames.is_some(), "does not apply to --obj: a mesh file is one still frame"),
        ("--time", a.time.is_some(), "does not apply to --obj: a mesh file does not move"),
        ("--size", a.size.is_some(), "does not apply to --obj: the camera file's width and height set the image size"),
        ("--wireframe", a.wireframe, scene_only),
        ("--normals", a.normals, scene_only),
        ("--supersample", a.supersample.is_some(), scene_only),
    ] {
        if given {
            return Err(Error::invalid(flag, why));
        }
    }
    match a.out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("png") => {}
        _ => return Err(Error::invalid("--out", format!("{} must end in .png", a.out.display()))),
    }
    super::check_output_dir(&a.out)?;
    let repeat = a.repeat.unwrap_or(1);
    if !(1..=MAX_FRAMES).contains(&repeat) {
        return Err(Error::out_of_range("--repeat", repeat, format!("[1, {MAX_FRAMES}]")));
    }
    let shading = match &a.shading {
        Some(name) => Shading::parse("--shading", name)?,
        None => Shading::Flat,
    };
    let (camera, width, height) = read_camera(camera_path)?;
    let light = match &a.light {
        Some(path) => read_light(path)?,
        None => MeshLight::default(),
    };
    let text = read_text(obj, swell::mesh::MAX_OBJ_BYTES, "MAX_OBJ_BYTES")?;
    let mesh = parse_obj(&text, &obj.display().to_string())?;
    let pool = thread_pool(a.threads.unwrap_or(0))?;
    let mut renderer = MeshRenderer::new();
    let mut times = Vec::with_capacity(repeat as usize);
    let mut rgba = Vec::new();
    pool.install(|| {
        for _ in 0..repeat {
            let start = Instant::now();
            renderer.render(&mesh, &camera, width, height, &light, shading);
            times.push(start.elapsed().as_secs_f64() * 1e3);
        }
        // No gamma: the bytes are what an OpenGL RGBA8 framebuffer holds, round(255 c).
        renderer
            .render(&mesh, &camera, width, height, &light, shading)
            .encode_rgba8(&DisplayEncoding::clipped(1.0, Some(1.0)), &mut rgba);
    });
    write_png(&a.out, width, height, &rgba)?;
    if a.repeat.is_some() {
        times.sort_by(f64::total_cmp);
        let n = times.len();
        let median = if n % 2 == 1 { times[n / 2] } else { 0.5 * (times[n / 2 - 1] + times[n / 2]) };
        println!("{}", serde_json::json!({ "median_ms": median }));
    } else {
        eprintln!("wrote {}", a.out.display());
    }
    Ok(())
}

fn read_text(path: &Path, max_bytes: u64, limit_name: &str) -> Result<String> {
    swell::limits::read_text_limited(path, max_bytes, limit_name)
}

fn read_camera(path: &Path) -> Result<(Camera, u32, u32)> {
    let text = read_text(path, MAX_VIEW_JSON_BYTES, "MAX_VIEW_JSON_BYTES")?;
    let view = parse_camera_json(&text, &path.display().to_string())?;
    Ok((view.camera, view.width, view.height))
}

fn read_light(path: &Path) -> Result<MeshLight> {
    parse_light_json(&read_text(path, MAX_VIEW_JSON_BYTES, "MAX_VIEW_JSON_BYTES")?, &path.display().to_string())
}
