//! The `[water]` section: which wave model, over which patch, with which look.
//!
//! In a scene file the model's own keys sit directly in `[water]` beside `model`, `size`, `cells`
//! and `center`; the look is in `[water.material]`:
//!
//! ```toml
//! [water]
//! model = "gerstner"
//! size = [200.0, 200.0]
//! cells = [256, 256]
//! [[water.waves]]
//! amplitude = 0.6
//! wavelength = 30.0
//! speed = 6.8
//! direction = [1.0, 0.2]
//! steepness = 0.6
//! ```

use glam::{Vec2, Vec3};
use serde::{de::DeserializeOwned, Deserialize, Serialize};

use crate::error::{check_finite_vec, check_range, Error, Result};
use crate::math::GridSpec;
use crate::shading::Shading;
use crate::water::{FftOcean, FftOceanParams, Gerstner, GerstnerWave, SineWave, SumOfSines, WaveModel};

/// The water patch and its sampling grid.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WaterSurface {
    /// Extent along x and z in metres, each > 0. Default 200 x 200.
    pub size: Vec2,
    /// Grid cells along x and z, each in [1, 4096]. Default 256 x 256.
    pub cells: [u32; 2],
    /// World (x, z) of the patch centre, metres. Default (0, 0).
    pub center: Vec2,
}

impl Default for WaterSurface {
    fn default() -> Self {
        Self { size: Vec2::splat(200.0), cells: [256, 256], center: Vec2::ZERO }
    }
}

impl WaterSurface {
    /// The sampling grid, checked (keys named under `water`).
    pub fn grid(&self) -> Result<GridSpec> {
        check_finite_vec("water.center", &self.center.to_array())?;
        GridSpec::new(self.center - 0.5 * self.size, self.size, self.cells[0], self.cells[1]).map_err(|e| match e {
            // GridSpec names its own fields; say where they came from in the scene.
            Error::OutOfRange { key, value, range } => {
                Error::OutOfRange { key: key.replace("grid.", "water."), value, range }
            }
            other => other,
        })
    }
}

/// How the water looks: `[water.material]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WaterMaterial {
    /// Linear RGB colour of light scattered back from the water body, components in [0, 1].
    pub color: Vec3,
    /// Shading model. Default `gouraud`.
    pub shading: Shading,
    /// Refractive index of water relative to air, in [1, 3]. Default 1.333 (fresh water, 20 °C).
    pub refractive_index: f32,
}

impl Default for WaterMaterial {
    fn default() -> Self {
        Self { color: Vec3::new(0.02, 0.11, 0.16), shading: Shading::Gouraud, refractive_index: 1.333 }
    }
}

impl WaterMaterial {
    /// Checks every field, naming keys under `key` (normally `water.material`).
    pub fn validate(&self, key: &str) -> Result<()> {
        for (i, c) in self.color.to_array().into_iter().enumerate() {
            check_range(&format!("{key}.color[{i}]"), c, 0.0, 1.0)?;
        }
        check_range(&format!("{key}.refractive_index"), self.refractive_index, 1.0, 3.0)
    }
}

/// Gerstner waves (paper 000): `model = "gerstner"` and a `[[water.waves]]` list.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GerstnerSpec {
    /// The waves, 0 to 64 of them.
    #[serde(default)]
    pub waves: Vec<GerstnerWave>,
}

/// A plain sum of sines: `model = "sines"` and a `[[water.waves]]` list.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SinesSpec {
    /// The waves, 0 to 64 of them.
    #[serde(default)]
    pub waves: Vec<SineWave>,
}

/// The wave model and its parameters, selected by `water.model`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "model", rename_all = "kebab-case")]
pub enum WaterModelSpec {
    /// `model = "gerstner"`.
    Gerstner(GerstnerSpec),
    /// `model = "sines"`.
    Sines(SinesSpec),
    /// `model = "fft"`: the spectral (Tessendorf) ocean; its keys sit in `[water]`.
    Fft(FftOceanParams),
}

/// The names `water.model` accepts.
pub const WATER_MODELS: &[&str] = &["gerstner", "sines", "fft"];

impl WaterModelSpec {
    /// Builds the model, validating its parameters.
    pub fn build(&self) -> Result<Box<dyn WaveModel>> {
        Ok(match self {
            WaterModelSpec::Gerstner(s) => Box::new(Gerstner::new(s.waves.clone())?),
            WaterModelSpec::Sines(s) => Box::new(SumOfSines::new(s.waves.clone())?),
            WaterModelSpec::Fft(p) => Box::new(FftOcean::new(p)?),
        })
    }

    fn from_table(model: &str, rest: toml::Table, source: &str) -> Result<Self> {
        Ok(match model {
            "gerstner" => WaterModelSpec::Gerstner(deserialize_at(rest, "water", source)?),
            "sines" => WaterModelSpec::Sines(deserialize_at(rest, "water", source)?),
            "fft" => WaterModelSpec::Fft(deserialize_at(rest, "water", source)?),
            other => {
                return Err(Error::Parse {
                    path: source.to_string(),
                    message: format!("water.model = \"{other}\" is not a model; valid: {}", WATER_MODELS.join(", ")),
                })
            }
        })
    }
}

/// The whole `[water]` section.
#[derive(Clone, Debug, PartialEq)]
pub struct WaterSpec {
    /// Patch and grid.
    pub surface: WaterSurface,
    /// Look.
    pub material: WaterMaterial,
    /// Model and its parameters.
    pub model: WaterModelSpec,
}

