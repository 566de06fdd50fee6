//! Float heightmaps: a [`HeightField`] as a one-channel `f32` OpenEXR image of heights in metres,
//! for tools that take float displacement (Blender, Houdini, game engines' terrain importers).
//!
//! Unlike the 16-bit PNG heightmap ([`crate::terrain::write_heightmap`]), nothing is quantised:
//! each sample is the field's `f32` height, so reading it back gives the very same numbers.
//! Image column i is field column i (+X); image row r (top row first) is field row r (+Z), as in
//! the PNG heightmap. The channel is `Y` (luminance), which every EXR viewer shows as grey.
//!
//! Beside `map.exr` the same sidecar as the PNG's is written, `map.exr.toml`, with
//! `height_scale = 1.0` and `height_offset = 0.0` (samples are already metres) and the extent.

use std::path::Path;

use super::{write_atomically, write_exr_gray, ExrCompression};
use crate::error::{Error, Result};
use crate::terrain::{sidecar_path, HeightField, HeightmapSidecar};

/// Writes `field` as a `Y` `f32` EXR at `path` (heights in metres, uncompressed) and its sidecar
/// `path.toml`, both atomically; returns the sidecar's contents.
pub fn write_heightmap_exr(path: &Path, field: &HeightField) -> Result<HeightmapSidecar> {
    // `HeightField::new` already refuses non-finite heights, so no NaN can reach the file.
    write_exr_gray(path, field.cols(), field.rows(), field.heights(), ExrCompression::None)?;
    let sidecar = HeightmapSidecar { height_scale: 1.0, height_offset: 0.0, extent: field.extent() };
    let side = sidecar_path(path);
    write_atomically(&side, |out| {
        // `{:?}` prints the shortest decimal that reads back to the same f32, always with a '.'.
        let text = format!(
            "# swell heightmap: EXR samples are heights in metres (height = height_offset + height_scale * sample)\n\
             height_scale = 1.0\nheight_offset = 0.0\nextent = [{:?}, {:?}]\n",
            sidecar.extent.x, sidecar.extent.y
        );
        out.write_all(text.as_bytes()).map_err(|e| Error::io(&side, e))
    })?;
    Ok(sidecar)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ::exr::prelude::read_first_flat_layer_from_file;
    use glam::Vec2;

    #[test]
    fn heights_read_back_exactly_and_in_place() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("map.exr");
        // Not square and not symmetric, so a swapped axis or flipped row would show.
        let field =
            HeightField::from_fn(7, 5, Vec2::new(60.0, 40.0), |x, z| 0.37 * x - 1.3 * z + 0.01 * x * z).unwrap();
        let side = write_heightmap_exr(&path, &field).unwrap();
        assert_eq!(side.extent, Vec2::new(60.0, 40.0));

        let image = read_first_flat_layer_from_file(&path).unwrap();
        assert_eq!((image.layer_data.size.width(), image.layer_data.size.height()), (7, 5));
        let channels = &image.layer_data.channel_data.list;
        assert_eq!(channels.len(), 1);
        assert_eq!(channels[0].name.to_string(), "Y");
        let read: Vec<f32> = channels[0].sample_data.values_as_f32().collect();
        assert_eq!(read, field.heights(), "every height comes back bit for bit");
        // Row 0 is the smallest z, column 0 the smallest x: the first sample is the corner (-30, -20).
        let corner = 0.37 * -30.0 - 1.3 * -20.0 + 0.01 * 600.0;
        assert!((read[0] - corner).abs() < 1e-4, "{} vs {corner}", read[0]);

        let text = std::fs::read_to_string(dir.path().join("map.exr.toml")).unwrap();
        let parsed: HeightmapSidecar = toml::from_str(&text).unwrap();
        assert_eq!(parsed, side);
    }
}
