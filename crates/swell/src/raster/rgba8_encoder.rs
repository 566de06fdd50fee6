//! Linear colour to display bytes, exactly as [`DisplayEncoding::encode`] computes them but
//! without a tone curve and a `powf` per channel.
//!
//! The encoding (times exposure, the tone curve, the sRGB curve or `c^(1/gamma)`, rounded to a
//! byte) is non-decreasing in the linear value, so it is fully described by the smallest linear
//! value reaching each byte 1..=255 (its thresholds, found once by bisection over the f32 bit
//! patterns: non-negative floats order as their bits). A channel's byte is the number of those
//! thresholds at or below it. The count comes from a table of buckets, each 1/256 of a binade
//! (the top 16 bits of the value: exponent and 8 mantissa bits), holding the count at the bucket's
//! lower end and the next threshold: as no two thresholds share a bucket (checked when the table
//! is built; adjacent thresholds are at least 0.39 % apart for every valid gamma, a bucket at
//! most 0.39 % wide, and the tone curves only spread them), one compare finishes the count.
//!
//! History (callgrind, one 1280 x 720 `ocean` frame): three `powf` per pixel, 271 M instructions;
//! a binary search over the thresholds, 102 M; a table indexed by sign, exponent and 7 mantissa
//! bits finished by a compare loop, 61 M (about 20 instructions per channel); this table, built
//! once per encoding and read eight channels at a time with AVX2 gathers where the CPU has them.

use glam::Vec3;

use crate::math::DisplayEncoding;

/// Right shift from an f32's bits to its bucket number: keeps sign, exponent and
/// [`MANTISSA_BITS`] mantissa bits.
const BUCKET_SHIFT: u32 = 23 - MANTISSA_BITS;
/// Mantissa bits of a bucket number: a bucket is 2^-8 of a binade wide (0.39 % at most), no
/// wider than the closest pair of thresholds (gamma 1 at the top byte: 1 / 254.5 = 0.393 %).
const MANTISSA_BITS: u32 = 8;
/// Most buckets a table may have: gamma 5 spans 45 binades between its first and last threshold
/// (11,500 buckets, 92 KB); beyond this the caller encodes each channel with the curve.
const MAX_BUCKETS: usize = 1 << 14;

/// The byte thresholds of one [`DisplayEncoding`] and the bucket table that counts them.
#[derive(Debug)]
pub struct Rgba8Encoder {
    encoding: DisplayEncoding,
    /// Per bucket from `first` on: the number of thresholds below the bucket's lower end,
    /// and the bits of the first threshold at or above it (NaN when none is). Interleaved so that
    /// one index (times 8 bytes) reaches both, as the AVX2 gathers read them.
    buckets: Vec<[u32; 2]>,
    /// Bucket number of `buckets[0]` (the bucket of the first threshold).
    first: u32,
}

