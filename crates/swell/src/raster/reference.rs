//! A slow, obviously-right rasterizer that the fast one is tested against.
//!
//! Every pixel of the viewport is tested against every triangle with edge functions evaluated from
//! scratch in `f64`, with the same snapping and top-left rule as [`super::triangle`]. No clipping:
//! callers pass triangles in front of the camera.

use glam::Vec4;

/// For each pixel (row-major), the index of the last triangle covering its centre (no depth test),
/// or `u32::MAX`; plus how many triangles covered each pixel.
pub fn coverage(positions: &[Vec4], indices: &[u32], width: u32, height: u32) -> (Vec<u32>, Vec<u32>) {
    let n = (width * height) as usize;
    let (mut owner, mut count) = (vec![u32::MAX; n], vec![0u32; n]);
    let snap = |p: Vec4| {
        // The same arithmetic as the fast path's window transform, so both snap to the same grid.
        let inv_w = 1.0 / p.w;
        let (nx, ny) = (p.x * inv_w, p.y * inv_w);
        let sx = ((0.5 * nx + 0.5) * width as f32 * 256.0).round() as f64 / 256.0;
        let sy = ((0.5 - 0.5 * ny) * height as f32 * 256.0).round() as f64 / 256.0;
        (sx, sy)
    };
    for (t, tri) in indices.chunks_exact(3).enumerate() {
        let mut v = [0, 1, 2].map(|k| snap(positions[tri[k] as usize]));
        let area = (v[1].0 - v[0].0) * (v[2].1 - v[0].1) - (v[1].1 - v[0].1) * (v[2].0 - v[0].0);
        if area == 0.0 {
            continue;
        }
        if area < 0.0 {
            v.swap(1, 2);
        }
        for py in 0..height {
            for px in 0..width {
                let (cx, cy) = (px as f64 + 0.5, py as f64 + 0.5);
                let inside = [(1, 2), (2, 0), (0, 1)].iter().all(|&(a, b)| {
                    let (dx, dy) = (v[b].0 - v[a].0, v[b].1 - v[a].1);
                    let e = dx * (cy - v[a].1) - dy * (cx - v[a].0);
                    e > 0.0 || (e == 0.0 && ((dy == 0.0 && dx > 0.0) || dy < 0.0))
                });
                if inside {
                    let i = (py * width + px) as usize;
                    owner[i] = t as u32;
                    count[i] += 1;
                }
            }
        }
    }
    (owner, count)
}
