//! `swell export`: the displaced surfaces and the camera as OBJ, glTF or GLB, one frame or many.

use std::path::{Path, PathBuf};

use swell::export::{
    body_meshes, world_meshes, write_glb, write_glb_animated, write_gltf, write_gltf_animated, write_obj, FrameRange,
    NodeAnimation, NodeTrack, MAX_FPS,
};
use swell::world::World;
use swell::{Error, Result};

use super::bake::progress_bar;
use super::{load_scene, thread_pool};
use crate::args::ExportArgs;

#[derive(Clone, Copy)]
enum Format {
    Obj,
    Gltf,
    Glb,
}

pub fn run(a: ExportArgs) -> Result<()> {
    let format = resolve_format(&a)?;
    let frames = a.frames.as_deref().map(|s| FrameRange::parse("--frames", s)).transpose()?;
    swell::limits::check_time("--time", a.time)?;
    if !(a.fps.is_finite() && a.fps > 0.0 && a.fps <= MAX_FPS) {
        return Err(Error::out_of_range("--fps", a.fps, format!("(0, {MAX_FPS}]")));
    }
    // The latest time the command simulates (`--time` and `--frames` exclude each other).
    let (last_key, last_time) = match frames {
        Some(r) => ("--frames / --fps (the last frame's time)", f64::from(r.last) / a.fps),
        None => ("--time", a.time),
    };
    swell::limits::check_time(last_key, last_time)?;
    super::check_output_dir(&a.out)?;
    let scene = load_scene(&a.source)?;
    super::check_steps(&scene, last_key, last_time)?;
    let aspect = scene.render.width as f32 / scene.render.height as f32;
    let pool = thread_pool(a.threads)?;
    pool.install(|| {
        let mut world = World::new(scene)?;
        super::advance_with_progress(
            &mut world,
            frames.map_or(a.time, |r| f64::from(r.first) / a.fps),
            World::advance,
        )?;
        let mut patch = world.new_patch_mesh();
        // The floating bodies' poses at every frame written, for their animation.
        let mut poses: Vec<(f32, Vec<swell::body::BodyPose>)> = Vec::new();
        let mut write = |path: &Path, t: f64| -> Result<()> {
            // Exports write the water's finite patch, whatever the scene draws: the models are
            // moved and the patch sampled, and no drawn surface is displaced.
            world.advance(t)?;
            if let Some(p) = &mut patch {
                world.sample_patch(p)?;
            }
            poses.push((t as f32, world.body_poses().to_vec()));
            // The bodies placed at their poses, after the water and the terrain.
            let bodies = body_meshes(&world, true);
            let mut meshes = world_meshes(&world, patch.as_ref());
            meshes.extend(bodies.iter().map(|b| b.named()));
            let camera = &world.scene.camera;
            match format {
                Format::Obj => write_obj(path, &meshes),
                Format::Gltf => write_gltf(path, &meshes, camera, aspect),
                Format::Glb => write_glb(path, &meshes, camera, aspect),
            }
        };
        match frames {
            None => {
                write(&a.out, a.time)?;
                eprintln!("wrote {}", a.out.display());
            }
            Some(range) => {
                let bar = progress_bar(u64::from(range.len()), "exporting");
                // issue 10: SIGINT/SIGTERM stop between frames; every file written is complete.
                let interrupt = crate::interrupt::Interrupt::install()?;
                for k in range.iter() {
                    interrupt.check(format_args!(
                        "{} of {} frames written, each complete; {} and later not written",
                        k - range.first,
                        range.len(),
                        frame_path(&a.out, k).display()
                    ))?;
                    write(&frame_path(&a.out, k), f64::from(k) / a.fps)?;
                    bar.inc(1);
                }
                bar.finish_and_clear();
                eprintln!(
                    "wrote {} files, {} to {}",
                    range.len(),
                    frame_path(&a.out, range.first).display(),
                    frame_path(&a.out, range.last).display()
                );
                if !world.bodies.is_empty() && !matches!(format, Format::Obj) {
                    let path = bodies_path(&a.out);
                    write_body_animation(&path, &world, &poses, format, aspect)?;
                    eprintln!("wrote {} (the bodies' motion over the frames)", path.display());
                }
            }
        }
        Ok(())
    })
}

