//! The floating bodies as meshes for the mesh writers: each hull flat-shaded (a normal per face,
//! so a crate keeps its edges), in the body's own frame (for a glTF node its pose moves) or
//! placed in the world at its pose (for OBJ and a single frame).

use glam::{Vec2, Vec3};

use super::NamedMesh;
use crate::body::{BodyPose, FloatingBody};
use crate::world::World;

/// One body's triangles, owned (the writers borrow them as a [`NamedMesh`]).
#[derive(Clone, Debug, PartialEq)]
pub struct BodyMesh {
    /// The body's name (`[[body]] name`): the node and material name.
    pub name: String,
    /// Vertex positions, m: three per hull triangle.
    pub positions: Vec<Vec3>,
    /// The triangle's unit normal at each of its vertices.
    pub normals: Vec<Vec3>,
    /// Texture coordinates (all zero: a body has no texture).
    pub uvs: Vec<Vec2>,
    /// 0, 1, 2, ...: the triangles in order.
    pub indices: Vec<u32>,
    /// The body's `color`, linear RGB.
    pub base_color: Vec3,
}

impl BodyMesh {
    /// `body`'s hull in colour `color`, at `pose` in the world, or in the body's frame (centre of
    /// mass at the origin) for `None`.
    pub fn of(body: &FloatingBody, color: Vec3, pose: Option<&BodyPose>) -> Self {
        let (rotation, position) =
            pose.map_or((glam::Quat::IDENTITY, Vec3::ZERO), |p| (p.rotation.as_quat(), p.position.as_vec3()));
        let hull = &body.hull;
        let mut m = BodyMesh {
            name: body.name.clone(),
            positions: Vec::with_capacity(hull.triangles.len() * 3),
            normals: Vec::with_capacity(hull.triangles.len() * 3),
            uvs: vec![Vec2::ZERO; hull.triangles.len() * 3],
            indices: (0..hull.triangles.len() as u32 * 3).collect(),
            base_color: color,
        };
        for t in &hull.triangles {
            let [a, b, c] = t.map(|i| position + rotation * hull.positions[i as usize]);
            let n = (b - a).cross(c - a).normalize_or(Vec3::Y);
            m.positions.extend([a, b, c]);
            m.normals.extend([n; 3]);
        }
        m
    }

    /// The mesh as the writers take it.
    pub fn named(&self) -> NamedMesh<'_> {
        NamedMesh {
            name: &self.name,
            positions: &self.positions,
            normals: &self.normals,
            uvs: &self.uvs,
            indices: &self.indices,
            base_color: self.base_color,
        }
    }
}

/// Every body of `world` in scene order: placed at its pose of the last update when `posed`,
/// else in its own frame.
pub fn body_meshes(world: &World, posed: bool) -> Vec<BodyMesh> {
    let poses = world.body_poses();
    world
        .bodies
        .bodies()
        .iter()
        .zip(&world.scene.bodies)
        .enumerate()
        .map(|(k, (b, spec))| BodyMesh::of(b, spec.color, if posed { poses.get(k) } else { None }))
        .collect()
}
