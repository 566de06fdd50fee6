//! The draw call: vertex data in, shaded pixels in a [`Framebuffer`] out.
//!
//! Three parallel stages, each deterministic:
//! 1. every vertex is classified against the clip planes and, when inside, projected to window
//!    space once (a grid vertex is shared by six triangles);
//! 2. triangles are set up in chunks of [`SETUP_CHUNK`], each chunk binning its own triangles
//!    into bands (parallel binning: no serial pass over all triangles). A triangle whose pixel box
//!    is at most 2 x 2 (most of a dense mesh's) is covered right there, 16 at a time in vector
//!    lanes (`tiny_triangles`), and binned as its covered pixels; larger ones as setup records;
//! 3. bands are rasterized in parallel, each walking the chunks in order, so every pixel sees its
//!    triangles in submission order whatever the number of threads.
//!
//! On the 513² terrain at 800 x 800 (524,288 triangles, `tools/llvmpipe/compare.sh`), covering
//! small triangles at setup took a Gouraud frame from 365 to 250 million instructions
//! (callgrind, one thread) and from 14.2 to 9.7 ms on two cores (docs/PERFORMANCE.md).

use std::sync::Mutex;

use glam::Vec3;
use rayon::prelude::*;

use super::clip::{clip_triangle, outcode};
use super::tiny_triangles::{classify, Class, Corners, Covers, LANES};
use super::triangle::{
    depth_at, perspective_weights, setup_clip_geometry, setup_geometry, to_window, SetupTriangle, WindowVertex,
};
use super::{ClipVertex, Framebuffer, Varying};

/// Rows per band: each band is one parallel task. 16 rows of a 1280-wide image (80 KiB of colour)
/// stay in a core's L2 cache while its triangles are drawn.
const BAND_ROWS: u32 = 16;

/// Triangles per setup task: large enough to amortise the task and its bins, small enough to
/// balance.
const SETUP_CHUNK: usize = 8192;
// A chunk is whole groups of small-triangle lanes: a triangle's index is its chunk's, group's and lane's.
const _: () = assert!(SETUP_CHUNK.is_multiple_of(LANES));

/// Vertices per projection task.
const VERTEX_TASK: usize = 4096;

/// Outcode bit of a vertex inside every clip plane whose window position is not finite; the
/// clipper ignores it (it is none of its planes) and the clipped setup drops the triangle.
const NOT_FINITE: u8 = 1 << 6;

/// Which triangles to skip.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Cull {
    /// Draw both sides.
    #[default]
    None,
    /// Skip triangles facing away (clockwise in NDC).
    Back,
}

/// What a fragment shader receives.
#[derive(Clone, Copy, Debug)]
pub struct Fragment<V> {
    /// Perspective-correct interpolated varyings.
    pub varying: V,
    /// Index of the triangle in the index buffer (`indices[3 * primitive..]`).
    pub primitive: u32,
    /// Pixel column.
    pub x: u32,
    /// Pixel row, 0 at the top.
    pub y: u32,
}

/// Buffers of one draw call kept between calls, so that steady-state frames do not allocate.
pub struct DrawScratch<V> {
    window: Vec<(u8, WindowVertex)>,
    chunks: Vec<Chunk<V>>,
    /// One per worker thread, for [`draw_deferred_with`]; each band locks the one of the thread
    /// it runs on (never contended) and leaves nothing in it the next band reads.
    deferred: Vec<Mutex<DeferredScratch<V>>>,
}

impl<V> Default for DrawScratch<V> {
    fn default() -> Self {
        Self { window: Vec::new(), chunks: Vec::new(), deferred: Vec::new() }
    }
}

