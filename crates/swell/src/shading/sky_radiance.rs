//! The sky made ready to look up: what the renderer calls, per pixel of background and per
//! reflected ray, instead of the model.
//!
//! The `gradient` sky is evaluated directly (it is a square root and a blend). The `preetham` sky
//! costs about a dozen `exp`, `acos` and `tan` per direction, too slow for every pixel of a
//! 1280x720 frame at 60 frames per second on two cores, so it is tabulated once per distinct
//! `[sky]` over the upper hemisphere and looked up bilinearly. The table is indexed by the
//! stereographic projection of the direction from the nadir, `(x, z) / (1 + y)`, which maps the
//! hemisphere onto the unit disc with cells of 1.8° at the horizon and 3.6° at the zenith at
//! [`TABLE_SIDE`] = 128: one division per lookup and no trigonometry.

use crate::math::{fast_exp2, Lanes, Mask, Vec3Lanes, LANES};
use glam::{Vec3, Vec3A};
use rayon::prelude::*;

use super::preetham::PreethamSky;
use crate::scene::{Sky, SkyModel};

/// Cells per side of the Preetham table (128² entries, 192 KiB, about 2 ms to build on one core).
pub const TABLE_SIDE: usize = 128;

/// A [`Sky`] with whatever it needs to be looked up fast; [`SkyRadiance::radiance`] is the one
/// call for the sky's radiance in a direction.
#[derive(Clone, Debug)]
pub struct SkyRadiance {
    /// The keys this was built for.
    sky: Sky,
    /// `preetham`: linear RGB radiance at the centres of a [`TABLE_SIDE`]² grid over
    /// u, v in [−1, 1] (row v, column u), cells outside the unit disc holding the horizon in
    /// their direction; empty for `gradient`.
    /// (16-byte `Vec3A` entries: one aligned SIMD load and lerp each.)
    table: Vec<Vec3A>,
}

impl SkyRadiance {
    /// Builds the lookup for `sky` (tabulates a `preetham` sky, on the rayon pool).
    pub fn new(sky: &Sky) -> Self {
        let mut s = Self { sky: *sky, table: Vec::new() };
        s.build();
        s
    }

    /// Makes this the lookup for `sky`, rebuilding only when a key changed (the renderer calls it
    /// every frame; the table's buffer is reused).
    pub fn update(&mut self, sky: &Sky) {
        if *sky != self.sky {
            self.sky = *sky;
            self.build();
        }
    }

    /// Whether the sky is looked up in a table (smooth at the scale of pixels, so callers may
    /// sample it sparsely) rather than evaluated directly.
    pub fn is_tabulated(&self) -> bool {
        !self.table.is_empty()
    }

    /// The keys it was built for.
    pub fn sky(&self) -> &Sky {
        &self.sky
    }

    fn build(&mut self) {
        if self.sky.model != SkyModel::Preetham {
            self.table.clear();
            return;
        }
        let sky = self.sky;
        let model = PreethamSky::new(sky.turbidity, sky.to_sun());
        self.table.resize(TABLE_SIDE * TABLE_SIDE, Vec3A::ZERO);
        self.table.par_chunks_mut(TABLE_SIDE).enumerate().for_each(|(j, row)| {
            let v = cell_centre(j);
            for (i, out) in row.iter_mut().enumerate() {
                *out = sky.preetham(&model, from_disc(cell_centre(i), v)).into();
            }
        });
    }

