//! Heightmap files (paper 001: "save the landscape to a file and load it back"): a grayscale PNG
//! whose grey levels map linearly to metres, plus a small TOML sidecar holding that mapping and the
//! horizontal extent.
//!
//! `height (m) = height_offset + height_scale * grey / grey_max`, with `grey_max` 65535 for 16-bit
//! images and 255 for 8-bit ones. Image column i is field column i (+X); image row r (top row
//! first) is field row r (+Z). Saving writes 16 bits with `height_offset` = the lowest height and
//! `height_scale` = the height range, so save-then-load is exact to half a grey level
//! (`range / 131070` metres).
//!
//! The sidecar of `map.png` is `map.png.toml`:
//! ```toml
//! height_scale = 57.25
//! height_offset = -12.5
//! extent = [500.0, 500.0]
//! ```

use std::path::{Path, PathBuf};

use glam::Vec2;
use image::{ColorType, ImageDecoder, ImageFormat, ImageReader, Limits};
use serde::{Deserialize, Serialize};

use super::height_field::{HeightField, MAX_TERRAIN_SIZE};
use crate::error::{check_finite_vec, check_positive, check_range, Error, Result};
use crate::io::{open_seekable, read_input, write_atomically};

/// Most bytes a heightmap may decode to: 4097 x 4097 pixels of 16-bit grey with alpha. Images are
/// refused from their header, before any pixel is decoded, so a small file claiming huge
/// dimensions (a decompression bomb) costs nothing.
pub const MAX_HEIGHTMAP_BYTES: u64 = 4 * (MAX_TERRAIN_SIZE as u64) * (MAX_TERRAIN_SIZE as u64);

/// The grey-to-metres mapping and extent stored beside a heightmap image.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeightmapSidecar {
    /// Metres between grey 0 and the brightest grey, > 0.
    pub height_scale: f32,
    /// Height (m) of grey 0, finite.
    pub height_offset: f32,
    /// Horizontal extent (x, z) in metres, each > 0.
    pub extent: Vec2,
}

impl HeightmapSidecar {
    /// Checks every field, naming keys under `key`.
    pub fn validate(&self, key: &str) -> Result<()> {
        check_positive(&format!("{key}.height_scale"), self.height_scale)?;
        check_range(&format!("{key}.height_offset"), self.height_offset, -1.0e6, 1.0e6)?;
        check_finite_vec(&format!("{key}.extent"), &self.extent.to_array())?;
        check_positive(&format!("{key}.extent[0]"), self.extent.x)?;
        check_positive(&format!("{key}.extent[1]"), self.extent.y)
    }
}

/// The sidecar path of heightmap `png`: the same name with `.toml` appended (`map.png.toml`).
pub fn sidecar_path(png: &Path) -> PathBuf {
    let mut name = png.as_os_str().to_owned();
    name.push(".toml");
    PathBuf::from(name)
}

/// Writes `field` as a 16-bit grayscale PNG at `path` and its sidecar beside it, both atomically;
/// returns the sidecar's contents.
pub fn write_heightmap(path: &Path, field: &HeightField) -> Result<HeightmapSidecar> {
    let (lo, hi) = field.min_max();
    // A flat field still needs a positive scale; any will do since every grey is then 0.
    let scale = if hi > lo { hi - lo } else { 1.0 };
    let sidecar = HeightmapSidecar { height_scale: scale, height_offset: lo, extent: field.extent() };
    let mut bytes = Vec::with_capacity(2 * field.heights().len());
    for &h in field.heights() {
        let g = ((h - lo) / scale * 65535.0).round().clamp(0.0, 65535.0) as u16;
        // PngEncoder takes 16-bit samples in native byte order and writes them big-endian.
        bytes.extend_from_slice(&g.to_ne_bytes());
    }
    let (w, h) = (field.cols() as u32, field.rows() as u32);
    write_atomically(path, |out| {
        let encoder = image::codecs::png::PngEncoder::new(out);
        image::ImageEncoder::write_image(encoder, &bytes, w, h, image::ExtendedColorType::L16)
            .map_err(|e| Error::Image { path: path.into(), message: e.to_string() })
    })?;
    let side = sidecar_path(path);
    write_atomically(&side, |out| {
        // `{:?}` prints the shortest decimal that reads back to the same f32, always with a '.'.
        let text = format!(
            "# swell heightmap: height (m) = height_offset + height_scale * grey / 65535\n\
             height_scale = {:?}\nheight_offset = {:?}\nextent = [{:?}, {:?}]\n",
            sidecar.height_scale, sidecar.height_offset, sidecar.extent.x, sidecar.extent.y
        );
        out.write_all(text.as_bytes()).map_err(|e| Error::io(&side, e))
    })?;
    Ok(sidecar)
}

