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

use glam::Vec2;
use serde::{de::DeserializeOwned, Deserialize, Serialize};

use super::water_extent::{LodSettings, WaterExtent};
use super::water_placement::WaterPlacement;
use crate::error::{check_finite_vec, Error, Result};
use crate::math::GridSpec;
use crate::water::{
    AiryParams, FftOceanParams, ModelParams, NoiseParams, RadialWaveParams, RiverParams, SpringMeshParams,
    SteepSinesParams, TessendorfParams, WaveModel, WaveSetParams,
};
pub use crate::water::{GerstnerSpec, SinesSpec};

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
    /// Turn of the patch and its waves about +Y through `center`, degrees in [-360, 360]
    /// (counter-clockwise seen from above). Default 0. See [`WaterPlacement`].
    #[serde(skip_serializing_if = "is_zero")]
    pub yaw_deg: f32,
    /// Uniform scale of the patch and its waves (extent and heights) about `center`, in
    /// (0, 10000]. Default 1. Named so as not to clash with the noise model's `scale`.
    #[serde(skip_serializing_if = "is_one")]
    pub uniform_scale: f32,
    /// `"unbounded"` (to the horizon) or `"patch"`; `None` takes
    /// [`WaterExtent::default_for`] the model (issue 17). Resolve with [`super::Scene::water_extent`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extent: Option<WaterExtent>,
    /// `[water.lod]`: the camera-following mesh of unbounded water.
    #[serde(skip_serializing_if = "is_default_lod")]
    pub lod: LodSettings,
}

fn is_default_lod(l: &LodSettings) -> bool {
    *l == LodSettings::default()
}

// Written only when set, so scenes without a transform save exactly as before.
fn is_zero(v: &f32) -> bool {
    *v == 0.0
}
fn is_one(v: &f32) -> bool {
    *v == 1.0
}

impl Default for WaterSurface {
    fn default() -> Self {
        Self {
            size: Vec2::splat(200.0),
            cells: [256, 256],
            center: Vec2::ZERO,
            yaw_deg: 0.0,
            uniform_scale: 1.0,
            extent: None,
            lod: LodSettings::default(),
        }
    }
}