impl Rgba8Encoder {
    /// The table of `encoding` (its exposure taken as is: metering is resolved before). `None`
    /// when the encoding is not known to be non-decreasing (exposure not positive and finite,
    /// gamma not positive and finite) or its thresholds do not fit the table: the caller then
    /// encodes each channel directly with [`DisplayEncoding::encode`].
    pub fn new(encoding: &DisplayEncoding) -> Option<Self> {
        let encoding = encoding.with_exposure(encoding.exposure);
        let valid_gamma = encoding.gamma.is_none_or(|g| g.is_finite() && g > 0.0);
        if !(encoding.exposure.is_finite() && encoding.exposure > 0.0 && valid_gamma) {
            return None;
        }
        let f = |bits: u32| encoding.encode(f32::from_bits(bits));
        // Negative values and NaN encode to 0 (they clamp to 0 first), as must 0 itself.
        if f(0) != 0 {
            return None;
        }
        let top = f32::INFINITY.to_bits();
        // `lower[k - 1]`: the smallest linear value encoded as k or more; NaN where none is.
        let mut lower = [f32::NAN; 255];
        for (k, slot) in (1..=255u8).zip(lower.iter_mut()) {
            if f(top) < k {
                break;
            }
            // Smallest bit pattern in [0, top] whose encoding reaches k.
            let (mut lo, mut hi) = (0u32, top);
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if f(mid) >= k {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            *slot = f32::from_bits(lo);
        }
        let finite = &lower[..lower.iter().take_while(|t| !t.is_nan()).count()];
        let bucket = |t: f32| t.to_bits() >> BUCKET_SHIFT;
        // One threshold per bucket at most, so that one compare finishes every count.
        if finite.windows(2).any(|p| bucket(p[0]) == bucket(p[1])) {
            return None;
        }
        let (first, last) = match (finite.first(), finite.last()) {
            (Some(&a), Some(&b)) => (bucket(a), bucket(b)),
            _ => (0, 0),
        };
        let n = (last - first) as usize + 1;
        if n > MAX_BUCKETS {
            return None;
        }
        // One merge-like sweep: bucket starts and thresholds both increase.
        let mut buckets = Vec::with_capacity(n);
        let mut k = 0;
        for b in first..=last {
            let start = f32::from_bits(b << BUCKET_SHIFT);
            while k < finite.len() && finite[k] < start {
                k += 1;
            }
            let next = if k < finite.len() { finite[k] } else { f32::NAN };
            buckets.push([k as u32, next.to_bits()]);
        }
        Some(Self { encoding, buckets, first })
    }

    /// Whether this table encodes `encoding` (metering resolved; compared bit for bit).
    pub fn encodes(&self, encoding: &DisplayEncoding) -> bool {
        self.encoding.same_as(encoding)
    }

    /// The byte of linear channel value `c`, equal to `self`'s encoding's
    /// [`DisplayEncoding::encode`].
    #[inline]
    pub fn encode(&self, c: f32) -> u8 {
        // Negative values, zero and NaN all encode to 0 (every threshold is positive).
        if c.is_nan() || c <= 0.0 {
            return 0;
        }
        // Below the first bucket: bucket 0, whose count is 0 and whose next threshold is above c;
        // beyond the last: the last bucket, whose next threshold c passes.
        let i = ((c.to_bits() >> BUCKET_SHIFT).saturating_sub(self.first) as usize).min(self.buckets.len() - 1);
        let [count, next] = self.buckets[i];
        (count + (f32::from_bits(next) <= c) as u32) as u8
    }

    /// Encodes a row of linear colours into RGBA8 (alpha 255); `dst.len()` is `4 * src.len()`.
    pub fn encode_row(&self, src: &[Vec3], dst: &mut [u8]) {
        debug_assert_eq!(dst.len(), 4 * src.len());
        #[cfg(target_arch = "x86_64")]
        // SAFETY: AVX2 checked first (the check is cached by std).
        let done = if crate::math::Isa::Avx2.is_available() { unsafe { self.encode_row_avx2(src, dst) } } else { 0 };
        #[cfg(not(target_arch = "x86_64"))]
        let done = 0;
        for (px, c) in dst[4 * done..].chunks_exact_mut(4).zip(&src[done..]) {
            px.copy_from_slice(&[self.encode(c.x), self.encode(c.y), self.encode(c.z), 255]);
        }
    }

    /// [`Self::encode_row`] for whole groups of 8 pixels (24 channels, three 8-lane vectors),
    /// [`Self::encode`]'s steps lane by lane; returns how many pixels it wrote.
    ///
    /// # Safety
    /// The CPU must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn encode_row_avx2(&self, src: &[Vec3], dst: &mut [u8]) -> usize {
        use std::arch::x86_64::*;

        let groups = src.len() / 8;
        // Vec3 is three packed f32 (glam's scalar Vec3, 12 bytes), so a row is 3 * len floats.
        const _: () = assert!(std::mem::size_of::<Vec3>() == 12);
        let floats = src.as_ptr().cast::<f32>();
        let table = self.buckets.as_ptr().cast::<i32>();
        let first = _mm256_set1_epi32(self.first as i32);
        let last = _mm256_set1_epi32(self.buckets.len() as i32 - 1);
        let zero = _mm256_setzero_si256();
        let mut bytes = [0u32; 24];
        for g in 0..groups {
            for (k, out) in bytes.chunks_exact_mut(8).enumerate() {
                // SAFETY: group g covers floats 24 g .. 24 g + 24 of the 3 * len; the bucket index
                // is clamped to [0, buckets.len() - 1], entries are 8 bytes, the second field at +4.
                unsafe {
                    let v = _mm256_loadu_ps(floats.add(24 * g + 8 * k));
                    let positive = _mm256_castps_si256(_mm256_cmp_ps::<_CMP_GT_OQ>(v, _mm256_setzero_ps()));
                    let bucket = _mm256_srli_epi32::<{ BUCKET_SHIFT as i32 }>(_mm256_castps_si256(v));
                    // Negative values have the sign bit, so a huge bucket number: clamped, then masked.
                    let i = _mm256_min_epu32(_mm256_max_epi32(_mm256_sub_epi32(bucket, first), zero), last);
                    let count = _mm256_i32gather_epi32::<8>(table, i);
                    let next = _mm256_i32gather_ps::<8>(table.add(1).cast::<f32>(), i);
                    // All ones (-1) where the next threshold is reached; NaN thresholds never are.
                    let reached = _mm256_castps_si256(_mm256_cmp_ps::<_CMP_LE_OQ>(next, v));
                    let byte = _mm256_and_si256(_mm256_sub_epi32(count, reached), positive);
                    _mm256_storeu_si256(out.as_mut_ptr().cast(), byte);
                }
            }
            for (p, px) in dst[32 * g..32 * g + 32].chunks_exact_mut(4).enumerate() {
                let [r, gr, b] = [bytes[3 * p], bytes[3 * p + 1], bytes[3 * p + 2]];
                px.copy_from_slice(&(r | gr << 8 | b << 16 | 0xff << 24).to_le_bytes());
            }
        }
        8 * groups
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::ToneCurve;

    /// Values where the encoding changes or could go wrong: dense over [0, 1.33], each threshold
    /// and its neighbouring floats, every bucket's lower end, and the special values.
    fn probes(table: &Rgba8Encoder) -> Vec<f32> {
        let mut values: Vec<f32> = (0..200_000).map(|i| i as f32 / 150_000.0).collect();
        values.extend([-1.0, -0.0, 0.0, f32::NAN, -f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 1e30, 1e-40, -1e-40]);
        // Every threshold is some bucket's next one.
        for t in table.buckets.iter().map(|b| f32::from_bits(b[1])).filter(|t| t.is_finite()) {
            values.extend([t, f32::from_bits(t.to_bits() - 1), f32::from_bits(t.to_bits() + 1)]);
        }
        let n = table.buckets.len() as u32;
        for b in table.first.saturating_sub(2)..table.first + n + 2 {
            let start = f32::from_bits(b << BUCKET_SHIFT);
            values.extend([start, f32::from_bits((b << BUCKET_SHIFT).saturating_sub(1))]);
        }
        values
    }

    fn encoding(exposure: f32, gamma: Option<f32>, tone_curve: ToneCurve) -> DisplayEncoding {
        DisplayEncoding { exposure, auto_exposure: false, tone_curve, gamma }
    }

    #[test]
    fn the_table_encodes_exactly_like_the_direct_curve() {
        for curve in ToneCurve::ALL.iter().copied() {
            for (exposure, gamma) in [(1.0, None), (1.7, None), (1.0, Some(1.0)), (0.6, Some(2.2)), (100.0, Some(5.0))]
            {
                let enc = encoding(exposure, gamma, curve);
                let table = Rgba8Encoder::new(&enc).unwrap();
                assert!(table.encodes(&enc) && !table.encodes(&enc.with_exposure(exposure * 2.0)));
                for c in probes(&table) {
                    assert_eq!(table.encode(c), enc.encode(c), "c = {c}, {enc:?}");
                }
            }
        }
        assert!(Rgba8Encoder::new(&DisplayEncoding::clipped(0.0, None)).is_none());
        assert!(Rgba8Encoder::new(&DisplayEncoding::clipped(1.0, Some(f32::NAN))).is_none());
    }

    #[test]
    fn every_valid_encoding_gets_a_one_compare_table() {
        // `[render]` allows an exposure in [1e-6, 100] times EV100's factor (1e-5 at EV100 24 to
        // 1e6 at -6) and gamma in [1, 5] or sRGB.
        for exposure in [1e-11, 1e-6, 0.01, 0.5, 1.0, 3.0, 100.0, 1e8] {
            for gamma in [None, Some(1.0), Some(1.5), Some(2.2), Some(3.7), Some(5.0)] {
                for curve in ToneCurve::ALL.iter().copied() {
                    let enc = encoding(exposure, gamma, curve);
                    assert!(Rgba8Encoder::new(&enc).is_some(), "{enc:?}");
                }
            }
        }
    }

    #[test]
    fn rows_encode_like_single_channels_whatever_their_length() {
        let table = Rgba8Encoder::new(&encoding(1.3, None, ToneCurve::Aces)).unwrap();
        let values = probes(&table);
        // Lengths around the 8-pixel groups of the AVX2 path, and one long row of every probe.
        for len in [0, 1, 7, 8, 9, 16, 23, values.len() / 3] {
            let src: Vec<Vec3> =
                (0..len).map(|i| Vec3::new(values[3 * i], values[3 * i + 1], values[3 * i + 2])).collect();
            let mut dst = vec![0u8; 4 * len];
            table.encode_row(&src, &mut dst);
            for (i, c) in src.iter().enumerate() {
                let want = [table.encode(c.x), table.encode(c.y), table.encode(c.z), 255];
                assert_eq!(dst[4 * i..4 * i + 4], want, "pixel {i} of {len}: {c}");
            }
        }
    }
}
