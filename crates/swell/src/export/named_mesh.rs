//! What the mesh writers take: a list of named triangle meshes, borrowed from a [`World`].
//!
//! ```
//! use swell::export::{world_meshes, write_glb, write_obj};
//! use swell::scene::preset;
//! use swell::world::World;
//!
//! let mut world = World::new(preset("sea")?)?;
//! world.advance(2.5)?; // the models only: an export samples the patch, it draws nothing
//! let patch = world.patch_mesh()?;
//! let dir = tempfile::tempdir().unwrap();
//! let aspect = world.scene.render.width as f32 / world.scene.render.height as f32;
//! let meshes = world_meshes(&world, patch.as_ref());
//! write_glb(&dir.path().join("sea.glb"), &meshes, &world.scene.camera, aspect)?;
//! write_obj(&dir.path().join("sea.obj"), &meshes)?;
//! # Ok::<(), swell::Error>(())
//! ```

use glam::{Vec2, Vec3};

use crate::mesh::SurfaceMesh;
use crate::world::World;

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

/// The meshes of `world` in a fixed order: the water's patch `water` (sampled by
/// [`World::patch_mesh`] or [`World::sample_patch`]; exports write the finite patch whatever the
/// scene draws), then any other surfaces the scene has.
pub fn world_meshes<'a>(world: &'a World, water: Option<&'a SurfaceMesh>) -> Vec<NamedMesh<'a>> {
    let mut meshes = Vec::new();
    if let (Some(w), Some(m)) = (&world.water, water) {
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
