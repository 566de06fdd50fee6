//! # swell: water surfaces over procedural terrain, simulated and rendered on the CPU
//!
//! The crate follows the data flow of a frame:
//!
//! ```text
//! parameters ─▶ water / terrain model ─▶ surface mesh ─▶ world ─▶ rasterizer + shading ─▶ image / file
//!   (scene)        (water::*)              (mesh::*)     (world::*)  (raster::*, shading::*)  (export::*)
//! ```
//!
//! A program that only wants moving water needs [`water`] and [`mesh`]; the renderer is optional.
//!
//! ## Cargo features
//!
//! Both on by default; without them (`default-features = false`) the crate is the simulation core:
//! `math`, `spectrum`, `water`, `terrain` (the generators), `mesh`, `error`, `limits` and the input
//! opening of `io`, depending on glam, rayon, serde, rand, rustfft and thiserror only (and libc on
//! unix, which rand already brings), none of image, exr, gif, toml, serde_json or tempfile.
//!
//! - **`render`**: scenes (`scene`, scene files in TOML), the world built from them (`world`, with
//!   `Water`), `shading` with image textures, the CPU rasterizer `raster`, the passes in `render`,
//!   PNG heightmaps in `terrain`, and the atomic file writes in `io`. One feature because a scene
//!   is what the passes draw and it loads image textures and PNG heightmaps.
//! - **`export`**: writing results, the `export` module (PNG, GIF, EXR, OBJ, glTF, bake sequences);
//!   implies `render`, since what it writes comes from scenes.
//!
//! ## Conventions (stated once, here)
//!
//! - **Units**: SI everywhere in the library: metres, seconds, radians, kilograms. Degrees and other
//!   units appear only at the edges (scene files, CLI) and carry the unit in the key (`fov_y_deg`).
//! - **Axes**: right-handed, **+Y up**. The water surface at rest is the plane **y = 0**; waves are
//!   described over the horizontal (x, z) plane, so a 2-D horizontal vector `Vec2(a, b)` means world
//!   `(x = a, z = b)`.
//! - **Camera**: given by `eye`, `target`, `up`, `fov_y_deg`, `near`, `far`, with OpenGL's look-at and
//!   perspective: view space looks down −Z, clip space has z in [−w, w]. Transforms are named
//!   `a_from_b` (`view_from_world`, `clip_from_view`).
//! - **Images**: the top row comes first in memory; colours are linear RGB until the final
//!   encoding (exposure, tone curve, sRGB: [`math::DisplayEncoding`]).
//! - **Light**: every radiance (sky, sun disc, lit surfaces, EXR pixels) is in one unit, 20,000
//!   cd/m² of luminance ([`math::RADIANCE_UNIT_NITS`]); a light's colour × intensity is E / π in
//!   it, E the irradiance on a surface facing the light.
//! - **Time** is `f64` seconds so that phases stay exact over long runs; per-vertex work is `f32`.
//! - **Exported files** follow glTF conventions (metres, +Y up, right-handed).
//! - **Randomness** always comes from an explicit seed; the same inputs give bit-identical output on
//!   any number of threads.
//!
//! ```
//! use swell::mesh::SurfaceMesh;
//! use swell::math::GridSpec;
//! use swell::water::{Gerstner, GerstnerWave, WaveModel};
//! use glam::Vec2;
//!
//! // One 20 m wave travelling along +X over a 100 m x 100 m patch of 64 x 64 cells.
//! let wave = GerstnerWave { amplitude: 0.5, wavelength: 20.0, speed: 5.6,
//!                           direction: Vec2::X, steepness: 0.5 };
//! let model = Gerstner::new(vec![wave]).unwrap();
//! let grid = GridSpec::centered(Vec2::new(100.0, 100.0), 64, 64).unwrap();
//! let mut mesh = SurfaceMesh::new(grid);
//! mesh.displace(&model, 2.0);
//! // +Y is up and water at rest is y = 0: every height stays within the amplitude.
//! assert!(mesh.positions.iter().all(|p| p.y.abs() <= 0.5 + 1e-6));
//! assert!(mesh.normals.iter().all(|n| n.y > 0.0));
//! // A single point, without any mesh:
//! let h = model.height_at(10.0, -3.0, 2.0);
//! assert!(h.abs() <= 0.5 + 1e-6);
//! ```

#![warn(missing_docs)]

pub mod body;
pub mod closed_set;
pub mod error;
#[cfg(feature = "export")]
pub mod export;
pub mod io;
pub mod limits;
pub mod math;
pub mod mesh;
#[cfg(feature = "render")]
pub mod raster;
#[cfg(feature = "render")]
pub mod render;
#[cfg(feature = "render")]
pub mod scene;
#[cfg(feature = "render")]
pub mod shading;
pub mod spectrum;
pub mod terrain;
pub mod water;
#[cfg(feature = "render")]
pub mod world;

pub use error::{Error, Result};
#[cfg(feature = "render")]
pub use world::Water;

/// Standard gravity g in m/s², used by every dispersion relation.
pub const GRAVITY: f32 = 9.81;
