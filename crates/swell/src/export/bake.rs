//! Baking a water model into map sequences, like Blender's ocean bake: per frame a displacement,
//! a normal and (where the model has foam) a foam map, as float EXR and optionally PNG.
//!
//! A bake directory holds `bake.json` ([`BakeManifest`]) and, for each frame `k` (file names use
//! at least four digits, `{k:04}`):
//!
//! | file | content |
//! |---|---|
//! | `disp_{k:04}.exr` | RGB `f32`: displacement (x, y, z) in metres of each grid point from its rest position (x, 0, z); height is G |
//! | `normal_{k:04}.exr` | RGB `f32`: unit normal, in world axes (x, y, z) or tangent space ([`NormalSpace`]) |
//! | `foam_{k:04}.exr` | `Y` `f32`: foam coverage in [0, 1] (only when the model has foam) |
//! | `*_{k:04}.png` | the same as 8- or 16-bit PNG (only with `png_bits`), encoded as `bake.json` says |
//!
//! Pixel (i, j) is grid vertex (i, j) (see [`super::write_exr_rgb`] for orientation).
//!
//! | `check_{k:04}.json` | the frame's record: each file's size and XXH64 checksum, written after them ([`super::bake_frame_record`]) |
//!
//! Long bakes: every file is written atomically, so a file that exists is complete, and a frame
//! is complete when its record exists and every file matches it; [`BakeSettings::resume`] skips
//! complete frames and bakes the others again (a missing, empty, truncated or changed file), and a
//! [`Shard`] bakes every N-th frame, so batch systems can split a bake over machines. The output
//! depends only on the scene and the settings, never on threads, shards or interruptions.
//!
//! Bakes never lie about what a directory holds (issue 37): a directory holds one bake. A bake
//! takes its shard's lock ([`super::bake_lock`]) before it looks at anything, so a second bake of
//! something else into a directory in use is refused, naming the holder, while the shards of one
//! bake share it. A `bake.json` of another bake (or one that is empty, not JSON or cut short) is
//! refused with or without `resume`, naming what differs, and so are frame files without a
//! `bake.json`: they are never adopted, and never silently mixed with another bake's.
//!
//! Speed: frames are simulated in order (time-stepped models need that) in batches, and each
//! batch is encoded and written in parallel while the next is simulated.
//!
//! ```
//! use swell::export::{Bake, BakeSettings, FrameRange};
//! use swell::scene::preset;
//! use swell::world::World;
//!
//! let mut scene = preset("sea")?;
//! scene.water.as_mut().unwrap().surface.cells = [32, 32];
//! let mut world = World::new(scene)?;
//! let dir = tempfile::tempdir().unwrap();
//! // Frames 0 to 2 (inclusive) at 24 fps, with 16-bit PNGs beside the EXRs.
//! let mut settings = BakeSettings::new(FrameRange::new("frames", 0, 2)?);
//! settings.png_bits = Some(16);
//! let bake = Bake::prepare(&mut world, dir.path(), settings)?;
//! bake.run(&mut world, &|frame| println!("frame {frame} done"))?;
//! assert!(dir.path().join("disp_0002.exr").is_file() && dir.path().join("bake.json").is_file());
//! assert_eq!(bake.manifest().grid.pixels, [33, 33]);
//! # Ok::<(), swell::Error>(())
//! ```

use std::path::{Path, PathBuf};

use glam::Vec3;
use rayon::prelude::*;

use super::bake_checksum::{hex, xxh64};
use super::bake_frame_record::{file_record, is_record_name, record_name, verify_frame, write_record, FrameRecord};
use super::bake_lock::BakeLock;
use super::bake_manifest::{
    BakeAxes, BakeFoam, BakeGrid, BakeManifest, BakeMap, BakePng, BakeUnits, BAKE_MANIFEST_VERSION,
};
use super::frame_range::{FrameRange, Shard};
use super::{write_atomically, write_exr_gray, write_exr_rgb, write_png_map, ExrCompression, NormalSpace};
use crate::error::{Error, Result};
use crate::math::GridSpec;
use crate::mesh::SurfaceMesh;
use crate::world::World;

/// Highest frame rate a bake accepts, frames per second.
pub const MAX_FPS: f64 = 1000.0;

/// Smallest automatic PNG displacement range, metres (a flat sea still gets a usable scale).
pub const MIN_PNG_RANGE_M: f32 = 0.01;

/// Headroom of the automatic PNG displacement range over the first frame's largest component:
/// later frames of a stationary sea rarely exceed the first by more than this.
pub const PNG_RANGE_HEADROOM: f32 = 1.5;

/// What to bake and how.
#[derive(Clone, Debug, PartialEq)]
pub struct BakeSettings {
    /// All frames of the bake (each shard bakes a subset).
    pub frames: FrameRange,
    /// Frames per second, in (0, [`MAX_FPS`]]: frame k is time k / fps seconds. Default 24.
    pub fps: f64,
    /// Which frames this run bakes. Default: all.
    pub shard: Shard,
    /// Skip frames that are complete (their record `check_{k:04}.json` exists and every file has
    /// the size and checksum it records), after checking `bake.json` describes the same bake;
    /// every other frame of the shard is baked again.
    pub resume: bool,
    /// Also write PNG maps of this many bits per sample (8 or 16).
    pub png_bits: Option<u8>,
    /// PNG displacement range R (m, > 0): components map from [-R, R]. Default: the first frame's
    /// largest absolute component times [`PNG_RANGE_HEADROOM`], rounded up to two significant
    /// digits, at least [`MIN_PNG_RANGE_M`].
    pub png_range_m: Option<f32>,
    /// EXR compression. Default none (fastest).
    pub compression: ExrCompression,
    /// The model's loop period in seconds, if it has one (recorded in `bake.json`).
    pub loop_period_s: Option<f64>,
    /// Maps of `cells` pixels per side instead of `cells + 1`: the last column and row, which
    /// repeat the first ones when the model is periodic over the patch (FFT ocean), are left out,
    /// so the maps tile with wrap-around sampling (a 512-cell ocean gives 512 x 512 maps).
    pub tile: bool,
    /// The space of the normal map: world (default) or tangent space of the flat patch with the
    /// OpenGL or DirectX green convention.
    pub normal_space: NormalSpace,
}

