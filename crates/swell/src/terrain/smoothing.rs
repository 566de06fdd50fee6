//! Neighbour averaging, step 2 of paper 001's "simple" algorithm (§1.3.1): each height becomes the
//! mean of itself and its neighbours (up to 9 values; fewer at the border). Paper 001 §2.1 applies
//! the same pass after diamond-square to soften it.

use rayon::prelude::*;

/// Most smoothing passes a scene may ask for; each pass widens the blur by one vertex, and 64 passes
/// already flatten all but the largest features.
pub const MAX_SMOOTHING_PASSES: u32 = 64;

/// Applies `passes` box-averaging passes to the `cols` x `rows` row-major `heights`, in place.
///
/// Each pass reads only the previous pass's values (never values already updated in this pass), so
/// the result does not depend on the order, or number of threads, that rows are processed in.
pub fn smooth(heights: &mut Vec<f32>, cols: usize, rows: usize, passes: u32) {
    debug_assert_eq!(heights.len(), cols * rows);
    if passes == 0 {
        return;
    }
    let mut next = vec![0.0f32; heights.len()];
    for _ in 0..passes {
        let src = &*heights;
        next.par_chunks_mut(cols).enumerate().for_each(|(j, out)| {
            let (j0, j1) = (j.saturating_sub(1), (j + 1).min(rows - 1));
            for (i, o) in out.iter_mut().enumerate() {
                let (i0, i1) = (i.saturating_sub(1), (i + 1).min(cols - 1));
                let mut sum = 0.0;
                for jj in j0..=j1 {
                    sum += src[jj * cols + i0..=jj * cols + i1].iter().sum::<f32>();
                }
                *o = sum / ((j1 - j0 + 1) * (i1 - i0 + 1)) as f32;
            }
        });
        std::mem::swap(heights, &mut next);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn averaging_keeps_planes_and_shrinks_spikes() {
        // A plane is its own 3x3 average in the interior.
        let (c, r) = (6, 5);
        let mut h: Vec<f32> = (0..c * r).map(|k| (k % c) as f32 * 2.0 + (k / c) as f32).collect();
        let before = h.clone();
        smooth(&mut h, c, r, 1);
        for j in 1..r - 1 {
            for i in 1..c - 1 {
                assert!((h[j * c + i] - before[j * c + i]).abs() < 1e-5);
            }
        }
        // A spike spreads into its 9 neighbours, keeping the total.
        let mut s = vec![0.0; 25];
        s[12] = 9.0;
        smooth(&mut s, 5, 5, 1);
        assert!((s[12] - 1.0).abs() < 1e-6 && (s[6] - 1.0).abs() < 1e-6 && s[0] == 0.0);
    }
}