/// One setup task's triangles and, per band, what it draws there, in submission order.
///
/// A triangle whose pixel box is at most 2 x 2 and whose extent is under 16 pixels (nearly every
/// triangle of a dense mesh: 97 % of the 513² terrain's at 800 x 800) is rasterized at setup, in
/// parallel, and binned as its covered pixels (fragment [`Entry`]s): a band then only depth-tests
/// them. Other triangles are kept as setup records and scanned per band. The records hold no varyings: `corners[i]` names triangle
/// `i`'s vertices (in its clockwise order), indices below the draw's vertex count into the
/// caller's vertices and the others into `clipped`, the varyings of vertices made by clipping.
/// Copying three varyings into every record made a Gouraud record half as large again for pixels
/// that mostly fail the depth test or are never covered.
struct Chunk<V> {
    triangles: Vec<SetupTriangle<()>>,
    /// Empty when `V` has no data (flat shading): nothing to look up.
    corners: Vec<[u32; 3]>,
    clipped: Vec<V>,
    bins: Vec<Vec<Entry>>,
}

/// What a chunk draws in a band: one covered pixel of a small triangle, or a large triangle.
#[derive(Clone, Copy, Debug)]
struct Entry {
    /// Row-major pixel index in the image for a fragment; [`Entry::TRIANGLE`] for a triangle.
    pixel: u32,
    /// Window-space depth of the fragment.
    z: f32,
    /// A fragment's triangle: its index in the draw's index buffer, with [`Entry::SWAPPED`] set
    /// when its vertices 1 and 2 were swapped at setup. A triangle: its index in
    /// [`Chunk::triangles`].
    index: u32,
    /// A fragment's perspective-correct weights of its triangle's (clockwise) corners; zeros
    /// when the draw interpolates nothing.
    weights: [f32; 3],
}

impl Entry {
    /// `pixel` of a triangle entry (a draw with a side over 2^16 bins no fragments).
    const TRIANGLE: u32 = u32::MAX;
    /// Flag in a fragment's `index`: an index buffer holds fewer than 2^32 entries, so fewer
    /// than 2^31 triangles.
    const SWAPPED: u32 = 1 << 31;

    /// Triangle `t` of the chunk.
    fn triangle(t: u32) -> Self {
        Self { pixel: Self::TRIANGLE, z: 0.0, index: t, weights: [0.0; 3] }
    }
}

/// Draws indexed triangles into `target` with a depth test (less-than), shading each visible
/// pixel with `shader`, which returns linear RGB. Allocates its buffers; [`draw_with`] reuses them.
///
/// `vertices` are in clip space; triangles are clipped, culled per `cull`, set up in parallel,
/// binned into bands and rasterized one band per task. The output does not depend on the number
/// of threads.
pub fn draw<V, S>(target: &mut Framebuffer, vertices: &[ClipVertex<V>], indices: &[u32], cull: Cull, shader: &S)
where
    V: Varying,
    S: Fn(&Fragment<V>) -> Vec3 + Sync,
{
    draw_with(&mut DrawScratch::default(), target, vertices, indices, cull, shader)
}

/// [`draw`] with caller-owned scratch buffers.
pub fn draw_with<V, S>(
    scratch: &mut DrawScratch<V>,
    target: &mut Framebuffer,
    vertices: &[ClipVertex<V>],
    indices: &[u32],
    cull: Cull,
    shader: &S,
) where
    V: Varying,
    S: Fn(&Fragment<V>) -> Vec3 + Sync,
{
    if !project_and_bin(scratch, target, vertices, indices, cull) {
        return;
    }
    let chunks = &scratch.chunks;
    for_each_band(target, |band, color, depth| raster_band(chunks, vertices, indices, band, color, depth, shader));
}

/// Stages 1 and 2 of a draw into `target`: projects the vertices and sets up and bins the
/// triangles; false when `target` has no pixels (nothing to draw).
fn project_and_bin<V: Varying>(
    scratch: &mut DrawScratch<V>,
    target: &Framebuffer,
    vertices: &[ClipVertex<V>],
    indices: &[u32],
    cull: Cull,
) -> bool {
    let (width, height) = (target.width(), target.height());
    if width == 0 || height == 0 {
        return false;
    }
    project_vertices(&mut scratch.window, vertices, width, height);
    setup_and_bin(scratch, vertices, indices, width, height, cull == Cull::Back);
    true
}