impl BakeSettings {
    /// Settings for `frames` with every default.
    pub fn new(frames: FrameRange) -> Self {
        Self {
            frames,
            fps: 24.0,
            shard: Shard::WHOLE,
            resume: false,
            png_bits: None,
            png_range_m: None,
            compression: ExrCompression::None,
            loop_period_s: None,
            tile: false,
            normal_space: NormalSpace::World,
        }
    }

    /// Checks every field; keys are named as the CLI options.
    pub fn validate(&self) -> Result<()> {
        if !(self.fps.is_finite() && self.fps > 0.0 && self.fps <= MAX_FPS) {
            return Err(Error::out_of_range("--fps", self.fps, format!("(0, {MAX_FPS}]")));
        }
        if let Some(b) = self.png_bits {
            if b != 8 && b != 16 {
                return Err(Error::invalid("--png", format!("{b} bits; valid: 8 or 16")));
            }
        }
        if let Some(r) = self.png_range_m {
            if self.png_bits.is_none() {
                return Err(Error::invalid("--png-range", "sets the range of PNG maps: it needs --png"));
            }
            crate::error::check_positive("--png-range", r)?;
        }
        let last = f64::from(self.frames.last) / self.fps;
        crate::limits::check_time("--frames / --fps (the last frame's time)", last)?;
        if let Some(p) = self.loop_period_s {
            if !(p.is_finite() && p > 0.0) {
                return Err(Error::out_of_range("loop period", p, "(0, inf) seconds"));
            }
        }
        Ok(())
    }
}

/// The loop period (s) of the world's water model, if it repeats exactly.
///
/// Taken from the scene: `tessendorf` (and `fft`) models with a `loop_period` key.
pub fn model_loop_period(world: &World) -> Option<f64> {
    world.scene.water.as_ref().and_then(|w| w.model.loop_period())
}

/// One map kind of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum MapKind {
    Disp,
    Normal,
    Foam,
}

impl MapKind {
    fn name(self) -> &'static str {
        match self {
            MapKind::Disp => "disp",
            MapKind::Normal => "normal",
            MapKind::Foam => "foam",
        }
    }
}

/// A bake ready to run: settings checked, directory locked, `bake.json` written, frames to do known.
///
/// It holds the directory's lock for its shard until it is dropped.
pub struct Bake {
    dir: PathBuf,
    settings: BakeSettings,
    manifest: BakeManifest,
    /// XXH64 of `bake.json`'s bytes, hex: what frame records and locks name the bake by.
    bake_json_xxh64: String,
    maps: Vec<MapKind>,
    grid: GridSpec,
    png_range_m: f32,
    todo: Vec<u32>,
    skipped: usize,
    damaged: Vec<(u32, String)>,
    notes: Vec<String>,
    lock: BakeLock,
    /// The floating bodies' names, in scene order; empty without bodies (no poses written).
    body_names: Vec<String>,
}

/// The fields of one frame, captured from the world so the world can move on.
/// Bytes one captured frame holds while it waits to be written (displacement, normal, foam) plus
/// its encoded files, for `samples` map pixels.
fn frame_bytes(samples: usize) -> u64 {
    (samples as u64).saturating_mul((12 + 12 + 4) * 2)
}

/// Frames per batch: two per thread so that writing keeps every core busy, but never so many that
/// the two batches in flight (one written while the next is simulated) pass half the memory budget
/// ([`crate::limits::MEMORY_BUDGET_BYTES`]): many threads on a large grid would otherwise hold
/// gigabytes of captured fields. At least one frame. The output does not depend on it.
fn batch_len(threads: usize, samples: usize) -> usize {
    let by_memory = crate::limits::MEMORY_BUDGET_BYTES / 2 / frame_bytes(samples).saturating_mul(2).max(1);
    (2 * threads).max(2).min(usize::try_from(by_memory).unwrap_or(usize::MAX)).max(1)
}

struct FrameFields {
    frame: u32,
    /// The frame's time, s.
    t: f64,
    disp: Vec<Vec3>,
    normal: Vec<Vec3>,
    foam: Vec<f32>,
    /// The floating bodies' poses at the frame (empty without bodies).
    poses: Vec<crate::body::BodyPose>,
}

