//! Paper 001's experiments (section 4.3, tables 4.1-4.2): z-buffer time of a heightmap terrain
//! against the number of threads and against the heightmap size.
//!
//! The paper timed its ZBuffer algorithm (100 runs averaged) on an i7-7700K (4 cores, 8 threads);
//! its figures are in seconds and compared with swell's directly. swell times one frame of the
//! same path: clear the buffers, transform the heightmap's vertices, shade each triangle flat
//! (paper 001 section 3.2: intensity `|n_y|`, a light at infinity straight above) and rasterize
//! with the depth test (`swell::raster::draw`), into an 800 x 800 image. The heightmap, the mesh
//! and the buffers are built once, outside the timing.

use glam::{Mat4, Vec2, Vec3, Vec4};
use rayon::prelude::*;
use swell::math::GridSpec;
use swell::mesh::SurfaceMesh;
use swell::raster::{draw, ClipVertex, Cull, Framebuffer};
use swell::Result;

use super::report::{PaperUnit, PlotKind, Point, Report, Series};
use super::timing::{measure, Stats};
use super::Context;
use crate::thread_pool::thread_pool;

/// Image size, pixels.
pub const IMAGE: (u32, u32) = (800, 800);
/// Side of the square terrain, metres, whatever the heightmap's resolution: every size covers the
/// same part of the image, so only the triangle count changes.
const EXTENT: f32 = 100.0;
/// Seed of the experiments' heightmap.
const SEED: u64 = 1;

/// Table 4.1: threads and z-buffer time (s) on a 33 x 33 heightmap.
const THREADS_33: [(u32, f64); 6] =
    [(1, 0.12207), (2, 0.10223), (4, 0.08782), (8, 0.08062), (16, 0.08563), (32, 0.09113)];
/// Table 4.2: heightmap side and z-buffer time (s) on 1 thread and on 8 threads.
const SIZES: [(usize, f64, f64); 5] = [
    (33, 0.12056, 0.08062),
    (65, 0.12524, 0.08262),
    (129, 0.15733, 0.08707),
    (257, 0.21563, 0.09875),
    (513, 0.35673, 0.12993),
];

/// A `size` x `size` diamond-square heightmap (row-major, metres) from `seed`: paper 001's own
/// generator (section 2.1) with the paper's halving roughness. `size` must be 2^n + 1, as in the
/// paper's tables. Timing depends only on `size`, not on the shape.
pub fn heightmap(size: usize, seed: u64) -> Vec<f32> {
    let params = swell::terrain::DiamondSquareParams { amplitude: 15.0, seed, ..Default::default() };
    swell::terrain::diamond_square(size as u32, glam::Vec2::splat(100.0), &params)
        .expect("the paper's heightmap sizes are all 2^n + 1")
        .heights()
        .to_vec()
}

/// A heightmap turned into a triangle mesh, with the buffers one z-buffer frame needs.
pub struct Terrain {
    mesh: SurfaceMesh,
    clip_from_world: Mat4,
    clip: Vec<ClipVertex<()>>,
    faces: Vec<Vec3>,
    target: Framebuffer,
}

impl Terrain {
    /// The `size` x `size` heightmap on the regular grid (two triangles per cell), seen from above
    /// at 40 degrees so that it fills most of an 800 x 800 image.
    pub fn new(size: usize, seed: u64) -> Result<Self> {
        let cells = size as u32 - 1;
        let mut mesh = SurfaceMesh::new(GridSpec::centered(Vec2::splat(EXTENT), cells, cells)?);
        for (p, h) in mesh.positions.iter_mut().zip(heightmap(size, seed)) {
            p.y = h;
        }
        let view =
            glam::camera::rh::view::look_at_mat4(Vec3::new(0.0, 85.0, 100.0), Vec3::new(0.0, -8.0, 0.0), Vec3::Y);
        let proj = glam::camera::rh::proj::opengl::perspective(
            45f32.to_radians(),
            IMAGE.0 as f32 / IMAGE.1 as f32,
            1.0,
            1000.0,
        );
        let triangles = mesh.indices.len() / 3;
        Ok(Self {
            clip: vec![ClipVertex::default(); mesh.positions.len()],
            faces: vec![Vec3::ZERO; triangles],
            target: Framebuffer::new(IMAGE.0, IMAGE.1),
            clip_from_world: proj * view,
            mesh,
        })
    }

    /// One z-buffer frame on the current rayon pool.
    pub fn draw(&mut self) {
        let ground = Vec3::new(0.35, 0.45, 0.25);
        let sky = Vec3::new(0.6, 0.7, 0.8);
        self.target.clear_with(|_, _| sky);
        let m = self.clip_from_world;
        self.clip.par_iter_mut().zip(self.mesh.positions.par_iter()).for_each(|(c, &p)| {
            c.position = m * Vec4::from((p, 1.0));
        });
        let positions = &self.mesh.positions;
        self.faces.par_iter_mut().zip(self.mesh.indices.par_chunks_exact(3)).for_each(|(c, t)| {
            let [a, b, d] = [0, 1, 2].map(|k| positions[t[k] as usize]);
            let n = (b - a).cross(d - a).normalize_or(Vec3::Y);
            *c = ground * n.y.abs();
        });
        let faces = &self.faces;
        draw(&mut self.target, &self.clip, &self.mesh.indices, Cull::None, &|f| faces[f.primitive as usize]);
    }