/// Most bytes of a heightmap sidecar read: 64 KiB. One holds three keys (under 200 bytes); the
/// bound keeps `/dev/zero` or a stray large file named `map.png.toml` from filling memory.
const MAX_SIDECAR_BYTES: u64 = 64 << 10;

/// Reads the sidecar of heightmap `png`, or `None` if there is no such file. It is opened by
/// [`crate::io::read_input`]: a FIFO with no writer is refused at once, never waited on.
pub fn read_sidecar(png: &Path) -> Result<Option<HeightmapSidecar>> {
    let side = sidecar_path(png);
    let bytes = match read_input(&side, MAX_SIDECAR_BYTES) {
        Ok(b) => b,
        Err(Error::Io { source, .. }) if source.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(e),
    };
    let parse_err = |message: String| Error::Parse { path: side.display().to_string(), message };
    if bytes.len() as u64 > MAX_SIDECAR_BYTES {
        return Err(parse_err(format!(
            "over the heightmap-sidecar limit of {MAX_SIDECAR_BYTES} bytes (MAX_SIDECAR_BYTES)"
        )));
    }
    let text = String::from_utf8(bytes).map_err(|_| parse_err("not UTF-8 text (a sidecar is TOML)".into()))?;
    let s: HeightmapSidecar = toml::from_str(&text).map_err(|e| parse_err(e.to_string().trim_end().into()))?;
    s.validate(&side.display().to_string())?;
    Ok(Some(s))
}

/// Grey levels of an 8- or 16-bit grayscale PNG, each divided by its maximum (so in [0, 1]), with
/// the image's width and height. Alpha, if any, is ignored.
///
/// Refuses, before decoding any pixel, images wider or taller than [`MAX_TERRAIN_SIZE`] or whose
/// decoded size would pass [`MAX_HEIGHTMAP_BYTES`]; refuses colour images. Opened by
/// [`crate::io::open_seekable`]: a FIFO with no writer is refused at once, and a pipe with one
/// (`<(...)`) is read into memory first, since decoding seeks.
pub fn read_grey_png(path: &Path) -> Result<(u32, u32, Vec<f32>)> {
    read_grey_png_from(open_seekable(path)?, path)
}

/// [`read_grey_png`] from bytes in memory; `name` is what errors call them.
pub fn decode_grey_png(bytes: &[u8], name: &Path) -> Result<(u32, u32, Vec<f32>)> {
    read_grey_png_from(std::io::Cursor::new(bytes), name)
}

/// Width and height a PNG's header claims, if `head` (its first 24 bytes or more) is a PNG header.
///
/// Read by hand so that a refusal can say what the file claimed; the codec only says that a limit
/// was exceeded.
pub fn png_header_size(head: &[u8]) -> Option<(u32, u32)> {
    const SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";
    if head.len() < 24 || &head[..8] != SIGNATURE || &head[12..16] != b"IHDR" {
        return None;
    }
    let be = |b: &[u8]| u32::from_be_bytes([b[0], b[1], b[2], b[3]]);
    Some((be(&head[16..20]), be(&head[20..24])))
}

