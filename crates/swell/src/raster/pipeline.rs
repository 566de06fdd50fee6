//! The draw call: vertex data in, shaded pixels in a [`Framebuffer`] out.

use glam::Vec3;
use rayon::prelude::*;

use super::clip::{clip_triangle, outcode};
use super::triangle::{setup, SetupTriangle};
use super::{ClipVertex, Framebuffer, Varying};

/// Rows per band: each band is one parallel task. 16 rows of a 1280-wide image (80 KiB of colour)
/// stay in a core's L2 cache while its triangles are drawn.
const BAND_ROWS: u32 = 16;

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

/// Draws indexed triangles into `target` with a depth test (less-than), shading each visible
/// pixel with `shader`, which returns linear RGB.
///
/// `vertices` are in clip space; triangles are clipped, culled per `cull`, set up in parallel,
/// binned into bands and rasterized one band per task. The output does not depend on the number
/// of threads.
pub fn draw<V, S>(target: &mut Framebuffer, vertices: &[ClipVertex<V>], indices: &[u32], cull: Cull, shader: &S)
where
    V: Varying,
    S: Fn(&Fragment<V>) -> Vec3 + Sync,
{
    let (width, height) = (target.width(), target.height());
    if width == 0 || height == 0 {
        return;
    }
    let triangles = setup_all(vertices, indices, width, height, cull == Cull::Back);
    let bands = bin(&triangles, height);
    let row = width as usize;
    target
        .color
        .par_chunks_mut(row * BAND_ROWS as usize)
        .zip(target.depth.par_chunks_mut(row * BAND_ROWS as usize))
        .zip(bands.par_iter())
        .enumerate()
        .for_each(|(band, ((color, depth), tris))| {
            let y0 = band as u32 * BAND_ROWS;
            let y1 = (y0 + BAND_ROWS).min(height) - 1;
            for &t in tris {
                let tri = &triangles[t as usize];
                tri.scan((y0, y1), |c| {
                    let i = (c.y - y0) as usize * row + c.x as usize;
                    if c.depth < depth[i] {
                        depth[i] = c.depth;
                        let frag =
                            Fragment { varying: tri.interpolate(c.weights), primitive: tri.primitive, x: c.x, y: c.y };
                        color[i] = shader(&frag);
                    }
                });
            }
        });
}

/// Triangles per setup task: large enough to amortise the task, small enough to balance.
const SETUP_CHUNK: usize = 4096;

fn setup_all<V: Varying>(
    vertices: &[ClipVertex<V>],
    indices: &[u32],
    width: u32,
    height: u32,
    cull_back: bool,
) -> Vec<SetupTriangle<V>> {
    let chunks: Vec<Vec<SetupTriangle<V>>> = indices
        .par_chunks(3 * SETUP_CHUNK)
        .enumerate()
        .map(|(c, idx)| {
            let mut out = Vec::with_capacity(idx.len() / 3);
            for (k, t) in idx.chunks_exact(3).enumerate() {
                let prim = (c * SETUP_CHUNK + k) as u32;
                let tri = [vertices[t[0] as usize], vertices[t[1] as usize], vertices[t[2] as usize]];
                let codes = tri.map(|v| outcode(v.position));
                if codes[0] & codes[1] & codes[2] != 0 {
                    continue; // wholly outside one plane
                }
                let crossed = codes[0] | codes[1] | codes[2];
                if crossed == 0 {
                    out.extend(setup(&tri, prim, width, height, cull_back));
                    continue;
                }
                let poly = clip_triangle(tri, crossed);
                for f in 1..poly.len.saturating_sub(1) {
                    let fan = [poly.vertices[0], poly.vertices[f], poly.vertices[f + 1]];
                    out.extend(setup(&fan, prim, width, height, cull_back));
                }
            }
            out
        })
        .collect();
    chunks.concat()
}

fn bin<V>(triangles: &[SetupTriangle<V>], height: u32) -> Vec<Vec<u32>> {
    let n_bands = height.div_ceil(BAND_ROWS) as usize;
    let mut bands = vec![Vec::new(); n_bands];
    for (i, t) in triangles.iter().enumerate() {
        for b in (t.min_y / BAND_ROWS)..=(t.max_y / BAND_ROWS) {
            bands[b as usize].push(i as u32);
        }
    }
    bands
}
