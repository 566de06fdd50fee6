//! Writing results to files: images and animations, meshes, baked map sequences, always atomically.

mod image_file;
// Meshes (OBJ, glTF), float maps (EXR) and bake sequences: issue 8.
mod array_job;
mod bake;
mod bake_bodies;
mod body_meshes;
// issue 37: frames verified on resume, one bake per directory, a lock naming its holder.
mod bake_checksum;
mod bake_frame_record;
mod bake_lock;
mod bake_manifest;
mod exr;
mod frame_range;
mod gltf;
mod heightmap_exr;
mod named_mesh;
mod normal_space;
mod obj;
// issue 33: a GIF at the renderer's speed, and PNG sequences.
mod frame_batches;
mod frame_pattern;
mod median_cut;
mod ordered_dither;
mod png_sequence;

pub use self::exr::{write_exr_gray, write_exr_rgb, ExrCompression};
pub use array_job::{resolve_shard, ResolvedShard, SHARD_COUNT_VAR};
// Kept here too for callers from before it moved down to `io` (terrain writes files as well).
pub use crate::io::write_atomically;
pub use bake::{model_loop_period, Bake, BakeSettings, MAX_FPS, MIN_PNG_RANGE_M, PNG_RANGE_HEADROOM};
pub use bake_bodies::{BakedBodies, BakedBody, BodyFramePose, BODIES_JSON};
pub use bake_checksum::{xxh64, Xxh64};
pub use bake_lock::{lock_name, BakeLock, LockHolder, MAX_LOCK_COMMAND_CHARS};
pub use bake_manifest::{
    AxisConversion, BakeAxes, BakeFoam, BakeGrid, BakeManifest, BakeMap, BakePng, BakeUnits, BAKE_MANIFEST_VERSION,
};
pub use body_meshes::{body_meshes, BodyMesh};
pub use frame_pattern::{FramePattern, MAX_PATTERN_WIDTH};
pub use frame_range::{FrameRange, Shard, MAX_FRAME, MAX_SHARDS};
pub use gltf::{
    gltf_document, gltf_document_animated, write_glb, write_glb_animated, write_gltf, write_gltf_animated,
    NodeAnimation, NodeTrack,
};
pub use heightmap_exr::write_heightmap_exr;
pub use image_file::{
    gif_delay_cs, gif_frame, write_gif, write_png, write_png_map, GIF_MAX_DITHER_LEVELS, MAX_GIF_FPS,
};
pub use median_cut::{median_cut_palette, CHANNEL_WEIGHTS};
pub use named_mesh::{world_meshes, NamedMesh};
pub use normal_space::NormalSpace;
pub use obj::{encode_obj, write_obj};
pub use ordered_dither::dither_to_palette;
pub use png_sequence::{is_complete_png, pending_frames, write_png_sequence};
