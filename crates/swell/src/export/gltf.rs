//! glTF 2.0 meshes and camera, as a `.gltf` JSON file with a `.bin` buffer beside it, or as one
//! binary `.glb` (Khronos glTF 2.0 specification, sections 3.6 "Binary data storage", 3.10
//! "Cameras", 4.4 "GLB file format").
//!
//! glTF's own conventions are swell's: metres, +Y up, right-handed, counter-clockwise front faces,
//! the texture origin at the top-left (uv v = 0 is the first image row), cameras looking down their
//! node's −Z with +Y up. So vertices go out unchanged, and the camera node's rotation is the
//! inverse of the scene camera's look-at.
//!
//! Layout: one buffer; per mesh four tightly packed buffer views (positions, normals, uv as `f32`,
//! indices as `u32`), one accessor each, one node each, one material each (its base colour); then a
//! node named `camera` holding the scene's perspective camera. With a [`NodeAnimation`] (the
//! floating bodies' motion), its tracks move mesh nodes: one time accessor shared by every
//! sampler, a translation and a rotation accessor per node, LINEAR samplers (glTF 2.0 section 3.11
//! "Animations": rotations interpolate by slerp).

use std::path::Path;

use glam::{Quat, Vec2, Vec3};
use serde_json::{json, Value};

use super::{write_atomically, NamedMesh};
use crate::error::{Error, Result};
use crate::scene::Camera;

/// glTF `componentType` of `f32` (Khronos glTF 2.0, table "Accessor component types").
const FLOAT: u32 = 5126;
/// glTF `componentType` of `u32`.
const UNSIGNED_INT: u32 = 5125;
/// Buffer-view target of vertex attributes (`ARRAY_BUFFER`).
const ARRAY_BUFFER: u32 = 34962;
/// Buffer-view target of indices (`ELEMENT_ARRAY_BUFFER`).
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
/// Primitive mode: a triangle list.
const TRIANGLES: u32 = 4;

/// Magic number of a GLB file ("glTF" in ASCII, little endian).
const GLB_MAGIC: u32 = 0x4654_6C67;
/// GLB chunk type of the JSON chunk ("JSON").
const GLB_JSON: u32 = 0x4E4F_534A;
/// GLB chunk type of the binary chunk ("BIN\0").
const GLB_BIN: u32 = 0x004E_4942;

/// The motion of some mesh nodes, sampled at shared times: what `swell export --frames` writes
/// for the floating bodies (their meshes in their own frame, moved by their poses).
#[derive(Clone, Copy, Debug)]
pub struct NodeAnimation<'a> {
    /// The animation's name.
    pub name: &'a str,
    /// Sample times, s, increasing (at least one).
    pub times: &'a [f32],
    /// One track per animated mesh.
    pub tracks: &'a [NodeTrack<'a>],
}

/// One mesh node's samples: its translation (m) and rotation (unit quaternion) at each time.
#[derive(Clone, Copy, Debug)]
pub struct NodeTrack<'a> {
    /// Index of the mesh (in the meshes written) whose node moves.
    pub mesh: usize,
    /// Translation at each time, m.
    pub translations: &'a [Vec3],
    /// Rotation at each time.
    pub rotations: &'a [Quat],
}

/// Writes `meshes` and `camera` (for images of `aspect` = width / height) as `path` (`.gltf`) plus
/// its buffer `path` with extension `.bin`, both atomically, the buffer first.
pub fn write_gltf(path: &Path, meshes: &[NamedMesh], camera: &Camera, aspect: f32) -> Result<()> {
    write_gltf_animated(path, meshes, camera, aspect, None)
}

