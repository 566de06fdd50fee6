//! Reading triangle meshes from Wavefront OBJ text (`v`, `vn`, `f`; everything else is skipped).

use std::collections::HashMap;

use glam::Vec3;

use crate::error::{Error, Result};

/// An indexed triangle mesh with one normal per vertex, as read from an OBJ file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    /// Vertex positions (the file's units).
    pub positions: Vec<Vec3>,
    /// Unit normal per vertex: the file's `vn` where faces give one, otherwise the area-weighted
    /// mean of the faces around the position.
    pub normals: Vec<Vec3>,
    /// Three vertex indices per triangle, in the file's winding.
    pub indices: Vec<u32>,
}

/// Most bytes of OBJ text read: 256 MiB (about 8 M triangles written plainly).
///
/// Parsing holds at most about 8 bytes per byte of text (a corner `1 ` is 2 bytes and costs a
/// 4-byte index per fan triangle, a `v` line of 8 bytes costs 12 + 24 bytes plus its hash entry),
/// so this bounds the reader at about 2 GiB, within [`crate::limits::MEMORY_BUDGET_BYTES`].
pub const MAX_OBJ_BYTES: u64 = 256 << 20;

/// Most vertices (distinct position/normal pairs) of a mesh read from OBJ: 16 M.
pub const MAX_OBJ_VERTICES: usize = 16 << 20;

/// Most triangles of a mesh read from OBJ (after splitting polygons into fans): 32 M.
pub const MAX_OBJ_TRIANGLES: usize = 32 << 20;

/// Parses OBJ text; `source` names the file in errors.
///
/// Faces may be `f v`, `f v/vt`, `f v//vn` or `f v/vt/vn`, with 1-based or negative (relative)
/// indices; polygons are split into fans. A vertex is each distinct (position, normal) pair. An
/// index outside the vertices read so far, a malformed number or a face of fewer than three
/// vertices is an error naming the line. Text over [`MAX_OBJ_BYTES`], or a mesh over
/// [`MAX_OBJ_VERTICES`] or [`MAX_OBJ_TRIANGLES`], is refused naming the limit.
pub fn parse_obj(text: &str, source: &str) -> Result<TriangleMesh> {
    if text.len() as u64 > MAX_OBJ_BYTES {
        return Err(Error::Parse {
            path: source.to_string(),
            message: format!("{} bytes is over the OBJ limit of {MAX_OBJ_BYTES} bytes (MAX_OBJ_BYTES)", text.len()),
        });
    }
    let mut v: Vec<Vec3> = Vec::new();
    let mut vn: Vec<Vec3> = Vec::new();
    let mut mesh = TriangleMesh::default();
    let mut without_normal: Vec<bool> = Vec::new();
    let mut seen: HashMap<(u32, u32), u32> = HashMap::new();
    for (line_no, line) in text.lines().enumerate() {
        let err =
            |msg: String| Error::Parse { path: source.to_string(), message: format!("line {}: {msg}", line_no + 1) };
        let line = line.split('#').next().unwrap_or("");
        let mut words = line.split_whitespace();
        let Some(kind) = words.next() else { continue };
        match kind {
            "v" | "vn" => {
                let xyz: Vec<f32> = words
                    .take(3)
                    .map(str::parse)
                    .collect::<std::result::Result<_, _>>()
                    .map_err(|e| err(format!("{e} in `{}`", line.trim())))?;
                if xyz.len() != 3 || xyz.iter().any(|c| !c.is_finite()) {
                    return Err(err(format!("`{}` needs three finite numbers", line.trim())));
                }
                let p = Vec3::new(xyz[0], xyz[1], xyz[2]);
                if kind == "v" {
                    v.push(p)
                } else {
                    vn.push(p.normalize_or(Vec3::Y))
                }
            }
            "f" => {
                let mut corners = Vec::new();
                for word in words {
                    let mut parts = word.split('/');
                    let resolve = |s: Option<&str>, len: usize, what: &str| -> Result<Option<u32>> {
                        let Some(s) = s.filter(|s| !s.is_empty()) else { return Ok(None) };
                        let i: i64 = s.parse().map_err(|_| err(format!("`{s}` is not a {what} index")))?;
                        let k = if i > 0 { i - 1 } else { len as i64 + i };
                        if i == 0 || k < 0 || k >= len as i64 {
                            return Err(err(format!("{what} index {i} is outside [1, {len}] (or [-{len}, -1])")));
                        }
                        Ok(Some(k as u32))
                    };
                    let p = resolve(parts.next(), v.len(), "vertex")?
                        .ok_or_else(|| err(format!("`{word}` has no vertex index")))?;
                    let _uv = parts.next();
                    let n = resolve(parts.next(), vn.len(), "normal")?;
                    let key = (p, n.unwrap_or(u32::MAX));
                    let index = *seen.entry(key).or_insert_with(|| {
                        mesh.positions.push(v[p as usize]);
                        mesh.normals.push(n.map_or(Vec3::ZERO, |n| vn[n as usize]));
                        without_normal.push(n.is_none());
                        (mesh.positions.len() - 1) as u32
                    });
                    corners.push(index);
                }
                if corners.len() < 3 {
                    return Err(err(format!("a face needs at least 3 vertices, found {}", corners.len())));
                }
                if mesh.positions.len() > MAX_OBJ_VERTICES {
                    return Err(err(format!("over the limit of {MAX_OBJ_VERTICES} vertices (MAX_OBJ_VERTICES)")));
                }
                if mesh.indices.len() / 3 + corners.len() - 2 > MAX_OBJ_TRIANGLES {
                    return Err(err(format!("over the limit of {MAX_OBJ_TRIANGLES} triangles (MAX_OBJ_TRIANGLES)")));
                }
                for k in 1..corners.len() - 1 {
                    mesh.indices.extend_from_slice(&[corners[0], corners[k], corners[k + 1]]);
                }
            }
            _ => {}
        }
    }
    if mesh.indices.is_empty() {
        // An empty image would look like a renderer bug; say what the file lacks instead.
        return Err(Error::Parse {
            path: source.into(),
            message: format!(
                "no triangles: a mesh needs `v` vertex lines and `f` face lines ({} vertices, 0 faces read)",
                mesh.positions.len()
            ),
        });
    }
    if without_normal.iter().any(|&b| b) {
        fill_missing_normals(&mut mesh, &without_normal);
    }
    Ok(mesh)
}