impl Bake {
    /// Checks `settings`, moves `world` to the first frame of the range (which fixes whether there
    /// is foam and the automatic PNG range, identically for every shard), creates `dir`, takes
    /// its lock for this shard ([`BakeLock`]), checks what `dir` already holds, writes
    /// `dir/bake.json`, and lists the frames still to bake.
    ///
    /// Refused, with nothing written (beyond creating `dir` when it did not exist): a directory
    /// whose lock another live process holds for this shard, or that a live process of another
    /// bake is using; a `bake.json` describing another bake, or that is empty, not JSON or cut
    /// short, with or without `resume`; frame files (maps or records) without a `bake.json`.
    /// Without `resume` every frame of the shard is baked (again); with it, only the frames that
    /// are not complete ([`BakeSettings::resume`]).
    pub fn prepare(world: &mut World, dir: &Path, settings: BakeSettings) -> Result<Self> {
        settings.validate()?;
        let spec = world
            .scene
            .water
            .clone()
            .ok_or_else(|| Error::invalid("water", "the scene has no [water] section: there is nothing to bake"))?;
        // Maps are the patch's own displacement over its own grid; placing the patch is the
        // engine's job, and world positions would not line up with the local grid.
        if !spec.surface.placement()?.is_identity() {
            return Err(Error::invalid(
                "water.yaw_deg",
                "bake writes maps in the patch's own frame: set yaw_deg = 0 and uniform_scale = 1 \
                 and turn or scale the patch in the engine that uses the maps",
            ));
        }
        // Maps sample the patch, whatever the scene draws: the drawn surface is not moved.
        world.advance(f64::from(settings.frames.first) / settings.fps)?;
        let mut mesh = world.new_patch_mesh().expect("a scene with [water] builds a water body");
        world.sample_patch(&mut mesh)?;
        let water = world.water.as_ref().expect("a scene with [water] builds a water body");
        let grid = mesh.grid;
        if settings.tile {
            check_tiles(water.model.spatial_period(), &grid)?;
        }
        let mut maps = vec![MapKind::Disp, MapKind::Normal];
        if mesh.has_foam {
            maps.push(MapKind::Foam);
        }
        let png_range_m = match settings.png_range_m {
            Some(r) => r,
            None => auto_png_range(&mesh.positions, &grid),
        };
        let mut manifest = manifest(&spec.to_table(), &grid, &settings, &maps, png_range_m);
        let body_names: Vec<String> = world.bodies.bodies().iter().map(|b| b.name.clone()).collect();
        if !body_names.is_empty() {
            // The bodies decide the poses' bytes: a resume with other bodies is another bake.
            let specs = toml::Value::try_from(&world.scene.bodies).expect("body specs serialise to TOML");
            manifest.bodies = Some(shortest_floats(serde_json::to_value(&specs).expect("TOML values convert to JSON")));
        }

        if dir.exists() && !dir.is_dir() {
            return Err(Error::invalid("--out", format!("{} exists and is not a directory", dir.display())));
        }
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        let json = manifest_json(&manifest);
        let bake_json_xxh64 = hex(xxh64(&json));
        // The lock first: what the directory holds cannot change under a bake that holds it
        // (another bake would be refused), so the checks below stay true.
        let mut notes = Vec::new();
        let lock = BakeLock::acquire(dir, settings.shard, &bake_json_xxh64, &mut notes)?;
        let manifest_path = dir.join("bake.json");
        if check_directory(dir, &manifest_path, &json, settings.resume)? {
            write_atomically(&manifest_path, |out| out.write_all(&json).map_err(|e| Error::io(&manifest_path, e)))?;
        }

        let mut bake = Bake {
            dir: dir.into(),
            settings,
            manifest,
            bake_json_xxh64,
            maps,
            grid,
            png_range_m,
            todo: vec![],
            skipped: 0,
            damaged: vec![],
            notes,
            lock,
            body_names,
        };
        let frames: Vec<u32> = bake.settings.shard.frames(bake.settings.frames).collect();
        if !bake.settings.resume {
            bake.todo = frames;
            return Ok(bake);
        }
        // Reading every file back is most of a resume's cost: frames in parallel, order kept.
        let checked: Vec<(u32, Result<(), String>)> =
            frames.into_par_iter().map(|frame| (frame, bake.check_frame(frame))).collect();
        for (frame, state) in checked {
            match state {
                Ok(()) => bake.skipped += 1,
                Err(why) => {
                    // A frame with no trace at all is simply not baked yet; one with files or a
                    // record that fail the check was damaged, and the caller hears of it.
                    let mut traces = bake.frame_files(frame).into_iter().chain([bake.record_path(frame)]);
                    if traces.any(|p| p.exists()) {
                        bake.damaged.push((frame, why));
                    }
                    bake.todo.push(frame);
                }
            }
        }
        Ok(bake)
    }

    /// `Ok` if `frame` is complete: its record belongs to this bake and every file matches it.
    fn check_frame(&self, frame: u32) -> Result<(), String> {
        verify_frame(&self.dir, frame, &self.frame_file_names(frame), &self.bake_json_xxh64)
    }

    /// Frames of this shard that had files or a record from before but failed the check of
    /// `resume` (a file missing, empty, truncated or changed, a record missing or from another
    /// bake), each with the first reason in words; they are among [`Bake::frames_to_bake`].
    pub fn damaged(&self) -> &[(u32, String)] {
        &self.damaged
    }

    /// What preparing the bake did that the user should hear of: stale locks removed, a lock taken
    /// over from another host. One sentence each.
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// The lock this bake holds on its directory and shard.
    pub fn lock(&self) -> &BakeLock {
        &self.lock
    }

    /// The manifest written as `bake.json`.
    pub fn manifest(&self) -> &BakeManifest {
        &self.manifest
    }

    /// Frames this run will bake, in order.
    pub fn frames_to_bake(&self) -> &[u32] {
        &self.todo
    }

    /// Frames of this shard skipped because they were complete (`resume`).
    pub fn skipped(&self) -> usize {
        self.skipped
    }

