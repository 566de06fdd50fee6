//! Seeded gradient noise (Perlin's 2002 "improved noise") with its analytic gradient, and fBm.
//!
//! Used by the noise water surface (paper 003 §1.1.1) and the noise terrain generator (paper 001
//! §1.3.2). Written from Perlin, "Improving Noise", SIGGRAPH 2002: a seeded permutation of 0..256,
//! the 12 cube-edge gradients, the quintic fade `6t^5 - 15t^4 + 10t^3`.

use glam::Vec3;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// A noise field fixed by its seed.
#[derive(Clone, Debug)]
pub struct Perlin {
    /// The permutation, repeated twice so `perm[perm[x] + y]` needs no wrapping.
    perm: [u8; 512],
}

/// Cube-edge gradient directions (Perlin 2002); none is axis-aligned, so no lattice direction is
/// preferred.
const GRADIENTS: [Vec3; 16] = [
    Vec3::new(1.0, 1.0, 0.0),
    Vec3::new(-1.0, 1.0, 0.0),
    Vec3::new(1.0, -1.0, 0.0),
    Vec3::new(-1.0, -1.0, 0.0),
    Vec3::new(1.0, 0.0, 1.0),
    Vec3::new(-1.0, 0.0, 1.0),
    Vec3::new(1.0, 0.0, -1.0),
    Vec3::new(-1.0, 0.0, -1.0),
    Vec3::new(0.0, 1.0, 1.0),
    Vec3::new(0.0, -1.0, 1.0),
    Vec3::new(0.0, 1.0, -1.0),
    Vec3::new(0.0, -1.0, -1.0),
    // Padding to 16 repeats four of the twelve, as in the reference implementation.
    Vec3::new(1.0, 1.0, 0.0),
    Vec3::new(0.0, -1.0, 1.0),
    Vec3::new(-1.0, 1.0, 0.0),
    Vec3::new(0.0, -1.0, -1.0),
];

fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

fn fade_derivative(t: f32) -> f32 {
    30.0 * t * t * (t * (t - 2.0) + 1.0)
}

impl Perlin {
    /// The noise field of `seed`.
    pub fn new(seed: u64) -> Self {
        let mut p: Vec<u8> = (0..=255).collect();
        p.shuffle(&mut ChaCha8Rng::seed_from_u64(seed));
        let mut perm = [0u8; 512];
        for i in 0..512 {
            perm[i] = p[i & 255];
        }
        Self { perm }
    }

    fn gradient(&self, x: i32, y: i32, z: i32) -> Vec3 {
        let p = &self.perm;
        let h = p[p[p[(x & 255) as usize] as usize + (y & 255) as usize] as usize + (z & 255) as usize];
        GRADIENTS[(h & 15) as usize]
    }

    /// Noise at `p` and its gradient; the value lies in about [-1, 1], is 0 at lattice points and
    /// repeats every 256 units along each axis.
    pub fn noise3_with_gradient(&self, p: Vec3) -> (f32, Vec3) {
        let cell = p.floor();
        // The lattice repeats every 256 cells: the cell is taken modulo 256 before it becomes an
        // integer, so that a point 10^30 m out (whose cell saturates i32) cannot overflow `ix + 1`.
        let wrapped = cell.rem_euclid(Vec3::splat(256.0));
        let (ix, iy, iz) = (wrapped.x as i32, wrapped.y as i32, wrapped.z as i32);
        let f = p - cell;
        let (u, v, w) = (fade(f.x), fade(f.y), fade(f.z));
        let (du, dv, dw) = (fade_derivative(f.x), fade_derivative(f.y), fade_derivative(f.z));
        // Corner gradients and their dot products with the offset to the point.
        let corner = |dx: i32, dy: i32, dz: i32| {
            let g = self.gradient(ix + dx, iy + dy, iz + dz);
            let off = f - Vec3::new(dx as f32, dy as f32, dz as f32);
            (g.dot(off), g)
        };
        let (n000, g000) = corner(0, 0, 0);
        let (n100, g100) = corner(1, 0, 0);
        let (n010, g010) = corner(0, 1, 0);
        let (n110, g110) = corner(1, 1, 0);
        let (n001, g001) = corner(0, 0, 1);
        let (n101, g101) = corner(1, 0, 1);
        let (n011, g011) = corner(0, 1, 1);
        let (n111, g111) = corner(1, 1, 1);
        // Trilinear interpolation written as a polynomial in (u, v, w) so its derivative is direct.
        let (k0, k1, k2, k3) = (n000, n100 - n000, n010 - n000, n001 - n000);
        let k4 = n110 - n010 - n100 + n000;
        let k5 = n011 - n001 - n010 + n000;
        let k6 = n101 - n001 - n100 + n000;
        let k7 = n111 - n011 - n101 - n110 + n100 + n001 + n010 - n000;
        let value = k0 + k1 * u + k2 * v + k3 * w + k4 * u * v + k5 * v * w + k6 * w * u + k7 * u * v * w;
        let (g0, g1, g2, g3) = (g000, g100 - g000, g010 - g000, g001 - g000);
        let g4 = g110 - g010 - g100 + g000;
        let g5 = g011 - g001 - g010 + g000;
        let g6 = g101 - g001 - g100 + g000;
        let g7 = g111 - g011 - g101 - g110 + g100 + g001 + g010 - g000;
        let grad = g0
            + g1 * u
            + g2 * v
            + g3 * w
            + g4 * u * v
            + g5 * v * w
            + g6 * w * u
            + g7 * u * v * w
            + Vec3::new(
                du * (k1 + k4 * v + k6 * w + k7 * v * w),
                dv * (k2 + k5 * w + k4 * u + k7 * w * u),
                dw * (k3 + k6 * u + k5 * v + k7 * u * v),
            );
        (value, grad)
    }

