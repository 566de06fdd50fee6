//! Seamless loops: every wave's frequency quantised to a whole number of cycles per loop period
//! T, and time reduced into the first period.
//!
//! Paper 003 eq. 10 (after Tessendorf 2001 §3.3) rounds each frequency *down*,
//! `w = floor(T w0 / 2π) 2π / T`. That freezes every wave slower than the base frequency 2π/T
//! (w becomes 0): a 2 s loop on a sea whose peak period is 8 s would hold its main waves still and
//! move the sea at a fraction of its speed. swell rounds to the *nearest non-zero* multiple instead:
//! no wave freezes, each frequency moves by at most half a quantum (a wave slower than half a
//! quantum speeds up to one cycle per loop), and [`LoopFit`] says when T is too short for the sea
//! to loop without visibly changing its speed.

use std::f64::consts::TAU;

/// Largest relative frequency change (10 %) at the sea's energetic frequencies that a loop makes
/// without a warning: beyond it, waves visibly change speed and the dispersion relation no longer
/// holds to the eye.
pub const MAX_LOOP_SHIFT: f64 = 0.1;

/// Whole number of cycles `m >= 1` that a wave of angular frequency `omega` (rad/s, >= 0) makes
/// in the loop period `period` (s, > 0): the nearest to `omega period / 2π`, at least one.
pub fn loop_cycles(omega: f64, period: f64) -> f64 {
    (omega * period / TAU).round().max(1.0)
}

/// `omega` (rad/s) quantised to the nearest non-zero multiple of `2π / period` (period in s, > 0,
/// checked by the callers, which name their key): every wave, and so the surface, repeats after
/// `period`.
pub fn quantize_to_period(omega: f32, period: f32) -> f32 {
    let period = f64::from(period);
    (loop_cycles(f64::from(omega), period) * TAU / period) as f32
}

/// `t` (s) reduced into the first loop period `[0, period)`: a looping surface at `t` is the
/// surface at this time. A time within a billionth of a period of a loop's start (`k / fps` that a
/// rounding error put beside `n T`) is that start, so the frame after an N-frame loop equals its
/// frame 0 bit for bit.
pub fn loop_time(t: f64, period: f64) -> f64 {
    let r = t.rem_euclid(period);
    let tolerance = 1e-9 * period;
    if r < tolerance || period - r < tolerance {
        0.0
    } else {
        r
    }
}

/// How well a loop period suits a sea: what the warning of [`LoopFit::warning`] is made of.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopFit {
    /// The loop period T, s.
    pub period: f64,
    /// The sea's own period scale, s: the peak period of a spectrum, the longest wave's period of a
    /// wave list.
    pub sea_period: f64,
    /// Largest relative change `|w_q - w| / w` over the sea's energetic frequencies.
    pub largest_shift: f64,
}

impl LoopFit {
    /// The fit of `period` (s) to a sea whose energetic angular frequencies (rad/s, > 0) are
    /// `omegas` and whose period scale is `sea_period` (s).
    pub fn new(period: f64, sea_period: f64, omegas: impl IntoIterator<Item = f64>) -> Self {
        let largest_shift = omegas
            .into_iter()
            .filter(|w| *w > 0.0)
            .map(|w| (loop_cycles(w, period) * TAU / period - w).abs() / w)
            .fold(0.0, f64::max);
        Self { period, sea_period, largest_shift }
    }

    /// The fit of `period` to a spectrum peaking at `peak_omega` (rad/s): its energetic band, from
    /// 0.7 to 3 times the peak frequency (where a JONSWAP or Pierson-Moskowitz sea holds most of its
    /// energy), sampled finely.
    pub fn for_spectrum(period: f64, peak_omega: f64) -> Self {
        const SAMPLES: usize = 400;
        let (lo, hi) = (0.7 * peak_omega, 3.0 * peak_omega);
        let omegas = (0..=SAMPLES).map(|i| lo + (hi - lo) * i as f64 / SAMPLES as f64);
        Self::new(period, TAU / peak_omega, omegas)
    }

    /// A warning for the key `key` (e.g. `water.loop_period`) when the period is shorter than the
    /// sea's period scale, or shifts its frequencies by more than [`MAX_LOOP_SHIFT`]; `None` when
    /// the loop keeps the sea as it is.
    pub fn warning(&self, key: &str) -> Option<String> {
        let shift = self.largest_shift * 100.0;
        let (t, sea) = (self.period, self.sea_period);
        if t < sea {
            Some(format!(
                "{key} = {t} s is shorter than the sea's period of {sea:.3} s: to loop, its waves change \
                 frequency by up to {shift:.0} % (the longest speed up to one cycle per loop); choose a \
                 period several times {sea:.3} s (docs/scene-format.md, Loops)"
            ))
        } else if self.largest_shift > MAX_LOOP_SHIFT {
            Some(format!(
                "{key} = {t} s changes the frequencies of the sea's waves by up to {shift:.0} % to loop (more \
                 than {:.0} %); a longer period keeps their speeds (docs/scene-format.md, Loops)",
                MAX_LOOP_SHIFT * 100.0
            ))
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::Dispersion;

    #[test]
    fn quantized_frequencies_are_the_nearest_non_zero_multiples() {
        let period = 20.0;
        let quantum = TAU / 20.0;
        for k in [0.001f32, 0.01, 0.1, 1.0, 10.0] {
            let w0 = Dispersion::Deep.omega(k);
            let w = quantize_to_period(w0, period);
            let n = f64::from(w) / quantum;
            assert!((n - n.round()).abs() < 1e-4 && n.round() >= 1.0, "k = {k}: {n}");
            // Nearest: at most half a quantum away, except that a slow wave rises to one cycle.
            let slow = f64::from(w0) < quantum / 2.0;
            assert!(slow || (f64::from(w - w0)).abs() <= quantum / 2.0 + 1e-6, "k = {k}");
            assert!(!slow || (f64::from(w) - quantum).abs() < 1e-6, "k = {k}");
        }
    }

    #[test]
    fn a_loop_returns_to_its_start_exactly() {
        assert_eq!(loop_time(20.0, 20.0), 0.0);
        assert_eq!(loop_time(480.0 / 24.0, 20.0), 0.0);
        assert_eq!(loop_time(12.5 * 3.0 + 1e-12, 12.5), 0.0);
        assert_eq!(loop_time(12.5 * 3.0 - 1e-12, 12.5), 0.0);
        assert_eq!(loop_time(25.0, 20.0), 5.0);
        assert_eq!(loop_time(-5.0, 20.0), 15.0);
    }

    #[test]
    fn a_loop_shorter_than_the_sea_warns_and_a_long_one_does_not() {
        let peak = TAU / 8.0; // 8 s peak period
        let short = LoopFit::for_spectrum(2.0, peak);
        assert!(short.warning("water.loop_period").unwrap().contains("shorter than the sea's period of 8.000 s"));
        let medium = LoopFit::for_spectrum(12.0, peak);
        assert!(medium.largest_shift > MAX_LOOP_SHIFT);
        assert!(medium.warning("water.loop_period").unwrap().contains("more than 10 %"));
        let long = LoopFit::for_spectrum(200.0, peak);
        assert!(long.largest_shift < 0.05, "{}", long.largest_shift);
        assert_eq!(long.warning("water.loop_period"), None);
    }
}
