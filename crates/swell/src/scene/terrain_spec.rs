//! The `[terrain]` section: which generator, how large, where, and how it looks.
//!
//! The generator's own keys sit directly in `[terrain]` beside `generator`, `size` and `extent`;
//! placement is in `[terrain.transform]` and the look in `[terrain.material]`:
//!
//! ```toml
//! [terrain]
//! generator = "diamond-square"
//! size = 257
//! extent = [400.0, 400.0]
//! roughness = 0.5
//! seed = 7
//! [terrain.transform]
//! translate = [0.0, -5.0, 0.0]
//! [terrain.material]
//! shading = "flat"
//! [terrain.far_land]
//! reach = 8000.0
//! ```
//!
//! `[terrain.far_land]`, when present, continues the field to the horizon
//! ([`crate::terrain::far_land`]).

use std::path::{Path, PathBuf};

use glam::Vec2;
use serde::{Deserialize, Serialize};

use super::water_spec::deserialize_at;
use super::TerrainMaterial;
use crate::error::{check_finite_vec, check_positive, check_range, Error, Result};
use crate::math::Transform;
use crate::terrain::{
    load_heightmap, ChannelParams, DiamondSquareParams, FarLandParams, FlatParams, GeneratorParams, HeightField,
    HeightmapOverrides, HillsParams, NoiseTerrainParams, RandomAverageParams, SlopeParams,
};
pub use crate::terrain::{DEFAULT_TERRAIN_EXTENT, DEFAULT_TERRAIN_SIZE};

/// A heightmap file: `generator = "heightmap"`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeightmapSpec {
    /// The PNG (8- or 16-bit grayscale), relative to the scene file's directory unless absolute.
    pub path: PathBuf,
    /// Metres per full grey range; overrides the sidecar's. Required without a sidecar.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height_scale: Option<f32>,
    /// Height (m) of grey 0; overrides the sidecar's. Default: the sidecar's, else 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height_offset: Option<f32>,
}

/// A heightmap file is a generator like the others: its size comes from the image.
impl GeneratorParams for HeightmapSpec {
    fn validate(&self, key: &str) -> Result<()> {
        if self.path.as_os_str().is_empty() {
            return Err(Error::invalid(format!("{key}.path"), "is empty; give the heightmap PNG's path"));
        }
        if let Some(s) = self.height_scale {
            check_positive(&format!("{key}.height_scale"), s)?;
        }
        if let Some(o) = self.height_offset {
            check_range(&format!("{key}.height_offset"), o, -1.0e6, 1.0e6)?;
        }
        Ok(())
    }

    fn check_size(&self, key: &str, size: u32) -> Result<()> {
        Err(Error::invalid(key, format!("{size} given, but a heightmap takes its size from the image; remove the key")))
    }

    fn generate(&self, _size: u32, extent: Option<Vec2>) -> Result<HeightField> {
        let overrides =
            HeightmapOverrides { height_scale: self.height_scale, height_offset: self.height_offset, extent };
        load_heightmap(&self.path, overrides)
            // A file that cannot be read is named with the key that names it.
            .map_err(|e| match e {
                Error::Io { .. } | Error::Image { .. } => Error::invalid("terrain.path", e.to_string()),
                other => other,
            })
    }
}