    /// Map width and height in pixels.
    fn map_size(&self) -> (usize, usize) {
        map_size(&self.grid, self.settings.tile)
    }

    /// Every map file of `frame`, under its final name (EXR, then PNG), without its record.
    pub fn frame_files(&self, frame: u32) -> Vec<PathBuf> {
        self.frame_file_names(frame).into_iter().map(|n| self.dir.join(n)).collect()
    }

    /// The record of `frame`, `check_{frame:04}.json`, written once all its files are.
    pub fn record_path(&self, frame: u32) -> PathBuf {
        self.dir.join(record_name(frame))
    }

    fn frame_file_names(&self, frame: u32) -> Vec<String> {
        let mut names: Vec<String> = self.maps.iter().map(|m| file_name(*m, frame, "exr")).collect();
        if self.settings.png_bits.is_some() {
            names.extend(self.maps.iter().map(|m| file_name(*m, frame, "png")));
        }
        if !self.body_names.is_empty() {
            names.push(super::bake_bodies::frame_file_name(frame));
        }
        names
    }

    /// Bakes the remaining frames; `on_frame(k)` is called (from any thread) once all files of
    /// frame k and then its record are written. `world` must be the one given to [`Bake::prepare`].
    pub fn run(&self, world: &mut World, on_frame: &(dyn Fn(u32) + Sync)) -> Result<()> {
        if self.todo.is_empty() {
            return self.gather_bodies();
        }
        let n = self.map_size().0 * self.map_size().1;
        let batch = batch_len(rayon::current_num_threads(), n);
        let alloc = || -> Vec<FrameFields> {
            (0..batch.min(self.todo.len()))
                .map(|_| FrameFields {
                    frame: 0,
                    t: 0.0,
                    poses: Vec::new(),
                    disp: vec![Vec3::ZERO; n],
                    normal: vec![Vec3::ZERO; n],
                    foam: vec![0.0; if self.maps.contains(&MapKind::Foam) { n } else { 0 }],
                })
                .collect()
        };
        let (mut ready, mut next) = (alloc(), alloc());
        let chunks: Vec<&[u32]> = self.todo.chunks(batch).collect();
        self.capture_batch(world, chunks[0], &mut ready)?;
        for (k, chunk) in chunks.iter().enumerate() {
            // Encode and write this batch while the next one is simulated.
            let (written, captured) = rayon::join(
                || ready[..chunk.len()].par_iter().try_for_each(|f| self.write_frame(f).map(|()| on_frame(f.frame))),
                || match chunks.get(k + 1) {
                    Some(c) => self.capture_batch(world, c, &mut next),
                    None => Ok(()),
                },
            );
            written?;
            captured?;
            std::mem::swap(&mut ready, &mut next);
        }
        self.gather_bodies()
    }

    /// Rewrites `bodies.json` from the poses of every frame of the bake the directory holds
    /// ([`super::bake_bodies::gather`]); nothing without bodies.
    fn gather_bodies(&self) -> Result<()> {
        if self.body_names.is_empty() {
            return Ok(());
        }
        let r = self.settings.frames;
        super::bake_bodies::gather(&self.dir, r.first..=r.last, &self.body_names).map(|_| ())
    }

    fn capture_batch(&self, world: &mut World, frames: &[u32], out: &mut [FrameFields]) -> Result<()> {
        let mut mesh = world.new_patch_mesh().expect("checked in prepare");
        for (&frame, fields) in frames.iter().zip(out.iter_mut()) {
            self.capture(world, frame, &mut mesh, fields)?;
        }
        Ok(())
    }

    /// Moves the world's models to `frame`, samples the patch into `mesh` and copies its fields
    /// out; refuses non-finite values.
    fn capture(&self, world: &mut World, frame: u32, mesh: &mut SurfaceMesh, out: &mut FrameFields) -> Result<()> {
        let t = f64::from(frame) / self.settings.fps;
        world.advance(t)?;
        world.sample_patch(mesh)?;
        out.frame = frame;
        out.t = t;
        out.poses.clear();
        out.poses.extend_from_slice(world.body_poses());
        let width = self.map_size().0;
        displacement(&mesh.positions, &self.grid, width, &mut out.disp);
        copy_rows(&mesh.normals, self.grid.verts_x(), width, &mut out.normal);
        let space = self.settings.normal_space;
        if space != NormalSpace::World {
            out.normal.par_iter_mut().for_each(|n| *n = space.from_world(*n));
        }
        if !out.foam.is_empty() {
            copy_rows(&mesh.foam, self.grid.verts_x(), width, &mut out.foam);
        }
        let finite = out.disp.par_iter().chain(out.normal.par_iter()).all(|v| v.is_finite())
            && out.foam.par_iter().all(|f| f.is_finite());
        if !finite {
            return Err(Error::Unstable(format!(
                "frame {frame} (t = {t} s) has non-finite displacement, normal or foam"
            )));
        }
        Ok(())
    }

