//! Terrain: height fields in metres and the generators that make them (paper 001), heightmap
//! files, simple bottoms for pools and beaches, river channels, and the far land that continues a
//! field to the horizon.
//!
//! Every generator takes a size (vertices per side), a horizontal extent in metres and its own
//! parameters (with `validate`), and returns a [`HeightField`] centred on the model origin. The
//! scene places it in the world with a [`crate::math::Transform`].

mod bottom;
mod channel;
mod diamond_square;
mod far_land;
mod generator_params;
mod height_field;
// PNG heightmaps and their TOML sidecars: files that scenes name, so behind the `render` feature
// with the scenes (image and toml are its dependencies).
#[cfg(feature = "render")]
mod heightmap_io;
mod hills;
mod lattice_random;
mod noise_terrain;
mod random_average;
mod smoothing;

pub use bottom::{flat, slope, FlatParams, SlopeParams};
pub use channel::{channel, ChannelParams};
pub use diamond_square::{check_diamond_square_size, diamond_square, DiamondSquareParams, MAX_AMPLITUDE};
pub use far_land::{far_land, FarLandMesh, FarLandParams, MAX_FAR_LAND_REACH, MAX_FAR_LAND_RINGS};
pub use generator_params::{GeneratorParams, DEFAULT_TERRAIN_EXTENT, DEFAULT_TERRAIN_SIZE};
pub use height_field::{HeightField, MAX_TERRAIN_SIZE};
#[cfg(feature = "render")]
pub use heightmap_io::{
    decode_grey_png, load_heightmap, png_header_size, read_grey_png, read_grey_png_from, read_sidecar, sidecar_path,
    write_heightmap, HeightmapOverrides, HeightmapSidecar, MAX_HEIGHTMAP_BYTES,
};
pub use hills::{hills, HillsParams, MAX_HILLS};
pub use lattice_random::{lattice_random, LatticeRandom};
pub use noise_terrain::{noise_terrain, NoiseTerrainParams};
pub use random_average::{random_average, RandomAverageParams};
pub use smoothing::{smooth, MAX_SMOOTHING_PASSES};
