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
        name: "ocean",
        description: "spectral (FFT) ocean: a JONSWAP wind sea of 14 m/s with choppy crests and foam",
        toml: include_str!("../../presets/ocean.toml"),
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