    /// Writes every file of one frame, the files in parallel, each atomically; reads each back
    /// for its size and checksum (what reached the disk, not what was meant to), then writes the
    /// frame's record, atomically, last.
    fn write_frame(&self, f: &FrameFields) -> Result<()> {
        let (w, h) = self.map_size();
        let compression = self.settings.compression;
        let mut jobs: Vec<(MapKind, bool)> = self.maps.iter().map(|&m| (m, false)).collect();
        if self.settings.png_bits.is_some() {
            jobs.extend(self.maps.iter().map(|&m| (m, true)));
        }
        let files = jobs
            .par_iter()
            .map(|&(map, png)| {
                let name = file_name(map, f.frame, if png { "png" } else { "exr" });
                let path = self.dir.join(&name);
                match (map, png) {
                    (MapKind::Disp, false) => write_exr_rgb(&path, w, h, &f.disp, compression),
                    (MapKind::Normal, false) => write_exr_rgb(&path, w, h, &f.normal, compression),
                    (MapKind::Foam, false) => write_exr_gray(&path, w, h, &f.foam, compression),
                    (_, true) => self.write_png(&path, map, f),
                }?;
                file_record(&self.dir, &name)
            })
            .collect::<Result<Vec<_>>>()?;
        let mut files = files;
        if !self.body_names.is_empty() {
            super::bake_bodies::write_frame(&self.dir, f.frame, f.t, &self.body_names, &f.poses)?;
            files.push(file_record(&self.dir, &super::bake_bodies::frame_file_name(f.frame))?);
        }
        let record = FrameRecord { frame: f.frame, bake_json_xxh64: self.bake_json_xxh64.clone(), files };
        write_record(&self.dir, &record)
    }

    fn write_png(&self, path: &Path, map: MapKind, f: &FrameFields) -> Result<()> {
        let (w, h) = (self.map_size().0 as u32, self.map_size().1 as u32);
        let bits = self.settings.png_bits.expect("only called with PNGs on");
        let unit = |v: f32, r: f32| 0.5 * (v / r + 1.0);
        match map {
            MapKind::Disp => {
                let r = self.png_range_m;
                let s: Vec<f32> = f.disp.iter().flat_map(|d| d.to_array().map(|c| unit(c, r))).collect();
                write_png_map(path, w, h, 3, bits, &s)
            }
            MapKind::Normal => {
                let s: Vec<f32> = f.normal.iter().flat_map(|n| n.to_array().map(|c| unit(c, 1.0))).collect();
                write_png_map(path, w, h, 3, bits, &s)
            }
            MapKind::Foam => write_png_map(path, w, h, 1, bits, &f.foam),
        }
    }
}

/// The file name of `map` for `frame` with extension `ext`: `disp_0042.exr`.
fn file_name(map: MapKind, frame: u32, ext: &str) -> String {
    format!("{}_{frame:04}.{ext}", map.name())
}

/// Whether `name` is the name of a bake's per-frame file, a map (`disp_`, `normal_` or `foam_`,
/// at least four digits, `.exr` or `.png`) or a record ([`is_record_name`]): the files that must
/// not be in a directory without `bake.json`.
fn is_frame_file_name(name: &str) -> bool {
    let map = [MapKind::Disp, MapKind::Normal, MapKind::Foam].iter().any(|m| {
        name.strip_prefix(m.name())
            .and_then(|r| r.strip_prefix('_'))
            .and_then(|r| r.strip_suffix(".exr").or_else(|| r.strip_suffix(".png")))
            .is_some_and(|d| d.len() >= 4 && d.bytes().all(|c| c.is_ascii_digit()))
    });
    map || is_record_name(name) || super::bake_bodies::is_frame_file_name(name)
}

/// Refuses `--tile` unless the water repeats over the bake's extent: its spatial period (m, if it
/// has one) must go a whole number of times into the grid's size along both axes, so the maps'
/// last column and row would repeat the first.
fn check_tiles(period: Option<f32>, grid: &GridSpec) -> Result<()> {
    let Some(p) = period else {
        return Err(Error::invalid(
            "--tile",
            "this water does not repeat in space, so its maps cannot tile; only an FFT ocean does (with one \
             cascade, or tile_cascades = true), over its patch_size",
        ));
    };
    for (axis, size) in [("x", grid.size.x), ("z", grid.size.y)] {
        let periods = f64::from(size) / f64::from(p);
        if periods.round() < 1.0 || (periods - periods.round()).abs() > 1e-5 * periods {
            return Err(Error::invalid(
                "--tile",
                format!(
                    "the water repeats every {p} m but the bake's grid is {size} m along {axis} ({periods:.4} \
                     periods); set water.size to a whole multiple of {p} m"
                ),
            ));
        }
    }
    Ok(())
}

/// Map width and height in pixels: vertices per side, or cells per side when `tile`.
fn map_size(grid: &GridSpec, tile: bool) -> (usize, usize) {
    if tile {
        (grid.cells_x as usize, grid.cells_z as usize)
    } else {
        (grid.verts_x(), grid.verts_z())
    }
}

/// Copies the first `width` values of each row of `src` (rows of `stride`) into `out` (rows of
/// `width`), as many rows as `out` holds.
fn copy_rows<T: Copy + Send + Sync>(src: &[T], stride: usize, width: usize, out: &mut [T]) {
    out.par_chunks_mut(width).zip(src.par_chunks(stride)).for_each(|(o, s)| o.copy_from_slice(&s[..width]));
}

/// Writes `positions[v] - rest(v)` for the first `width` vertices of each row, as many rows as
/// `out` holds, rows in parallel.
fn displacement(positions: &[Vec3], grid: &GridSpec, width: usize, out: &mut [Vec3]) {
    let nx = grid.verts_x();
    out.par_chunks_mut(width).zip(positions.par_chunks(nx)).enumerate().for_each(|(j, (d, p))| {
        for (i, (d, p)) in d.iter_mut().zip(p).enumerate() {
            let r = grid.rest_position(i, j);
            *d = *p - Vec3::new(r.x, 0.0, r.y);
        }
    });
}

