//! What the mesh writers take: a list of named triangle meshes, borrowed from a [`World`].
//!
//! ```
//! use swell::export::{world_meshes, write_glb, write_obj};
//! use swell::scene::{preset, World};
//!
//! let mut world = World::new(preset("sea")?)?;
//! world.update(2.5)?;
//! let dir = tempfile::tempdir().unwrap();
//! let aspect = world.scene.render.width as f32 / world.scene.render.height as f32;
//! write_glb(&dir.path().join("sea.glb"), &world_meshes(&world), &world.scene.camera, aspect)?;
//! write_obj(&dir.path().join("sea.obj"), &world_meshes(&world))?;
//! # Ok::<(), swell::Error>(())
//! ```

use glam::{Vec2, Vec3};

use crate::scene::World;

/// One triangle mesh to export, borrowed from wherever it lives.
///
/// Positions are world metres (+Y up), normals unit length, uv in [0, 1]^2 with v along +Z (so v = 0
/// is the first image row, as in glTF), and `indices` a triangle list winding counter-clockwise seen
/// from the side the normals point to.
#[derive(Clone, Copy, Debug)]
pub struct NamedMesh<'a> {
    /// Object / node name in the file (`water`, `terrain`).
    pub name: &'a str,
    /// Vertex positions, metres.
    pub positions: &'a [Vec3],
    /// Unit normals, one per vertex.
    pub normals: &'a [Vec3],
    /// Texture coordinates, one per vertex.
    pub uvs: &'a [Vec2],
    /// Triangle list, three indices per triangle, each `< positions.len()`.
    pub indices: &'a [u32],
    /// Linear RGB base colour, components in [0, 1]; becomes the glTF material's `baseColorFactor`.
    pub base_color: Vec3,
}

/// The meshes of `world` at the time of its last [`World::update`], in a fixed order: the water
/// surface (named `water`), then any other surfaces the scene has.
pub fn world_meshes(world: &World) -> Vec<NamedMesh<'_>> {
    let mut meshes = Vec::new();
    if let Some(w) = &world.water {
        let m = &w.mesh;
        meshes.push(NamedMesh {
            name: "water",
            positions: &m.positions,
            normals: &m.normals,
            uvs: &m.uvs,
            indices: &m.indices,
            base_color: w.material.color,
        });
    }
    if let Some(t) = &world.terrain {
        let m = &t.mesh;
        meshes.push(NamedMesh {
            name: "terrain",
            positions: &m.positions,
            normals: &m.normals,
            uvs: &m.uvs,
            indices: &m.indices,
            base_color: t.material.sand,
        });
    }
    meshes
}
