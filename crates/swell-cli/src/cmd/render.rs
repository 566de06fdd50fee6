//! `swell render`: one frame to PNG, or `--frames N` to an animated GIF; or, with `--obj`, one
//! mesh seen by one camera, for comparison with an OpenGL renderer.

use std::path::Path;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use swell::export::{write_gif, write_png, FrameRange, MAX_FPS, MAX_GIF_FPS};
use swell::mesh::parse_obj;
use swell::render::{parse_camera_json, parse_light_json, MeshLight, MeshRenderer, Renderer, MAX_VIEW_JSON_BYTES};
use swell::scene::Shading;
use swell::scene::{Camera, MAX_IMAGE_SIDE};
use swell::world::World;
use swell::{Error, Result};

use super::{load_scene, thread_pool};
use crate::args::RenderArgs;

/// Most frames one animation may have: see `swell::limits`.
use swell::limits::MAX_FRAMES;

enum Output {
    Png,
    Gif { frames: FrameRange },
}

pub fn run(a: RenderArgs) -> Result<()> {
    if a.obj.is_some() {
        return run_mesh(&a);
    }
    // The comparison mode's own flags act only with --obj: refused, not ignored.
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
    let output = resolve_output(&a)?;
    let time = a.time.unwrap_or(0.0);
    swell::limits::check_time("--time", time)?;
    // The latest time the command simulates: the frame's, or the animation's last frame's.
    let last_time = match &output {
        Output::Png => time,
        Output::Gif { frames } => time + f64::from(frames.last) / a.fps,
    };
    swell::limits::check_time("--time + last frame / --fps", last_time)?;
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
    if let Some(n) = a.supersample {
        scene.render.supersample = n;
        scene.render.validate("render").map_err(|e| match e {
            Error::OutOfRange { value, range, .. } => Error::OutOfRange { key: "--supersample".into(), value, range },
            other => other,
        })?;
    }
    let threads = a.threads.unwrap_or(scene.render.threads);
    let pool = thread_pool(threads)?;
    let (width, height) = (scene.render.width, scene.render.height);
    let (exposure, gamma) = (scene.render.exposure, scene.render.gamma);
    let mut world = World::new(scene)?;
    let mut renderer = Renderer::new();
    pool.install(|| match output {
        Output::Png => {
            super::advance_with_progress(&mut world, time)?;
            let mut rgba = Vec::new();
            renderer.render(&world).encode_rgba8(exposure, gamma, &mut rgba);
            write_png(&a.out, width, height, &rgba)
        }
        Output::Gif { frames } => {
            let bar = ProgressBar::new(u64::from(frames.len())).with_style(
                ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} frames, {elapsed} elapsed, ETA {eta}")
                    .expect("valid template")
                    .progress_chars("=> "),
            );
            bar.set_message(format!("rendering {}", a.out.display()));
            super::advance_with_progress(&mut world, time + f64::from(frames.first) / a.fps)?;
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
                    world.update(time + f64::from(frames.first + k as u32) / a.fps)?;
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
    let frames = a.frames.as_deref().map(|f| FrameRange::parse("--frames", f)).transpose()?;
    if !(a.fps.is_finite() && a.fps > 0.0 && a.fps <= MAX_FPS) {
        return Err(Error::out_of_range("--fps", a.fps, format!("(0, {MAX_FPS}]")));
    }
    let output = match (ext.as_deref(), frames) {
        (Some("png"), None) => Output::Png,
        (Some("png"), Some(_)) => {
            return Err(Error::invalid("--out", "--frames writes an animation: give a .gif output"))
        }
        (Some("gif"), Some(frames)) => {
            if frames.len() > MAX_FRAMES {
                return Err(Error::out_of_range(
                    "--frames",
                    format!("{} frames", frames.len()),
                    format!("[1, {MAX_FRAMES}] frames"),
                ));
            }
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
        _ => {
            return Err(Error::invalid(
                "--out",
                format!("{} must end in .png (one frame) or .gif (an animation)", a.out.display()),
            ))
        }
    };
    super::check_output_dir(&a.out)?;
    Ok(output)
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
        renderer.render(&mesh, &camera, width, height, &light, shading).encode_rgba8(1.0, Some(1.0), &mut rgba);
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
