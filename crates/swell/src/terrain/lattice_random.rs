//! Random numbers addressed by position: the same (seed, stream, x, y) always gives the same
//! number, whatever order or thread computes it. This is what lets diamond-square fill a level in
//! parallel and still match the one-thread result bit for bit.

/// The golden-ratio increment of SplitMix64 (Steele, Lea and Flood, "Fast splittable pseudorandom
/// number generators", OOPSLA 2014).
const GOLDEN: u64 = 0x9E37_79B9_7F4A_7C15;

/// SplitMix64's output function: a bijective 64-bit mixer whose output bits each depend on every
/// input bit (same paper).
#[inline]
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A uniform number in [-1, 1) for lattice point (x, y) of `stream` (e.g. a diamond-square level)
/// under `seed`; the same as `LatticeRandom::new(seed).at(stream, x, y)`.
pub fn lattice_random(seed: u64, stream: u32, x: u32, y: u32) -> f32 {
    LatticeRandom::new(seed).at(stream, x, y)
}

/// The lattice random numbers of one seed, with the seed's mixing done once.
#[derive(Clone, Copy, Debug)]
pub struct LatticeRandom {
    mixed_seed: u64,
}

impl LatticeRandom {
    /// The numbers of `seed`.
    pub fn new(seed: u64) -> Self {
        Self { mixed_seed: mix(seed.wrapping_add(GOLDEN)) }
    }

    /// A uniform number in [-1, 1) for lattice point (x, y) of `stream`.
    ///
    /// `mix(mix(seed + GOLDEN) + key * GOLDEN)` with `key = stream << 42 | y << 21 | x`, so x and
    /// y below 2^21 and streams below 2^22 never share a key. The top 24 bits give the float, so
    /// every value is an exact multiple of 2^-23.
    #[inline]
    pub fn at(&self, stream: u32, x: u32, y: u32) -> f32 {
        debug_assert!(x < 1 << 21 && y < 1 << 21 && stream < 1 << 22);
        let key = ((stream as u64) << 42) | ((y as u64) << 21) | x as u64;
        let z = mix(self.mixed_seed.wrapping_add(key.wrapping_mul(GOLDEN)));
        (z >> 40) as f32 * (2.0 / (1u64 << 24) as f32) - 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_in_range_and_seed_dependent() {
        let n = 200_000;
        let mut sum = 0.0f64;
        let mut sum_sq = 0.0f64;
        for k in 0..n {
            let r = lattice_random(7, 3, k % 1000, k / 1000);
            assert!((-1.0..1.0).contains(&r));
            sum += r as f64;
            sum_sq += (r * r) as f64;
        }
        // Uniform on [-1, 1): mean 0, variance 1/3; tolerances are ~5 standard errors.
        assert!((sum / n as f64).abs() < 0.007);
        assert!((sum_sq / n as f64 - 1.0 / 3.0).abs() < 0.004);
        assert_ne!(lattice_random(7, 0, 1, 2), lattice_random(8, 0, 1, 2));
        assert_ne!(lattice_random(7, 0, 1, 2), lattice_random(7, 0, 2, 1));
        assert_eq!(lattice_random(7, 0, 1, 2), lattice_random(7, 0, 1, 2));
    }
}