/// [`write_gltf`] with an optional node animation.
pub fn write_gltf_animated(
    path: &Path,
    meshes: &[NamedMesh],
    camera: &Camera,
    aspect: f32,
    animation: Option<&NodeAnimation>,
) -> Result<()> {
    let bin_path = path.with_extension("bin");
    let bin_name = bin_path.file_name().and_then(|n| n.to_str()).ok_or_else(|| {
        Error::invalid("--out", format!("{} needs a UTF-8 file name for its .bin buffer", path.display()))
    })?;
    let (doc, bin) = gltf_document_animated(meshes, camera, aspect, Some(&uri_escape(bin_name)), animation)?;
    write_atomically(&bin_path, |out| out.write_all(&bin).map_err(|e| Error::io(&bin_path, e)))?;
    let text = serde_json::to_vec_pretty(&doc).expect("a JSON value always serialises");
    write_atomically(path, |out| out.write_all(&text).map_err(|e| Error::io(path, e)))
}

/// Writes `meshes` and `camera` as one binary glTF (`.glb`) file, atomically.
pub fn write_glb(path: &Path, meshes: &[NamedMesh], camera: &Camera, aspect: f32) -> Result<()> {
    write_glb_animated(path, meshes, camera, aspect, None)
}

/// [`write_glb`] with an optional node animation.
pub fn write_glb_animated(
    path: &Path,
    meshes: &[NamedMesh],
    camera: &Camera,
    aspect: f32,
    animation: Option<&NodeAnimation>,
) -> Result<()> {
    let (doc, bin) = gltf_document_animated(meshes, camera, aspect, None, animation)?;
    let mut json = serde_json::to_vec(&doc).expect("a JSON value always serialises");
    // Chunks are 4-byte aligned: JSON padded with spaces, binary with zeros (GLB spec 4.4.3).
    json.resize(json.len().next_multiple_of(4), b' ');
    let mut bin = bin;
    bin.resize(bin.len().next_multiple_of(4), 0);
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let total = u32::try_from(total)
        .map_err(|_| Error::invalid("--out", format!("{} would exceed the 4 GiB a GLB can hold", path.display())))?;
    write_atomically(path, |out| {
        let mut put = |bytes: &[u8]| out.write_all(bytes).map_err(|e| Error::io(path, e));
        put(&GLB_MAGIC.to_le_bytes())?;
        put(&2u32.to_le_bytes())?;
        put(&total.to_le_bytes())?;
        put(&(json.len() as u32).to_le_bytes())?;
        put(&GLB_JSON.to_le_bytes())?;
        put(&json)?;
        put(&(bin.len() as u32).to_le_bytes())?;
        put(&GLB_BIN.to_le_bytes())?;
        put(&bin)
    })
}

/// The glTF JSON document and its binary buffer. `buffer_uri` is the buffer's file name for a
/// `.gltf`, or `None` for a GLB (whose buffer is the file's binary chunk).
pub fn gltf_document(
    meshes: &[NamedMesh],
    camera: &Camera,
    aspect: f32,
    buffer_uri: Option<&str>,
) -> Result<(Value, Vec<u8>)> {
    gltf_document_animated(meshes, camera, aspect, buffer_uri, None)
}

