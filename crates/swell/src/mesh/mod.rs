//! Surface meshes: the regular triangle grid that wave models displace and the renderer draws, and
//! triangle meshes read from OBJ files.

mod clipmap;
mod obj;
mod surface_mesh;

pub use clipmap::Clipmap;
pub use obj::{parse_obj, TriangleMesh, MAX_OBJ_BYTES, MAX_OBJ_TRIANGLES, MAX_OBJ_VERTICES};
pub use surface_mesh::SurfaceMesh;
