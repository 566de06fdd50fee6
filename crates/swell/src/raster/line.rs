//! Depth-tested lines, for overlays (wireframe, normals).

use glam::{Vec3, Vec4};

use super::clip::GUARD_BAND;
use super::Framebuffer;

/// Clip planes for lines: near, far and the guard band, as `dot(plane, p) >= 0` inside.
const PLANES: [Vec4; 6] = [
    Vec4::new(0.0, 0.0, 1.0, 1.0),
    Vec4::new(0.0, 0.0, -1.0, 1.0),
    Vec4::new(1.0, 0.0, 0.0, GUARD_BAND),
    Vec4::new(-1.0, 0.0, 0.0, GUARD_BAND),
    Vec4::new(0.0, 1.0, 0.0, GUARD_BAND),
    Vec4::new(0.0, -1.0, 0.0, GUARD_BAND),
];

/// Clips segment a-b (clip space) to the clip volume (Liang-Barsky in homogeneous coordinates);
/// `None` when nothing is left.
pub fn clip_line(a: Vec4, b: Vec4) -> Option<(Vec4, Vec4)> {
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    for plane in PLANES {
        let (da, db) = (plane.dot(a), plane.dot(b));
        if da < 0.0 && db < 0.0 {
            return None;
        }
        if da < 0.0 {
            t0 = t0.max(da / (da - db));
        } else if db < 0.0 {
            t1 = t1.min(da / (da - db));
        }
    }
    (t0 <= t1).then(|| (a.lerp(b, t0), a.lerp(b, t1)))
}

/// Draws the segment between clip-space points `a` and `b` in `color`, one pixel wide, where it is
/// not behind what the depth buffer holds (less-or-equal). Depth is interpolated
/// perspective-correctly; the depth buffer is not written, so lines never hide each other.
///
/// A DDA along the major axis: one pixel per column (or row), at the pixel whose centre is nearest
/// the line.
pub fn draw_line(fb: &mut Framebuffer, a: Vec4, b: Vec4, color: Vec3) {
    let Some((a, b)) = clip_line(a, b) else { return };
    let (w, h) = (fb.width() as f32, fb.height() as f32);
    let win = |p: Vec4| {
        let inv_w = 1.0 / p.w;
        Vec4::new((0.5 * p.x * inv_w + 0.5) * w, (0.5 - 0.5 * p.y * inv_w) * h, 0.5 * p.z * inv_w + 0.5, inv_w)
    };
    let (pa, pb) = (win(a), win(b));
    let d = pb - pa;
    let steps = d.x.abs().max(d.y.abs()).ceil().max(1.0) as u32;
    let width = fb.width() as usize;
    for k in 0..=steps {
        let t = k as f32 / steps as f32;
        let p = pa + d * t;
        let (x, y) = (p.x.floor(), p.y.floor());
        if x < 0.0 || y < 0.0 || x >= w || y >= h {
            continue;
        }
        // Window depth is affine in screen space, so it interpolates linearly.
        let i = y as usize * width + x as usize;
        if p.z <= fb.depth[i] {
            fb.color[i] = color;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_behind_a_surface_is_hidden_and_one_in_front_is_drawn() {
        let mut fb = Framebuffer::new(20, 10);
        for (i, d) in fb.depth.iter_mut().enumerate() {
            *d = if i % 20 < 10 { 0.4 } else { 1.0 };
        }
        // A horizontal line across the middle at NDC depth 0 (window depth 0.5).
        draw_line(&mut fb, Vec4::new(-1.0, 0.0, 0.0, 1.0), Vec4::new(1.0, 0.0, 0.0, 1.0), Vec3::ONE);
        let row = 5 * 20;
        assert!(fb.color[row..row + 10].iter().all(|&c| c == Vec3::ZERO), "hidden behind depth 0.4");
        assert!(fb.color[row + 10..row + 20].iter().all(|&c| c == Vec3::ONE), "drawn over depth 1");
    }

    #[test]
    fn lines_crossing_the_near_plane_are_clipped() {
        let (a, b) = clip_line(Vec4::new(0.0, 0.0, 0.5, 1.0), Vec4::new(0.0, 0.0, -3.0, -1.0)).unwrap();
        assert!(a.z >= -a.w - 1e-6 && b.z >= -b.w - 1e-6 && b.w > 0.0);
        assert!(clip_line(Vec4::new(0.0, 0.0, -2.0, 1.0), Vec4::new(0.0, 0.0, -3.0, 1.0)).is_none());
    }
}