/// Runs `draw` on every band of `target` in parallel, one band per task: bands differ in cost by
/// orders of magnitude (many small triangles at the horizon, a few large ones in front, none in
/// the sky), and rayon's adaptive split otherwise leaves one thread a long run of costly bands
/// while the other waits.
fn for_each_band(target: &mut Framebuffer, draw: impl Fn(Band, &mut [Vec3], &mut [f32]) + Sync) {
    let (row, height) = (target.width() as usize, target.height());
    target
        .color
        .par_chunks_mut(row * BAND_ROWS as usize)
        .zip(target.depth.par_chunks_mut(row * BAND_ROWS as usize))
        .enumerate()
        .with_max_len(1)
        .for_each(|(index, (color, depth))| draw(Band { index, row, height }, color, depth));
}

/// [`draw_with`] with deferred shading: the bands are drawn first, keeping only the nearest
/// fragment of each pixel, then `shade` colours each covered pixel once, a row's covered pixels
/// per call (their perspective-correct varyings left to right, and as many colours to write).
/// The image is bit-identical to [`draw_with`] with a shader that shades one fragment's varying
/// the same way; per-pixel shading costs what the visible pixels cost, not every fragment that
/// passed the depth test on the way.
pub fn draw_deferred_with<V, S>(
    scratch: &mut DrawScratch<V>,
    target: &mut Framebuffer,
    vertices: &[ClipVertex<V>],
    indices: &[u32],
    cull: Cull,
    shade: &S,
) where
    V: Varying,
    S: Fn(&[V], &mut [Vec3]) + Sync,
{
    if !project_and_bin(scratch, target, vertices, indices, cull) {
        return;
    }
    let workers = rayon::current_num_threads().max(1);
    scratch.deferred.resize_with(workers, Default::default);
    let (chunks, deferred) = (&scratch.chunks, &scratch.deferred);
    for_each_band(target, |band, color, depth| {
        // Which worker's buffers a band uses changes nothing in the image: each band resets them.
        let worker = rayon::current_thread_index().unwrap_or(0) % deferred.len();
        let mut mine = deferred[worker].lock().unwrap_or_else(|e| e.into_inner());
        raster_band_deferred(chunks, vertices, indices, band, color, depth, &mut mine, shade)
    });
}

/// Which band [`raster_band`] draws: rows `index * BAND_ROWS ..` of an image `row` pixels wide
/// and `height` high.
#[derive(Clone, Copy)]
struct Band {
    index: usize,
    row: usize,
    height: u32,
}

impl Band {
    /// Its first row of the image.
    fn first_row(self) -> u32 {
        self.index as u32 * BAND_ROWS
    }
}

/// Draws band `band` (`color` and `depth` its pixels):
/// every chunk's triangles and fragments binned to it, in submission order.
// The three stages stay out of line so that profiles (perf, callgrind) name them.
#[inline(never)]
fn raster_band<V: Varying, S>(
    chunks: &[Chunk<V>],
    vertices: &[ClipVertex<V>],
    indices: &[u32],
    band: Band,
    color: &mut [Vec3],
    depth: &mut [f32],
    shader: &S,
) where
    S: Fn(&Fragment<V>) -> Vec3 + Sync,
{
    let (row, y0) = (band.row, band.first_row());
    // A triangle's corners are gathered once, when its walk starts, not per pixel (they are
    // looked up by index in a vertex array of megabytes).
    walk_band(
        chunks,
        band,
        depth,
        color,
        |chunk, triangle| corner_varyings(chunk, triangle, vertices),
        #[inline(always)]
        |color, i, corners, at| {
            let varying = varying_at(at.tri, corners, at.cov.linear);
            color[i] = shader(&Fragment { varying, primitive: at.tri.primitive, x: at.cov.x, y: at.cov.y })
        },
        #[inline(always)]
        |color, i, entry| {
            let varying = fragment_varying(entry, indices, vertices);
            let (x, y) = ((i % row) as u32, y0 + (i / row) as u32);
            color[i] = shader(&Fragment { varying, primitive: entry.index & !Entry::SWAPPED, x, y })
        },
    );
}

/// The varyings of a fragment entry: its triangle's corners, found through the index buffer,
/// weighted by its perspective-correct weights (defaults when `V` carries no data).
#[inline(always)]
fn fragment_varying<V: Varying>(entry: &Entry, indices: &[u32], vertices: &[ClipVertex<V>]) -> V {
    if std::mem::size_of::<V>() == 0 {
        return V::default();
    }
    let [a, b, d] = fragment_corners(entry.index, indices, vertices);
    V::weighted(&a, &b, &d, entry.weights)
}