/// [`read_grey_png`] from any seekable reader; `name` is what errors call the data.
pub fn read_grey_png_from<R: std::io::BufRead + std::io::Seek>(
    mut input: R,
    name: &Path,
) -> Result<(u32, u32, Vec<f32>)> {
    let path = name;
    let img_err = |message: String| Error::Image { path: path.into(), message };
    let mut head = [0u8; 24];
    let got = read_up_to(&mut input, &mut head).map_err(|e| Error::io(path, e))?;
    if let Some((w, h)) = png_header_size(&head[..got]) {
        // Two bytes of grey and two of alpha per pixel at most.
        let bytes = (4 * w as u64).saturating_mul(h as u64);
        if w > MAX_TERRAIN_SIZE || h > MAX_TERRAIN_SIZE || bytes > MAX_HEIGHTMAP_BYTES {
            return Err(img_err(format!(
                "header claims {w} x {h} pixels, over the heightmap limit of {MAX_TERRAIN_SIZE} x \
                 {MAX_TERRAIN_SIZE} pixels (MAX_TERRAIN_SIZE); refused before decoding"
            )));
        }
    }
    input.seek(std::io::SeekFrom::Start(0)).map_err(|e| Error::io(path, e))?;
    let mut reader = ImageReader::new(input);
    reader.set_format(ImageFormat::Png);
    // A second guard inside the decoder; the side limits are left to the check below, which
    // names the dimensions and the budget.
    let mut limits = Limits::default();
    limits.max_alloc = Some(MAX_HEIGHTMAP_BYTES + (16 << 20));
    reader.limits(limits);
    // Reading the header is all `into_decoder` does; dimensions are checked before decoding.
    let decoder = reader.into_decoder().map_err(|e| img_err(format!("not a readable PNG heightmap: {e}")))?;
    let (w, h) = decoder.dimensions();
    let bytes = decoder.total_bytes();
    if w > MAX_TERRAIN_SIZE || h > MAX_TERRAIN_SIZE || bytes > MAX_HEIGHTMAP_BYTES {
        return Err(img_err(format!(
            "{w} x {h} pixels ({bytes} bytes decoded) exceeds the heightmap budget of \
             {MAX_TERRAIN_SIZE} x {MAX_TERRAIN_SIZE} pixels and {MAX_HEIGHTMAP_BYTES} bytes"
        )));
    }
    if w < 2 || h < 2 {
        return Err(img_err(format!("{w} x {h} pixels: a heightmap needs at least 2 x 2")));
    }
    let color = decoder.color_type();
    if !matches!(color, ColorType::L8 | ColorType::La8 | ColorType::L16 | ColorType::La16) {
        return Err(img_err(format!("{color:?} image: a heightmap must be 8- or 16-bit grayscale")));
    }
    let image = image::DynamicImage::from_decoder(decoder).map_err(|e| img_err(e.to_string()))?;
    let grey: Vec<f32> = match color {
        ColorType::L8 | ColorType::La8 => image.to_luma8().pixels().map(|p| p.0[0] as f32 / 255.0).collect(),
        _ => image.to_luma16().pixels().map(|p| p.0[0] as f32 / 65535.0).collect(),
    };
    Ok((w, h, grey))
}