    /// Noise at `p`, in about [-1, 1].
    pub fn noise3(&self, p: Vec3) -> f32 {
        self.noise3_with_gradient(p).0
    }

    /// 2-D noise at (x, y): the 3-D field on the plane z = 0.
    pub fn noise2(&self, x: f32, y: f32) -> f32 {
        self.noise3(Vec3::new(x, y, 0.0))
    }

    /// Fractional Brownian motion: `sum_{o < octaves} persistence^o noise(lacunarity^o p)` and its
    /// gradient. The value lies within ± `sum persistence^o`.
    pub fn fbm3_with_gradient(&self, p: Vec3, octaves: u32, persistence: f32, lacunarity: f32) -> (f32, Vec3) {
        let (mut value, mut grad) = (0.0, Vec3::ZERO);
        let (mut amp, mut freq) = (1.0, 1.0);
        for octave in 0..octaves {
            // Offset each octave so that lattice zeros of different octaves do not line up.
            let shift = Vec3::splat(octave as f32 * 19.19);
            let (n, g) = self.noise3_with_gradient(p * freq + shift);
            value += amp * n;
            grad += g * (amp * freq);
            amp *= persistence;
            freq *= lacunarity;
        }
        (value, grad)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gradient_matches_finite_differences() {
        let n = Perlin::new(7);
        let eps = 1e-3;
        for i in 0..200 {
            let p = Vec3::new(i as f32 * 0.173 - 3.1, (i * 7 % 13) as f32 * 0.311, i as f32 * 0.057);
            let (_, g) = n.noise3_with_gradient(p);
            let fd = Vec3::new(
                n.noise3(p + Vec3::X * eps) - n.noise3(p - Vec3::X * eps),
                n.noise3(p + Vec3::Y * eps) - n.noise3(p - Vec3::Y * eps),
                n.noise3(p + Vec3::Z * eps) - n.noise3(p - Vec3::Z * eps),
            ) / (2.0 * eps);
            assert!((g - fd).length() < 2e-2, "at {p}: analytic {g} vs {fd}");
        }
    }

    #[test]
    fn seeded_bounded_and_zero_on_the_lattice() {
        let (a, b) = (Perlin::new(1), Perlin::new(1));
        let c = Perlin::new(2);
        let mut differs = false;
        for i in 0..500 {
            let p = Vec3::new(i as f32 * 0.37, i as f32 * 0.21, i as f32 * 0.13);
            assert_eq!(a.noise3(p), b.noise3(p));
            differs |= a.noise3(p) != c.noise3(p);
            assert!(a.noise3(p).abs() <= 1.1);
        }
        assert!(differs);
        assert_eq!(a.noise3(Vec3::new(3.0, 5.0, 7.0)), 0.0);
    }

    /// Found by the water_query fuzz target (issue 37): at 10^10 and more the cell saturated i32
    /// and `ix + 1` overflowed. Now any finite point gives finite noise, and the lattice's period
    /// of 256 holds across negative and large cells alike.
    #[test]
    fn any_finite_point_gives_finite_noise_and_the_period_holds() {
        let n = Perlin::new(3);
        for x in [1.0e10, -1.0e10, 3.0e9, f32::MAX, -f32::MAX, 2.2e-38, 1.0e30] {
            let (v, g) = n.noise3_with_gradient(Vec3::new(x, 0.5 * x, 1.25));
            assert!(v.is_finite() && g.is_finite(), "at {x}: {v} {g}");
        }
        for k in [-3.0, 1.0, 4096.0] {
            // Quarters, so that p + 256 k is exact in f32 and only the period is tested.
            let p = Vec3::new(10.25, -7.75, 0.5);
            assert_eq!(n.noise3(p), n.noise3(p + Vec3::new(256.0 * k, -256.0 * k, 0.0)), "k = {k}");
        }
    }
}
