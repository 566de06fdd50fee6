//! Surface meshes: the regular triangle grid that wave models displace, the camera-following rings
//! of an unbounded sea, the one of them a frame draws, and triangle meshes read from OBJ files.

mod clipmap;
mod drawn_surface;
mod obj;
mod surface_mesh;

pub use clipmap::Clipmap;
pub use drawn_surface::DrawnSurface;
pub use obj::{parse_obj, TriangleMesh, MAX_OBJ_BYTES, MAX_OBJ_TRIANGLES, MAX_OBJ_VERTICES};
pub use surface_mesh::SurfaceMesh;