/// Fills as much of `buf` as `input` holds, stopping early only at its end.
fn read_up_to(input: &mut impl std::io::Read, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut n = 0;
    while n < buf.len() {
        match input.read(&mut buf[n..]) {
            Ok(0) => break,
            Ok(k) => n += k,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(n)
}

/// Where a loaded heightmap's mapping comes from: explicit values win over the sidecar's.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HeightmapOverrides {
    /// Metres per full grey range; required if there is no sidecar.
    pub height_scale: Option<f32>,
    /// Height of grey 0 (m); 0 if neither given nor in a sidecar.
    pub height_offset: Option<f32>,
    /// Extent (m); [200, 200] if neither given nor in a sidecar.
    pub extent: Option<Vec2>,
}

/// Loads heightmap `path` (any 8- or 16-bit grayscale PNG) as a field, taking the mapping from
/// `overrides` first, then from the sidecar.
pub fn load_heightmap(path: &Path, overrides: HeightmapOverrides) -> Result<HeightField> {
    // A missing image is the first thing to say, before the sidecar it would have had.
    std::fs::metadata(path).map_err(|e| Error::io(path, e))?;
    let sidecar = read_sidecar(path)?;
    let height_scale = overrides.height_scale.or(sidecar.map(|s| s.height_scale)).ok_or_else(|| {
        Error::invalid(
            "terrain.height_scale",
            format!(
                "{} has no sidecar {}: give terrain.height_scale (metres per full grey range) \
                 and terrain.height_offset",
                path.display(),
                sidecar_path(path).display()
            ),
        )
    })?;
    let height_offset = overrides.height_offset.or(sidecar.map(|s| s.height_offset)).unwrap_or(0.0);
    let extent = overrides.extent.or(sidecar.map(|s| s.extent)).unwrap_or(Vec2::splat(200.0));
    let (w, h, grey) = read_grey_png(path)?;
    HeightField::new(w, h, extent, grey.into_iter().map(|g| height_offset + height_scale * g).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::{diamond_square, DiamondSquareParams};

    #[test]
    fn save_then_load_is_within_one_grey_level() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("map.png");
        let p = DiamondSquareParams { amplitude: 30.0, corners: [-5.0, 0.0, 3.0, 12.0], ..Default::default() };
        let field = diamond_square(129, Vec2::new(300.0, 250.0), &p).unwrap();
        let side = write_heightmap(&path, &field).unwrap();
        assert_eq!(read_sidecar(&path).unwrap(), Some(side));
        let back = load_heightmap(&path, HeightmapOverrides::default()).unwrap();
        assert_eq!((back.cols(), back.rows(), back.extent()), (129, 129, Vec2::new(300.0, 250.0)));
        let grey = side.height_scale / 65535.0;
        let worst = field.heights().iter().zip(back.heights()).map(|(a, b)| (a - b).abs()).fold(0.0, f32::max);
        assert!(worst <= grey, "worst error {worst} m vs one grey level {grey} m");
        let (lo, hi) = field.min_max();
        assert!((back.min_max().0 - lo).abs() <= grey && (back.min_max().1 - hi).abs() <= grey);
    }

    #[test]
    fn eight_bit_images_load_with_explicit_scale() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("grey8.png");
        let px: Vec<u8> = (0..12).map(|k| (k * 20) as u8).collect();
        image::GrayImage::from_raw(4, 3, px).unwrap().save(&path).unwrap();
        let e = load_heightmap(&path, HeightmapOverrides::default()).unwrap_err().to_string();
        assert!(e.starts_with("terrain.height_scale:") && e.contains("no sidecar"), "{e}");
        let o = HeightmapOverrides { height_scale: Some(51.0), height_offset: Some(-1.0), extent: Some(Vec2::ONE) };
        let f = load_heightmap(&path, o).unwrap();
        assert_eq!((f.cols(), f.rows()), (4, 3));
        assert!((f.height(3, 2) - (-1.0 + 51.0 * 220.0 / 255.0)).abs() < 1e-4);
        // Colour images are refused by name.
        let rgb = dir.path().join("rgb.png");
        image::RgbImage::new(4, 4).save(&rgb).unwrap();
        let e = load_heightmap(&rgb, o).unwrap_err().to_string();
        assert!(e.contains("Rgb8") && e.contains("grayscale"), "{e}");
    }

    /// CRC-32 (ISO 3309, as PNG chunks use), bit by bit: slow and obviously right.
    fn crc32(bytes: &[u8]) -> u32 {
        let mut c = 0xFFFF_FFFFu32;
        for &b in bytes {
            c ^= b as u32;
            for _ in 0..8 {
                c = if c & 1 != 0 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 };
            }
        }
        !c
    }

    #[test]
    fn headers_claiming_the_largest_sizes_are_refused_without_overflow() {
        // Found by the heightmap_png fuzzer: 0xFFFFFFFF x 0xFFFFFFFF overflowed the byte estimate.
        let mut png = b"\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR".to_vec();
        png.extend([0xFF; 8]);
        png.extend([8, 0, 0, 0, 0, 0, 0, 0, 0]);
        let e = decode_grey_png(&png, Path::new("max.png")).unwrap_err().to_string();
        assert!(e.contains("4294967295 x 4294967295") && e.contains("MAX_TERRAIN_SIZE"), "{e}");
        assert_eq!(png_header_size(&png[..23]), None);
        assert!(decode_grey_png(b"", Path::new("empty.png")).is_err());
    }

    #[test]
    fn oversized_images_are_refused_from_the_header() {
        // A valid 2 x 2 PNG whose header is rewritten to claim 60000 x 60000 pixels (7.2 GB of
        // 16-bit grey): a decompression bomb in miniature. It must fail fast, before decoding.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bomb.png");
        image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::new(2, 2).save(&path).unwrap();
        let mut png = std::fs::read(&path).unwrap();
        // Signature (8 bytes), IHDR length (4) and type (4), then width and height.
        png[16..20].copy_from_slice(&60_000u32.to_be_bytes());
        png[20..24].copy_from_slice(&60_000u32.to_be_bytes());
        let crc = crc32(&png[12..29]);
        png[29..33].copy_from_slice(&crc.to_be_bytes());
        std::fs::write(&path, &png).unwrap();
        let start = std::time::Instant::now();
        let e = read_grey_png(&path).unwrap_err().to_string();
        assert!(e.contains("60000 x 60000 pixels") && e.contains("refused before decoding"), "{e}");
        assert!(e.contains("bomb.png"), "{e}");
        assert!(start.elapsed().as_secs_f32() < 1.0);
        // Just over the side limit, also refused.
        png[16..20].copy_from_slice(&(MAX_TERRAIN_SIZE + 1).to_be_bytes());
        png[20..24].copy_from_slice(&2u32.to_be_bytes());
        let crc = crc32(&png[12..29]);
        png[29..33].copy_from_slice(&crc.to_be_bytes());
        std::fs::write(&path, &png).unwrap();
        assert!(read_grey_png(&path).is_err());
    }
}