/// The automatic PNG displacement range: see [`BakeSettings::png_range_m`].
fn auto_png_range(positions: &[Vec3], grid: &GridSpec) -> f32 {
    let mut d = vec![Vec3::ZERO; positions.len()];
    displacement(positions, grid, grid.verts_x(), &mut d);
    let max = d.iter().map(|v| v.abs().max_element()).filter(|m| m.is_finite()).fold(0.0f32, f32::max);
    round_up_2_digits(max * PNG_RANGE_HEADROOM).max(MIN_PNG_RANGE_M)
}

/// Rounds a positive `x` up to two significant decimal digits (1.234 -> 1.3), so the range in
/// `bake.json` reads as a plain number.
fn round_up_2_digits(x: f32) -> f32 {
    if !(x > 0.0 && x.is_finite()) {
        return 0.0;
    }
    let scale = 10f64.powi(1 - f64::from(x).log10().floor() as i32);
    ((f64::from(x) * scale).ceil() / scale) as f32
}

fn manifest(
    water: &toml::Table,
    grid: &GridSpec,
    s: &BakeSettings,
    maps: &[MapKind],
    png_range_m: f32,
) -> BakeManifest {
    let mut params = water.clone();
    params.remove("material");
    let model = params.get("model").and_then(|m| m.as_str()).unwrap_or("unknown").to_string();
    let seed = params.get("seed").and_then(|v| v.as_integer()).and_then(|i| u64::try_from(i).ok());
    let loop_frames = s.loop_period_s.and_then(|p| {
        let n = p * s.fps;
        ((n - n.round()).abs() < 1e-6 * n.max(1.0)).then_some(n.round() as u64)
    });
    let png_pattern = |m: MapKind| s.png_bits.map(|_| format!("{}_{{frame:04}}.png", m.name()));
    BakeManifest {
        manifest_version: BAKE_MANIFEST_VERSION,
        swell_version: env!("CARGO_PKG_VERSION").into(),
        units: BakeUnits::si(),
        axes: BakeAxes::swell(),
        model,
        model_params: shortest_floats(serde_json::to_value(&params).expect("TOML values convert to JSON")),
        seed,
        grid: BakeGrid {
            cells: [grid.cells_x, grid.cells_z],
            pixels: [map_size(grid, s.tile).0 as u32, map_size(grid, s.tile).1 as u32],
            tile: s.tile,
            origin_m: grid.origin.to_array(),
            size_m: grid.size.to_array(),
            spacing_m: grid.spacing().to_array(),
            layout: "pixel (i, j) = grid vertex (i, j) resting at origin_m + (i, j) * spacing_m; columns run along +X, \
                     rows (top to bottom) along +Z; mesh uv = (i / cells[0], j / cells[1])"
                .into(),
        },
        fps: s.fps,
        frames: [s.frames.first, s.frames.last],
        loop_period_s: s.loop_period_s,
        loop_frames,
        maps: maps
            .iter()
            .map(|&m| BakeMap {
                name: m.name().into(),
                exr: format!("{}_{{frame:04}}.exr", m.name()),
                png: png_pattern(m),
                channels: match m {
                    MapKind::Disp => "R, G, B = displacement x, y (height), z in metres from the rest position (x, 0, z)",
                    MapKind::Normal => s.normal_space.channels(),
                    MapKind::Foam => "Y = foam coverage in [0, 1]",
                }
                .into(),
            })
            .collect(),
        normal_space: s.normal_space,
        foam: maps.contains(&MapKind::Foam).then(foam_model),
        exr_compression: s.compression,
        png: s.png_bits.map(|bits| BakePng {
            bits,
            displacement_range_m: png_range_m,
            encoding: format!(
                "sample s in [0, {max}]; disp: component = (2 s / {max} - 1) * displacement_range_m (clamped to that range); \
                 normal: component = 2 s / {max} - 1; foam: coverage = s / {max}",
                max = (1u32 << bits) - 1
            ),
        }),
        bodies: None,
    }
}

/// What the foam map means. Every model with foam in swell makes it the same way
/// (`water/foam.rs`): coverage from the Jacobian of the horizontal displacement, optionally kept
/// and faded over time.
fn foam_model() -> BakeFoam {
    BakeFoam {
        quantity: "coverage".into(),
        range: [0.0, 1.0],
        model: "jacobian-threshold".into(),
        description: format!(
            "fraction of the surface around each vertex covered by foam, in [0, 1]: active whitecaps c = \
             Phi((model_params.foam_threshold - J) / sigma), the chance that the surface breaks there, where J is the \
             Jacobian of the horizontal displacement of the first cascade and sigma the spread of the Jacobian of the \
             waves it does not resolve (the sea's total slope variance as Cox and Munk measured it against the wind, \
             less the resolved one; at least {min_spread}; Dupuy and Bruneton 2012), so the coverage follows the \
             wind, not the grid; with persistence, residual foam is produced at the rate c / {active} s and fades \
             with time constant model_params.foam_fade_s, summed on a fixed lattice of times {step} s apart (the \
             nearest step dividing loop_period_s for a loop) in blocks that forget foam older than the previous \
             block (weight below {cut}), so a frame's foam depends on its time alone, never on the frames baked \
             before it; the value is min(1, max(c, residual)) (crates/swell/src/water/foam.rs)",
            min_spread = crate::water::FOAM_MIN_SPREAD,
            active = crate::water::FOAM_ACTIVE_TIME_S,
            step = crate::water::FOAM_LATTICE_STEP_S,
            cut = crate::water::FOAM_MEMORY_CUT,
        ),
    }
}

