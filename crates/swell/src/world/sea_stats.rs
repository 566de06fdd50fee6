//! The sea state a spectral scene realises (`swell stats`): the spectrum's expectations beside the
//! statistics of the very field a bake or an export of the scene writes.

use serde::Serialize;

use crate::error::{Error, Result};
use crate::mesh::SurfaceMesh;
use crate::scene::{Scene, WaterModelSpec, WaterSpec};
use crate::spectrum::WindSea;
use crate::water::{FftOcean, WaveModel};

/// What `swell stats` reports (JSON keys as named).
///
/// The realised statistics (`hs_realised_m`, heights, `foam_coverage`) are taken over the scene's
/// water grid (`[water] size` and `cells`), displaced exactly as `swell bake` and `swell export`
/// displace it at that time, all cascades summed: what the maps hold, not the FFT grid alone.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SeaStats {
    /// Time of the field, s.
    pub time_s: f64,
    /// Significant height `4 sqrt(var(y))` of the displaced grid's heights, m.
    pub hs_realised_m: f64,
    /// The spectrum's own expectation, m: for a parametric spectrum `4 sqrt(m0)` over the wave
    /// vectors the cascades hold; for `spectrum = "table"` the input table's Hs as wavespectra
    /// computes it (`hs()`, with its tail), whatever part of it the cascades hold.
    pub hs_expected_m: f64,
    /// Peak period of the sea's spectrum, s (for TMA, the peak of the finite-depth spectrum).
    pub peak_period_s: f64,
    /// The input spectrum's smooth peak period (wavespectra's `tp()`), s; `null` without an
    /// interior peak. For a table, on the table's own grid; for a parametric spectrum, sampled
    /// from 0.01 to 2 Hz in 2 % steps and every 5°.
    pub tp_expected_s: Option<f64>,
    /// The same of the realised sea: every wave the cascades hold, binned on that grid
    /// ([`FftOcean::realised_spectrum`]), s.
    pub tp_realised_s: Option<f64>,
    /// The input's mean direction at the peak (wavespectra's `dpm()`), degrees the waves come
    /// from, nautical (0 = from north, −Z; 90 = from east, +X), [0, 360).
    pub dpm_expected_deg: Option<f64>,
    /// The same of the realised sea, degrees.
    pub dpm_realised_deg: Option<f64>,
    /// The input's directional spread (wavespectra's `dspr()`), degrees.
    pub dspr_expected_deg: Option<f64>,
    /// The same of the realised sea, degrees.
    pub dspr_realised_deg: Option<f64>,
    /// Mean height of the displaced grid, m.
    pub mean_height_m: f64,
    /// Lowest height of the displaced grid, m.
    pub min_height_m: f64,
    /// Highest height of the displaced grid, m.
    pub max_height_m: f64,
    /// Mean foam coverage of the grid's vertices in [0, 1] (the baked foam map's mean).
    pub foam_coverage: f64,
    /// FFT grid side N, as built (with `[water.blender]`, from Blender's keys).
    pub grid: u32,
    /// Side of the first cascade's patch, m, as built.
    pub patch_size_m: f32,
    /// Number of cascades.
    pub cascades: u32,
    /// Size of the water grid the statistics are over, m (x, z).
    pub surface_size_m: [f32; 2],
    /// Cells of that grid (x, z).
    pub surface_cells: [u32; 2],
}

/// The sea state of `scene`'s FFT ocean at time `t` (s): the error names `water.model` when the
/// scene has no spectral sea.
pub fn sea_stats(scene: &Scene, t: f64) -> Result<SeaStats> {
    if !t.is_finite() {
        return Err(Error::out_of_range("time", t, "finite seconds"));
    }
    let water = scene.water.as_ref().ok_or_else(|| Error::invalid("water", "the scene has no [water] table"))?;
    water_sea_stats(water, t)
}