impl WaterSurface {
    /// Where the patch sits in the world, checked (keys named under `water`).
    pub fn placement(&self) -> Result<WaterPlacement> {
        WaterPlacement::new(self.center, self.yaw_deg, self.uniform_scale)
    }

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

pub use super::water_material::WaterMaterial;

/// Declares the water models: one line each, `Variant = "name" => ParamsType`, with the
/// variant's doc. Generates [`WaterModelSpec`], [`WATER_MODELS`], parsing by name and the dispatch
/// to each model's [`ModelParams`]: the compiler checks that every model is in every one of them.
macro_rules! water_models {
    ($( $(#[$doc:meta])* $variant:ident = $name:literal => $params:ty ),+ $(,)?) => {
        /// The wave model and its parameters, selected by `water.model`.
        #[derive(Clone, Debug, PartialEq, Serialize)]
        #[serde(tag = "model")]
        pub enum WaterModelSpec {
            $( $(#[$doc])* #[serde(rename = $name)] $variant($params), )+
        }

        /// The names `water.model` accepts, in the order the viewer's menu lists them.
        pub const WATER_MODELS: &[&str] = &[$($name),+];

        impl WaterModelSpec {
            /// The model's parameters behind their common interface.
            pub fn params(&self) -> &dyn ModelParams {
                match self { $(WaterModelSpec::$variant(p) => p,)+ }
            }

            /// The `water.model` name of this spec.
            pub fn name(&self) -> &'static str {
                match self { $(WaterModelSpec::$variant(_) => $name,)+ }
            }

            /// The model called `name` with its default parameters, `None` for an unknown name.
            pub fn default_for(name: &str) -> Option<Self> {
                match name { $($name => Some(WaterModelSpec::$variant(<$params>::default())),)+ _ => None }
            }

            fn from_table(model: &str, rest: toml::Table, source: &str) -> Result<Self> {
                Ok(match model {
                    $($name => WaterModelSpec::$variant(deserialize_at(rest, "water", source)?),)+
                    other => {
                        return Err(Error::Parse {
                            path: source.to_string(),
                            message: format!(
                                "water.model = \"{other}\" is not a model; valid: {}",
                                WATER_MODELS.join(", ")
                            ),
                        })
                    }
                })
            }
        }
    };
}

water_models! {
    /// `model = "gerstner"`: Gerstner waves (paper 000), a `[[water.waves]]` list.
    Gerstner = "gerstner" => GerstnerSpec,
    /// `model = "sines"`: a plain sum of sines, a `[[water.waves]]` list.
    Sines = "sines" => SinesSpec,
    /// `model = "tessendorf"`: Gerstner waves in Tessendorf's form with dispersion (paper 003).
    Tessendorf = "tessendorf" => TessendorfParams,
    /// `model = "wave-set"`: Gerstner waves generated from wind, spread and medians (paper 000 §2.4).
    WaveSet = "wave-set" => WaveSetParams,
    /// `model = "airy"`: linear sum of sines with dispersion (paper 000 eqs. 2-3).
    Airy = "airy" => AiryParams,
    /// `model = "steep-sines"`: paper 003's `A ((sin S + 1) / 2)^k`.
    SteepSines = "steep-sines" => SteepSinesParams,
    /// `model = "radial"`: paper 002's circular wave.
    Radial = "radial" => RadialWaveParams,
    /// `model = "noise"`: drifting Perlin fBm (paper 003 §1.1.1).
    Noise = "noise" => NoiseParams,
    /// `model = "springs"`: Hooke spring lattice (paper 003 §1.1.3).
    Springs = "springs" => SpringMeshParams,
    /// `model = "river"`: paper 004's river between oscillating banks.
    River = "river" => RiverParams,
    /// `model = "fft"`: the spectral (Tessendorf) ocean; its keys sit in `[water]`.
    Fft = "fft" => FftOceanParams,
}

impl WaterModelSpec {
    /// The period (s) after which the model repeats exactly, if it was given one.
    pub fn loop_period(&self) -> Option<f64> {
        self.params().loop_period()
    }

    /// A warning when the loop period is too short for the sea (`spectrum/loop_period.rs`):
    /// shorter than the sea's period, or changing its energetic frequencies by more than
    /// [`crate::spectrum::MAX_LOOP_SHIFT`]. `None` without a loop or when the loop fits. Assumes
    /// the parameters are valid.
    pub fn loop_warning(&self) -> Option<String> {
        self.params().loop_warning()
    }

    /// Fixed time steps a time-stepped model takes from its start to reach time `t` (s), its
    /// warm-up included: the spring mesh integrates from t = 0, so a late time costs steps (the
    /// CLI shows progress and refuses more than [`crate::water::MAX_STEPS_PER_ADVANCE`] up front).
    /// `None` for the models that are functions of time.
    pub fn steps_to(&self, t: f64) -> Option<f64> {
        self.params().steps_to(t)
    }

    /// The time (s) a time-stepped model reaches after `steps` of its fixed steps from its start,
    /// its warm-up subtracted: the inverse of [`WaterModelSpec::steps_to`]. `None` for the models
    /// that are functions of time.
    pub fn time_after_steps(&self, steps: f64) -> Option<f64> {
        self.params().time_after_steps(steps)
    }

    /// Whether the built model keeps a state that a click or a stone can disturb
    /// ([`WaveModel::disturb`] returns true): the spring mesh. Closed-form models are functions
    /// of time alone. Lets a caller (the viewer) decide without building the model.
    pub fn takes_disturbances(&self) -> bool {
        self.params().takes_disturbances()
    }

    /// Checks the model's parameters without building it (keys named under `water`).
    pub fn validate(&self) -> Result<()> {
        self.params().validate()
    }

    /// Bytes the built model allocates for its own state, an estimate ([`ModelParams::estimate_bytes`]).
    pub fn estimate_bytes(&self) -> u64 {
        self.params().estimate_bytes()
    }

    /// Builds the model, validating its parameters.
    pub fn build(&self) -> Result<Box<dyn WaveModel>> {
        self.params().build()
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
    /// Density of the water, kg/m³, in [`crate::body::WATER_DENSITY_RANGE`] (default
    /// [`crate::body::SEA_WATER_DENSITY`], sea water; 1000 for fresh): what floats bodies.
    pub density: f32,
}

/// Keys of `[water]` that belong to the patch rather than to the model.
const SURFACE_KEYS: [&str; 7] = ["size", "cells", "center", "yaw_deg", "uniform_scale", "extent", "lod"];

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
        let density = match table.remove("density") {
            Some(toml::Value::Float(d)) => d as f32,
            Some(toml::Value::Integer(d)) => d as f32,
            Some(v) => {
                return Err(Error::Parse {
                    path: source.into(),
                    message: format!("water.density = {v} must be a number (kg/m³)"),
                })
            }
            None => crate::body::SEA_WATER_DENSITY,
        };
        let material = match table.remove("material") {
            Some(v) => deserialize_at(v, "water.material", source)?,
            None => WaterMaterial::default(),
        };
        Ok(Self {
            surface: deserialize_at(surface, "water", source)?,
            material,
            model: WaterModelSpec::from_table(&model, table, source)?,
            density,
        })
    }

    /// The `[water]` table as written to a scene file.
    pub fn to_table(&self) -> toml::Table {
        let mut t = to_table(&self.model);
        t.extend(to_table(&self.surface));
        t.insert("material".into(), toml::Value::Table(to_table(&self.material)));
        if self.density != crate::body::SEA_WATER_DENSITY {
            t.insert("density".into(), toml::Value::Float(f64::from(self.density)));
        }
        t
    }

    /// Checks every key, the model's included, without building anything.
    pub fn validate(&self) -> Result<()> {
        self.surface.grid()?;
        self.surface.placement()?;
        self.surface.lod.validate()?;
        if let Some(e) = self.surface.extent {
            e.validate(&self.model)?;
        }
        self.material.validate("water.material")?;
        let (lo, hi) = crate::body::WATER_DENSITY_RANGE;
        crate::error::check_range("water.density", self.density, lo, hi)?;
        self.model.validate()
    }
}

fn to_table<T: Serialize>(v: &T) -> toml::Table {
    toml::Table::try_from(v).expect("swell's own scene types always serialise to a TOML table")
}

/// Deserialises `value` as `T`, reporting errors with the full key path (`water.waves[2].speed`).
///
/// serde lets a struct be written as an array, field by position (`lod = [4, 96, 0.5]`), which
/// a scene file must not (issue 37): a key order is not part of the format, and a reader of the
/// file cannot tell which number is which. So the value read is written back and every place
/// where the file holds an array but `T` writes a table is refused, naming its key path.
pub(crate) fn deserialize_at<T: DeserializeOwned + Serialize>(
    value: impl Into<toml::Value>,
    prefix: &str,
    source: &str,
) -> Result<T> {
    let value = value.into();
    let shape = value.clone();
    let parsed: T = serde_path_to_error::deserialize(value).map_err(|e| {
        let inner = e.path().to_string();
        let key = match (prefix.is_empty(), inner.as_str()) {
            (true, _) => inner.clone(),
            (false, ".") => prefix.to_string(),
            (false, p) if p.starts_with('[') => format!("{prefix}{p}"),
            (false, p) => format!("{prefix}.{p}"),
        };
        // toml's own message may end in a line `in `waves.speed``: the key path in front says it
        // already, more fully.
        let message = e.into_inner().to_string();
        let message = message.lines().filter(|l| !l.starts_with("in `")).collect::<Vec<_>>().join(" ");
        Error::Parse { path: source.to_string(), message: format!("{key}: {}", message.trim_end()) }
    })?;
    // A type that cannot be written as TOML (none of the scene's) has no shape to compare with.
    if let Ok(written) = toml::Value::try_from(&parsed) {
        if let Some(key) = array_for_table(&shape, &written, prefix.to_string()) {
            let shown = if key.is_empty() { "the scene".to_string() } else { key };
            return Err(Error::Parse {
                path: source.to_string(),
                message: format!(
                    "{shown}: must be a table (a [section] or {{ key = value, ... }}), found an array; \
                     its fields are named, not given by position"
                ),
            });
        }
    }
    Ok(parsed)
}

/// The key path of the first place where `read` (as the file has it) holds an array and
/// `written` (the same value written back) a table, if any.
fn array_for_table(read: &toml::Value, written: &toml::Value, at: String) -> Option<String> {
    use toml::Value::{Array, Table};
    let join = |key: &str| if at.is_empty() { key.to_string() } else { format!("{at}.{key}") };
    match (read, written) {
        (Array(_), Table(_)) => Some(at),
        (Table(r), Table(w)) => r.iter().find_map(|(k, v)| w.get(k).and_then(|wv| array_for_table(v, wv, join(k)))),
        (Array(r), Array(w)) => {
            r.iter().zip(w).enumerate().find_map(|(i, (v, wv))| array_for_table(v, wv, format!("{at}[{i}]")))
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Shading;
    use crate::water::DropSchedule;

    fn parse(text: &str) -> Result<WaterSpec> {
        WaterSpec::from_table(toml::from_str(text).unwrap(), "test")
    }

    #[test]
    fn takes_disturbances_says_what_the_built_model_does() {
        for name in crate::scene::PRESETS.iter().map(|p| p.name) {
            let Some(water) = crate::scene::preset(name).unwrap().water else { continue };
            let mut model = water.model.build().unwrap();
            let took = model.disturb(0.0, 0.0, 0.1, 1.0).unwrap();
            assert_eq!(water.model.takes_disturbances(), took, "preset {name}");
        }
    }

    #[test]
    fn seeds_a_scene_file_cannot_store_are_refused_not_panicked_on() {
        let too_big = i64::MAX as u64 + 1;
        let models = [
            WaterModelSpec::WaveSet(WaveSetParams { seed: too_big, ..Default::default() }),
            WaterModelSpec::Noise(NoiseParams { seed: too_big, ..Default::default() }),
            WaterModelSpec::Springs(SpringMeshParams {
                drops: Some(DropSchedule { interval: 1.0, radius: 1.0, depth: 0.1, seed: too_big }),
                ..Default::default()
            }),
        ];
        for model in models {
            let e = model.build().err().expect("a seed above i64::MAX is refused").to_string();
            assert!(e.contains("seed") && e.contains(&too_big.to_string()), "{e}");
        }
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

    #[test]
    fn every_model_parses_with_its_defaults_builds_and_round_trips() {
        for name in WATER_MODELS {
            let w = parse(&format!("model = '{name}'\n")).unwrap_or_else(|e| panic!("{name}: {e}"));
            w.model.build().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(WaterSpec::from_table(w.to_table(), "again").unwrap(), w, "{name}");
        }
        let w = parse(
            "model = 'tessendorf'\nloop_period = 30.0\ndispersion = { type = 'finite-depth', depth = 4.0 }\n\
             [[waves]]\namplitude = 0.5\nwavelength = 20.0\ndirection = [1.0, 0.0]\n",
        )
        .unwrap();
        assert_eq!(WaterSpec::from_table(w.to_table(), "again").unwrap(), w);
        let w = parse("model = 'springs'\ncenter = [0.0, 0.0]\nedges = 'free'\ndrops = { interval = 2.0, radius = 1.0, depth = 0.1 }\n")
            .unwrap();
        assert_eq!(WaterSpec::from_table(w.to_table(), "again").unwrap(), w);
        let e = parse("model = 'springs'\ntime_step = 2.0\n").unwrap().model.build().err().unwrap();
        assert!(e.to_string().starts_with("water.time_step = 2 is outside (0, 0.53"), "{e}");
        let e = parse("model = 'radial'\nwave_center = [1.0]\n").unwrap_err();
        assert!(e.to_string().contains("water.wave_center"), "{e}");
        let e = parse("model = 'tessendorf'\ndispersion = { type = 'shallow' }\n").unwrap_err();
        assert!(e.to_string().contains("water.dispersion"), "{e}");
    }
}