    /// The image of the last [`Terrain::draw`].
    #[cfg(test)]
    pub fn framebuffer(&self) -> &Framebuffer {
        &self.target
    }
}

/// Times z-buffer frames of a `size` heightmap on `threads` threads.
fn zbuffer_time(ctx: &Context, size: usize, threads: u32) -> Result<Stats> {
    let pool = thread_pool(threads)?;
    let mut terrain = Terrain::new(size, SEED)?;
    measure(ctx.reps, || {
        pool.install(|| terrain.draw());
        Ok(())
    })
}

fn report(ctx: &Context, experiment: &'static str, title: &str, table: &str, x_label: &str) -> Report {
    Report {
        experiment,
        title: title.into(),
        source: format!("paper 001, table {table}"),
        setup: vec![
            format!(
                "One z-buffer frame at {}x{} pixels: clear, vertex transform, flat shading (|n_y|, light above), \
                 rasterization with depth test (`swell::raster::draw`).",
                IMAGE.0, IMAGE.1
            ),
            "Heightmap: `bench::paper001::heightmap` (4 octaves of sines, seed 1) on a 100 m square, two \
             triangles per cell; built once, not timed."
                .into(),
            "Threads: a rayon pool of exactly N workers (more than the machine's cores oversubscribes, as in the \
             paper)."
                .into(),
            "Paper machine: Intel Core i7-7700K, 4 cores / 8 threads, Windows 10; its figures are seconds, \
             converted to ms."
                .into(),
        ],
        x_label: x_label.into(),
        paper_unit: PaperUnit::Seconds,
        plot: PlotKind::Relative,
        series: vec![],
        machine: ctx.machine.clone(),
        repetitions: ctx.reps,
    }
}

/// `zbuffer-threads`: table 4.1 (33 x 33), and the same at 513 x 513.
pub fn zbuffer_threads(ctx: &Context) -> Result<Report> {
    let mut r = report(ctx, "zbuffer-threads", "z-buffer time against threads", "4.1", "threads");
    for size in [33, 513] {
        let mut points = Vec::new();
        for (threads, paper) in THREADS_33 {
            ctx.progress(&format!("{size}x{size} on {threads} threads"));
            let swell = zbuffer_time(ctx, size, threads)?;
            let paper = (size == 33).then_some(paper);
            points.push(Point { x: threads as f64, label: threads.to_string(), swell, paper });
        }
        r.series.push(Series { name: format!("{size}x{size} heightmap"), points });
    }
    Ok(r)
}

/// `zbuffer-sizes`: table 4.2, on 1 thread and on all threads (the paper's 8 threads were all of
/// its machine's).
pub fn zbuffer_sizes(ctx: &Context) -> Result<Report> {
    let mut r =
        report(ctx, "zbuffer-sizes", "z-buffer time against heightmap size", "4.2", "heightmap side (vertices)");
    let all = ctx.machine.logical_cores as u32;
    let all_name = format!("all threads ({all} here, 8 in the paper)");
    for (threads, name) in [(1, "1 thread".to_string()), (all, all_name)] {
        let mut points = Vec::new();
        for (size, one, eight) in SIZES {
            ctx.progress(&format!("{size}x{size} on {threads} threads"));
            let swell = zbuffer_time(ctx, size, threads)?;
            let paper = if threads == 1 { one } else { eight };
            points.push(Point { x: size as f64, label: format!("{size}x{size}"), swell, paper: Some(paper) });
        }
        r.series.push(Series { name, points });
    }
    Ok(r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heightmap_is_deterministic_bounded_and_seeded() {
        let a = heightmap(33, 7);
        assert_eq!(a.len(), 33 * 33);
        assert_eq!(a, heightmap(33, 7));
        assert_ne!(a, heightmap(33, 8));
        // Offsets start at 15 m and halve each level, so no height exceeds 30 m.
        assert!(a.iter().all(|h| h.is_finite() && h.abs() <= 30.0));
        assert!(a.iter().any(|h| h.abs() > 1.0));
    }

    #[test]
    fn terrain_image_is_the_same_on_one_and_two_threads() {
        let image = |threads| {
            let mut t = Terrain::new(33, SEED).unwrap();
            thread_pool(threads).unwrap().install(|| t.draw());
            t.framebuffer().color.clone()
        };
        let one = image(1);
        assert_eq!(one, image(2));
        // The terrain covers much of the frame (pixels differing from the sky colour).
        let sky = Vec3::new(0.6, 0.7, 0.8);
        let covered = one.iter().filter(|&&c| c != sky).count();
        assert!(covered > one.len() / 3, "terrain covers only {covered} pixels");
    }
}