/// The file of the bodies' animation beside an export to `out` = `DIR/STEM.EXT`:
/// `DIR/STEM_bodies.EXT`.
fn bodies_path(out: &Path) -> PathBuf {
    let stem = out.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let name = match out.extension() {
        Some(ext) => format!("{stem}_bodies.{}", ext.to_string_lossy()),
        None => format!("{stem}_bodies"),
    };
    out.with_file_name(name)
}

/// Writes the bodies in their own frames with one glTF animation, "bodies", moving each by its
/// pose at every exported frame (`poses`: time and the poses in scene order).
fn write_body_animation(
    path: &Path,
    world: &World,
    poses: &[(f32, Vec<swell::body::BodyPose>)],
    format: Format,
    aspect: f32,
) -> Result<()> {
    let meshes = body_meshes(world, false);
    let named: Vec<_> = meshes.iter().map(|m| m.named()).collect();
    let times: Vec<f32> = poses.iter().map(|(t, _)| *t).collect();
    let samples: Vec<(Vec<glam::Vec3>, Vec<glam::Quat>)> = (0..meshes.len())
        .map(|k| poses.iter().map(|(_, p)| (p[k].position.as_vec3(), p[k].rotation.as_quat())).unzip())
        .collect();
    let tracks: Vec<NodeTrack> = samples
        .iter()
        .enumerate()
        .map(|(mesh, (translations, rotations))| NodeTrack { mesh, translations, rotations })
        .collect();
    let animation = NodeAnimation { name: "bodies", times: &times, tracks: &tracks };
    let camera = &world.scene.camera;
    match format {
        Format::Gltf => write_gltf_animated(path, &named, camera, aspect, Some(&animation)),
        _ => write_glb_animated(path, &named, camera, aspect, Some(&animation)),
    }
}

/// Frame `k` of an export to `out` = `DIR/STEM.EXT` goes to `DIR/STEM_kkkk.EXT` (at least four
/// digits); a glTF's buffer beside it is `DIR/STEM_kkkk.bin`.
fn frame_path(out: &Path, k: u32) -> PathBuf {
    let stem = out.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let name = match out.extension() {
        Some(ext) => format!("{stem}_{k:04}.{}", ext.to_string_lossy()),
        None => format!("{stem}_{k:04}"),
    };
    out.with_file_name(name)
}

fn resolve_format(a: &ExportArgs) -> Result<Format> {
    let ext = a.out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let parse = |name: &str| match name {
        "obj" => Some(Format::Obj),
        "gltf" => Some(Format::Gltf),
        "glb" => Some(Format::Glb),
        _ => None,
    };
    let Some(given) = &a.format else {
        return ext.as_deref().and_then(parse).ok_or_else(|| {
            Error::invalid(
                "--out",
                format!(
                    "cannot tell the format of {}: give --format obj|gltf|glb or end it in .obj, .gltf or .glb",
                    a.out.display()
                ),
            )
        });
    };
    let name = given.to_ascii_lowercase();
    let format =
        parse(&name).ok_or_else(|| Error::invalid("--format", format!("`{given}` is not one of obj, gltf, glb")))?;
    // Issue 37: `--format obj --out x.glb` wrote OBJ text into x.glb. An extension that names a
    // format must name this one; another extension (`.mesh`) leaves the choice to --format.
    match ext {
        Some(e) if e != name && parse(&e).is_some() => Err(Error::invalid(
            "--out",
            format!("{} ends in .{e} but --format is {name}: end it in .{name} or drop --format", a.out.display()),
        )),
        _ => Ok(format),
    }
}
