//! Wavefront OBJ meshes: plain text every 3-D tool reads.
//!
//! Each [`NamedMesh`] becomes an object (`o name`) with `v`, `vt`, `vn` and `f v/vt/vn` lines;
//! indices are 1-based and global across objects, as the format requires. Floats are written in
//! Rust's shortest round-trip form, so a reader gets back exactly the `f32` values we had.
//! OBJ puts the texture origin at the bottom-left of an image, glTF and swell at the top-left, so
//! `vt` is written as `(u, 1 - v)`: an image mapped onto the OBJ lands where it lands on the glTF.

use std::io::Write;
use std::path::Path;

use super::{write_atomically, NamedMesh};
use crate::error::{Error, Result};

/// Writes `meshes` to `path` as OBJ, atomically.
pub fn write_obj(path: &Path, meshes: &[NamedMesh]) -> Result<()> {
    write_atomically(path, |out| encode_obj(out, meshes).map_err(|e| Error::io(path, e)))
}

/// Writes `meshes` as OBJ text to `out`.
pub fn encode_obj(out: &mut dyn Write, meshes: &[NamedMesh]) -> std::io::Result<()> {
    writeln!(out, "# swell {}: metres, +Y up, right-handed", env!("CARGO_PKG_VERSION"))?;
    let mut base = 1u64;
    for m in meshes {
        debug_assert!(m.normals.len() == m.positions.len() && m.uvs.len() == m.positions.len());
        writeln!(out, "o {}", m.name)?;
        for p in m.positions {
            writeln!(out, "v {} {} {}", p.x, p.y, p.z)?;
        }
        for t in m.uvs {
            writeln!(out, "vt {} {}", t.x, 1.0 - t.y)?;
        }
        for n in m.normals {
            writeln!(out, "vn {} {} {}", n.x, n.y, n.z)?;
        }
        for tri in m.indices.chunks_exact(3) {
            let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| base + u64::from(i));
            writeln!(out, "f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}")?;
        }
        base += m.positions.len() as u64;
    }
    Ok(())
}
