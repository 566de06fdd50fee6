//! The query API (issue 37): from the input bytes, the water of a preset (each water model is in
//! one) on a small grid (an FFT grid of 32², a spring lattice of 24²), placed anywhere (centre,
//! turn, scale, patch or unbounded), asked about points whose coordinates are any bit patterns
//! (NaN, infinities, subnormals, 10^30 m) at times the input picks, in single and double
//! precision. It must hold that:
//!
//! - a batch holding a non-finite coordinate, or one past `MAX_QUERY_COORDINATE_M`, is refused
//!   and leaves the output as it was;
//! - every other point gets a finite height and a unit normal where `has_water_at` says there is
//!   water, and NaN where it says there is none; single and double precision agree on coverage
//!   and, near the origin, on the height;
//! - answers depend only on the scene and the time: asked again after other times, and from a
//!   fresh `Water`, they are the same bits;
//! - `displace` and `foam` fill their buffers with finite numbers.
//!
//! Never a panic or a hang: stepped models (the spring mesh) are asked at most 40 s ahead.
#![no_main]

use glam::{DVec2, DVec3, Vec2, Vec3};
use libfuzzer_sys::fuzz_target;
use swell::scene::{preset, WaterExtent, PRESETS};
use swell::world::MAX_QUERY_COORDINATE_M;
use swell::Water;

#[path = "common/input_bytes.rs"]
mod input_bytes;
use input_bytes::Bytes;

/// A coordinate (m): mostly a sensible one (within a few hundred metres, or far out), sometimes
/// any f64 bit pattern at all.
fn coordinate(b: &mut Bytes) -> f64 {
    match b.byte() % 8 {
        0 => f64::from_bits(b.u64()),
        1 => b.pick(&[f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -0.0, f64::MIN_POSITIVE, 1.0e30, 1.0e6]),
        2 => (b.u64() % 2_000_000) as f64 * 1.0e3 - 1.0e9,
        _ => (b.u64() % 1_000_000) as f64 * 1.0e-3 - 500.0,
    }
}

/// Preset names with water, as the library lists them.
fn presets_with_water() -> Vec<&'static str> {
    PRESETS.iter().map(|p| p.name).filter(|n| preset(n).is_ok_and(|s| s.water.is_some())).collect()
}

