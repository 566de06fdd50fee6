//! `bake.json`: what a bake directory holds and how to read it, written once per bake.

use serde::{Deserialize, Serialize};

use super::{ExrCompression, NormalSpace};

/// The layout version of `bake.json` this swell writes. Version 2 added `manifest_version`,
/// `units`, `normal_space`, `axes` and `foam`; the maps of a version 1 bake are those of a
/// version 2 bake in world normal space.
pub const BAKE_MANIFEST_VERSION: u32 = 2;

/// The manifest of a bake directory, stored as `DIR/bake.json`.
///
/// It holds everything that determines the frames' bytes and nothing else (no dates, no paths), so
/// every shard of a bake writes the same manifest and `--resume` can check it is continuing the
/// same bake.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BakeManifest {
    /// Layout version of this file, [`BAKE_MANIFEST_VERSION`]: readers check it first.
    pub manifest_version: u32,
    /// Version of swell that baked (`CARGO_PKG_VERSION`).
    pub swell_version: String,
    /// Units of every length and time in the bake and its maps.
    pub units: BakeUnits,
    /// swell's axes and how to turn them into other tools' axes.
    pub axes: BakeAxes,
    /// The water model (`water.model` of the scene: `gerstner`, `sines`, ...).
    pub model: String,
    /// The model's and patch's keys from the scene's `[water]` section, as JSON.
    pub model_params: serde_json::Value,
    /// The model's random seed (`water.seed`), if it has one.
    pub seed: Option<u64>,
    /// The sampling grid the maps are pixels of.
    pub grid: BakeGrid,
    /// Frames per second: frame `k` is time `k / fps` seconds.
    pub fps: f64,
    /// First and last frame of the whole bake (inclusive; shards bake subsets of it).
    pub frames: [u32; 2],
    /// Period (s) after which the model repeats exactly, if it has one.
    pub loop_period_s: Option<f64>,
    /// `loop_period_s * fps` when that is a whole number: bake frames `0..loop_frames - 1` for a
    /// seamless loop (frame `loop_frames` equals frame 0).
    pub loop_frames: Option<u64>,
    /// The maps written per frame.
    pub maps: Vec<BakeMap>,
    /// The space of the normal map (`--normal-space`).
    pub normal_space: NormalSpace,
    /// What the foam map means, when there is one.
    pub foam: Option<BakeFoam>,
    /// Compression of the EXR files (all lossless).
    pub exr_compression: ExrCompression,
    /// The PNG versions, if `--png` was given.
    pub png: Option<BakePng>,
    /// The scene's floating bodies (`[[body]]`, as JSON), when it has any: their poses are
    /// written per frame as `bodies_{frame:04}.json` and gathered into `bodies.json`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bodies: Option<serde_json::Value>,
}

/// The grid of a bake: map pixel (i, j) is grid vertex (i, j).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BakeGrid {
    /// Cells along x and z.
    pub cells: [u32; 2],
    /// Map width and height in pixels: vertices along x and z, `cells + 1` (the last column and
    /// row repeat the first ones when the model tiles the patch), or `cells` when `tile`.
    pub pixels: [u32; 2],
    /// Whether the repeated last column and row were left out (`--tile`).
    pub tile: bool,
    /// World (x, z) of pixel (0, 0), metres.
    pub origin_m: [f32; 2],
    /// Patch extent along x and z, metres.
    pub size_m: [f32; 2],
    /// Pixel spacing along x and z, metres.
    pub spacing_m: [f32; 2],
    /// How pixels map to the world, in words.
    pub layout: String,
}

/// One kind of map in the bake.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BakeMap {
    /// Short name: `disp`, `normal` or `foam`.
    pub name: String,
    /// File name pattern, Python-format style: `disp_{frame:04}.exr`.
    pub exr: String,
    /// PNG file name pattern, if PNGs are written.
    pub png: Option<String>,
    /// EXR channels and what each holds.
    pub channels: String,
}

/// How the PNG versions encode the float maps.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BakePng {
    /// Bits per sample: 8 or 16.
    pub bits: u8,
    /// Displacement range R in metres: a component d is stored as `(d / R + 1) / 2` of full scale,
    /// clamped, so `d = (2 * s / max - 1) * R` with `max = 2^bits - 1`.
    pub displacement_range_m: f32,
    /// The encodings, in words.
    pub encoding: String,
}

/// Units of a bake's lengths and times.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BakeUnits {
    /// Unit of displacements, grid positions and sizes: `"metre"`.
    pub length: String,
    /// Unit of times and periods: `"second"`.
    pub time: String,
}

impl BakeUnits {
    /// swell's units: metres and seconds.
    pub fn si() -> Self {
        Self { length: "metre".into(), time: "second".into() }
    }
}

/// A change of axes: `target = matrix * swell` for positions, displacements and world normals.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AxisConversion {
    /// Row-major 3 x 3 matrix (entries -1, 0 or 1) taking swell (x, y, z) to the target's axes.
    pub matrix: [[i8; 3]; 3],
    /// The same in words, e.g. `Blender (X, Y, Z) = swell (x, -z, y)`.
    pub formula: String,
}

/// swell's axes and conversions to the axes of tools that read bakes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BakeAxes {
    /// swell's own convention, in words (right-handed, +Y up, water at rest at y = 0).
    pub swell: String,
    /// To Blender (right-handed, +Z up): a +90 degree rotation about X.
    pub to_blender: AxisConversion,
    /// To glTF 2.0 (right-handed, +Y up, metres): the identity.
    pub to_gltf: AxisConversion,
}

impl BakeAxes {
    /// The conversions swell's axes have.
    pub fn swell() -> Self {
        Self {
            swell: "right-handed, +Y up, metres; water at rest at y = 0; map columns along +X, rows (top to bottom) along +Z"
                .into(),
            to_blender: AxisConversion {
                matrix: [[1, 0, 0], [0, 0, -1], [0, 1, 0]],
                formula: "Blender (X, Y, Z) = swell (x, -z, y): rotate +90 degrees about X (Z up)".into(),
            },
            to_gltf: AxisConversion {
                matrix: [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
                formula: "glTF (x, y, z) = swell (x, y, z): identity (both +Y up, right-handed, metres)".into(),
            },
        }
    }
}

/// What a foam map holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BakeFoam {
    /// The quantity stored: `"coverage"`, the fraction of the surface around a vertex that is foam.
    pub quantity: String,
    /// Range of the stored values: `[0, 1]`.
    pub range: [f32; 2],
    /// How the model makes foam, as a short name (`"jacobian-threshold"`).
    pub model: String,
    /// The model in words, naming its keys in `model_params`.
    pub description: String,
}
