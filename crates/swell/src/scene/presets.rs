//! Built-in scenes. Each is an ordinary scene file under `crates/swell/presets/`, so every preset
//! doubles as an example of the format and is read by the same parser as a user's file.

use super::Scene;
use crate::error::{Error, Result};

/// A built-in scene: its name, a one-line description and its TOML text.
pub struct Preset {
    /// Name used with `--preset`.
    pub name: &'static str,
    /// One line saying what it shows.
    pub description: &'static str,
    /// The scene file.
    pub toml: &'static str,
}

/// Every preset, in the order `swell presets` lists them.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "sea",
        description: "open sea: 10 Gerstner waves from a westerly wind under a clear sky",
        toml: include_str!("../../presets/sea.toml"),
    },
    Preset {
        name: "lake",
        description: "lake: 6 Gerstner waves generated from a light breeze (wave-set)",
        toml: include_str!("../../presets/lake.toml"),
    },
    Preset {
        name: "tessendorf",
        description: "ocean swell: 8 Gerstner waves in Tessendorf's form, finite-depth dispersion, loops every 60 s",
        toml: include_str!("../../presets/tessendorf.toml"),
    },
    Preset {
        name: "airy",
        description: "pond ripples: 6 linear waves with capillary-gravity dispersion",
        toml: include_str!("../../presets/airy.toml"),
    },
    Preset {
        name: "steep-sines",
        description: "paper 003's steep sum of sines A ((sin S + 1) / 2)^k",
        toml: include_str!("../../presets/steep-sines.toml"),
    },
    Preset {
        name: "pool",
        description: "paper 002's pool: a radial sine wave over [-1, 1]^2 seen through a 20 degree lens",
        toml: include_str!("../../presets/pool.toml"),
    },
    Preset {
        name: "noise",
        description: "drifting Perlin-noise water (5 octaves)",
        toml: include_str!("../../presets/noise.toml"),
    },
    Preset {
        name: "springs",
        description: "Hooke spring lattice with drops falling every 4 s",
        toml: include_str!("../../presets/springs.toml"),
    },
    Preset {
        name: "river",
        description: "paper 004's river between two oscillating banks",
        toml: include_str!("../../presets/river.toml"),
    },
    Preset {
        name: "paper-000-fig-4-1",
        description: "paper 000 figure 4.1: main wave along (1,1) plus waves along (1,0) and (0,1)",
        toml: include_str!("../../presets/paper-000-fig-4-1.toml"),
    },
    Preset {
        name: "paper-000-fig-4-2",
        description: "paper 000 figure 4.2: a single long, gentle wave along (1,1)",
        toml: include_str!("../../presets/paper-000-fig-4-2.toml"),
    },
    Preset {
        name: "paper-000-fig-4-3",
        description: "paper 000 figure 4.3: steep main wave plus waves along (1,0) and (-1,2)",
        toml: include_str!("../../presets/paper-000-fig-4-3.toml"),
    },
    Preset {
        name: "paper-000-fig-4-4",
        description: "paper 000 figure 4.4: main wave plus four waves fanned around (1,1)",
        toml: include_str!("../../presets/paper-000-fig-4-4.toml"),
    },
    Preset {
        name: "paper-000-fig-4-5",
        description: "paper 000 figure 4.5: main wave plus nine waves of various lengths and directions",
        toml: include_str!("../../presets/paper-000-fig-4-5.toml"),
    },
    // Times of day under the physical sky (issue 18).
    Preset {
        name: "noon",
        description: "open sea at noon under Preetham's physical clear sky, the sun high and white",
        toml: include_str!("../../presets/noon.toml"),
    },
    Preset {
        name: "evening",
        description: "open sea in the evening: a low orange sun ahead and its glitter path (Preetham sky)",
        toml: include_str!("../../presets/evening.toml"),
    },
    Preset {
        name: "hazy",
        description: "open sea on a hazy afternoon: turbidity 7 and aerial perspective",
        toml: include_str!("../../presets/hazy.toml"),
    },
    // Terrain presets (issue 5).
    Preset {
        name: "terrain",
        description: "a diamond-square landscape with no water, flat-shaded in paper 001's look",
        toml: include_str!("../../presets/terrain.toml"),
    },
    Preset {
        name: "valley-lake",
        description: "a lake flooding a diamond-square valley, small Gerstner waves",
        toml: include_str!("../../presets/valley-lake.toml"),
    },
    Preset {
        name: "coast",
        description: "swell running up a sloping sea floor to a sandy beach",
        toml: include_str!("../../presets/coast.toml"),
    },
    Preset {
        name: "ocean",
        description: "spectral (FFT) ocean: a JONSWAP wind sea of 14 m/s with choppy crests and foam",
        toml: include_str!("../../presets/ocean.toml"),
    },
    Preset {
        name: "flotsam",
        description: "100 crates adrift on the spectral (FFT) ocean: floating bodies on the water as drawn",
        toml: include_str!("../../presets/flotsam.toml"),
    },
    Preset {
        name: "ocean-blender",
        description: "FFT ocean given by Blender's Ocean modifier keys ([water.blender]): aligned Phillips sea",
        toml: include_str!("../../presets/ocean-blender.toml"),
    },
];

/// The scene of preset `name`, parsed and validated.
pub fn preset(name: &str) -> Result<Scene> {
    let p = PRESETS.iter().find(|p| p.name == name).ok_or_else(|| Error::UnknownPreset {
        name: name.to_string(),
        available: PRESETS.iter().map(|p| p.name).collect::<Vec<_>>().join(", "),
    })?;
    Scene::from_toml(p.toml, &format!("preset {name}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_parses_validates_and_round_trips() {
        for p in PRESETS {
            let s = preset(p.name).unwrap_or_else(|e| panic!("preset {}: {e}", p.name));
            let again = Scene::from_toml(&s.to_toml(), "round trip").unwrap();
            assert_eq!(again, s, "preset {} does not round-trip", p.name);
        }
    }

    #[test]
    fn unknown_presets_list_the_valid_names() {
        let e = preset("tsunami").err().unwrap().to_string();
        assert!(e.contains("tsunami") && e.contains("sea"), "{e}");
    }
}
