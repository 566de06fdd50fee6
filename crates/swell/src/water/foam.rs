//! Foam from the folding of a choppy surface, with optional persistence.
//!
//! Where horizontal displacement squeezes the surface, the Jacobian of the horizontal map
//! `J = (1 + Dxx)(1 + Dzz) - Dxz²` falls below 1; at 0 the surface folds over (a breaking crest).
//! Tessendorf 2001 §3.5 suggests marking foam where J drops below a threshold. swell turns that into
//! a coverage in [0, 1] that rises linearly over [`FOAM_RAMP`] below the threshold (soft-edged
//! whitecaps rather than a hard mask), and optionally keeps foam after the crest has passed, fading
//! as `exp(-dt / fade)`.

use rayon::prelude::*;

/// Jacobian range (dimensionless) below the threshold over which coverage goes from 0 to 1: wide
/// enough that whitecaps have soft edges on a 256² grid, narrow enough that they stay on the crests.
pub const FOAM_RAMP: f32 = 0.25;

/// Foam coverage in [0, 1] for Jacobian `jacobian` and threshold `threshold`.
#[inline]
pub fn foam_coverage(jacobian: f32, threshold: f32) -> f32 {
    ((threshold - jacobian) / FOAM_RAMP).clamp(0.0, 1.0)
}

/// A foam field on a periodic n x n grid, updated once per time step.
///
/// With persistence the field depends on the sequence of updates (foam left behind by earlier
/// crests), not on t alone: an update at a time not after the previous one starts afresh, so a
/// replay from the start reproduces the same foam.
#[derive(Clone, Debug)]
pub struct FoamField {
    /// Grid side.
    pub n: usize,
    /// Coverage in [0, 1], row-major `[z][x]`.
    pub values: Vec<f32>,
    /// Fade time constant (s); 0 keeps nothing from one update to the next.
    pub fade: f32,
    /// Coverage threshold on the Jacobian.
    pub threshold: f32,
    last_time: Option<f64>,
}

impl FoamField {
    /// An empty n x n field.
    pub fn new(n: usize, threshold: f32, fade: f32) -> Self {
        Self { n, values: vec![0.0; n * n], fade, threshold, last_time: None }
    }

    /// Updates the field for time `t` (s) from the Jacobian at each sample `(i, j)` (column, row).
    pub fn update(&mut self, t: f64, jacobian: impl Fn(usize, usize) -> f32 + Sync) {
        let decay = self.start_update(t);
        let (n, threshold) = (self.n, self.threshold);
        self.values.par_chunks_mut(n).enumerate().for_each(|(j, row)| {
            for (i, v) in row.iter_mut().enumerate() {
                *v = foam_coverage(jacobian(i, j), threshold).max(*v * decay);
            }
        });
    }

    /// Starts an update for time `t` (s) done by the caller (the FFT ocean fuses it into its own
    /// pass): records t and returns the factor in [0, 1] to apply to the previous coverage, so
    /// each value becomes `foam_coverage(J, threshold).max(old * decay)`, as [`FoamField::update`].
    pub fn start_update(&mut self, t: f64) -> f32 {
        let decay = match self.last_time {
            Some(t0) if t > t0 && self.fade > 0.0 => (-(t - t0) / f64::from(self.fade)).exp() as f32,
            _ => 0.0,
        };
        self.last_time = Some(t);
        decay
    }

    /// Mean coverage over the field, in [0, 1].
    pub fn mean(&self) -> f32 {
        (self.values.iter().map(|&v| f64::from(v)).sum::<f64>() / self.values.len() as f64) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coverage_ramps_below_the_threshold_and_fades_after() {
        assert_eq!(foam_coverage(1.0, 0.5), 0.0);
        assert_eq!(foam_coverage(0.5, 0.5), 0.0);
        assert_eq!(foam_coverage(0.5 - FOAM_RAMP, 0.5), 1.0);
        let mut f = FoamField::new(2, 0.5, 1.0);
        f.update(0.0, |_, _| -1.0);
        assert!(f.values.iter().all(|&v| v == 1.0));
        f.update(1.0, |_, _| 1.0);
        assert!(f.values.iter().all(|&v| (v - (-1.0f32).exp()).abs() < 1e-6));
        // Going back in time starts afresh.
        f.update(0.5, |_, _| 1.0);
        assert!(f.values.iter().all(|&v| v == 0.0));
    }
}
