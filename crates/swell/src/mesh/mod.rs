//! Surface meshes: the regular triangle grid that wave models displace and the renderer draws.

mod surface_mesh;

pub use surface_mesh::SurfaceMesh;
