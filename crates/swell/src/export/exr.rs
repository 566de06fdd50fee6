//! OpenEXR images of float fields (displacement, normals, foam), through the `exr` crate.
//!
//! Pixel (i, j) is grid vertex (i, j): x to the right is +X, rows downwards are +Z, the first row
//! is the grid's smallest z. That is the view from above (looking down −Y) and matches the mesh
//! uv (v = 0 is the first row), so a baked map lays straight onto an exported mesh.
//! Files are single-part scan-line images written in increasing line order on one thread, so the
//! same field always gives the same bytes.

use std::io::Cursor;
use std::path::Path;

use ::exr::prelude::{Blocks, Compression, Encoding, Image, LineOrder, SpecificChannels, WritableImage};
use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::write_atomically;
use crate::error::{Error, Result};

/// How EXR pixel data is compressed; every choice is lossless for `f32`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ExrCompression {
    /// Raw samples: the fastest to write and read, the largest files (12 bytes per RGB pixel).
    #[default]
    None,
    /// Run-length encoding: cheap, helps only on flat areas.
    Rle,
    /// Deflate over blocks of 16 lines: several times slower to write; float wave fields are
    /// nearly incompressible (a few percent smaller), smooth fields gain more.
    Zip,
    /// Wavelet (PIZ): slower still, slightly smaller than ZIP on wave fields.
    Piz,
}

impl ExrCompression {
    /// Every name, as accepted by [`ExrCompression::parse`].
    pub const NAMES: &'static [&'static str] = &["none", "rle", "zip", "piz"];

    /// Parses a name from [`ExrCompression::NAMES`]; `key` names the option in the error.
    pub fn parse(key: &str, s: &str) -> Result<Self> {
        Ok(match s {
            "none" => Self::None,
            "rle" => Self::Rle,
            "zip" => Self::Zip,
            "piz" => Self::Piz,
            _ => return Err(Error::invalid(key, format!("`{s}` is not one of {}", Self::NAMES.join(", ")))),
        })
    }

    fn encoding(self) -> Encoding {
        let compression = match self {
            Self::None => Compression::Uncompressed,
            Self::Rle => Compression::RLE,
            Self::Zip => Compression::ZIP16,
            Self::Piz => Compression::PIZ,
        };
        Encoding { compression, blocks: Blocks::ScanLines, line_order: LineOrder::Increasing }
    }
}

/// Writes a `width` x `height` field of vectors as an RGB `f32` EXR (R = x, G = y, B = z),
/// atomically. `data` is row-major, first row first.
pub fn write_exr_rgb(
    path: &Path,
    width: usize,
    height: usize,
    data: &[Vec3],
    compression: ExrCompression,
) -> Result<()> {
    assert_eq!(data.len(), width * height, "the field must have width x height samples");
    let channels = SpecificChannels::rgb(|p: ::exr::math::Vec2<usize>| {
        let v = data[p.y() * width + p.x()];
        (v.x, v.y, v.z)
    });
    let image = Image::from_encoded_channels((width, height), compression.encoding(), channels);
    encode(path, |cursor| image.write().non_parallel().to_buffered(cursor))
}

/// Writes a `width` x `height` scalar field as a one-channel (`Y`) `f32` EXR, atomically.
pub fn write_exr_gray(
    path: &Path,
    width: usize,
    height: usize,
    data: &[f32],
    compression: ExrCompression,
) -> Result<()> {
    assert_eq!(data.len(), width * height, "the field must have width x height samples");
    let channels = SpecificChannels::build()
        .with_channel("Y")
        .with_pixel_fn(|p: ::exr::math::Vec2<usize>| (data[p.y() * width + p.x()],));
    let image = Image::from_encoded_channels((width, height), compression.encoding(), channels);
    encode(path, |cursor| image.write().non_parallel().to_buffered(cursor))
}

/// The exr crate needs a seekable writer: encode into memory, then write the bytes atomically.
fn encode(path: &Path, write: impl FnOnce(&mut Cursor<Vec<u8>>) -> ::exr::error::UnitResult) -> Result<()> {
    let mut cursor = Cursor::new(Vec::new());
    write(&mut cursor).map_err(|e| Error::Image { path: path.into(), message: e.to_string() })?;
    let bytes = cursor.into_inner();
    write_atomically(path, |out| out.write_all(&bytes).map_err(|e| Error::io(path, e)))
}