/// The varyings at the (clockwise) corners of the triangle a fragment entry's `index` names.
#[inline(always)]
fn fragment_corners<V: Varying>(index: u32, indices: &[u32], vertices: &[ClipVertex<V>]) -> [V; 3] {
    let t = (index & !Entry::SWAPPED) as usize * 3;
    let (a, b, d) = (indices[t] as usize, indices[t + 1] as usize, indices[t + 2] as usize);
    let (a, b, d) = (vertices[a].varying, vertices[b].varying, vertices[d].varying);
    if index & Entry::SWAPPED != 0 {
        [a, d, b]
    } else {
        [a, b, d]
    }
}

/// The nearest triangle found so far at a pixel of a deferred draw: which one and where in it.
#[derive(Clone, Copy, Debug, Default)]
struct Hit {
    /// Chunk and triangle record within it; [`Hit::FRAGMENT`] and a fragment entry's `index`
    /// for a triangle binned as fragments.
    chunk: u32,
    triangle: u32,
    /// A record's screen-space barycentric weights ([`super::triangle::Coverage::linear`]), or a
    /// fragment's perspective-correct ones.
    weights: [f32; 3],
}

impl Hit {
    /// `chunk` of a hit by a fragment entry.
    const FRAGMENT: u32 = u32::MAX;
}

/// The varyings of triangle `triangle` of `chunk` at its three (clockwise) corners; defaults
/// when `V` carries no data (flat shading).
#[inline(always)]
fn corner_varyings<V: Varying>(chunk: &Chunk<V>, triangle: u32, vertices: &[ClipVertex<V>]) -> [V; 3] {
    if std::mem::size_of::<V>() == 0 {
        return [V::default(); 3];
    }
    let varying_of = |k: u32| match vertices.get(k as usize) {
        Some(v) => v.varying,
        None => chunk.clipped[k as usize - vertices.len()],
    };
    let [a, b, d] = chunk.corners[triangle as usize];
    [varying_of(a), varying_of(b), varying_of(d)]
}

/// The perspective-correct varyings of triangle `tri` (whose corners carry `corners`) at the pixel
/// with linear weights `linear`. Both draws interpolate here, so they give bit-identical
/// varyings.
#[inline(always)]
fn varying_at<V: Varying>(tri: &SetupTriangle<()>, corners: &[V; 3], linear: [f32; 3]) -> V {
    if std::mem::size_of::<V>() != 0 {
        V::weighted(&corners[0], &corners[1], &corners[2], tri.perspective_weights(linear))
    } else {
        V::default()
    }
}

/// Where a pixel of a band is covered: the chunk's index, the triangle (index and setup) and the
/// coverage.
struct Covered<'a> {
    chunk_index: u32,
    triangle: u32,
    tri: &'a SetupTriangle<()>,
    cov: super::triangle::Coverage,
}

/// Walks everything binned to `band` in submission order. For each covered pixel of a triangle
/// record whose depth it passes (strictly nearer: the first of equal depths wins), it writes the
/// new depth and calls `nearer(pixel, prepared, covered)`, `prepared` being what
/// `begin(chunk, triangle)` returned when the triangle's walk started; for each fragment entry
/// that passes, it writes the depth and calls `fragment(pixel, entry)`. `pixel` indexes the band;
/// both get `out`, what they write to.
#[inline(always)]
fn walk_band<V: Varying, T, O: ?Sized>(
    chunks: &[Chunk<V>],
    band: Band,
    depth: &mut [f32],
    out: &mut O,
    mut begin: impl FnMut(&Chunk<V>, u32) -> T,
    mut nearer: impl FnMut(&mut O, usize, &T, Covered),
    mut fragment: impl FnMut(&mut O, usize, &Entry),
) {
    let Band { index: band, row, height } = band;
    let y0 = band as u32 * BAND_ROWS;
    let y1 = (y0 + BAND_ROWS).min(height) - 1;
    // Fragment entries hold image pixel indices; the band starts at this one.
    let base = y0 as usize * row;
    for (c, chunk) in chunks.iter().enumerate() {
        for entry in &chunk.bins[band] {
            if entry.pixel != Entry::TRIANGLE {
                let i = entry.pixel as usize - base;
                if entry.z < depth[i] {
                    depth[i] = entry.z;
                    fragment(out, i, entry);
                }
                continue;
            }
            let t = entry.index;
            let tri = &chunk.triangles[t as usize];
            let prepared = begin(chunk, t);
            tri.scan(
                (y0, y1),
                // Inlined into both of the scan's loops: a call per pixel cost a Gouraud pixel
                // a third of its instructions (callgrind, `coast`).
                #[inline(always)]
                |cov| {
                    let i = (cov.y - y0) as usize * row + cov.x as usize;
                    let z = tri.depth(cov.linear);
                    if z < depth[i] {
                        depth[i] = z;
                        nearer(out, i, &prepared, Covered { chunk_index: c as u32, triangle: t, tri, cov });
                    }
                },
            );
        }
    }
}

