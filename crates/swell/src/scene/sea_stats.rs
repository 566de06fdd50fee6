//! The sea state a spectral scene realises at a time: what `swell stats` prints, for every
//! front end (CLI, C, Python) from one place.

use serde::Serialize;

use super::{Scene, WaterModelSpec};
use crate::error::{Error, Result};
use crate::water::{FftOcean, WaveModel};

/// The sea state of a scene's FFT ocean at one time, with the JSON keys of `swell stats`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SeaStats {
    /// Time of the fields, s.
    pub time_s: f64,
    /// Significant height `4 sqrt(var(h))` realised on the grid, m.
    pub hs_realised_m: f64,
    /// The spectrum's expectation `4 sqrt(m0)` over the grid's wave vectors, m.
    pub hs_expected_m: f64,
    /// Peak period of the spectrum, s.
    pub peak_period_s: f64,
    /// Mean height, m.
    pub mean_height_m: f64,
    /// Lowest height on the grid, m.
    pub min_height_m: f64,
    /// Highest height on the grid, m.
    pub max_height_m: f64,
    /// Mean foam coverage in [0, 1].
    pub foam_coverage: f64,
    /// FFT grid side as built (with `[water.blender]`, from Blender's keys), samples.
    pub grid: u32,
    /// Patch side as built, m.
    pub patch_size_m: f32,
    /// Cascades as built.
    pub cascades: u32,
}

impl SeaStats {
    /// The sea state of `scene`'s FFT ocean at time `t` (s, finite). An error names `water.model`
    /// when the scene has no spectral sea (`model = "fft"`), and `t` when it is not finite.
    pub fn of_scene(scene: &Scene, t: f64) -> Result<Self> {
        if !t.is_finite() {
            return Err(Error::out_of_range("t", t, "finite seconds"));
        }
        let params = match scene.water.as_ref().map(|w| &w.model) {
            Some(WaterModelSpec::Fft(p)) => p,
            _ => return Err(Error::invalid("water.model", "swell stats needs a spectral sea: model = \"fft\"")),
        };
        let mut ocean = FftOcean::new(params)?;
        ocean.advance(t)?;
        let s = ocean.sea_state();
        let built = ocean.params();
        Ok(Self {
            time_s: s.time,
            hs_realised_m: s.hs_realised,
            hs_expected_m: s.hs_expected,
            peak_period_s: s.peak_period,
            mean_height_m: s.mean_height,
            min_height_m: s.min_height,
            max_height_m: s.max_height,
            foam_coverage: s.foam_coverage,
            grid: built.grid,
            patch_size_m: built.patch_size,
            cascades: built.cascades,
        })
    }

    /// Pretty-printed JSON, exactly what `swell stats` prints.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("plain JSON values")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ocean_preset_has_stats_and_the_sea_preset_is_refused() {
        let s = SeaStats::of_scene(&crate::scene::preset("ocean").unwrap(), 2.5).unwrap();
        assert_eq!(s.time_s, 2.5);
        assert!(s.hs_realised_m > 0.0 && s.min_height_m < 0.0 && s.max_height_m > 0.0);
        let v: serde_json::Value = serde_json::from_str(&s.to_json()).unwrap();
        assert_eq!(v["grid"], s.grid);
        let e = SeaStats::of_scene(&crate::scene::preset("sea").unwrap(), 0.0).unwrap_err();
        assert_eq!(e.to_string(), "water.model: swell stats needs a spectral sea: model = \"fft\"");
    }
}