    /// Radiance (linear RGB, the renderer's units) of the sky along unit world direction `dir`,
    /// without the sun disc.
    #[inline]
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        if self.table.is_empty() {
            return self.sky.gradient(dir);
        }
        if dir.y >= 0.0 {
            let k = 1.0 / (1.0 + dir.y);
            return self.lookup(dir.x * k, dir.z * k);
        }
        let l = (dir.x * dir.x + dir.z * dir.z).sqrt();
        let horizon = if l > 1e-6 { self.lookup(dir.x / l, dir.z / l) } else { self.lookup(1.0, 0.0) };
        horizon.lerp(self.sky.ground * self.sky.night_fade(), (-dir.y * 8.0).min(1.0))
    }

    /// Bilinear lookup at disc coordinates (u, v).
    #[inline]
    fn lookup(&self, u: f32, v: f32) -> Vec3 {
        // Cell coordinates, clamped to the centres of the edge cells (max/min also send NaN to 0).
        const HALF: f32 = 0.5 * TABLE_SIDE as f32;
        const LAST: f32 = (TABLE_SIDE - 2) as f32;
        let fx = (u * HALF + (HALF - 0.5)).max(0.0);
        let fy = (v * HALF + (HALF - 0.5)).max(0.0);
        // The lower corner stays one short of the last cell so that its neighbour exists; the
        // weight then reaches 1 at the last centre.
        let (bx, by) = (fx.min(LAST), fy.min(LAST));
        let (i, j) = (bx as usize, by as usize);
        let (tx, ty) = ((fx - i as f32).min(1.0), (fy - j as f32).min(1.0));
        let k = j * TABLE_SIDE + i;
        let t = &self.table[k..k + TABLE_SIDE + 2];
        let top = t[0].lerp(t[1], tx);
        let bottom = t[TABLE_SIDE].lerp(t[TABLE_SIDE + 1], tx);
        top.lerp(bottom, ty).into()
    }

    /// [`Self::radiance`] along many unit directions, bit for bit: the gradient, or the table's
    /// disc coordinates, cell indices, weights and bilinear blend computed for all lanes at once
    /// (the same IEEE operations in the same order as the scalar path), only the four corners
    /// read lane by lane. Lane by lane it was a quarter of a `noon` frame (the water reflects the
    /// sky twice per pixel).
    #[inline(always)]
    pub fn radiance_lanes(&self, dir: Vec3Lanes) -> Vec3Lanes {
        if self.table.is_empty() {
            return self.sky.gradient_lanes(dir);
        }
        // Above the horizon: stereographic from the nadir. Below (or NaN, as in `radiance`): the
        // horizon in the direction's azimuth, blended into the ground.
        let up = Mask(std::array::from_fn(|i| if dir.y.0[i] >= 0.0 { u32::MAX } else { 0 }));
        let k = Lanes::splat(1.0) / (Lanes::splat(1.0) + dir.y);
        let l = (dir.x * dir.x + dir.z * dir.z).sqrt();
        let flat = l.gt(1e-6);
        let u = up.select(dir.x * k, flat.select(dir.x / l, 1.0));
        let v = up.select(dir.z * k, flat.select(dir.z / l, 0.0));
        let sky = self.lookup_lanes(u, v);
        if !Mask(up.0.map(|m| !m)).any() {
            return sky;
        }
        let s = (-dir.y * 8.0).min(1.0);
        let ground = Vec3Lanes::splat(self.sky.ground * self.sky.night_fade());
        let below = sky.scale(Lanes::splat(1.0) - s) + ground.scale(s);
        up.select3(sky, below)
    }

    /// [`Self::lookup`] of many disc coordinates: the scaling to cells in lanes, then each lane's
    /// four corners and blend exactly as [`Self::lookup`] does them.
    #[inline(always)]
    fn lookup_lanes(&self, u: Lanes, v: Lanes) -> Vec3Lanes {
        const HALF: f32 = 0.5 * TABLE_SIDE as f32;
        const LAST: f32 = (TABLE_SIDE - 2) as f32;
        let fx = (u * HALF + (HALF - 0.5)).max(0.0);
        let fy = (v * HALF + (HALF - 0.5)).max(0.0);
        // Cells and weights for all lanes at once (the conversions vectorise; per lane they were
        // most of the lookup's instructions).
        // (Plain loops: `std::array::from_fn` is not always inlined, and then stays scalar.)
        let (bx, by) = (fx.min(LAST), fy.min(LAST));
        let (mut i, mut j) = ([0_i32; LANES], [0_i32; LANES]);
        for n in 0..LANES {
            // SAFETY: `max(0.0)` above sent NaN and negatives to 0 and `min(LAST)` caps the rest,
            // so both are finite and in [0, LAST], where the unchecked conversion is exact. (The
            // saturating `as i32`, which checks for NaN and range, was a third of the lookup.)
            (i[n], j[n]) = unsafe { (bx.0[n].to_int_unchecked::<i32>(), by.0[n].to_int_unchecked::<i32>()) };
        }
        let (mut tx, mut ty, mut k) = (fx, fy, [0_i32; LANES]);
        for n in 0..LANES {
            tx.0[n] = (fx.0[n] - i[n] as f32).min(1.0);
            ty.0[n] = (fy.0[n] - j[n] as f32).min(1.0);
            k[n] = j[n] * TABLE_SIDE as i32 + i[n];
        }
        // Then each lane's four corners, read and blended exactly as `lookup` does.
        let mut out = Vec3Lanes::splat(Vec3::ZERO);
        for n in 0..LANES {
            let (k, tx, ty) = (k[n] as usize, tx.0[n], ty.0[n]);
            let t = &self.table[k..k + TABLE_SIDE + 2];
            let c = t[0].lerp(t[1], tx).lerp(t[TABLE_SIDE].lerp(t[TABLE_SIDE + 1], tx), ty);
            (out.x.0[n], out.y.0[n], out.z.0[n]) = (c.x, c.y, c.z);
        }
        out
    }

    /// Aerial perspective: `color` of a surface at world `p` seen from `eye`, faded towards the
    /// sky's horizon in the view's direction by `1 − exp(−d / haze_distance)` over the distance
    /// d; `color` unchanged when `haze_distance` is 0.
    #[inline]
    pub fn aerial_perspective(&self, eye: Vec3, p: Vec3, color: Vec3) -> Vec3 {
        let h = self.sky.haze_distance;
        if h <= 0.0 {
            return color;
        }
        let d = p - eye;
        // e^x as 2^(x log2 e) by the vectorisable `fast_exp2` (relative error < 1e-6), here and
        // in the lanes: the standard `exp`, one call per lane, was a tenth of a `hazy` frame.
        let fade = 1.0 - fast_exp2(-d.length() / h * std::f32::consts::LOG2_E);
        let horizon = self.radiance(Vec3::new(d.x, 0.0, d.z).normalize_or(Vec3::X));
        color.lerp(horizon, fade)
    }
}