/// Keys of `[water]` that belong to the patch rather than to the model.
const SURFACE_KEYS: [&str; 3] = ["size", "cells", "center"];

impl WaterSpec {
    /// Reads the `[water]` table; `source` names the file in errors.
    pub fn from_table(mut table: toml::Table, source: &str) -> Result<Self> {
        let model = match table.remove("model") {
            Some(toml::Value::String(s)) => s,
            Some(v) => {
                return Err(Error::Parse {
                    path: source.into(),
                    message: format!("water.model = {v} must be a string, one of {}", WATER_MODELS.join(", ")),
                })
            }
            None => {
                return Err(Error::Parse {
                    path: source.into(),
                    message: format!("water.model is missing; valid: {}", WATER_MODELS.join(", ")),
                })
            }
        };
        let mut surface = toml::Table::new();
        for key in SURFACE_KEYS {
            if let Some(v) = table.remove(key) {
                surface.insert(key.to_string(), v);
            }
        }
        let material = match table.remove("material") {
            Some(v) => deserialize_at(v, "water.material", source)?,
            None => WaterMaterial::default(),
        };
        Ok(Self {
            surface: deserialize_at(surface, "water", source)?,
            material,
            model: WaterModelSpec::from_table(&model, table, source)?,
        })
    }

    /// The `[water]` table as written to a scene file.
    pub fn to_table(&self) -> toml::Table {
        let mut t = to_table(&self.model);
        t.extend(to_table(&self.surface));
        t.insert("material".into(), toml::Value::Table(to_table(&self.material)));
        t
    }

    /// Checks everything that does not need the model built.
    pub fn validate(&self) -> Result<()> {
        self.surface.grid()?;
        self.material.validate("water.material")
    }
}

fn to_table<T: Serialize>(v: &T) -> toml::Table {
    toml::Table::try_from(v).expect("swell's own scene types always serialise to a TOML table")
}

/// Deserialises `value` as `T`, reporting errors with the full key path (`water.waves[2].speed`).
pub(crate) fn deserialize_at<T: DeserializeOwned>(
    value: impl Into<toml::Value>,
    prefix: &str,
    source: &str,
) -> Result<T> {
    serde_path_to_error::deserialize(value.into()).map_err(|e| {
        let inner = e.path().to_string();
        let key = match (prefix.is_empty(), inner.as_str()) {
            (true, _) => inner.clone(),
            (false, ".") => prefix.to_string(),
            (false, p) if p.starts_with('[') => format!("{prefix}{p}"),
            (false, p) => format!("{prefix}.{p}"),
        };
        Error::Parse { path: source.to_string(), message: format!("{key}: {}", e.into_inner()) }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<WaterSpec> {
        WaterSpec::from_table(toml::from_str(text).unwrap(), "test")
    }

    #[test]
    fn a_gerstner_section_round_trips_through_toml() {
        let w = parse(
            "model = 'gerstner'\nsize = [10.0, 20.0]\ncells = [8, 16]\n[material]\nshading = 'flat'\n\
             [[waves]]\namplitude = 1.0\nwavelength = 10.0\nspeed = 3.0\ndirection = [1.0, 0.0]\nsteepness = 0.5\n",
        )
        .unwrap();
        assert_eq!(w.surface.cells, [8, 16]);
        assert_eq!(w.material.shading, Shading::Flat);
        let back = WaterSpec::from_table(w.to_table(), "again").unwrap();
        assert_eq!(back, w);
    }

    #[test]
    fn an_fft_section_round_trips_through_toml() {
        let w = parse(
            "model = 'fft'\ngrid = 64\nspectrum = 'tma'\ndepth = 12.0\nspreading = 'donelan-banner'\n\
             loop_period = 30.0\n[swell]\nheight = 0.8\n",
        )
        .unwrap();
        let WaterModelSpec::Fft(p) = &w.model else { panic!("not fft: {:?}", w.model) };
        assert_eq!((p.grid, p.depth, p.swell.unwrap().height), (64, Some(12.0), 0.8));
        assert_eq!(WaterSpec::from_table(w.to_table(), "again").unwrap(), w);
        w.model.build().unwrap();
    }

    #[test]
    fn errors_name_the_full_key_path() {
        let e = parse("model = 'gerstner'\n[[waves]]\namplitude = 1.0\nwavelength = 'x'\n").unwrap_err();
        assert!(e.to_string().contains("water.waves[0].wavelength"), "{e}");
        let e = parse("model = 'gerstner'\nbogus = 1\n").unwrap_err();
        assert!(e.to_string().contains("bogus"), "{e}");
        let e = parse("model = 'tsunami'\n").unwrap_err();
        assert!(e.to_string().contains("gerstner, sines"), "{e}");
        let e = parse("model = 'fft'\ngrid = 100\n").unwrap().model.build().err().unwrap();
        assert_eq!(e.to_string(), "water.grid = 100 is outside powers of two in [16, 2048]");
        let e = parse("model = 'fft'\nspectrum = 'bretschneider'\n").unwrap_err();
        assert!(e.to_string().contains("water.spectrum"), "{e}");
        let e = parse("model = 'sines'\ncells = [0, 4]\n").unwrap();
        assert_eq!(e.validate().unwrap_err().to_string(), "water.cells[0] = 0 is outside [1, 4096]");
    }
}
