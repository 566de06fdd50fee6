//! Wave spectra and the physics they share: what frequency a wave of a given length has
//! ([`Dispersion`]), and (with the FFT ocean) how much energy each wave carries.
//!
//! Ocean wave spectra: how the variance of the sea surface is spread over frequency and direction.
//!
//! Everything here is in physical units so that a sea synthesised from a spectrum has real heights
//! in metres (no normalisation to a maximum height):
//!
//! - a **frequency spectrum** `S(w)` (m² s/rad) gives the variance per unit angular frequency, with
//!   `m0 = ∫ S(w) dw` the variance of the height (m²) and `Hs = 4 sqrt(m0)` the significant wave height;
//! - a **wavenumber spectrum** `Φ(k) = S(w(k)) dw/dk` (m³/rad) is the same variance per unit wavenumber;
//! - a **directional spreading** `D(θ)` (1/rad, `∫ D dθ = 1` over (-π, π]) shares it over directions
//!   without changing it;
//! - the **directional wavenumber spectrum** `F(kx, kz) = Φ(k) D(θ) / k` (m⁴/rad², i.e. m² per
//!   (rad/m)²) is what a spectral ocean samples: `∫∫ F dkx dkz = m0`.
//!
//! The wind-sea models ([`Phillips`], [`PiersonMoskowitz`], [`Jonswap`], [`Tma`]) and a [`Swell`]
//! component are composed with a [`Spreading`] into a [`DirectionalSpectrum`]; a measured sea
//! comes as tables `E(f, θ)` ([`SpectrumTable`], from CSV or a buoy's files) summed in a
//! [`TableSum`], and any sea's parameters (Hs, Tp, Dpm, Dspr) are taken on a
//! [`GriddedSpectrum`] as wavespectra defines them.

mod dispersion;

pub use dispersion::{Dispersion, SURFACE_TENSION, WATER_DENSITY};
pub use loop_period::{loop_cycles, loop_time, quantize_to_period, LoopFit, MAX_LOOP_SHIFT};
mod directional;
mod gridded_spectrum;
mod jonswap;
mod loop_period;
mod ndbc;
mod phillips;
mod pierson_moskowitz;
mod spectrum_csv;
mod spectrum_kind;
mod spectrum_table;
mod spreading;
mod swell;
mod tma;

pub use directional::{DirectionalSpectrum, WindSea};
pub use gridded_spectrum::{GriddedSpectrum, SpectrumStats, TAIL_FROM_HZ};
pub use jonswap::{Jonswap, JONSWAP_GAMMA, JONSWAP_SIGMA_ABOVE, JONSWAP_SIGMA_BELOW};
pub use ndbc::{parse_ndbc, NdbcEstimator, NdbcFiles, NdbcLayout, NdbcRecord, MAX_NDBC_FILE_BYTES};
pub use phillips::{Phillips, PHILLIPS_ALPHA};
pub use pierson_moskowitz::{u19_5_from_u10, PiersonMoskowitz, PM_ALPHA, PM_BETA};
pub use spectrum_csv::{parse_spectrum_csv, spectrum_csv, MAX_CSV_ROWS};
pub use spectrum_kind::SpectrumKind;
pub use spectrum_table::{
    DirectionAxis, DirectionConvention, FrequencyAxis, SpectrumTable, TableConvention, TableSum, FREQ_RANGE_HZ,
    MAX_EFTH,
};
pub use spreading::{Spreading, SpreadingFunction};
pub use swell::Swell;
pub use tma::{tma_depth_factor, Tma};

/// Standard gravity in f64 (m/s²), the same value as [`crate::GRAVITY`]; spectra are set up in f64.
pub const G: f64 = crate::GRAVITY as f64;

/// Spectral moment `∫ S(w) w^n dw` of a frequency spectrum by Simpson's rule on [w_lo, w_hi] with
/// `steps` (even) intervals. Used to normalise shapes and by tests; not on any hot path.
pub fn frequency_moment(s: impl Fn(f64) -> f64, n: i32, w_lo: f64, w_hi: f64, steps: usize) -> f64 {
    let steps = steps + steps % 2;
    let h = (w_hi - w_lo) / steps as f64;
    let f = |w: f64| s(w) * w.powi(n);
    let mut sum = f(w_lo) + f(w_hi);
    for i in 1..steps {
        let w = w_lo + i as f64 * h;
        sum += if i % 2 == 1 { 4.0 } else { 2.0 } * f(w);
    }
    sum * h / 3.0
}
