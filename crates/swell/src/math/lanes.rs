//! Many floats at a time, for the per-pixel shading loops: every operation is a plain loop over
//! [`LANES`] lanes, which the compiler turns into vector instructions (SSE on any x86-64, AVX2
//! inside a function compiled for it). Each lane does the same IEEE operations in the same order as scalar
//! code would, so results do not depend on the vector width.

use std::ops::{Add, Div, Mul, Neg, Sub};

use glam::Vec3;

/// Number of lanes. 64 rather than a vector register's 8: a loop of 8 is unrolled into straight
/// code that the compiler then vectorises only in part (its superword pass gives up on long
/// chains: callgrind counted 384 instructions per water pixel), while a loop of 64 stays a loop
/// and is vectorised whole (206 per pixel, and 20-30 % less time per frame on the `sea` preset).
pub const LANES: usize = 64;

/// [`LANES`] `f32`s, one per pixel (or vertex) of a batch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lanes(pub [f32; LANES]);

/// [`LANES`] booleans, the result of comparing [`Lanes`]: all bits set (true) or none, as vector
/// compare instructions give them, so that a choice is three bit operations (a `bool` array makes
/// the compiler pack and unpack bytes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mask(pub [u32; LANES]);

macro_rules! lanewise {
    ($a:expr, |$i:ident| $body:expr) => {{
        let _ = &$a;
        let mut out = [Default::default(); LANES];
        for $i in 0..LANES {
            out[$i] = $body;
        }
        out
    }};
}

impl Lanes {
    /// Every lane `v`.
    #[inline(always)]
    pub fn splat(v: f32) -> Self {
        Self([v; LANES])
    }
    /// Lane `i` is `f(i)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> f32) -> Self {
        // A plain loop rather than `std::array::from_fn`, which is not always inlined and then
        // keeps the loop scalar.
        let mut out = [0.0; LANES];
        for (i, o) in out.iter_mut().enumerate() {
            *o = f(i);
        }
        Self(out)
    }
    /// `f` applied to each lane.
    #[inline(always)]
    pub fn map(self, f: impl Fn(f32) -> f32) -> Self {
        Self(lanewise!(self, |i| f(self.0[i])))
    }
    /// Square root of each lane.
    #[inline(always)]
    pub fn sqrt(self) -> Self {
        self.map(f32::sqrt)
    }
    /// Lane-wise minimum (`f32::min`: a NaN lane takes the other operand).
    #[inline(always)]
    pub fn min(self, o: impl Into<Lanes>) -> Self {
        let o = o.into();
        Self(lanewise!(self, |i| self.0[i].min(o.0[i])))
    }
    /// Lane-wise maximum (`f32::max`).
    #[inline(always)]
    pub fn max(self, o: impl Into<Lanes>) -> Self {
        let o = o.into();
        Self(lanewise!(self, |i| self.0[i].max(o.0[i])))
    }
    /// Absolute value of each lane.
    #[inline(always)]
    pub fn abs(self) -> Self {
        self.map(f32::abs)
    }
    /// `a < b` per lane.
    #[inline(always)]
    pub fn lt(self, o: impl Into<Lanes>) -> Mask {
        let o = o.into();
        Mask(lanewise!(self, |i| if self.0[i] < o.0[i] { u32::MAX } else { 0 }))
    }
    /// `a > b` per lane.
    #[inline(always)]
    pub fn gt(self, o: impl Into<Lanes>) -> Mask {
        let o = o.into();
        Mask(lanewise!(self, |i| if self.0[i] > o.0[i] { u32::MAX } else { 0 }))
    }
    /// `a <= b` per lane.
    #[inline(always)]
    pub fn le(self, o: impl Into<Lanes>) -> Mask {
        let o = o.into();
        Mask(lanewise!(self, |i| if self.0[i] <= o.0[i] { u32::MAX } else { 0 }))
    }
}

impl Mask {
    /// Lane-wise choice: `yes` where set, `no` elsewhere.
    #[inline(always)]
    pub fn select(self, yes: impl Into<Lanes>, no: impl Into<Lanes>) -> Lanes {
        let (a, b) = (yes.into(), no.into());
        Lanes(lanewise!(self, |i| f32::from_bits((a.0[i].to_bits() & self.0[i]) | (b.0[i].to_bits() & !self.0[i]))))
    }
    /// Lane-wise choice of vectors.
    #[inline(always)]
    pub fn select3(self, yes: Vec3Lanes, no: Vec3Lanes) -> Vec3Lanes {
        Vec3Lanes { x: self.select(yes.x, no.x), y: self.select(yes.y, no.y), z: self.select(yes.z, no.z) }
    }
    /// Whether any lane is set.
    #[inline(always)]
    pub fn any(self) -> bool {
        self.0.iter().fold(0, |acc, &m| acc | m) != 0
    }
    /// Lanes set in both.
    #[inline(always)]
    pub fn and(self, o: Mask) -> Mask {
        Mask(lanewise!(self, |i| self.0[i] & o.0[i]))
    }
}

impl From<f32> for Lanes {
    #[inline(always)]
    fn from(v: f32) -> Self {
        Self::splat(v)
    }
}

