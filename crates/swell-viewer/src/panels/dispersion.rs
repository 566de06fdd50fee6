//! The dispersion relation editor (`dispersion = { type = ..., depth = ... }`), shared by the models
//! whose wave speeds follow from their wavelengths (Tessendorf, Airy, wave sets).

use eframe::egui::Ui;
use swell::spectrum::Dispersion;

use super::{fields, keys};

/// Depth (m) offered when switching from deep water to a relation that needs one.
pub const DEFAULT_DEPTH_M: f32 = 10.0;

/// The relation's scene-file name (`type`).
pub fn dispersion_name(d: &Dispersion) -> &'static str {
    match d {
        Dispersion::Deep => "deep",
        Dispersion::FiniteDepth { .. } => "finite-depth",
        Dispersion::Capillary { .. } => "capillary",
    }
}

/// `d` switched to the relation named `name`, keeping its depth where both have one.
pub fn switch_dispersion(d: Dispersion, name: &str) -> Dispersion {
    let depth = match d {
        Dispersion::Deep => DEFAULT_DEPTH_M,
        Dispersion::FiniteDepth { depth } | Dispersion::Capillary { depth } => depth,
    };
    match name {
        "finite-depth" => Dispersion::FiniteDepth { depth },
        "capillary" => Dispersion::Capillary { depth },
        _ => Dispersion::Deep,
    }
}

/// Two grid rows: the relation and, when it has one, the depth (m, > 0; refused by validation
/// otherwise). Returns whether `d` changed.
pub fn show(ui: &mut Ui, d: &mut Dispersion) -> bool {
    let mut name = dispersion_name(d);
    let options = [
        ("deep", "deep: w² = g k"),
        ("finite-depth", "finite depth: w² = g k tanh kD"),
        ("capillary", "capillary: w² = (g k + σ/ρ k³) tanh kD"),
    ];
    let mut changed = false;
    if fields::choice(ui, "dispersion", &mut name, &options) {
        *d = switch_dispersion(*d, name);
        changed = true;
    }
    keys::edits("water.dispersion", &["type"]);
    if let Dispersion::FiniteDepth { depth } | Dispersion::Capillary { depth } = d {
        changed |= fields::number(ui, "water depth D", depth, 0.1, " m");
        keys::edits("water.dispersion", &["depth"]);
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn switching_keeps_the_depth_and_names_match_the_scene_format() {
        let d = switch_dispersion(Dispersion::Deep, "finite-depth");
        assert_eq!(d, Dispersion::FiniteDepth { depth: DEFAULT_DEPTH_M });
        let c = switch_dispersion(Dispersion::FiniteDepth { depth: 3.0 }, "capillary");
        assert_eq!(c, Dispersion::Capillary { depth: 3.0 });
        assert_eq!(switch_dispersion(c, "deep"), Dispersion::Deep);
        for d in [Dispersion::Deep, d, c] {
            let text = toml::to_string(&toml::Table::try_from(d).unwrap()).unwrap();
            let t: toml::Table = toml::from_str(&text).unwrap();
            assert_eq!(t["type"].as_str(), Some(dispersion_name(&d)));
        }
    }
}