impl SkyRadiance {
    /// [`Self::aerial_perspective`] of many points at once, bit for bit: distances, fades and
    /// horizon directions in lanes, the horizon through [`Self::radiance_lanes`]; `color`
    /// unchanged when `haze_distance` is 0.
    #[inline(always)]
    pub fn aerial_perspective_lanes(&self, eye: Vec3, p: Vec3Lanes, color: Vec3Lanes) -> Vec3Lanes {
        let h = self.sky.haze_distance;
        if h <= 0.0 {
            return color;
        }
        let d = p - Vec3Lanes::splat(eye);
        let fade = Lanes::splat(1.0) - (-d.length() / h * std::f32::consts::LOG2_E).map(fast_exp2);
        let flat = Vec3Lanes { x: d.x, y: Lanes::splat(0.0), z: d.z }.normalize_or(Vec3::X);
        let horizon = self.radiance_lanes(flat);
        // glam's lerp, `a (1 - s) + b s`, per component.
        color.scale(Lanes::splat(1.0) - fade) + horizon.scale(fade)
    }
}

/// Disc coordinate of the centre of cell `i`, in (−1, 1).
fn cell_centre(i: usize) -> f32 {
    (i as f32 + 0.5) / TABLE_SIDE as f32 * 2.0 - 1.0
}

