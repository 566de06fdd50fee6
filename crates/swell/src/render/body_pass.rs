//! Draws the floating bodies at their poses, lit like the terrain (ambient plus Lambert, in the
//! haze), each in its `[[body]] color`. Drawn after the terrain and before the water, so the
//! water's depth test hides what lies under the surface.
//!
//! All bodies go through one shaded draw: the per-vertex attribute the water uses for foam carries
//! each vertex's body index here, constant over a triangle, so one draw colours every body.

use glam::{Vec3, Vec4};

use super::shaded_draw::{ShadedDraw, ShadedMesh, SurfaceShader};
use super::FrameContext;
use crate::body::BodyPose;
use crate::raster::Framebuffer;
use crate::scene::Shading;
use crate::shading::{lambert, Environment, SurfaceVarying};
use crate::world::World;

/// Angle (rad) below which the faces around a hull vertex share its normal: a sphere or a hull's
/// round bilge shades smooth, a box's edges stay sharp.
const SMOOTH_ANGLE_RAD: f32 = 0.6;

/// The bodies' triangles at this frame's poses, kept from frame to frame.
#[derive(Default)]
pub(crate) struct BodyMeshes {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    /// Body index per vertex, as `f32` (the shaded mesh's foam channel).
    body: Vec<f32>,
    indices: Vec<u32>,
    /// Per-hull-vertex normals in the body frame, scratch.
    smooth: Vec<Vec3>,
}

/// Lambert-lit bodies, coloured by the body index the mesh carries.
struct BodyShader<'a> {
    env: &'a Environment<'a>,
    colors: &'a [Vec3],
}

impl SurfaceShader for BodyShader<'_> {
    fn shade(&self, p: &SurfaceVarying) -> Vec3 {
        let k = (p.foam.round().max(0.0) as usize).min(self.colors.len().saturating_sub(1));
        let albedo = self.colors.get(k).copied().unwrap_or(Vec3::splat(0.5));
        self.env.haze(p.position, albedo * lambert(self.env, p.position, p.normal))
    }
}

impl BodyMeshes {
    /// Fills the buffers with every body's hull at `poses`.
    fn build(&mut self, world: &World, poses: &[BodyPose]) {
        self.positions.clear();
        self.normals.clear();
        self.body.clear();
        self.indices.clear();
        for (k, (b, pose)) in world.bodies.bodies().iter().zip(poses).enumerate() {
            let hull = &b.hull;
            let rotation = pose.rotation.as_quat();
            let position = pose.position.as_vec3();
            self.smooth.clear();
            self.smooth.resize(hull.positions.len(), Vec3::ZERO);
            let face = |t: &[u32; 3]| {
                let [a, b, c] = t.map(|i| hull.positions[i as usize]);
                (b - a).cross(c - a)
            };
            for t in &hull.triangles {
                let n = face(t);
                for &i in t {
                    self.smooth[i as usize] += n;
                }
            }
            for t in &hull.triangles {
                let n = face(t).normalize_or(Vec3::Y);
                for &i in t {
                    let s = self.smooth[i as usize].normalize_or(n);
                    let corner = if s.dot(n) > SMOOTH_ANGLE_RAD.cos() { s } else { n };
                    self.indices.push(self.positions.len() as u32);
                    self.positions.push(position + rotation * hull.positions[i as usize]);
                    self.normals.push(rotation * corner);
                    self.body.push(k as f32);
                }
            }
        }
    }
}

/// Draws `world`'s bodies at their poses of the last update into `fb`.
pub(crate) fn draw(
    fb: &mut Framebuffer,
    frame: &FrameContext,
    world: &World,
    meshes: &mut BodyMeshes,
    draw: &mut ShadedDraw,
) {
    let poses = world.body_poses();
    if poses.is_empty() {
        return;
    }
    meshes.build(world, poses);
    let colors: Vec<Vec3> = world.scene.bodies.iter().map(|b| b.color).collect();
    let shader = BodyShader { env: &frame.env, colors: &colors };
    let mesh = ShadedMesh {
        positions: &meshes.positions,
        normals: &meshes.normals,
        foam: Some(&meshes.body),
        unresolved: None,
        indices: &meshes.indices,
    };
    let clip_from_world = frame.clip_from_world;
    draw.draw(fb, mesh, &|p| clip_from_world * Vec4::from((p, 1.0)), Shading::Gouraud, &shader);
}