/// The text of `bake.json`. It is compared byte for byte with a directory's `bake.json`, and its
/// checksum names the bake in frame records and locks, so it must be a pure function of the
/// manifest.
fn manifest_json(manifest: &BakeManifest) -> Vec<u8> {
    let value = shortest_floats(serde_json::to_value(manifest).expect("the manifest always serialises"));
    let mut text = serde_json::to_vec_pretty(&value).expect("a JSON value always serialises");
    text.push(b'\n');
    text
}

/// Most values are `f32` (scene parameters, grid): print those in their shortest `f32` form
/// (0.576, not 0.5759999752044678), which reads back to the same `f32`. Values that are not exactly
/// an `f32` (an `f64` frame rate such as 1/3) keep every digit.
fn shortest_floats(v: serde_json::Value) -> serde_json::Value {
    use serde_json::Value;
    match v {
        Value::Number(n) if n.is_f64() => {
            let f = n.as_f64().expect("checked");
            if f64::from(f as f32) != f {
                return Value::Number(n);
            }
            (f as f32)
                .to_string()
                .parse::<f64>()
                .ok()
                .and_then(serde_json::Number::from_f64)
                .map_or(Value::Number(n), Value::Number)
        }
        Value::Array(a) => Value::Array(a.into_iter().map(shortest_floats).collect()),
        Value::Object(o) => Value::Object(o.into_iter().map(|(k, v)| (k, shortest_floats(v))).collect()),
        other => other,
    }
}

/// What `dir` already holds, against the bake about to start (whose `bake.json` text is `json`):
/// `Ok(true)` if `bake.json` is to be written (there is none), `Ok(false)` if the same one is
/// there. Refused: a `bake.json` that is not this bake's, with or without `resume` (the message
/// names the real cause: empty, not JSON, cut short, not a manifest, another version, or the keys
/// that differ), and frame files with no `bake.json` (they belong to no known bake).
fn check_directory(dir: &Path, path: &Path, json: &[u8], resume: bool) -> Result<bool> {
    let key = if resume { "--resume" } else { "--out" };
    let advice = "bake into a new directory, or delete the old bake's files first";
    let mut looked_twice = false;
    let old = loop {
        match std::fs::read(path) {
            Ok(bytes) => break bytes,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(Error::io(path, e)),
        }
        {
            let entries = std::fs::read_dir(dir).map_err(|e| Error::io(dir, e))?;
            let mut stray: Vec<String> = entries
                .filter_map(|e| e.ok())
                .filter_map(|e| e.file_name().to_str().map(str::to_string))
                .filter(|n| is_frame_file_name(n))
                .collect();
            if stray.is_empty() {
                return Ok(true);
            }
            // Another shard of this bake may have written bake.json and then frames since the
            // read above (bake.json always comes first): look again once before refusing.
            if !looked_twice && path.exists() {
                looked_twice = true;
                continue;
            }
            stray.sort();
            let shown = stray.iter().take(3).cloned().collect::<Vec<_>>().join(", ");
            let more = if stray.len() > 3 { format!(", ... {} files in all", stray.len()) } else { String::new() };
            return Err(Error::invalid(
                key,
                format!(
                    "{} holds frame files ({shown}{more}) but no bake.json, so nothing says which bake they \
                     belong to: they are neither resumed nor baked over; {advice}",
                    dir.display()
                ),
            ));
        }
    };
    if old == json {
        return Ok(false);
    }
    match manifest_mismatch(&old, json) {
        // The same values written otherwise (reformatted by hand): this bake, in this swell's text.
        None => Ok(true),
        Some(what) => Err(Error::invalid(key, format!("{} {what}; {advice}", path.display()))),
    }
}

/// Why the bytes `old` of a directory's `bake.json` are not the manifest `new` this bake writes,
/// in words that follow the file's path: the real cause first (empty, not JSON, cut short, not a
/// bake manifest, another `manifest_version`), else every key path that differs; `None` when the
/// two hold the same values.
fn manifest_mismatch(old: &[u8], new: &[u8]) -> Option<String> {
    use serde_json::error::Category;
    if old.iter().all(u8::is_ascii_whitespace) {
        return Some(format!("is empty ({} bytes): there is no manifest in it to compare with", old.len()));
    }
    let old: serde_json::Value = match serde_json::from_slice(old) {
        Ok(v) => v,
        Err(e) if e.classify() == Category::Eof => {
            return Some(format!(
                "is cut short: its JSON ends at line {} column {} before it is complete ({} bytes)",
                e.line(),
                e.column(),
                old.len()
            ))
        }
        Err(e) => return Some(format!("is not JSON ({e})")),
    };
    let new: serde_json::Value = serde_json::from_slice(new).expect("this swell's manifest is JSON");
    let Some(fields) = old.as_object() else {
        return Some(format!("is not a bake manifest: it holds a JSON {}, not an object", json_kind(&old)));
    };
    // Every manifest_version had these keys; without them it is some other JSON file.
    if !["swell_version", "maps", "frames"].iter().all(|k| fields.contains_key(*k)) {
        return Some(
            "is not a bake manifest: it lacks `swell_version`, `maps` or `frames`, which every bake.json has".into(),
        );
    }
    let new_version = new.get("manifest_version").and_then(|n| n.as_u64()).unwrap_or(1);
    let old_version = match fields.get("manifest_version") {
        None => 1,
        Some(v) => match v.as_u64() {
            Some(n) => n,
            None => return Some(format!("has manifest_version = {v}, which is not a whole number")),
        },
    };
    if old_version != new_version {
        return Some(format!(
            "has manifest_version {old_version}, this swell writes {new_version}: it was baked by another version of swell"
        ));
    }
    let mut keys = Vec::new();
    differences(&old, &new, String::new(), &mut keys);
    if keys.is_empty() {
        return None;
    }
    let keys: Vec<String> = keys.iter().map(|k| format!("`{k}`")).collect();
    let verb = if keys.len() == 1 { "differs" } else { "differ" };
    Some(format!("describes a different bake ({} {verb})", keys.join(", ")))
}