/// Gives vertices without a file normal the area-weighted mean normal of the faces around their
/// position.
fn fill_missing_normals(mesh: &mut TriangleMesh, missing: &[bool]) {
    let mut sum: HashMap<[u32; 3], Vec3> = HashMap::new();
    let key = |p: Vec3| p.to_array().map(f32::to_bits);
    for t in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[t[k] as usize]);
        // The cross product's length is twice the area: the weighting comes for free.
        let n = (b - a).cross(c - a);
        for p in [a, b, c] {
            *sum.entry(key(p)).or_insert(Vec3::ZERO) += n;
        }
    }
    for (i, &m) in missing.iter().enumerate() {
        if m {
            mesh.normals[i] = sum.get(&key(mesh.positions[i])).copied().unwrap_or(Vec3::Y).normalize_or(Vec3::Y);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_with_and_without_normals_and_polygons() {
        let m = parse_obj(
            "# a square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 2\nf 1//1 2//1 3//1 4//1\nf -4 -2 -1\n",
            "t",
        )
        .unwrap();
        assert_eq!(m.indices.len(), 9);
        assert!(m.normals.iter().all(|n| (*n - Vec3::Z).length() < 1e-6), "{:?}", m.normals);
        assert_eq!(m.positions.len(), 4 + 3);
    }

    #[test]
    fn a_file_without_triangles_is_refused() {
        for text in ["", "v 0 0 0\nv 1 0 0\n", "{\"eye\": [0, 1, 2]}\n"] {
            let e = parse_obj(text, "m.obj").unwrap_err().to_string();
            assert!(e.starts_with("m.obj: no triangles"), "{e}");
        }
    }

    #[test]
    fn bad_indices_and_numbers_are_errors_naming_the_line() {
        let e = parse_obj("v 0 0 0\nv 1 0 0\nf 1 2 3\n", "m.obj").unwrap_err().to_string();
        assert!(e.contains("m.obj") && e.contains("line 3") && e.contains("3 is outside [1, 2]"), "{e}");
        let e = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "m.obj").unwrap_err().to_string();
        assert!(e.contains("0 is outside"), "{e}");
        let e = parse_obj("v 0 x 0\n", "m.obj").unwrap_err().to_string();
        assert!(e.contains("line 1"), "{e}");
        let e = parse_obj("v 0 0 0\nv 1 0 0\nf 1 2\n", "m.obj").unwrap_err().to_string();
        assert!(e.contains("at least 3"), "{e}");
        let e = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", "m.obj").unwrap_err().to_string();
        assert!(e.contains("normal index 1 is outside [1, 0]"), "{e}");
    }
}
