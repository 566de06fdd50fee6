//! OpenEXR images of float fields (displacement, normals, foam), through the `exr` crate.
//!
//! Pixel (i, j) is grid vertex (i, j): x to the right is +X, rows downwards are +Z, the first row
//! is the grid's smallest z. That is the view from above (looking down −Y) and matches the mesh
//! uv (v = 0 is the first row), so a baked map lays straight onto an exported mesh.
//! Files are single-part scan-line images written in increasing line order on one thread, so the
//! same field always gives the same bytes.
//!
//! Uncompressed files (the bake's default) skip the exr crate's generic per-pixel image writer:
//! its header and offset table are kept (the crate's own `infer_meta_data` and `block::write`),
//! and the pixel lines, which uncompressed are just each channel's samples in little-endian order,
//! are laid out directly from the field. The bytes are identical to the generic writer's (tested);
//! only the time differs, about an order of magnitude on a 513 x 513 map.

use std::io::Cursor;
use std::path::Path;

use ::exr::block::chunk::{Chunk, CompressedBlock, CompressedScanLineBlock};
use ::exr::block::writer::ChunksWriter;
use ::exr::meta::Headers;
use ::exr::prelude::{Blocks, Compression, Encoding, Image, LineOrder, SpecificChannels, WritableImage};
use glam::Vec3;

use super::write_atomically;
use crate::error::{Error, Result};

crate::closed_set! {
    /// How EXR pixel data is compressed; every choice is lossless for `f32`.
    #[derive(Default)]
    pub enum ExrCompression: "an EXR compression" {
        /// Raw samples: the fastest to write and read, the largest files (12 bytes per RGB pixel).
        #[default]
        None = "none",
        /// Run-length encoding: cheap, helps only on flat areas.
        Rle = "rle",
        /// Deflate over blocks of 16 lines: several times slower to write; float wave fields are
        /// nearly incompressible (a few percent smaller), smooth fields gain more.
        Zip = "zip",
        /// Wavelet (PIZ): slower still, slightly smaller than ZIP on wave fields.
        Piz = "piz",
    }
}

impl ExrCompression {
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
    if compression == ExrCompression::None {
        let headers = image.write().infer_meta_data();
        return encode(path, |cursor| {
            write_raw_lines(cursor, headers, width, height, |name, row, out| {
                // Only the R, G and B channels exist: the header is the one inferred just above.
                let pick: fn(&Vec3) -> f32 = match name {
                    "R" => |v| v.x,
                    "G" => |v| v.y,
                    _ => |v| v.z,
                };
                out.extend(data[row * width..(row + 1) * width].iter().flat_map(|v| pick(v).to_le_bytes()));
            })
        });
    }
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
    if compression == ExrCompression::None {
        let headers = image.write().infer_meta_data();
        return encode(path, |cursor| {
            write_raw_lines(cursor, headers, width, height, |_, row, out| {
                out.extend(data[row * width..(row + 1) * width].iter().flat_map(|v| v.to_le_bytes()))
            })
        });
    }
    encode(path, |cursor| image.write().non_parallel().to_buffered(cursor))
}

/// Writes an uncompressed scan-line image with the exr crate's header and offset table, one
/// line per block (as uncompressed files have): for each line, each channel of the header in its
/// (alphabetical) order, `line(channel name, row, out)` appends `width` little-endian `f32`s.
fn write_raw_lines(
    cursor: &mut Cursor<Vec<u8>>,
    headers: Headers,
    width: usize,
    height: usize,
    line: impl Fn(&str, usize, &mut Vec<u8>),
) -> ::exr::error::UnitResult {
    let names: Vec<String> = headers[0].channels.list.iter().map(|c| c.name.to_string()).collect();
    let line_bytes = names.len() * width * 4;
    cursor.get_mut().reserve(height * (line_bytes + 16) + 1024);
    ::exr::block::write(cursor, headers, true, |_meta, writer| {
        for row in 0..height {
            let mut pixels = Vec::with_capacity(line_bytes);
            for name in &names {
                line(name, row, &mut pixels);
            }
            let block = CompressedScanLineBlock { y_coordinate: row as i32, compressed_pixels_le: pixels };
            writer.write_chunk(row, Chunk { layer_index: 0, compressed_block: CompressedBlock::ScanLine(block) })?;
        }
        Ok(())
    })
}

/// The exr crate needs a seekable writer: encode into memory, then write the bytes atomically.
fn encode(path: &Path, write: impl FnOnce(&mut Cursor<Vec<u8>>) -> ::exr::error::UnitResult) -> Result<()> {
    let mut cursor = Cursor::new(Vec::new());
    write(&mut cursor).map_err(|e| Error::Image { path: path.into(), message: e.to_string() })?;
    let bytes = cursor.into_inner();
    write_atomically(path, |out| out.write_all(&bytes).map_err(|e| Error::io(path, e)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fast uncompressed path must give the generic writer's bytes exactly.
    #[test]
    fn raw_lines_are_the_generic_writers_bytes() {
        let dir = tempfile::tempdir().unwrap();
        let (w, h) = (13, 7);
        let rgb: Vec<Vec3> =
            (0..w * h).map(|k| Vec3::new(k as f32 * 0.5, -(k as f32), (k * k) as f32 * 1e-3)).collect();
        let grey: Vec<f32> = (0..w * h).map(|k| (k as f32).sin()).collect();
        let generic = |path: &Path, gray: bool| {
            let encoding = ExrCompression::None.encoding();
            if gray {
                let ch = SpecificChannels::build()
                    .with_channel("Y")
                    .with_pixel_fn(|p: ::exr::math::Vec2<usize>| (grey[p.y() * w + p.x()],));
                let image = Image::from_encoded_channels((w, h), encoding, ch);
                encode(path, |c| image.write().non_parallel().to_buffered(c)).unwrap();
            } else {
                let ch = SpecificChannels::rgb(|p: ::exr::math::Vec2<usize>| {
                    let v = rgb[p.y() * w + p.x()];
                    (v.x, v.y, v.z)
                });
                let image = Image::from_encoded_channels((w, h), encoding, ch);
                encode(path, |c| image.write().non_parallel().to_buffered(c)).unwrap();
            }
            std::fs::read(path).unwrap()
        };
        let fast_rgb = dir.path().join("fast_rgb.exr");
        write_exr_rgb(&fast_rgb, w, h, &rgb, ExrCompression::None).unwrap();
        assert_eq!(std::fs::read(&fast_rgb).unwrap(), generic(&dir.path().join("g_rgb.exr"), false));
        let fast_grey = dir.path().join("fast_grey.exr");
        write_exr_gray(&fast_grey, w, h, &grey, ExrCompression::None).unwrap();
        assert_eq!(std::fs::read(&fast_grey).unwrap(), generic(&dir.path().join("g_grey.exr"), true));
    }
}
