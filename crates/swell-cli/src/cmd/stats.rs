//! `swell stats`: the sea state a spectral scene realises, as JSON.

use swell::scene::WaterModelSpec;
use swell::water::{FftOcean, WaveModel};
use swell::{Error, Result};

use super::load_scene;
use crate::args::StatsArgs;

pub fn run(a: StatsArgs) -> Result<()> {
    if !a.time.is_finite() {
        return Err(Error::out_of_range("--time", a.time, "finite seconds"));
    }
    let scene = load_scene(&a.source)?;
    let params = match scene.water.as_ref().map(|w| &w.model) {
        Some(WaterModelSpec::Fft(p)) => p.clone(),
        _ => return Err(Error::invalid("water.model", "swell stats needs a spectral sea: model = \"fft\"")),
    };
    let mut ocean = FftOcean::new(&params)?;
    ocean.advance(a.time)?;
    let s = ocean.sea_state();
    let json = serde_json::json!({
        "time_s": s.time,
        "hs_realised_m": s.hs_realised,
        "hs_expected_m": s.hs_expected,
        "peak_period_s": s.peak_period,
        "mean_height_m": s.mean_height,
        "min_height_m": s.min_height,
        "max_height_m": s.max_height,
        "foam_coverage": s.foam_coverage,
        // As built: with [water.blender] these come from Blender's keys.
        "grid": ocean.params().grid,
        "patch_size_m": ocean.params().patch_size,
        "cascades": ocean.params().cascades,
    });
    println!("{}", serde_json::to_string_pretty(&json).expect("plain JSON values"));
    Ok(())
}