/// `null`, `boolean`, `number`, `string` or `array`: what a JSON value is, for messages.
fn json_kind(v: &serde_json::Value) -> &'static str {
    match v {
        serde_json::Value::Null => "null",
        serde_json::Value::Bool(_) => "boolean",
        serde_json::Value::Number(_) => "number",
        serde_json::Value::String(_) => "string",
        serde_json::Value::Array(_) => "array",
        serde_json::Value::Object(_) => "object",
    }
}

/// Appends to `out` the key path of every difference between two JSON values, in key order,
/// descending into objects (an array or a value that differs is one path).
fn differences(a: &serde_json::Value, b: &serde_json::Value, at: String, out: &mut Vec<String>) {
    use serde_json::Value::Object;
    let path = |k: &str| if at.is_empty() { k.to_string() } else { format!("{at}.{k}") };
    match (a, b) {
        (Object(a), Object(b)) => {
            for (k, va) in a {
                match b.get(k) {
                    Some(vb) if vb == va => {}
                    Some(vb) => differences(va, vb, path(k), out),
                    None => out.push(path(k)),
                }
            }
            out.extend(b.keys().filter(|k| !a.contains_key(*k)).map(|k| path(k)));
        }
        _ if a != b => out.push(at),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn differences_list_every_differing_key_path() {
        let a = serde_json::json!({"fps": 24.0, "grid": {"cells": [8, 8], "tile": false}, "maps": [1], "x": 1});
        let b = serde_json::json!({"fps": 30.0, "grid": {"cells": [8, 8], "tile": true}, "maps": [2], "y": 1});
        let mut out = vec![];
        differences(&a, &b, String::new(), &mut out);
        assert_eq!(out, ["fps", "grid.tile", "maps", "x", "y"]);
        out.clear();
        differences(&a, &a, String::new(), &mut out);
        assert!(out.is_empty());
    }

    #[test]
    fn a_foreign_bake_json_is_named_by_its_real_cause() {
        let new = br#"{"manifest_version": 2, "swell_version": "1", "maps": [], "frames": [0, 3], "fps": 24.0}"#;
        let why = |old: &[u8]| manifest_mismatch(old, new).unwrap_or_else(|| "the same".into());
        assert!(why(b"").starts_with("is empty (0 bytes)"), "{}", why(b""));
        assert!(why(b" \n").starts_with("is empty (2 bytes)"));
        assert!(why(br#"{"manifest_version": 2, "swell"#).starts_with("is cut short"), "{}", why(b"{"));
        assert!(why(b"hello").starts_with("is not JSON"), "{}", why(b"hello"));
        assert!(why(b"[1, 2]").contains("a JSON array, not an object"));
        assert!(why(b"{}").contains("lacks `swell_version`"));
        let old_version = br#"{"swell_version": "0.1", "maps": [], "frames": [0, 3], "fps": 24.0}"#;
        assert!(why(old_version).starts_with("has manifest_version 1, this swell writes 2"));
        let other = br#"{"manifest_version": 2, "swell_version": "1", "maps": [], "frames": [0, 9], "fps": 30.0}"#;
        assert_eq!(why(other), "describes a different bake (`fps`, `frames` differ)");
        // The same values in other text are the same bake.
        let spaced = br#"{ "manifest_version": 2, "fps": 24.0, "swell_version": "1", "maps": [], "frames": [0,3] }"#;
        assert_eq!(manifest_mismatch(spaced, new), None);
    }

    #[test]
    fn frame_file_names_are_recognised() {
        for name in ["disp_0000.exr", "normal_12345.png", "foam_0042.exr", "check_0007.json"] {
            assert!(is_frame_file_name(name), "{name}");
        }
        for name in ["bake.json", "bake.lock", "disp_000.exr", "disp_0000.tif", "notes.txt", ".swell-x.tmp"] {
            assert!(!is_frame_file_name(name), "{name}");
        }
    }

    #[test]
    fn png_ranges_round_up_to_two_digits() {
        assert_eq!(round_up_2_digits(1.234), 1.3);
        assert_eq!(round_up_2_digits(0.0456), 0.046);
        assert_eq!(round_up_2_digits(12.0), 12.0);
        assert_eq!(round_up_2_digits(0.0), 0.0);
    }

    #[test]
    fn batches_keep_two_frames_per_thread_within_half_the_memory_budget() {
        // Small maps: two frames per thread, at least two.
        assert_eq!(batch_len(1, 513 * 513), 2);
        assert_eq!(batch_len(8, 513 * 513), 16);
        // 256 threads on a 4097² map: the memory bound wins, and two batches fit in half the budget.
        let big = 4097 * 4097;
        let b = batch_len(256, big);
        assert!(b < 512, "batch {b}");
        assert!(2 * b as u64 * frame_bytes(big) <= crate::limits::MEMORY_BUDGET_BYTES / 2);
        // A map so large that one frame passes the bound still bakes, one frame at a time.
        assert_eq!(batch_len(4, usize::MAX / 2), 1);
    }
}