fuzz_target!(|data: &[u8]| {
    let mut b = Bytes(data);
    let names = presets_with_water();
    let name = names[usize::from(b.byte()) % names.len()];
    let mut scene = preset(name).unwrap();
    let Some(water_spec) = scene.water.as_mut() else { return };
    let s = &mut water_spec.surface;
    s.cells = [u32::from(b.byte() % 12) + 1, u32::from(b.byte() % 12) + 1];
    s.center = Vec2::new(b.pick(&[0.0, 37.5, -1.0e4, 1.0e6]), b.pick(&[0.0, -12.0, 2.5e5]));
    s.yaw_deg = b.pick(&[0.0, 30.0, -90.0, 359.0]);
    s.uniform_scale = b.pick(&[1.0, 0.25, 3.0]);
    s.extent = b.pick(&[None, Some(WaterExtent::Patch), Some(WaterExtent::Unbounded)]);
    let center = s.center;
    // Small models, so that an input takes milliseconds: the FFT ocean on a 32² grid, the spring
    // lattice 24² (the properties checked do not depend on the size).
    let text: String = scene
        .to_toml()
        .lines()
        .map(|l| match l {
            l if l.starts_with("grid = ") => "grid = 32".to_string(),
            l if l.starts_with("lattice = ") => "lattice = [24, 24]".to_string(),
            l => l.to_string(),
        })
        .map(|l| l + "\n")
        .collect();
    // A placement or extent the model cannot take is refused: that is an answer too.
    let Ok(mut water) = Water::from_toml(&text, "fuzz") else { return };

    let count = usize::from(b.byte() % 9);
    let points: Vec<DVec2> = (0..count).map(|_| DVec2::new(coordinate(&mut b), coordinate(&mut b))).collect();
    let narrow: Vec<Vec2> = points.iter().map(|p| p.as_vec2()).collect();
    let times: Vec<f64> = (0..3).map(|_| f64::from(b.byte() % 160) * 0.25).collect();

    let mut heights = vec![f64::from_bits(0x7ff4_dead_beef_0001); count];
    let mut normals = vec![DVec3::splat(7.0); count];
    let (mut h32, mut n32) = (vec![7.0f32; count], vec![Vec3::splat(7.0); count]);
    // What the queries take: finite coordinates within MAX_QUERY_COORDINATE_M of the origin.
    let within = |x: f64, z: f64| x.abs() <= MAX_QUERY_COORDINATE_M && z.abs() <= MAX_QUERY_COORDINATE_M;
    let finite = points.iter().all(|p| within(p.x, p.y));
    let narrow_finite = narrow.iter().all(|p| within(f64::from(p.x), f64::from(p.y)));
    let mut answers = Vec::new();
    for &t in &times {
        let asked = water.heights_at_f64(t, &points, &mut heights);
        if !finite {
            assert!(asked.is_err(), "a non-finite or too distant point was answered");
            assert!(heights.iter().all(|h| h.to_bits() == 0x7ff4_dead_beef_0001), "a refused call wrote");
            assert!(water.normals_at_f64(t, &points, &mut normals).is_err());
            assert!(normals.iter().all(|n| *n == DVec3::splat(7.0)));
            continue;
        }
        asked.unwrap();
        water.normals_at_f64(t, &points, &mut normals).unwrap();
        for (k, p) in points.iter().enumerate() {
            let wet = water.has_water_at_f64(*p);
            if wet {
                assert!(heights[k].is_finite(), "{name}: height {} at {p} t = {t}", heights[k]);
                assert!((normals[k].length() - 1.0).abs() < 1e-6, "{name}: normal {} at {p}", normals[k]);
                assert!(normals[k].y > 0.0, "{name}: normal {} at {p} points down", normals[k]);
            } else {
                assert!(heights[k].is_nan() && normals[k].is_nan(), "{name}: water off the patch at {p}");
            }
        }
        // Single precision: refused where the narrowed point is past the limit too; near the
        // origin, the same water and nearly the same height.
        match water.heights_at(t, &narrow, &mut h32) {
            Ok(()) => {
                assert!(narrow_finite);
                water.normals_at(t, &narrow, &mut n32).unwrap();
                for (k, (p, q)) in points.iter().zip(&narrow).enumerate() {
                    // Near the origin only, the water's centre too: a centre 10^6 m out moves an
                    // f32 point's frame by centimetres, which the f64 queries are there to avoid.
                    let near = p.abs().max_element() < 1.0e3 && center.abs().max_element() < 1.0e3;
                    if near && water.has_water_at(*q) == water.has_water_at_f64(*p) {
                        let d = (f64::from(h32[k]) - heights[k]).abs();
                        assert!(
                            heights[k].is_nan() && h32[k].is_nan() || d < 1e-2,
                            "{name}: f32 {} f64 {} at {p}",
                            h32[k],
                            heights[k]
                        );
                    }
                }
            }
            Err(_) => assert!(!narrow_finite, "finite f32 points refused"),
        }
        answers.push((heights.clone(), normals.clone()));
    }
    if !finite {
        return;
    }
    // The same times again, in reverse, and from a fresh water: the same bits.
    let mut fresh = Water::from_toml(&text, "fuzz").unwrap();
    for (w, order) in [(&mut water, true), (&mut fresh, false)] {
        for (i, &t) in times.iter().enumerate().rev() {
            let (mut h, mut n) = (vec![0.0; count], vec![DVec3::ZERO; count]);
            w.heights_at_f64(t, &points, &mut h).unwrap();
            w.normals_at_f64(t, &points, &mut n).unwrap();
            let same = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same(&h, &answers[i].0), "{name}: heights at t = {t} changed (again: {order})");
            let flat = |v: &[DVec3]| v.iter().flat_map(|v| v.to_array()).collect::<Vec<f64>>();
            assert!(same(&flat(&n), &flat(&answers[i].1)), "{name}: normals at t = {t} changed");
        }
    }
    // The grid: finite positions and normals, foam in [0, 1] where the model has it.
    let n = water.vertex_count();
    let (mut pos, mut nrm, mut foam) = (vec![Vec3::ZERO; n], vec![Vec3::ZERO; n], vec![0.0f32; n]);
    let t = times[0];
    water.displace(t, &mut pos, &mut nrm).unwrap();
    assert!(pos.iter().chain(&nrm).all(|v| v.is_finite()));
    if water.foam(t, &mut foam).unwrap() {
        assert!(foam.iter().all(|f| (0.0..=1.0).contains(f)), "{name}: foam out of [0, 1]");
    }
});
