//! The mesh-and-camera mode: one triangle mesh, one directional light, no sky or water, lit the way
//! OpenGL's fixed-function pipeline lights a diffuse surface, so that swell's rasterizer can be
//! compared with an OpenGL renderer image for image and time for time.

use glam::{Vec3, Vec4};

use super::shaded_draw::{ShadedDraw, ShadedMesh, SurfaceShader};
use crate::error::{check_finite_vec, check_non_negative, Error, Result};
use crate::mesh::TriangleMesh;
use crate::raster::Framebuffer;
use crate::scene::{Camera, Shading};
use crate::shading::SurfaceVarying;

/// A directional light and a diffuse material: `base * (ambient + color * max(0, N.L))`,
/// `L = -dir` (colours linear).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshLight {
    /// Direction in which the light travels (any non-zero length).
    pub dir: Vec3,
    /// Light colour, linear RGB >= 0.
    pub color: Vec3,
    /// Ambient term, linear RGB >= 0.
    pub ambient: Vec3,
    /// Surface colour, linear RGB >= 0.
    pub base_color: Vec3,
    /// Colour of pixels no triangle covers, linear RGB >= 0.
    pub background: Vec3,
}

impl Default for MeshLight {
    /// Light from above and behind the viewer's right shoulder, white on light grey.
    fn default() -> Self {
        Self {
            dir: Vec3::new(-0.4, -1.0, -0.6),
            color: Vec3::splat(0.8),
            ambient: Vec3::splat(0.2),
            base_color: Vec3::splat(0.8),
            background: Vec3::ZERO,
        }
    }
}

impl MeshLight {
    /// Checks every field, naming keys under `key`.
    pub fn validate(&self, key: &str) -> Result<()> {
        check_finite_vec(&format!("{key}.dir"), &self.dir.to_array())?;
        if self.dir.length() < 1e-6 {
            return Err(Error::invalid(format!("{key}.dir"), "must be non-zero"));
        }
        for (name, c) in [
            ("color", self.color),
            ("ambient", self.ambient),
            ("base_color", self.base_color),
            ("background", self.background),
        ] {
            for (i, v) in c.to_array().into_iter().enumerate() {
                check_non_negative(&format!("{key}.{name}[{i}]"), v)?;
            }
        }
        Ok(())
    }
}

/// [`MeshLight`] as a surface shader, with the unit vector towards the light worked out once.
struct MeshLightShader<'a> {
    light: &'a MeshLight,
    to_light: Vec3,
}

impl SurfaceShader for MeshLightShader<'_> {
    fn shade(&self, p: &SurfaceVarying) -> Vec3 {
        let light = self.light;
        light.base_color * (light.ambient + light.color * p.normal.dot(self.to_light).max(0.0))
    }
}

/// Renders [`TriangleMesh`]es, keeping its buffers between calls (no allocation once warm).
#[derive(Default)]
pub struct MeshRenderer {
    framebuffer: Option<Framebuffer>,
    draw: ShadedDraw,
}

impl MeshRenderer {
    /// A renderer with no buffers yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Draws `mesh` seen by `camera` into a `width` x `height` image (each in [1,
    /// [`crate::scene::MAX_IMAGE_SIDE`]], the caller's to check) with a depth test and no culling.
    ///
    /// `Flat` lights each triangle with its geometric normal, `Gouraud` each vertex with its
    /// normal, `Phong` and `BlinnPhong` each pixel with the interpolated normal (the light model
    /// has no specular term, so the two agree).
    pub fn render(
        &mut self,
        mesh: &TriangleMesh,
        camera: &Camera,
        width: u32,
        height: u32,
        light: &MeshLight,
        shading: Shading,
    ) -> &Framebuffer {
        let fb = self.framebuffer.get_or_insert_with(|| Framebuffer::new(width, height));
        if (fb.width(), fb.height()) != (width, height) {
            fb.resize(width, height);
        }
        let background = light.background;
        fb.clear_with(|_, _| background);
        let clip_from_world = camera.clip_from_world(width as f32 / height as f32);
        let shader = MeshLightShader { light, to_light: -light.dir.normalize() };
        self.draw.draw(
            fb,
            ShadedMesh::plain(&mesh.positions, &mesh.normals, &mesh.indices),
            &|p| clip_from_world * Vec4::from((p, 1.0)),
            shading,
            &shader,
        );
        fb
    }
}
