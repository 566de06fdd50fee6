//! Blender's Ocean modifier parameters (`[water.blender]`), mapped onto swell's FFT ocean so that a
//! Blender scene can be carried over.
//!
//! Blender's modifier (a port of the Houdini Ocean Toolkit, with spectra from EncinoWaves) is read
//! here with Blender's meaning of each key (Blender manual, "Ocean Modifier"; Python API
//! `bpy.types.OceanModifier`):
//!
//! - the simulation grid has `resolution²` samples per side (Blender 2.8+; FFTW takes any size),
//!   which swell rounds up to the next power of two so that the grid is never coarser than Blender's;
//! - heights are scaled so that the largest |height| at t = 0 is `wave_scale` metres (Blender's
//!   "normalise factor"): the spectrum's own level is discarded;
//! - `wave_alignment x 10` is the exponent p of `|cos θ|^p` (0: waves in every direction);
//! - `damping` removes that fraction of the waves travelling against the wind;
//! - `sharpen_peak_jonswap x 10` is the JONSWAP peak enhancement γ, clamped to [1, 6] as Blender does.
//!
//! The spectra themselves are swell's textbook ones (JONSWAP, Pierson-Moskowitz, TMA, Phillips);
//! where Blender's formulas differ (listed in `docs/scene-format.md`, "Blender parity") swell does
//! what is physically right, so the same keys give the same kind of sea, not the same numbers.

use serde::{Deserialize, Serialize};

use crate::error::{check_count, check_range, Error, Result};
use crate::spectrum::{SpectrumKind, Spreading};

/// Smallest and largest `resolution`: `resolution²` must give a grid in swell's 16..2048.
pub const BLENDER_RESOLUTION_RANGE: (u32, u32) = (4, 45);

/// Blender's JONSWAP peak enhancement is clamped to this range (Blender `ocean_spectrum.cc`).
const BLENDER_GAMMA_RANGE: (f32, f32) = (1.0, 6.0);

/// The Ocean modifier's simulation keys with Blender's names, defaults and meaning.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BlenderOcean {
    /// Blender's "Resolution", in [4, 45]: the grid has `resolution²` samples per side, rounded
    /// up to a power of two (7 -> 49 -> 64). Default 7.
    pub resolution: u32,
    /// Side of the simulated (tiling) patch, m, in [1, 100000]. Default 50.
    pub spatial_size: f32,
    /// Largest |height| at t = 0, m, in [0, 100]; every output scales with it. Default 1.
    pub wave_scale: f32,
    /// Shortest wavelength scale l, m, in [0, 100]: Phillips's `exp(-k² l²)` cutoff. Default 0.01.
    pub wave_scale_min: f32,
    /// Alignment a in [0, 10]: waves follow `|cos θ|^(10 a)` about the wind. Default 0.
    pub wave_alignment: f32,
    /// Wind direction, degrees from +X towards +Z, in [-360, 360] (Blender's "Direction" with
    /// Blender's -Y as swell's +Z, the glTF axes). Default 0.
    pub wave_direction_deg: f32,
    /// Fraction in [0, 1] of the waves against the wind removed (only when `wave_alignment > 0`,
    /// as in Blender). Default 0.5.
    pub damping: f32,
    /// Horizontal displacement factor, in [0, 2] (Blender allows more; beyond 2 the surface
    /// folds everywhere). Default 1.
    pub choppiness: f32,
    /// Wind speed, m/s, in [0.5, 60]; swell takes it as U10. Default 30.
    pub wind_velocity: f32,
    /// Water depth, m, in [0.1, 10000], used by the dispersion relation (and by TMA). Default 200.
    pub depth: f32,
    /// Spectrum: Blender's "Turbulent Ocean" is `phillips`, "Established Ocean"
    /// `pierson-moskowitz`, "Established Ocean (Sharp Peaks)" `jonswap`, "Shallow Water" `tma`
    /// (Blender's `texel-marsen-arsloe` is read too). Default `phillips`.
    pub spectrum: SpectrumKind,
    /// Fetch, km, in [0.1, 10000] (JONSWAP and TMA). Default 120.
    pub fetch_jonswap: f32,
    /// Peak sharpening s in [0, 1]: γ = 10 s clamped to [1, 6] (JONSWAP and TMA). Default 0 (γ = 1).
    pub sharpen_peak_jonswap: f32,
    /// Blender's "Random Seed" (`seed` is accepted too). Default 0. swell draws its own random
    /// numbers, so the sea has the same statistics as Blender's, not the same waves.
    #[serde(alias = "seed")]
    pub random_seed: u32,
}