/// Like [`raster_band`], but each pixel is shaded once, after the whole band is drawn, with the
/// varyings of its nearest fragment: no shading is spent on fragments a nearer one hides later.
/// `shade` gets one row's covered pixels at a time, left to right, so it can shade them in batches;
/// when they are one unbroken span (most rows of open water) it writes their colours in place.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn raster_band_deferred<V: Varying, S>(
    chunks: &[Chunk<V>],
    vertices: &[ClipVertex<V>],
    indices: &[u32],
    band: Band,
    color: &mut [Vec3],
    depth: &mut [f32],
    scratch: &mut DeferredScratch<V>,
    shade: &S,
) where
    S: Fn(&[V], &mut [Vec3]) + Sync,
{
    let n = depth.len();
    let DeferredScratch { hits, covered, varyings, columns, colors } = scratch;
    hits.resize(n, Hit::default());
    covered.clear();
    covered.resize(n, false);
    walk_band(
        chunks,
        band,
        depth,
        &mut (&mut hits[..], &mut covered[..]),
        |_, _| (),
        |(hits, covered), i, _, at| {
            hits[i] = Hit { chunk: at.chunk_index, triangle: at.triangle, weights: at.cov.linear };
            covered[i] = true;
        },
        |(hits, covered), i, entry| {
            hits[i] = Hit { chunk: Hit::FRAGMENT, triangle: entry.index, weights: entry.weights };
            covered[i] = true;
        },
    );
    let row = band.row;
    for (r, (hits, covered)) in hits.chunks_exact(row).zip(covered.chunks_exact(row)).enumerate() {
        varyings.clear();
        columns.clear();
        // Neighbouring pixels of a row mostly share their triangle (about 30 pixels each on the
        // unbounded sea): its record and its three corners' varyings are looked up once per run,
        // not per pixel (they are gathered from a vertex array of megabytes).
        // A fragment hit has no record (`None`): its weights are already perspective-correct.
        let mut current: Option<Run<V>> = None;
        for (x, (hit, _)) in hits.iter().zip(covered).enumerate().filter(|(_, (_, &c))| c) {
            let (tri, corners) = match current {
                Some((c, t, tri, corners)) if c == hit.chunk && t == hit.triangle => (tri, corners),
                _ => {
                    let (tri, corners) = if hit.chunk == Hit::FRAGMENT {
                        (None, fragment_corners(hit.triangle, indices, vertices))
                    } else {
                        let chunk = &chunks[hit.chunk as usize];
                        (Some(&chunk.triangles[hit.triangle as usize]), corner_varyings(chunk, hit.triangle, vertices))
                    };
                    current = Some((hit.chunk, hit.triangle, tri, corners));
                    (tri, corners)
                }
            };
            varyings.push(match tri {
                Some(tri) => varying_at(tri, &corners, hit.weights),
                None => V::weighted(&corners[0], &corners[1], &corners[2], hit.weights),
            });
            columns.push(x as u32);
        }
        let (Some(&first), Some(&last)) = (columns.first(), columns.last()) else { continue };
        let out = &mut color[r * row..(r + 1) * row];
        if (last - first) as usize + 1 == columns.len() {
            // One span: shaded straight into the row.
            shade(varyings, &mut out[first as usize..=last as usize]);
            continue;
        }
        colors.clear();
        colors.resize(varyings.len(), Vec3::ZERO);
        shade(varyings, colors);
        for (&x, c) in columns.iter().zip(colors.iter()) {
            out[x as usize] = *c;
        }
    }
}

