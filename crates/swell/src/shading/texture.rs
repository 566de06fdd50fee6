//! Colour textures: bilinear sampling with wrap-around, a procedural water pattern and image files,
//! and the water material's texture ([`WaterMaterial::load_texture`]).

use std::path::Path;

use glam::{Vec2, Vec3};

use crate::error::{Error, Result};
use crate::math::srgb_to_linear;
use crate::scene::WaterMaterial;

/// Largest texture side in texels, to bound memory (16384² linear RGB texels is 3 GiB).
pub const MAX_TEXTURE_SIDE: u32 = 16384;

/// A linear-RGB image sampled with bilinear filtering and repeat (wrap) addressing.
///
/// Texture coordinates are in tiles: (0, 0) is the top-left corner of the image, u runs along its
/// rows, and every integer step repeats it. Texel (i, j) has its centre at ((i + ½)/w, (j + ½)/h).
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    width: u32,
    height: u32,
    texels: Vec<Vec3>,
}

impl Texture {
    /// A texture of `width` x `height` linear-RGB texels, top row first. Fails when a side is 0 or
    /// above [`MAX_TEXTURE_SIDE`] or the texel count does not match.
    pub fn new(width: u32, height: u32, texels: Vec<Vec3>) -> Result<Self> {
        crate::error::check_count("texture width", width, 1, MAX_TEXTURE_SIDE)?;
        crate::error::check_count("texture height", height, 1, MAX_TEXTURE_SIDE)?;
        if texels.len() != width as usize * height as usize {
            return Err(Error::invalid("texture", format!("{} texels for {width} x {height}", texels.len())));
        }
        Ok(Self { width, height, texels })
    }

    /// Reads a PNG or JPEG file (sRGB-encoded, as image files are) into linear RGB. Opened by
    /// [`crate::io::open_seekable`]: a FIFO with no writer is refused at once instead of
    /// blocking, and a pipe with one is read into memory first, since decoding seeks.
    pub fn from_file(path: &Path) -> Result<Self> {
        let mut reader = image::ImageReader::new(crate::io::open_seekable(path)?);
        // As `ImageReader::open` does: the extension's format unless the content says otherwise.
        if let Ok(format) = image::ImageFormat::from_path(path) {
            reader.set_format(format);
        }
        let img = reader
            .with_guessed_format()
            .map_err(|e| Error::io(path, e))?
            .decode()
            .map_err(|e| Error::Image { path: path.into(), message: e.to_string() })?
            .to_rgb8();
        let texels = img.pixels().map(|p| Vec3::from_array(p.0.map(|c| srgb_to_linear(c as f32 / 255.0)))).collect();
        Self::new(img.width(), img.height(), texels)
            .map_err(|e| Error::Image { path: path.into(), message: e.to_string() })
    }

    /// A tiling water pattern around `base` (linear RGB): brighter crossing ridges, like light
    /// focused by small waves, over slightly darker troughs.
    ///
    /// It is a sum of sines with integer wave numbers, so it tiles exactly; the phases come from a
    /// fixed hash, so the pattern is the same on every run.
    pub fn procedural_water(base: Vec3) -> Self {
        // (k_u, k_v, phase): integer wave numbers per tile keep the pattern periodic.
        const WAVES: [(f32, f32, f32, f32); 6] = [
            (3.0, 1.0, 0.3, 1.0),
            (-2.0, 3.0, 1.9, 1.0),
            (1.0, -4.0, 4.1, 1.0),
            (5.0, 2.0, 2.7, 1.0),
            (-4.0, -5.0, 5.3, 1.0),
            (7.0, -3.0, 0.9, 1.0),
        ];
        let highlight = (base * 2.5 + Vec3::splat(0.08)).min(Vec3::ONE);
        let shadow = base * 0.7;
        Self::from_sines(&WAVES, |s| {
            // Ridges where the sum crosses zero: 1 on the crossing, falling off quickly.
            let ridge = (1.0 - (s * 6.0).abs()).max(0.0).powi(2);
            let t = 0.5 + 0.5 * s;
            shadow.lerp(base, t) + (highlight - base) * ridge
        })
    }

    /// A 256² tile from a weighted mean `s` in [-1, 1] of sines `(k_u, k_v, phase, weight)` over
    /// the tile's (u, v) (integer wave numbers: it tiles exactly; fixed phases: the same on every
    /// run), each texel `colour(s)`.
    fn from_sines(waves: &[(f32, f32, f32, f32)], colour: impl Fn(f32) -> Vec3) -> Self {
        const SIDE: u32 = 256;
        let total: f32 = waves.iter().map(|w| w.3).sum();
        let mut texels = Vec::with_capacity((SIDE * SIDE) as usize);
        for j in 0..SIDE {
            for i in 0..SIDE {
                let (u, v) = ((i as f32 + 0.5) / SIDE as f32, (j as f32 + 0.5) / SIDE as f32);
                let s: f32 = waves
                    .iter()
                    .map(|&(ku, kv, ph, w)| w * (std::f32::consts::TAU * (ku * u + kv * v) + ph).sin())
                    .sum::<f32>()
                    / total;
                texels.push(colour(s));
            }
        }
        Self { width: SIDE, height: SIDE, texels }
    }