/// Declares the terrain generators: one line each, `Variant = "name" => ParamsType`, with the
/// variant's doc. Generates [`TerrainGenerator`], [`TERRAIN_GENERATORS`], parsing by name and the
/// dispatch to each generator's [`GeneratorParams`].
macro_rules! terrain_generators {
    ($( $(#[$doc:meta])* $variant:ident = $name:literal => $params:ty ),+ $(,)?) => {
        /// The generator and its parameters, selected by `terrain.generator`.
        #[derive(Clone, Debug, PartialEq, Serialize)]
        #[serde(tag = "generator")]
        pub enum TerrainGenerator {
            $( $(#[$doc])* #[serde(rename = $name)] $variant($params), )+
        }

        /// The names `terrain.generator` accepts.
        pub const TERRAIN_GENERATORS: &[&str] = &[$($name),+];

        impl TerrainGenerator {
            /// The generator's parameters behind their common interface.
            pub fn params(&self) -> &dyn GeneratorParams {
                match self { $(Self::$variant(p) => p,)+ }
            }

            /// The `terrain.generator` name of this generator.
            pub fn name(&self) -> &'static str {
                match self { $(Self::$variant(_) => $name,)+ }
            }

            /// Reads the generator's keys (everything in `[terrain]` but the common keys).
            pub fn from_table(generator: &str, rest: toml::Table, source: &str) -> Result<Self> {
                Ok(match generator {
                    $($name => Self::$variant(deserialize_at(rest, "terrain", source)?),)+
                    other => {
                        return Err(Error::Parse {
                            path: source.to_string(),
                            message: format!(
                                "terrain.generator = \"{other}\" is not a generator; valid: {}",
                                TERRAIN_GENERATORS.join(", ")
                            ),
                        })
                    }
                })
            }
        }
    };
}

terrain_generators! {
    /// `generator = "diamond-square"` (paper 001 §2.1).
    DiamondSquare = "diamond-square" => DiamondSquareParams,
    /// `generator = "random-average"` (paper 001 §1.3.1).
    RandomAverage = "random-average" => RandomAverageParams,
    /// `generator = "noise"` (paper 001 §1.3.2).
    Noise = "noise" => NoiseTerrainParams,
    /// `generator = "hills"` (paper 001 §1.3.3).
    Hills = "hills" => HillsParams,
    /// `generator = "flat"`.
    Flat = "flat" => FlatParams,
    /// `generator = "slope"`.
    Slope = "slope" => SlopeParams,
    /// `generator = "heightmap"`: a PNG heightmap file and its sidecar.
    Heightmap = "heightmap" => HeightmapSpec,
    /// `generator = "channel"` (paper 004's river between banks).
    Channel = "channel" => ChannelParams,
}

impl TerrainGenerator {
    /// Checks the generator's parameters, naming keys under `terrain`.
    pub fn validate(&self) -> Result<()> {
        self.params().validate("terrain")
    }
}

/// The whole `[terrain]` section.
#[derive(Clone, Debug, PartialEq)]
pub struct TerrainSpec {
    /// Vertices per side; `None` = [`DEFAULT_TERRAIN_SIZE`] (heightmaps take the image's size and
    /// refuse this key). Diamond-square needs 2^n + 1.
    pub size: Option<u32>,
    /// Horizontal extent (x, z) in metres before the transform; `None` = [`DEFAULT_TERRAIN_EXTENT`]
    /// (heightmaps: the sidecar's, else the default).
    pub extent: Option<Vec2>,
    /// Placement in the world.
    pub transform: Transform,
    /// Look.
    pub material: TerrainMaterial,
    /// Generator and its parameters.
    pub generator: TerrainGenerator,
    /// Land beyond the field to the horizon (`[terrain.far_land]`); `None` (no such table): the
    /// terrain ends at its field's edge.
    pub far_land: Option<FarLandParams>,
}

/// Keys of `[terrain]` that are not the generator's.
const COMMON_KEYS: [&str; 2] = ["size", "extent"];

impl TerrainSpec {
    /// Reads the `[terrain]` table; `source` names the file in errors.
    pub fn from_table(mut table: toml::Table, source: &str) -> Result<Self> {
        let generator = match table.remove("generator") {
            Some(toml::Value::String(s)) => s,
            Some(v) => {
                return Err(Error::Parse {
                    path: source.into(),
                    message: format!(
                        "terrain.generator = {v} must be a string, one of {}",
                        TERRAIN_GENERATORS.join(", ")
                    ),
                })
            }
            None => {
                return Err(Error::Parse {
                    path: source.into(),
                    message: format!("terrain.generator is missing; valid: {}", TERRAIN_GENERATORS.join(", ")),
                })
            }
        };
        let mut common = toml::Table::new();
        for key in COMMON_KEYS {
            if let Some(v) = table.remove(key) {
                common.insert(key.to_string(), v);
            }
        }
        let common: CommonKeys = deserialize_at(common, "terrain", source)?;
        let transform = match table.remove("transform") {
            Some(v) => deserialize_at(v, "terrain.transform", source)?,
            None => Transform::IDENTITY,
        };
        let material = match table.remove("material") {
            Some(v) => deserialize_at(v, "terrain.material", source)?,
            None => TerrainMaterial::default(),
        };
        let far_land = match table.remove("far_land") {
            Some(v) => Some(deserialize_at(v, "terrain.far_land", source)?),
            None => None,
        };
        Ok(Self {
            size: common.size,
            extent: common.extent,
            transform,
            material,
            generator: TerrainGenerator::from_table(&generator, table, source)?,
            far_land,
        })
    }

    /// The `[terrain]` table as written to a scene file.
    pub fn to_table(&self) -> toml::Table {
        let mut t = to_table(&self.generator);
        t.extend(to_table(&CommonKeys { size: self.size, extent: self.extent }));
        t.insert("transform".into(), toml::Value::Table(to_table(&self.transform)));
        t.insert("material".into(), toml::Value::Table(to_table(&self.material)));
        if let Some(far) = &self.far_land {
            t.insert("far_land".into(), toml::Value::Table(to_table(far)));
        }
        t
    }

    /// Checks everything that does not need a file read.
    pub fn validate(&self) -> Result<()> {
        if let Some(size) = self.size {
            self.generator.params().check_size("terrain.size", size)?;
        }
        if let Some(e) = self.extent {
            check_finite_vec("terrain.extent", &e.to_array())?;
            check_positive("terrain.extent[0]", e.x)?;
            check_positive("terrain.extent[1]", e.y)?;
        }
        self.transform.validate("terrain.transform")?;
        self.material.validate("terrain.material")?;
        if let Some(far) = &self.far_land {
            far.validate("terrain.far_land")?;
        }
        self.generator.validate()
    }

    /// Runs the generator (or loads the heightmap) and returns the field in model space.
    pub fn build(&self) -> Result<HeightField> {
        self.validate()?;
        self.generator.params().generate(self.size.unwrap_or(DEFAULT_TERRAIN_SIZE), self.extent)
    }

    /// Makes a relative heightmap path relative to `dir` (the scene file's directory).
    pub fn resolve_paths(&mut self, dir: &Path) {
        if let TerrainGenerator::Heightmap(h) = &mut self.generator {
            if h.path.is_relative() {
                h.path = dir.join(&h.path);
            }
        }
    }
}

/// `size` and `extent`, read apart from the generator's keys.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct CommonKeys {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    size: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    extent: Option<Vec2>,
}

fn to_table<T: Serialize>(v: &T) -> toml::Table {
    toml::Table::try_from(v).expect("swell's own scene types always serialise to a TOML table")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<TerrainSpec> {
        let t = TerrainSpec::from_table(toml::from_str(text).unwrap(), "test")?;
        t.validate()?;
        Ok(t)
    }

    #[test]
    fn a_section_round_trips_and_builds() {
        let t = parse(
            "generator = 'diamond-square'\nsize = 33\nextent = [50.0, 40.0]\nroughness = 0.6\nseed = 9\n\
             [transform]\ntranslate = [1.0, -2.0, 0.0]\nrotate_deg = [0.0, 30.0, 0.0]\n[material]\nshading = 'flat'\n\
             [far_land]\nreach = 900.0\nrelief = 12.0\n",
        )
        .unwrap();
        assert_eq!(TerrainSpec::from_table(t.to_table(), "again").unwrap(), t);
        let f = t.build().unwrap();
        assert_eq!((f.cols(), f.extent()), (33, Vec2::new(50.0, 40.0)));
        for g in ["random-average", "noise", "hills", "flat", "slope", "channel"] {
            let t = parse(&format!("generator = '{g}'\nsize = 17\n")).unwrap();
            assert_eq!(TerrainSpec::from_table(t.to_table(), "again").unwrap(), t);
            assert_eq!(t.build().unwrap().cols(), 17, "{g}");
        }
    }

    #[test]
    fn errors_name_the_key_and_the_rule() {
        let e = parse("generator = 'diamond-square'\nsize = 100\n").unwrap_err().to_string();
        assert!(e.starts_with("terrain.size: 100 is not a diamond-square size") && e.contains("2^n + 1"), "{e}");
        let e = parse("generator = 'volcano'\n").unwrap_err().to_string();
        assert!(e.contains("volcano") && e.contains("diamond-square, random-average"), "{e}");
        let e = parse("generator = 'noise'\noctaves = 40\n").unwrap_err().to_string();
        assert_eq!(e, "terrain.octaves = 40 is outside [1, 16]");
        let e = parse("generator = 'flat'\nroughness = 0.5\n").unwrap_err().to_string();
        assert!(e.contains("unknown field `roughness`"), "{e}");
        let e = parse("generator = 'heightmap'\npath = 'x.png'\nsize = 65\n").unwrap_err().to_string();
        assert!(e.starts_with("terrain.size: 65 given, but a heightmap"), "{e}");
        let e = parse("generator = 'flat'\n[transform]\nscale = [1.0, -1.0, 1.0]\n").unwrap_err().to_string();
        assert!(e.starts_with("terrain.transform.scale[1] = -1"), "{e}");
        let e = parse("generator = 'flat'\n[material]\nrock_slope_deg = 95.0\n").unwrap_err().to_string();
        assert!(e.starts_with("terrain.material.rock_slope_deg = 95"), "{e}");
        let e = parse("generator = 'flat'\n[far_land]\nreach = 2e6\n").unwrap_err().to_string();
        assert_eq!(e, "terrain.far_land.reach = 2000000 is outside [1, 1000000]");
        let e = parse("generator = 'flat'\n[far_land]\nrelief = -1.0\n").unwrap_err().to_string();
        assert_eq!(e, "terrain.far_land.relief = -1 is outside [0, 100000]");
        let e = parse("generator = 'flat'\n[far_land]\nfeature_size = 0.5\n").unwrap_err().to_string();
        assert_eq!(e, "terrain.far_land.feature_size = 0.5 is outside [1, 1000000]");
        let e = parse("generator = 'flat'\n[far_land]\nheight = 3.0\n").unwrap_err().to_string();
        assert!(e.contains("terrain.far_land") && e.contains("unknown field `height`"), "{e}");
    }

    #[test]
    fn every_generator_gives_the_same_field_on_one_and_two_threads() {
        for g in ["diamond-square", "random-average", "noise", "hills", "flat", "slope", "channel"] {
            let t = parse(&format!("generator = '{g}'\nsize = 129\n")).unwrap();
            let run = |threads| {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                pool.install(|| t.build()).unwrap()
            };
            let (a, b) = (run(1), run(2));
            assert!(a.heights().iter().zip(b.heights()).all(|(x, y)| x.to_bits() == y.to_bits()), "{g}");
        }
    }

    #[test]
    fn relative_heightmap_paths_follow_the_scene_file() {
        let mut t = parse("generator = 'heightmap'\npath = 'maps/a.png'\nheight_scale = 10.0\n").unwrap();
        t.resolve_paths(Path::new("/scenes"));
        assert!(matches!(&t.generator, TerrainGenerator::Heightmap(h) if h.path == Path::new("/scenes/maps/a.png")));
    }
}
