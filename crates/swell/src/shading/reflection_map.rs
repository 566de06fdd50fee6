//! The terrain a calm water surface mirrors (paper 003 §2: water reflects the sky *and the terrain
//! above it*), as a planar reflection: the terrain mirrored about the water at rest (y = 0),
//! rendered from the frame's own camera into an image of the frame's size.
//!
//! Seen from the eye, a flat mirror at y = 0 shows at each pixel what the mirrored world shows at
//! the same pixel, so a flat water point reads the image where it projects itself. A wave tilts
//! the normal and so the reflected ray; [`ReflectionMap::sample`] follows the tilted ray for the
//! distance the untilted one travels behind the mirror and reads the image where that point
//! projects (one step of a screen-space search: exact for a flat surface, a good approximation
//! while the tilt is small, which is what planar reflections assume; Fernando, *GPU Gems* 2004,
//! ch. 19 and the classic mirror technique of Kilgard 1999).
//!
//! The mirrored render clips everything that stands below the water with an oblique near plane
//! (Lengyel, "Oblique view frustum depth projection and clipping", JGT 10(2), 2005): clip-space
//! `z` is replaced by `k h − w`, with h the point's height above the water before mirroring, so
//! the clipper's near plane `z >= −w` becomes `h >= 0`, and window depth `k h / 2w` still grows
//! along each view ray (for an eye above the water), which keeps the depth test correct.

use glam::{Mat4, Vec3, Vec4};

use crate::raster::Framebuffer;
use crate::scene::Camera;

/// A rendered planar reflection and how to read it. Built by the renderer each frame when the
/// scene has terrain above the water and the eye is above the water.
pub struct ReflectionMap<'a> {
    /// The mirrored terrain: linear RGB where `depth < 1`, nothing (sky) where `depth == 1`.
    image: &'a Framebuffer,
    clip_from_world: Mat4,
    eye: Vec3,
    forward: Vec3,
    /// Camera right, scaled by `tan(fov_y / 2) * aspect`: a ray through NDC x moves by x of it.
    right: Vec3,
    /// Camera up, scaled by `tan(fov_y / 2)`.
    up: Vec3,
    /// `k` of the oblique depth `z = k h − w`.
    depth_scale: f32,
}

impl<'a> ReflectionMap<'a> {
    /// The oblique depth scale `k` for `camera` and `aspect` = width / height.
    ///
    /// A visible mirrored point at depth h below the mirror lies at least `eye.y + h` from the eye
    /// and within the angle θ of the frustum's corner from the view axis, so `w >= (eye.y + h)
    /// cos θ` and `h / w < 1 / cos θ`; `k = 2 cos θ` (less a margin) keeps window depth
    /// `k h / 2w` below 1 for everything on screen, so the far plane clips nothing visible.
    pub fn depth_scale(camera: &Camera, aspect: f32) -> f32 {
        let t = (0.5 * camera.fov_y_deg.to_radians()).tan();
        let cos_corner = 1.0 / (1.0 + t * t * (1.0 + aspect * aspect)).sqrt();
        2.0 * 0.99 * cos_corner
    }

    /// Clip-space position of world point `p` mirrored about y = 0, with the oblique near plane
    /// at the water for `depth_scale` ([`ReflectionMap::depth_scale`]).
    pub fn mirrored_clip(clip_from_world: &Mat4, depth_scale: f32, p: Vec3) -> Vec4 {
        let mut c = *clip_from_world * Vec4::new(p.x, -p.y, p.z, 1.0);
        c.z = depth_scale * p.y - c.w;
        c
    }

    /// Reads `image`, rendered with [`ReflectionMap::mirrored_clip`] for `camera`'s
    /// `clip_from_world` at `image`'s aspect ratio. The eye must be above the water (y > 0).
    pub fn new(image: &'a Framebuffer, camera: &Camera, clip_from_world: Mat4) -> Self {
        let aspect = image.width() as f32 / image.height() as f32;
        let forward = (camera.target - camera.eye).normalize();
        let right = forward.cross(camera.up).normalize();
        let up = right.cross(forward);
        let t = (0.5 * camera.fov_y_deg.to_radians()).tan();
        Self {
            image,
            clip_from_world,
            eye: camera.eye,
            forward,
            right: right * t * aspect,
            up: up * t,
            depth_scale: Self::depth_scale(camera, aspect),
        }
    }

    /// Linear RGB of the mirrored terrain seen from water point `p` (world m) along the unit
    /// reflected ray `r` (pointing up, `r.y > 0`), or `None` where the ray sees the sky.
    pub fn sample(&self, p: Vec3, r: Vec3) -> Option<Vec3> {
        // Behind the mirror, the reflected ray continues as the mirrored ray from the mirrored point.
        let pm = Vec3::new(p.x, -p.y, p.z);
        let rm = Vec3::new(r.x, -r.y, r.z);
        // How far the untilted ray travels behind the mirror before it meets the terrain.
        let behind = self.mirrored_point(self.pixel_of(pm)?)?.distance(pm);
        let i = self.pixel_of(pm + rm * behind)?;
        (self.image.depth[i] < 1.0).then(|| self.image.color[i])
    }

    /// Index of the pixel world point `q` projects into, `None` off screen or behind the eye.
    fn pixel_of(&self, q: Vec3) -> Option<usize> {
        let c = self.clip_from_world * Vec4::from((q, 1.0));
        if c.w <= 0.0 {
            return None;
        }
        let (w, h) = (self.image.width() as f32, self.image.height() as f32);
        let x = (0.5 * c.x / c.w + 0.5) * w;
        let y = (0.5 - 0.5 * c.y / c.w) * h;
        // The negated comparisons also reject NaN.
        if !(x >= 0.0 && x < w && y >= 0.0 && y < h) {
            return None;
        }
        Some(y as usize * self.image.width() as usize + x as usize)
    }

    /// The mirrored-world point drawn at pixel `i`, recovered from its oblique depth, or `None`
    /// where the pixel shows no terrain.
    fn mirrored_point(&self, i: usize) -> Option<Vec3> {
        let depth = self.image.depth[i];
        if depth >= 1.0 {
            return None;
        }
        let width = self.image.width() as usize;
        let (px, py) = ((i % width) as f32 + 0.5, (i / width) as f32 + 0.5);
        let ndc_x = 2.0 * px / width as f32 - 1.0;
        let ndc_y = 1.0 - 2.0 * py / self.image.height() as f32;
        // q = eye + s d has view depth w = s (d's forward component is 1) and height below the
        // mirror h = −(eye.y + s d.y); depth = k h / 2s solves for s.
        let d = self.forward + self.right * ndc_x + self.up * ndc_y;
        let k = self.depth_scale;
        let s = -k * self.eye.y / (2.0 * depth + k * d.y);
        (s > 0.0 && s.is_finite()).then(|| self.eye + d * s)
    }
}