/// [`sea_stats`] of a scene's `[water]` alone (what [`crate::world::Water`] keeps).
pub fn water_sea_stats(water: &WaterSpec, t: f64) -> Result<SeaStats> {
    if !t.is_finite() {
        return Err(Error::out_of_range("time", t, "finite seconds"));
    }
    let WaterModelSpec::Fft(params) = &water.model else {
        return Err(Error::invalid("water.model", "swell stats needs a spectral sea: model = \"fft\""));
    };
    let mut ocean = FftOcean::new(params)?;
    ocean.advance(t)?;
    let grid = water.surface.grid()?;
    let mut mesh = SurfaceMesh::new(grid);
    mesh.displace(&ocean, t);
    let count = mesh.positions.len() as f64;
    let heights = || mesh.positions.iter().map(|p| f64::from(p.y));
    let mean = heights().sum::<f64>() / count;
    let variance = heights().map(|h| (h - mean).powi(2)).sum::<f64>() / count;
    let foam = if mesh.has_foam { mesh.foam.iter().map(|&f| f64::from(f)).sum::<f64>() / count } else { 0.0 };
    let state = ocean.sea_state();
    let axes = ocean.spectrum().stats_grid();
    let expected = axes.stats();
    let realised = ocean.realised_spectrum(&axes).stats();
    let tabulated = matches!(ocean.spectrum().wind_sea, WindSea::Table(_));
    Ok(SeaStats {
        time_s: t,
        hs_realised_m: 4.0 * variance.sqrt(),
        hs_expected_m: if tabulated { expected.hs_m } else { state.hs_expected },
        peak_period_s: state.peak_period,
        tp_expected_s: expected.tp_s,
        tp_realised_s: realised.tp_s,
        dpm_expected_deg: expected.dpm_deg,
        dpm_realised_deg: realised.dpm_deg,
        dspr_expected_deg: expected.dspr_deg,
        dspr_realised_deg: realised.dspr_deg,
        mean_height_m: mean,
        min_height_m: heights().fold(f64::INFINITY, f64::min),
        max_height_m: heights().fold(f64::NEG_INFINITY, f64::max),
        foam_coverage: foam,
        grid: ocean.params().grid,
        patch_size_m: ocean.params().patch_size,
        cascades: ocean.params().cascades,
        surface_size_m: grid.size.to_array(),
        surface_cells: [grid.cells_x, grid.cells_z],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::World;

    fn scene(extra: &str) -> Scene {
        let text = format!(
            "[water]\nmodel = 'fft'\ngrid = 64\npatch_size = 120.0\nsize = [90.0, 70.0]\ncells = [45, 35]\n{extra}"
        );
        Scene::from_toml(&text, "t").unwrap()
    }

    #[test]
    fn stats_describe_the_field_a_bake_writes_with_every_cascade() {
        let s = scene("wind_speed = 16.0\ncascades = 3\nchoppiness = 1.3\n");
        let stats = sea_stats(&s, 9.0).unwrap();
        let mut world = World::new(s).unwrap();
        world.advance(9.0).unwrap();
        let mesh = world.patch_mesh().unwrap().unwrap();
        let n = mesh.positions.len() as f64;
        let mean = mesh.positions.iter().map(|p| f64::from(p.y)).sum::<f64>() / n;
        let var = mesh.positions.iter().map(|p| (f64::from(p.y) - mean).powi(2)).sum::<f64>() / n;
        assert_eq!(stats.hs_realised_m, 4.0 * var.sqrt());
        assert_eq!(stats.foam_coverage, mesh.foam.iter().map(|&f| f64::from(f)).sum::<f64>() / n);
        assert!(stats.foam_coverage > 0.0);
        assert_eq!((stats.surface_size_m, stats.surface_cells, stats.cascades), ([90.0, 70.0], [45, 35], 3));
    }

    #[test]
    fn tma_reports_its_own_peak_period() {
        let deep = sea_stats(&scene("spectrum = 'jonswap'\nwind_speed = 14.0\ndepth = 1000.0\n"), 0.0).unwrap();
        let shallow = sea_stats(&scene("spectrum = 'tma'\nwind_speed = 14.0\ndepth = 3.0\n"), 0.0).unwrap();
        assert!(
            shallow.peak_period_s < 0.99 * deep.peak_period_s,
            "{} vs {}",
            shallow.peak_period_s,
            deep.peak_period_s
        );
    }

    #[test]
    fn a_scene_without_a_spectral_sea_is_refused_by_key() {
        let e = sea_stats(&crate::scene::preset("sea").unwrap(), 0.0).unwrap_err().to_string();
        assert!(e.starts_with("water.model"), "{e}");
        let e = sea_stats(&scene(""), f64::NAN).unwrap_err().to_string();
        assert!(e.starts_with("time = NaN"), "{e}");
    }
}