impl Default for BlenderOcean {
    fn default() -> Self {
        Self {
            resolution: 7,
            spatial_size: 50.0,
            wave_scale: 1.0,
            wave_scale_min: 0.01,
            wave_alignment: 0.0,
            wave_direction_deg: 0.0,
            damping: 0.5,
            choppiness: 1.0,
            wind_velocity: 30.0,
            depth: 200.0,
            spectrum: SpectrumKind::Phillips,
            fetch_jonswap: 120.0,
            sharpen_peak_jonswap: 0.0,
            random_seed: 0,
        }
    }
}

impl BlenderOcean {
    /// swell's grid side for `resolution`: `resolution²` rounded up to a power of two.
    pub fn grid(&self) -> u32 {
        (self.resolution * self.resolution).next_power_of_two()
    }

    /// Checks every key, naming it `key.name` (normally `water.blender.name`).
    pub fn validate(&self, key: &str) -> Result<()> {
        let k = |name: &str| format!("{key}.{name}");
        let (lo, hi) = BLENDER_RESOLUTION_RANGE;
        check_count(&k("resolution"), self.resolution, lo, hi)?;
        check_range(&k("spatial_size"), self.spatial_size, 1.0, 100_000.0)?;
        check_range(&k("wave_scale"), self.wave_scale, 0.0, 100.0)?;
        check_range(&k("wave_scale_min"), self.wave_scale_min, 0.0, 100.0)?;
        check_range(&k("wave_alignment"), self.wave_alignment, 0.0, 10.0)?;
        check_range(&k("wave_direction_deg"), self.wave_direction_deg, -360.0, 360.0)?;
        check_range(&k("damping"), self.damping, 0.0, 1.0)?;
        check_range(&k("choppiness"), self.choppiness, 0.0, 2.0)?;
        check_range(&k("wind_velocity"), self.wind_velocity, 0.5, 60.0)?;
        check_range(&k("depth"), self.depth, 0.1, 10_000.0)?;
        check_range(&k("fetch_jonswap"), self.fetch_jonswap, 0.1, 10_000.0)?;
        check_range(&k("sharpen_peak_jonswap"), self.sharpen_peak_jonswap, 0.0, 1.0)?;
        if self.spectrum == SpectrumKind::Table {
            return Err(Error::invalid(
                k("spectrum"),
                "Blender's Ocean modifier has no tabulated spectrum: give spectrum = \"table\" in [water], without [water.blender]",
            ));
        }
        Ok(())
    }

    /// The JONSWAP peak enhancement γ Blender uses: `10 x sharpen_peak_jonswap`, clamped to
    /// [1, 6] as Blender does.
    pub fn gamma(&self) -> f32 {
        let (lo, hi) = BLENDER_GAMMA_RANGE;
        (10.0 * self.sharpen_peak_jonswap).clamp(lo, hi)
    }

    /// The directional spreading Blender applies: `|cos θ|^p`, p = 10 x alignment, and against
    /// the wind a factor `(1 - damping)^p` for Phillips (Blender damps the cosine before raising it)
    /// or `1 - damping` for the other spectra, none when p = 0 (Blender `ocean.cc`, `ocean_spectrum.cc`).
    pub fn spreading(&self) -> Spreading {
        let exponent = 10.0 * f64::from(self.wave_alignment);
        let keep = 1.0 - f64::from(self.damping);
        let against = match self.spectrum {
            _ if exponent == 0.0 => 1.0,
            SpectrumKind::Phillips => keep.powf(exponent),
            _ => keep,
        };
        Spreading::CosPower { exponent, against }
    }
}