/// The triangle of a run of a deferred row's pixels: chunk and triangle as in [`Hit`], its setup
/// record (none for a fragment hit) and its corners' varyings.
type Run<'a, V> = (u32, u32, Option<&'a SetupTriangle<()>>, [V; 3]);

/// One worker's buffers for [`raster_band_deferred`], kept between draws.
struct DeferredScratch<V> {
    hits: Vec<Hit>,
    covered: Vec<bool>,
    /// A row's covered pixels: their varyings and columns, left to right.
    varyings: Vec<V>,
    columns: Vec<u32>,
    colors: Vec<Vec3>,
}

impl<V> Default for DeferredScratch<V> {
    fn default() -> Self {
        Self { hits: Vec::new(), covered: Vec::new(), varyings: Vec::new(), columns: Vec::new(), colors: Vec::new() }
    }
}

#[inline(never)]
fn project_vertices<V: Varying>(out: &mut Vec<(u8, WindowVertex)>, vertices: &[ClipVertex<V>], w: u32, h: u32) {
    out.resize(vertices.len(), (0, WindowVertex::default()));
    // Blocks of a fixed size per task, each a plain loop: vertices outside the view cost less and
    // come in runs, and the per-vertex work is only a few dozen instructions.
    out.par_chunks_mut(VERTEX_TASK).zip(vertices.par_chunks(VERTEX_TASK)).for_each(|(out, vertices)| {
        for (o, v) in out.iter_mut().zip(vertices) {
            let code = outcode(v.position);
            *o = if code == 0 {
                let window = to_window(v.position, w, h);
                // A w so small that 1/w overflows (below about 3e-39) passes every plane but has
                // no window position (it saturates to the ends of i32): such a vertex goes the
                // clipper's way, whose setup drops non-finite vertices.
                let finite = window.inv_w.is_finite() && window.z.is_finite();
                (if finite { 0 } else { NOT_FINITE }, window)
            } else {
                (code, WindowVertex::default())
            };
        }
    });
}

