//! Wave spectra and the physics they share: what frequency a wave of a given length has
//! ([`Dispersion`]), and (with the FFT ocean) how much energy each wave carries.

mod dispersion;

pub use dispersion::{quantize_to_period, Dispersion, SURFACE_TENSION, WATER_DENSITY};