    /// A tiling pattern of flowing water around `base` (linear RGB): bright, narrow streaks
    /// drawn out along v (the flow, +Z on the water) over darker water, as foam lines and the
    /// sky's glints stretched by the current look on a river.
    ///
    /// Like [`Texture::procedural_water`] it is a sum of sines with integer wave numbers per tile
    /// (so it tiles exactly) and fixed phases (so it is the same on every run); here the wave
    /// numbers across (u) are 3 to 7 and along (v) 1 to 2, so each feature is several times
    /// longer than it is wide, yet broad enough for a mesh shaded per vertex (a few vertices
    /// per streak) to draw it.
    pub fn procedural_streaks(base: Vec3) -> Self {
        // (k_u, k_v, phase, weight): the first four are the streaks, the last two slow swells of
        // brightness along the flow that make the motion readable at a glance.
        const WAVES: [(f32, f32, f32, f32); 8] = [
            (3.0, 1.0, 0.4, 1.0),
            (-5.0, 1.0, 2.3, 0.9),
            (7.0, -2.0, 4.4, 0.7),
            (-6.0, 2.0, 1.1, 0.5),
            (4.0, -1.0, 5.6, 0.8),
            (5.0, 1.0, 3.0, 0.6),
            (1.0, 2.0, 0.9, 0.7),
            (-2.0, 1.0, 2.0, 0.6),
        ];
        let highlight = (base * 3.0 + Vec3::splat(0.12)).min(Vec3::ONE);
        let shadow = base * 0.55;
        Self::from_sines(&WAVES, |s| {
            // Streaks where the sum peaks: thin bright lines on the crests of the pattern.
            let streak = ((s - 0.25) / 0.35).clamp(0.0, 1.0).powi(2);
            let t = (0.5 + 0.9 * s).clamp(0.0, 1.0);
            shadow.lerp(base, t) + (highlight - base) * streak
        })
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The texel at integer coordinates, wrapped into the image.
    pub fn texel(&self, i: i64, j: i64) -> Vec3 {
        let x = i.rem_euclid(self.width as i64) as usize;
        let y = j.rem_euclid(self.height as i64) as usize;
        self.texels[y * self.width as usize + x]
    }

    /// Bilinearly filtered colour at `uv` (tiles), repeating in both directions. Non-finite
    /// coordinates give the texel at (0, 0) rather than NaN.
    pub fn sample(&self, uv: Vec2) -> Vec3 {
        if !uv.is_finite() {
            return self.texels[0];
        }
        // Wrap first so large offsets (a texture that has flowed for hours) keep their precision.
        let u = uv.x.rem_euclid(1.0) * self.width as f32 - 0.5;
        let v = uv.y.rem_euclid(1.0) * self.height as f32 - 0.5;
        let (i, j) = (u.floor(), v.floor());
        let (fu, fv) = (u - i, v - j);
        let (i, j) = (i as i64, j as i64);
        let top = self.texel(i, j).lerp(self.texel(i + 1, j), fu);
        let bottom = self.texel(i, j + 1).lerp(self.texel(i + 1, j + 1), fu);
        top.lerp(bottom, fv)
    }
}

impl WaterMaterial {
    /// Loads (or generates) the texture the material names; `None` without one.
    pub fn load_texture(&self) -> Result<Option<Texture>> {
        match self.texture.as_deref() {
            None => Ok(None),
            Some("procedural") => Ok(Some(Texture::procedural_water(self.color))),
            Some("streaks") => Ok(Some(Texture::procedural_streaks(self.color))),
            // A file that cannot be read is named with the key that names it.
            Some(path) => Texture::from_file(std::path::Path::new(path))
                .map(Some)
                .map_err(|e| Error::invalid("water.material.texture", e.to_string())),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checker() -> Texture {
        let t = vec![Vec3::ZERO, Vec3::ONE, Vec3::ONE, Vec3::ZERO];
        Texture::new(2, 2, t).unwrap()
    }

    #[test]
    fn texel_centres_are_exact_and_midpoints_blend() {
        let t = checker();
        assert_eq!(t.sample(Vec2::new(0.25, 0.25)), Vec3::ZERO);
        assert_eq!(t.sample(Vec2::new(0.75, 0.25)), Vec3::ONE);
        // Halfway between two texel centres: the average.
        assert!((t.sample(Vec2::new(0.5, 0.25)) - Vec3::splat(0.5)).length() < 1e-6);
        // The wrap blends the last column with the first.
        assert!((t.sample(Vec2::new(0.0, 0.25)) - Vec3::splat(0.5)).length() < 1e-6);
    }

    #[test]
    fn sampling_repeats_with_period_one() {
        let t = Texture::procedural_water(Vec3::new(0.02, 0.11, 0.16));
        for (u, v) in [(0.1, 0.7), (0.93, 0.02), (0.5, 0.5)] {
            let a = t.sample(Vec2::new(u, v));
            for shift in [Vec2::new(1.0, 0.0), Vec2::new(-3.0, 2.0), Vec2::new(17.0, -5.0)] {
                assert!((t.sample(Vec2::new(u, v) + shift) - a).length() < 1e-4);
            }
        }
        assert!(t.sample(Vec2::new(f32::NAN, 0.0)).is_finite());
    }

    #[test]
    fn the_procedural_pattern_is_seamless_across_the_tile_edge() {
        let t = Texture::procedural_water(Vec3::new(0.02, 0.11, 0.16));
        let n = t.width() as i64;
        let max_step = |a: Vec3, b: Vec3| (a - b).abs().max_element();
        let inner = (0..n - 1).map(|i| max_step(t.texel(i, 7), t.texel(i + 1, 7))).fold(0.0, f32::max);
        let across = max_step(t.texel(n - 1, 7), t.texel(n, 7));
        assert!(across <= inner * 1.5 + 1e-6, "seam step {across} vs inner {inner}");
    }

    #[test]
    fn a_missing_file_is_an_error_naming_it() {
        let e = Texture::from_file(Path::new("/nonexistent/water.png")).unwrap_err();
        assert!(e.to_string().contains("/nonexistent/water.png"), "{e}");
    }
}