#[inline(never)]
fn setup_and_bin<V: Varying>(
    scratch: &mut DrawScratch<V>,
    vertices: &[ClipVertex<V>],
    indices: &[u32],
    width: u32,
    height: u32,
    cull_back: bool,
) {
    let n_bands = height.div_ceil(BAND_ROWS) as usize;
    let n_chunks = indices.len().div_ceil(3 * SETUP_CHUNK);
    scratch.chunks.resize_with(n_chunks, || Chunk {
        triangles: Vec::new(),
        corners: Vec::new(),
        clipped: Vec::new(),
        bins: Vec::new(),
    });
    let has_varying = std::mem::size_of::<V>() != 0;
    // Indices at or above this name `Chunk::clipped` (index buffers are u32, so are vertex counts).
    let n_vertices = vertices.len() as u32;
    let window = &scratch.window;
    // Fragment entries name pixels by a u32 index and triangles by a 31-bit one; every image and
    // index buffer this crate makes fits, and anything larger keeps to triangle records.
    // Sides up to 2^16 also keep window coordinates (inside the guard band) far inside i32, as the
    // small-triangle lanes' 32-bit arithmetic needs.
    let fragments = width <= 1 << 16 && height <= 1 << 16 && indices.len() / 3 < Entry::SWAPPED as usize;
    // One chunk per task, for the same balance as the bands: triangles outside the view come in runs.
    let chunks = scratch.chunks.par_iter_mut().zip(indices.par_chunks(3 * SETUP_CHUNK)).enumerate().with_max_len(1);
    chunks.for_each(|(c, (chunk, idx))| {
        chunk.triangles.clear();
        chunk.corners.clear();
        chunk.clipped.clear();
        chunk.bins.resize_with(n_bands, Vec::new);
        chunk.bins.iter_mut().for_each(Vec::clear);
        let Chunk { triangles, corners, clipped, bins } = chunk;
        // `bins` passed in, not captured: the fragment path below pushes to it too.
        let mut emit = |bins: &mut [Vec<Entry>], tri: Option<(SetupTriangle<()>, bool)>, [a, b, d]: [u32; 3]| {
            if let Some((t, swapped)) = tri {
                let i = triangles.len() as u32;
                // Half-open: an inclusive range's `exhausted` flag is one more compare and branch
                // per triangle (callgrind: 2.7 fewer branches per triangle on the 513² terrain).
                for band in (t.min_y / BAND_ROWS)..(t.max_y / BAND_ROWS + 1) {
                    bins[band as usize].push(Entry::triangle(i));
                }
                triangles.push(t);
                if has_varying {
                    corners.push(if swapped { [a, d, b] } else { [a, b, d] });
                }
            }
        };
        let (mut lanes, mut covers) = (Corners::default(), Covers::default());
        for (g, group) in idx.chunks(3 * LANES).enumerate() {
            // Small triangles, LANES at a time: classified and covered in vector lanes.
            for (k, t) in group.chunks_exact(3).enumerate() {
                let (a, b, d) = (&window[t[0] as usize], &window[t[1] as usize], &window[t[2] as usize]);
                lanes.unclipped[k] = fragments && (a.0 | b.0 | d.0) == 0;
                for (v, w) in [a, b, d].into_iter().enumerate() {
                    lanes.x[v][k] = w.1.x;
                    lanes.y[v][k] = w.1.y;
                }
            }
            lanes.unclipped[group.len() / 3..].fill(false);
            classify(&lanes, width, height, cull_back, &mut covers);
            for (k, t) in group.chunks_exact(3).enumerate() {
                let prim = (c * SETUP_CHUNK + g * LANES + k) as u32;
                match covers.class(k) {
                    Class::Nothing => continue,
                    Class::Tiny => {
                        let (a, b, d) = (&window[t[0] as usize].1, &window[t[1] as usize].1, &window[t[2] as usize].1);
                        let swapped = covers.swapped[k];
                        let (b, d) = if swapped { (d, b) } else { (b, d) };
                        let (z, inv_w) = ([a.z, b.z, d.z], [a.inv_w, b.inv_w, d.inv_w]);
                        let index = prim | if swapped { Entry::SWAPPED } else { 0 };
                        covers.fragments(k, |x, y, linear| {
                            let weights = if has_varying { perspective_weights(&inv_w, linear) } else { [0.0; 3] };
                            let z = depth_at(&z, linear);
                            bins[(y / BAND_ROWS) as usize].push(Entry { pixel: y * width + x, z, index, weights });
                        });
                        continue;
                    }
                    Class::General => {}
                }
                let (a, b, d) = (window[t[0] as usize], window[t[1] as usize], window[t[2] as usize]);
                if a.0 & b.0 & d.0 != 0 {
                    continue; // wholly outside one plane
                }
                let crossed = a.0 | b.0 | d.0;
                if crossed == 0 {
                    // Large, or small but with an extent the lanes' 32 bits do not hold (a big
                    // triangle the viewport clamps to a few pixels): a setup record.
                    emit(bins, setup_geometry(&[a.1, b.1, d.1], prim, width, height, cull_back), [t[0], t[1], t[2]]);
                    continue;
                }
                let tri = [vertices[t[0] as usize], vertices[t[1] as usize], vertices[t[2] as usize]];
                let poly = clip_triangle(tri, crossed);
                let base = n_vertices + clipped.len() as u32;
                if has_varying && poly.len >= 3 {
                    clipped.extend(poly.vertices[..poly.len].iter().map(|v| v.varying));
                }
                for f in 1..poly.len.saturating_sub(1) {
                    let fan = [poly.vertices[0].position, poly.vertices[f].position, poly.vertices[f + 1].position];
                    let k = f as u32;
                    emit(
                        bins,
                        setup_clip_geometry(fan, prim, width, height, cull_back),
                        [base, base + k, base + k + 1],
                    );
                }
            }
        }
    });
}