macro_rules! binary {
    ($tr:ident, $f:ident, $op:tt) => {
        impl<T: Into<Lanes>> $tr<T> for Lanes {
            type Output = Lanes;
            #[inline(always)]
            fn $f(self, o: T) -> Lanes {
                let o = o.into();
                Lanes(lanewise!(self, |i| self.0[i] $op o.0[i]))
            }
        }
        impl $tr<Lanes> for f32 {
            type Output = Lanes;
            #[inline(always)]
            fn $f(self, o: Lanes) -> Lanes {
                Lanes::splat(self) $op o
            }
        }
    };
}
binary!(Add, add, +);
binary!(Sub, sub, -);
binary!(Mul, mul, *);
binary!(Div, div, /);

impl Neg for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn neg(self) -> Lanes {
        self.map(|v| -v)
    }
}

/// [`LANES`] 3-vectors, one per lane, stored as three [`Lanes`] (x, y and z of each).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vec3Lanes {
    /// x of each lane.
    pub x: Lanes,
    /// y of each lane.
    pub y: Lanes,
    /// z of each lane.
    pub z: Lanes,
}

impl Vec3Lanes {
    /// Every lane `v`.
    #[inline(always)]
    pub fn splat(v: Vec3) -> Self {
        Self { x: Lanes::splat(v.x), y: Lanes::splat(v.y), z: Lanes::splat(v.z) }
    }
    /// Lane `i` is `f(i)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> Vec3) -> Self {
        let mut out = Self::splat(Vec3::ZERO);
        for i in 0..LANES {
            out.set_lane(i, f(i));
        }
        out
    }
    /// Lane `i` as a vector.
    #[inline(always)]
    pub fn lane(&self, i: usize) -> Vec3 {
        Vec3::new(self.x.0[i], self.y.0[i], self.z.0[i])
    }
    /// Sets lane `i` to `v`.
    #[inline(always)]
    pub fn set_lane(&mut self, i: usize, v: Vec3) {
        (self.x.0[i], self.y.0[i], self.z.0[i]) = (v.x, v.y, v.z);
    }
    /// Dot product per lane (`x*x + y*y + z*z` in glam's order).
    #[inline(always)]
    pub fn dot(self, o: Vec3Lanes) -> Lanes {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// Cross product per lane (`self × o`, glam's formula).
    #[inline(always)]
    pub fn cross(self, o: Vec3Lanes) -> Vec3Lanes {
        Self { x: self.y * o.z - self.z * o.y, y: self.z * o.x - self.x * o.z, z: self.x * o.y - self.y * o.x }
    }
    /// Dot product with one vector.
    #[inline(always)]
    pub fn dot1(self, o: Vec3) -> Lanes {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// Each lane scaled by `s`.
    #[inline(always)]
    pub fn scale(self, s: impl Into<Lanes>) -> Self {
        let s = s.into();
        Self { x: self.x * s, y: self.y * s, z: self.z * s }
    }
    /// Length of each lane.
    #[inline(always)]
    pub fn length(self) -> Lanes {
        self.dot(self).sqrt()
    }
    /// Each lane at unit length, or `fallback` where its length is zero or not finite (glam's
    /// `normalize_or`).
    #[inline(always)]
    pub fn normalize_or(self, fallback: Vec3) -> Self {
        let rcp = 1.0 / self.length();
        // Finite and non-zero (NaN fails both comparisons).
        let ok =
            Mask(lanewise!(rcp, |i| if (rcp.0[i].abs() < f32::INFINITY) & (rcp.0[i] != 0.0) { u32::MAX } else { 0 }));
        ok.select3(self.scale(rcp), Self::splat(fallback))
    }
    /// Linear interpolation per lane, `self + (o - self) t`.
    #[inline(always)]
    pub fn lerp(self, o: Vec3Lanes, t: Lanes) -> Self {
        self + (o - self).scale(t)
    }
}

impl Add for Vec3Lanes {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self { x: self.x + o.x, y: self.y + o.y, z: self.z + o.z }
    }
}
impl Sub for Vec3Lanes {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self { x: self.x - o.x, y: self.y - o.y, z: self.z - o.z }
    }
}
impl Neg for Vec3Lanes {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self { x: -self.x, y: -self.y, z: -self.z }
    }
}
impl Mul<Vec3> for Vec3Lanes {
    type Output = Self;
    /// Component-wise product with one vector (a colour times a per-lane colour).
    #[inline(always)]
    fn mul(self, o: Vec3) -> Self {
        Self { x: self.x * o.x, y: self.y * o.y, z: self.z * o.z }
    }
}
impl Mul<Vec3Lanes> for Vec3Lanes {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Vec3Lanes) -> Self {
        Self { x: self.x * o.x, y: self.y * o.y, z: self.z * o.z }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_do_what_scalars_do() {
        let a = Lanes::from_fn(|i| i as f32 - 3.5);
        let b = Lanes::splat(2.0);
        for i in 0..LANES {
            let x = i as f32 - 3.5;
            assert_eq!((a * b + 1.0).0[i], x * 2.0 + 1.0);
            assert_eq!((a / b - a).0[i], x / 2.0 - x);
            assert_eq!(a.abs().sqrt().0[i], x.abs().sqrt());
            assert_eq!(a.lt(0.0).select(1.0, -1.0).0[i], if x < 0.0 { 1.0 } else { -1.0 });
        }
        let v = Vec3Lanes::from_fn(|i| Vec3::new(i as f32, 0.0, 0.0));
        let n = v.normalize_or(Vec3::Y);
        assert_eq!(n.lane(0), Vec3::Y, "zero length takes the fallback");
        assert_eq!(n.lane(3), Vec3::X);
        assert_eq!(v.lane(5), Vec3::new(5.0, 0.0, 0.0).normalize_or(Vec3::Y) * 5.0);
    }
}