/// [`gltf_document`] with an optional node animation, checked first: tracks naming meshes that
/// exist, as many samples as times, finite values, increasing times.
pub fn gltf_document_animated(
    meshes: &[NamedMesh],
    camera: &Camera,
    aspect: f32,
    buffer_uri: Option<&str>,
    animation: Option<&NodeAnimation>,
) -> Result<(Value, Vec<u8>)> {
    if let Some(a) = animation {
        check_animation(a, meshes.len())?;
    }
    let mut bin = Vec::new();
    let (mut views, mut accessors, mut gltf_meshes, mut nodes, mut materials) =
        (vec![], vec![], vec![], vec![], vec![]);
    for (k, m) in meshes.iter().enumerate() {
        check_mesh(m)?;
        let n = m.positions.len();
        let (lo, hi) = bounds(m.positions);
        let mut attribute = |bytes: &[u8], count: usize, kind: &str, target: u32, ctype: u32| {
            views.push(json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len(), "target": target}));
            bin.extend_from_slice(bytes);
            accessors
                .push(json!({"bufferView": views.len() - 1, "componentType": ctype, "count": count, "type": kind}));
            accessors.len() - 1
        };
        let pos = attribute(&vec3_bytes(m.positions), n, "VEC3", ARRAY_BUFFER, FLOAT);
        let nrm = attribute(&vec3_bytes(m.normals), n, "VEC3", ARRAY_BUFFER, FLOAT);
        let uv = attribute(&vec2_bytes(m.uvs), n, "VEC2", ARRAY_BUFFER, FLOAT);
        let idx_bytes: Vec<u8> = m.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let idx = attribute(&idx_bytes, m.indices.len(), "SCALAR", ELEMENT_ARRAY_BUFFER, UNSIGNED_INT);
        accessors[pos]["min"] = json!(lo.to_array());
        accessors[pos]["max"] = json!(hi.to_array());
        let c = m.base_color;
        materials.push(json!({
            "name": m.name,
            "pbrMetallicRoughness": {"baseColorFactor": [c.x, c.y, c.z, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.1},
            "doubleSided": true
        }));
        gltf_meshes.push(json!({
            "name": m.name,
            "primitives": [{
                "attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv},
                "indices": idx, "mode": TRIANGLES, "material": k
            }]
        }));
        nodes.push(json!({"name": m.name, "mesh": k}));
    }
    let mut animations = Vec::new();
    if let Some(a) = animation {
        // Animation data: buffer views without a target (they are not vertex data).
        let mut data = |bytes: Vec<u8>, count: usize, kind: &str| {
            views.push(json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len()}));
            bin.extend_from_slice(&bytes);
            accessors
                .push(json!({"bufferView": views.len() - 1, "componentType": FLOAT, "count": count, "type": kind}));
            accessors.len() - 1
        };
        let n = a.times.len();
        let input = data(a.times.iter().flat_map(|t| t.to_le_bytes()).collect(), n, "SCALAR");
        let outputs: Vec<(usize, usize)> = a
            .tracks
            .iter()
            .map(|tr| {
                let t = data(vec3_bytes(tr.translations), n, "VEC3");
                let r = data(
                    tr.rotations.iter().flat_map(|q| q.to_array()).flat_map(f32::to_le_bytes).collect(),
                    n,
                    "VEC4",
                );
                (t, r)
            })
            .collect();
        accessors[input]["min"] = json!([a.times[0]]);
        accessors[input]["max"] = json!([a.times[n - 1]]);
        let (mut samplers, mut channels) = (vec![], vec![]);
        for (tr, &(t, r)) in a.tracks.iter().zip(&outputs) {
            for (output, path) in [(t, "translation"), (r, "rotation")] {
                samplers.push(json!({"input": input, "output": output, "interpolation": "LINEAR"}));
                channels.push(json!({"sampler": samplers.len() - 1, "target": {"node": tr.mesh, "path": path}}));
            }
            // The node rests at the first sample, for viewers that do not play animations.
            nodes[tr.mesh]["translation"] = json!(tr.translations[0].to_array());
            nodes[tr.mesh]["rotation"] = json!(tr.rotations[0].to_array());
        }
        animations.push(json!({"name": a.name, "samplers": samplers, "channels": channels}));
    }
    // glTF cameras look down their node's -Z with +Y up, exactly OpenGL's view space, so the node's
    // transform is the inverse of the look-at (world_from_view).
    let (_, rotation, translation) = camera.view_from_world().inverse().to_scale_rotation_translation();
    nodes.push(json!({
        "name": "camera", "camera": 0,
        "translation": translation.to_array(), "rotation": rotation.normalize().to_array()
    }));
    let mut buffer = json!({"byteLength": bin.len()});
    if let Some(uri) = buffer_uri {
        buffer["uri"] = json!(uri);
    }
    let mut doc = json!({
        "asset": {"version": "2.0", "generator": concat!("swell ", env!("CARGO_PKG_VERSION"))},
        "scene": 0,
        "scenes": [{"name": "swell", "nodes": (0..nodes.len()).collect::<Vec<_>>()}],
        "nodes": nodes,
        "cameras": [{"name": "camera", "type": "perspective", "perspective": {
            "yfov": camera.fov_y_deg.to_radians(), "aspectRatio": aspect, "znear": camera.near, "zfar": camera.far
        }}],
    });
    if !gltf_meshes.is_empty() {
        doc["meshes"] = json!(gltf_meshes);
        doc["materials"] = json!(materials);
        doc["accessors"] = json!(accessors);
        doc["bufferViews"] = json!(views);
        doc["buffers"] = json!([buffer]);
    }
    if !animations.is_empty() {
        doc["animations"] = json!(animations);
    }
    Ok((doc, bin))
}