/// The unit direction whose stereographic projection from the nadir is (u, v); points outside
/// the unit disc give the horizon in their direction.
fn from_disc(u: f32, v: f32) -> Vec3 {
    let r2 = u * u + v * v;
    if r2 >= 1.0 {
        let r = r2.sqrt();
        return Vec3::new(u / r, 0.0, v / r);
    }
    let k = 1.0 / (1.0 + r2);
    Vec3::new(2.0 * u * k, (1.0 - r2) * k, 2.0 * v * k)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn preetham(elevation: f32, azimuth: f32, turbidity: f32) -> Sky {
        Sky {
            model: SkyModel::Preetham,
            sun_elevation_deg: elevation,
            sun_azimuth_deg: azimuth,
            turbidity,
            ..Sky::default()
        }
    }

    fn directions() -> impl Iterator<Item = Vec3> {
        (0..40).flat_map(|a| {
            (0..12).map(move |e| {
                let (az, el) = ((a as f32 * 9.1).to_radians(), (e as f32 * 7.3 + 0.4).to_radians());
                Vec3::new(az.sin() * el.cos(), el.sin(), -az.cos() * el.cos())
            })
        })
    }

    /// The lane path gives the scalar path's bits, above and below the horizon, straight up and
    /// down, at the table's edges and for NaN.
    #[test]
    fn lanes_agree_with_the_scalar_lookup_bit_for_bit() {
        let table = SkyRadiance::new(&preetham(20.0, 70.0, 3.0));
        let mut dirs: Vec<Vec3> = directions().collect();
        dirs.extend(directions().map(|d| Vec3::new(d.x, -d.y, d.z)));
        dirs.extend([Vec3::Y, -Vec3::Y, Vec3::X, Vec3::new(0.0, -0.0, 1.0), Vec3::NAN, Vec3::new(1e-8, -1.0, 0.0)]);
        for chunk in dirs.chunks(crate::math::LANES) {
            let lanes = Vec3Lanes::from_fn(|i| chunk[i % chunk.len()]);
            let got = table.radiance_lanes(lanes);
            for (i, d) in chunk.iter().enumerate() {
                let (a, b) = (got.lane(i), table.radiance(*d));
                assert_eq!(a.to_array().map(f32::to_bits), b.to_array().map(f32::to_bits), "{d}: {a} vs {b}");
            }
        }
    }

    /// The haze in lanes is the scalar haze, bit for bit, near and far, for both sky models.
    #[test]
    fn haze_in_lanes_agrees_with_the_scalar_haze() {
        for sky in [preetham(20.0, 70.0, 3.0), Sky::default()] {
            let table = SkyRadiance::new(&Sky { haze_distance: 900.0, ..sky });
            let eye = Vec3::new(3.0, 12.0, -40.0);
            let p =
                Vec3Lanes::from_fn(|i| Vec3::new(i as f32 * 37.0 - 900.0, (i % 5) as f32 - 2.0, i as f32 * i as f32));
            let color = Vec3Lanes::from_fn(|i| Vec3::new(0.1, 0.02 * i as f32, 0.3));
            let got = table.aerial_perspective_lanes(eye, p, color);
            for i in 0..crate::math::LANES {
                let want = table.aerial_perspective(eye, p.lane(i), color.lane(i));
                assert_eq!(got.lane(i).to_array().map(f32::to_bits), want.to_array().map(f32::to_bits), "lane {i}");
            }
        }
    }

    #[test]
    fn the_table_matches_the_model_within_two_percent() {
        for (el, az, t) in [(45.0, 135.0, 2.5), (8.0, 250.0, 3.0), (75.0, 10.0, 6.0)] {
            let sky = preetham(el, az, t);
            let table = SkyRadiance::new(&sky);
            for d in directions() {
                let (exact, fast) = (sky.radiance(d), table.radiance(d));
                // Relative to the brightest channel; the circumsolar peak is the steepest part.
                let err = (exact - fast).abs().max_element() / exact.max_element().max(1e-3);
                let near_sun = d.dot(sky.to_sun()) > 0.99;
                assert!(err < if near_sun { 0.1 } else { 0.02 }, "sun {el}/{az}, T {t}, {d}: {exact} vs {fast}");
            }
            // Below the horizon: the horizon blending into the ground, as in the gradient sky.
            let down = table.radiance(Vec3::new(0.3, -0.9, 0.2).normalize());
            assert!((down - sky.ground).abs().max_element() < 1e-4);
        }
    }

    #[test]
    fn the_gradient_sky_is_looked_up_exactly_as_before() {
        let sky = Sky::default();
        let r = SkyRadiance::new(&sky);
        for d in directions().chain([Vec3::new(0.2, -0.5, 0.8).normalize(), -Vec3::Y]) {
            assert_eq!(r.radiance(d), sky.radiance(d));
        }
        // Haze off by default: colours pass unchanged.
        let c = Vec3::new(0.1, 0.2, 0.3);
        assert_eq!(r.aerial_perspective(Vec3::ZERO, Vec3::splat(1e4), c), c);
    }

    #[test]
    fn the_sky_is_brighter_near_the_sun_and_in_the_renderer_s_unit() {
        let sky = preetham(30.0, 90.0, 3.0);
        let r = SkyRadiance::new(&sky);
        let lum = |c: Vec3| c.dot(Vec3::new(0.2126, 0.7152, 0.0722));
        let near = lum(r.radiance(Vec3::new(1.0, 0.62, 0.0).normalize()));
        let opposite = lum(r.radiance(Vec3::new(-1.0, 0.62, 0.0).normalize()));
        assert!(near > 2.0 * opposite, "{near} vs {opposite}");
        // The model's kcd/m² over the 20 kcd/m² unit.
        let d = Vec3::new(0.3, 0.5, -0.4).normalize();
        let model = super::super::preetham::PreethamSky::new(3.0, sky.to_sun());
        assert!((lum(r.radiance(d)) * 20.0 / model.yxy(d).0 as f32 - 1.0).abs() < 0.02);
        // A clear noon sky in the gradient's range: zenith and horizon between 0.05 and 1.5.
        let noon = SkyRadiance::new(&preetham(60.0, 180.0, 2.5));
        for d in [Vec3::Y, Vec3::new(0.0, 0.05, -1.0).normalize()] {
            let c = noon.radiance(d);
            assert!(c.min_element() > 0.02 && c.max_element() < 1.5, "{d}: {c}");
        }
        // After sunset the sky fades out.
        let night = SkyRadiance::new(&preetham(-10.0, 180.0, 2.5));
        assert_eq!(night.radiance(Vec3::Y), Vec3::ZERO);
    }

    #[test]
    fn haze_fades_distant_surfaces_to_the_horizon() {
        let sky = Sky { haze_distance: 100.0, ..preetham(20.0, 200.0, 4.0) };
        let r = SkyRadiance::new(&sky);
        let eye = Vec3::new(0.0, 5.0, 0.0);
        let c = Vec3::new(0.05, 0.1, 0.02);
        let horizon = r.radiance(Vec3::new(0.0, 0.0, -1.0));
        let near = r.aerial_perspective(eye, Vec3::new(0.0, 0.0, -1.0), c);
        let mid = r.aerial_perspective(eye, Vec3::new(0.0, 0.0, -100.0), c);
        let far = r.aerial_perspective(eye, Vec3::new(0.0, 0.0, -1e5), c);
        // 5.1 m away: 5 % of the way.
        assert!((near - c).length() < 0.06 * (horizon - c).length());
        // At d = haze_distance (about 100 m): 1 − 1/e of the way.
        let expected = c.lerp(horizon, 1.0 - (-(100.0f32.hypot(5.0)) / 100.0).exp());
        assert!((mid - expected).abs().max_element() < 1e-4, "{mid} vs {expected}");
        assert!((far - horizon).abs().max_element() < 1e-4);
    }
}
