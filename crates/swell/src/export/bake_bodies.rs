//! The floating bodies' poses in a bake (issue 34): `bodies_NNNN.json` per frame, checked and
//! resumed like the frame's maps, and `bodies.json`, every baked frame's poses per body, gathered
//! from them at the end of each run.
//!
//! Per-frame files make `--frames`, `--shard` and `--resume` work for poses exactly as for maps:
//! a frame's poses are written with its maps and named in its record, so a damaged one is baked
//! again, and shards never write the same file. `bodies.json` is then rebuilt from whatever frames
//! the directory holds, so the last shard to finish (or a `--resume` with nothing left to bake)
//! leaves it complete.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::write_atomically;
use crate::body::BodyPose;
use crate::error::{Error, Result};

/// Name of the gathered poses file in a bake directory.
pub const BODIES_JSON: &str = "bodies.json";

/// One body at one frame: centre of mass (world m) and orientation (unit quaternion x, y, z, w).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BodyFramePose {
    /// The frame number.
    pub frame: u32,
    /// Its time, s (`frame / fps`).
    pub t: f64,
    /// Centre of mass, world metres.
    pub position: [f64; 3],
    /// Rotation from the body's frame to the world, quaternion [x, y, z, w].
    pub rotation: [f64; 4],
}

/// One body's frames in `bodies.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BakedBody {
    /// The body's name (`[[body]] name`).
    pub name: String,
    /// Every baked frame, in order.
    pub frames: Vec<BodyFramePose>,
}

/// `bodies.json`: `{"bodies": [{"name": ..., "frames": [{"frame", "t", "position", "rotation"}]}]}`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BakedBodies {
    /// The bodies in the scene's order.
    pub bodies: Vec<BakedBody>,
}

/// One frame's file, `bodies_NNNN.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct FramePoses {
    frame: u32,
    t: f64,
    /// (name, pose) in the scene's order.
    bodies: Vec<NamedPose>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct NamedPose {
    name: String,
    position: [f64; 3],
    rotation: [f64; 4],
}

/// The file name of `frame`'s poses: `bodies_0042.json`.
pub(crate) fn frame_file_name(frame: u32) -> String {
    format!("bodies_{frame:04}.json")
}

/// Whether `name` is a per-frame poses file's name.
pub(crate) fn is_frame_file_name(name: &str) -> bool {
    name.strip_prefix("bodies_")
        .and_then(|r| r.strip_suffix(".json"))
        .is_some_and(|d| d.len() >= 4 && d.bytes().all(|c| c.is_ascii_digit()))
}

/// Writes `frame`'s poses (`names` and `poses` in the scene's order) to `dir`, atomically.
pub(crate) fn write_frame(dir: &Path, frame: u32, t: f64, names: &[String], poses: &[BodyPose]) -> Result<()> {
    let file = FramePoses {
        frame,
        t,
        bodies: names
            .iter()
            .zip(poses)
            .map(|(n, p)| NamedPose {
                name: n.clone(),
                position: p.position.to_array(),
                rotation: p.rotation.to_array(),
            })
            .collect(),
    };
    let path = dir.join(frame_file_name(frame));
    let json = serde_json::to_vec(&file).expect("poses serialise to JSON");
    write_atomically(&path, |out| out.write_all(&json).map_err(|e| Error::io(&path, e)))
}

/// Gathers every `bodies_NNNN.json` of `frames` in `dir` into `dir/bodies.json`, atomically;
/// `names` are the scene's bodies. A frame file that does not parse is an error naming it (the
/// run that wrote it checked it, so it was damaged since: `--resume` bakes it again).
pub(crate) fn gather(dir: &Path, frames: impl Iterator<Item = u32>, names: &[String]) -> Result<BakedBodies> {
    let mut out =
        BakedBodies { bodies: names.iter().map(|n| BakedBody { name: n.clone(), frames: Vec::new() }).collect() };
    for frame in frames {
        let path = dir.join(frame_file_name(frame));
        let bytes = match std::fs::read(&path) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => continue,
            Err(e) => return Err(Error::io(&path, e)),
        };
        let poses: FramePoses = serde_json::from_slice(&bytes).map_err(|e| Error::Parse {
            path: path.display().to_string(),
            message: format!("{e}; bake again with --resume to rewrite it"),
        })?;
        for (body, p) in out.bodies.iter_mut().zip(poses.bodies) {
            body.frames.push(BodyFramePose {
                frame: poses.frame,
                t: poses.t,
                position: p.position,
                rotation: p.rotation,
            });
        }
    }
    let path = dir.join(BODIES_JSON);
    let json = serde_json::to_vec_pretty(&out).expect("poses serialise to JSON");
    write_atomically(&path, |o| o.write_all(&json).map_err(|e| Error::io(&path, e)))?;
    Ok(out)
}