/// Refuses an animation glTF cannot hold: no times, times not increasing or not finite, a track
/// naming no mesh, a track with other than one sample per time, or a non-finite sample.
fn check_animation(a: &NodeAnimation, meshes: usize) -> Result<()> {
    let key = format!("animation {}", a.name);
    let increasing = a.times.windows(2).all(|w| w[1] > w[0]);
    if a.times.is_empty() || !increasing || !a.times.iter().all(|t| t.is_finite()) {
        return Err(Error::invalid(key, "needs one or more finite, increasing times"));
    }
    for tr in a.tracks {
        if tr.mesh >= meshes || tr.translations.len() != a.times.len() || tr.rotations.len() != a.times.len() {
            return Err(Error::invalid(
                &key,
                format!("track of mesh {}: one translation and rotation per time", tr.mesh),
            ));
        }
        if !tr.translations.iter().all(|v| v.is_finite()) || !tr.rotations.iter().all(|q| q.is_finite()) {
            return Err(Error::invalid(&key, format!("track of mesh {}: a non-finite sample", tr.mesh)));
        }
    }
    Ok(())
}

/// Refuses meshes glTF cannot hold or that carry NaN.
fn check_mesh(m: &NamedMesh) -> Result<()> {
    let n = m.positions.len();
    let key = format!("{}.vertices", m.name);
    if n == 0 || m.normals.len() != n || m.uvs.len() != n || !m.indices.len().is_multiple_of(3) {
        return Err(Error::invalid(key, "a mesh needs vertices, one normal and uv each, and whole triangles"));
    }
    let finite = |v: &[f32]| v.iter().all(|c| c.is_finite());
    if !m.positions.iter().chain(m.normals).all(|v| finite(&v.to_array()))
        || !m.uvs.iter().all(|t| finite(&t.to_array()))
    {
        return Err(Error::invalid(key, "non-finite position, normal or uv (the simulation diverged)"));
    }
    if m.indices.iter().any(|&i| i as usize >= n) {
        return Err(Error::invalid(key, "an index points past the last vertex"));
    }
    Ok(())
}

/// Component-wise minimum and maximum (glTF requires them on POSITION accessors).
fn bounds(p: &[Vec3]) -> (Vec3, Vec3) {
    p.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)))
}

fn vec3_bytes(v: &[Vec3]) -> Vec<u8> {
    v.iter().flat_map(|p| p.to_array()).flat_map(f32::to_le_bytes).collect()
}

fn vec2_bytes(v: &[Vec2]) -> Vec<u8> {
    v.iter().flat_map(|p| p.to_array()).flat_map(f32::to_le_bytes).collect()
}

/// Percent-encodes what a relative URI may not hold bare (RFC 3986 section 2), so that any file
/// name works as the buffer's `uri`.
fn uri_escape(name: &str) -> String {
    let mut s = String::with_capacity(name.len());
    for b in name.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~".contains(&b) {
            s.push(b as char);
        } else {
            s.push_str(&format!("%{b:02X}"));
        }
    }
    s
}
