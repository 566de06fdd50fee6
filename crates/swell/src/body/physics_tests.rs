//! The physics the bodies must show (issue 34): Archimedes, the heave period and its decay, a buoy
//! riding and drifting on a wave, energy that never grows on still water, and poses that depend
//! only on the time.

use glam::{DVec3, Vec2, Vec3};

use super::*;
use crate::water::{Airy, AiryParams, AiryWave, WaveModel};

const RHO: f32 = 1025.0;

fn bodies(specs: &[BodySpec]) -> FloatingBodies {
    FloatingBodies::from_specs(specs, RHO).unwrap()
}

fn boxed(size: [f32; 3], density: f32, y: f32) -> BodySpec {
    let mut b = BodySpec::new(BodyShape::Box, &size, Vec3::new(0.0, y, 0.0));
    b.density = Some(density);
    b
}

/// The y of body 0 at every step from 0 to `seconds`, on still water.
fn heave(spec: BodySpec, seconds: f64) -> (FloatingBodies, Vec<f64>) {
    let mut b = bodies(&[spec]);
    let n = FloatingBodies::step_at(seconds);
    let mut ys = Vec::with_capacity(n as usize);
    for k in 0..=n {
        b.advance(FloatingBodies::step_time(k), &mut StillWater).unwrap();
        ys.push(b.bodies()[0].state.position.y);
    }
    (b, ys)
}

#[test]
fn a_box_of_half_the_water_s_density_floats_at_half_its_height() {
    let (b, ys) = heave(boxed([1.0, 0.5, 2.0], 0.5 * RHO, 0.1), 30.0);
    // The middle of the last two seconds' swing (drag has taken most of it by then).
    let tail = &ys[ys.len() - 240..];
    let y = 0.5 * (tail.iter().copied().fold(f64::MAX, f64::min) + tail.iter().copied().fold(f64::MIN, f64::max));
    // Its centre at the water line: half of its 0.5 m height under water, within 1 %.
    assert!(y.abs() < 0.01 * 0.25, "centre at {y} m");
    // The submerged volume reported is the box's below the water line (1 m x 2 m across).
    let v = b.bodies()[0].report.submerged_volume;
    let below = (0.25 - ys.last().unwrap()) * 2.0;
    assert!((v - below).abs() < 1e-6, "submerged {v} m³, {below} m³ below the water line");
    // Upright still.
    let up = b.bodies()[0].state.orientation * DVec3::Y;
    assert!(up.y > 0.9999, "{up}");
}

#[test]
fn a_sphere_floats_at_the_closed_form_draft() {
    let (r, density) = (0.5f64, 300.0f32);
    let mut s = BodySpec::new(BodyShape::Sphere, &[r as f32], Vec3::new(0.0, 0.3, 0.0));
    s.density = Some(density);
    let (_, ys) = heave(s, 30.0);
    // The cap of height h under water holds the sphere's weight: π h² (3r - h) / 3 = (ρb/ρw) 4/3 π r³.
    let target = f64::from(density / RHO) * 4.0 * r.powi(3);
    let (mut lo, mut hi) = (0.0, 2.0 * r);
    for _ in 0..60 {
        let h = 0.5 * (lo + hi);
        if h * h * (3.0 * r - h) < target {
            lo = h
        } else {
            hi = h
        }
    }
    let draft = r - ys.last().unwrap();
    // The hull is a 320-triangle icosphere of the sphere's volume: its draft within 2 % of r.
    assert!((draft - lo).abs() < 0.02 * r, "draft {draft} m, closed form {lo} m");
}

#[test]
fn a_box_heaves_at_its_hydrostatic_period_and_drag_decays_it() {
    let (x, y, z, density) = (1.0f32, 0.5f32, 2.0f32, 400.0f32);
    let mass = f64::from(x * y * z * density);
    let stiffness = f64::from(RHO * crate::GRAVITY * x * z);
    // No added mass is modelled: the period is that of the mass on the water line's spring.
    let period = std::f64::consts::TAU * (mass / stiffness).sqrt();
    let rest = f64::from(y) * (0.5 - f64::from(density / RHO));
    let mut free = boxed([x, y, z], density, rest as f32 + 0.05);
    (free.drag, free.linear_drag) = (0.0, 0.0);
    let (_, ys) = heave(free, 10.0);
    let crossings: Vec<f64> = ys
        .windows(2)
        .enumerate()
        .filter(|(_, w)| (w[0] - rest) * (w[1] - rest) < 0.0)
        .map(|(k, w)| {
            let f = (w[0] - rest) / (w[0] - w[1]);
            (k as f64 + f) / f64::from(BODY_STEP_HZ)
        })
        .collect();
    let measured = 2.0 * (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    // Semi-implicit Euler lengthens the period by (ω Δt)² / 24, under 0.1 % here.
    assert!((measured / period - 1.0).abs() < 0.01, "period {measured} s, expected {period} s");
    // Undamped, the amplitude holds; with drag, it decays.
    let swing = |ys: &[f64], from: f64| {
        let k = (from * f64::from(BODY_STEP_HZ)) as usize;
        ys[k..k + 240].iter().map(|y| (y - rest).abs()).fold(0.0, f64::max)
    };
    assert!((swing(&ys, 8.0) / 0.05 - 1.0).abs() < 0.05, "undamped swing {}", swing(&ys, 8.0));
    let (_, damped) = heave(boxed([x, y, z], density, rest as f32 + 0.05), 10.0);
    let (early, late) = (swing(&damped, 0.0), swing(&damped, 8.0));
    assert!(late < 0.5 * early, "damped swing {early} -> {late}");
}

/// Kinetic, gravitational and the still water's potential energy of body 0 (J): the water's
/// `-ρ g ∫ y dV` over the submerged volume, whose fall is the buoyancy's work.
fn energy(b: &FloatingBodies) -> f64 {
    let body = &b.bodies()[0];
    let s = body.state;
    let tris: Vec<[DVec3; 3]> = body
        .hull
        .triangles
        .iter()
        .map(|t| t.map(|i| s.position + s.orientation * body.hull.positions[i as usize].as_dvec3()))
        .collect();
    let g = f64::from(crate::GRAVITY);
    body.kinetic_energy() + body.material.mass * g * s.position.y
        - b.water_density() * g * water_forces::first_moment_below_zero(&tris)
}

#[test]
fn on_still_water_energy_never_grows_over_a_hundred_thousand_steps() {
    let mut spec = boxed([0.8, 0.6, 1.5], 600.0, 0.4);
    spec.rotation_deg = Vec3::new(20.0, 15.0, -25.0);
    spec.angular_velocity = Vec3::new(0.5, -1.0, 0.7);
    spec.velocity = Vec3::new(0.3, 0.0, -0.2);
    let mut b = bodies(&[spec]);
    b.advance(0.0, &mut StillWater).unwrap();
    let start = energy(&b);
    let mut highest = start;
    let mut last = start;
    for k in 1..=100_000u64 {
        b.advance(FloatingBodies::step_time(k), &mut StillWater).unwrap();
        if k % 10 == 0 {
            last = energy(&b);
            assert!(last.is_finite());
            highest = highest.max(last);
        }
    }
    // The step's own energy error is a few parts in a thousand of the swing at the start; drag
    // takes far more than that at once.
    assert!(highest <= start + 1e-3 * start.abs(), "energy rose from {start} J to {highest} J");
    assert!(last < start, "{start} J -> {last} J");
}

fn three_bodies() -> Vec<BodySpec> {
    let mut a = boxed([1.0, 0.4, 1.6], 450.0, 0.5);
    a.rotation_deg = Vec3::new(30.0, 10.0, 5.0);
    let mut s = BodySpec::new(BodyShape::Sphere, &[0.3], Vec3::new(4.0, 0.2, -2.0));
    s.velocity = Vec3::new(1.0, 0.0, 0.0);
    let c = BodySpec::new(BodyShape::Capsule, &[0.25, 1.5], Vec3::new(-3.0, 1.0, 3.0));
    vec![a, s, c]
}

fn wave() -> Airy {
    let w = AiryWave { amplitude: 0.5, wavelength: 40.0, direction: Vec2::X, phase: 0.0 };
    Airy::new(AiryParams { waves: vec![w], ..Default::default() }).unwrap()
}

fn poses_on_wave(threads: usize, times: &[f64]) -> Vec<Vec<BodyPose>> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| {
        let mut model = wave();
        let mut b = bodies(&three_bodies());
        times
            .iter()
            .map(|&t| {
                b.advance(t, &mut ModelWater { model: &mut model }).unwrap();
                b.poses_at(t).unwrap()
            })
            .collect()
    })
}

#[test]
fn poses_depend_only_on_the_time_not_threads_frame_rate_or_resumes() {
    let one = poses_on_wave(1, &[0.5, 1.0 / 3.0 + 1.0, 2.5, 4.0]);
    let two = poses_on_wave(2, &[0.5, 1.0 / 3.0 + 1.0, 2.5, 4.0]);
    assert_eq!(one, two);
    // At 60 fps and straight to the end (a resumed bake), the same poses at 4 s.
    let frames: Vec<f64> = (0..=240).map(|k| k as f64 / 60.0).collect();
    let fine = poses_on_wave(2, &frames);
    let once = poses_on_wave(1, &[4.0]);
    assert_eq!(fine.last(), once.last());
    // Going back in time starts again from t = 0 and gives the same answer.
    let back = poses_on_wave(2, &[4.0, 1.0 / 3.0 + 1.0]);
    assert_eq!(back[1], one[1]);
}

#[test]
fn a_small_buoy_rides_a_wave_and_drifts_with_it() {
    let mut model = wave();
    let mut s = BodySpec::new(BodyShape::Sphere, &[0.25], Vec3::new(0.0, 0.0, 0.0));
    s.density = Some(500.0);
    let mut b = bodies(&[s]);
    let omega = (f64::from(crate::GRAVITY) * std::f64::consts::TAU / 40.0).sqrt();
    let period = std::f64::consts::TAU / omega;
    let (mut lo, mut hi, mut wlo, mut whi) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    let mut x_settled = 0.0;
    let mut t = 0.0;
    while t < 60.0 {
        b.advance(t, &mut ModelWater { model: &mut model }).unwrap();
        let p = b.bodies()[0].state.position;
        assert!(p.is_finite());
        if (10.0..10.0 + 3.0 * period).contains(&t) {
            (lo, hi) = (lo.min(p.y), hi.max(p.y));
            let h = f64::from(model.height_at(p.x as f32, p.z as f32, t));
            (wlo, whi) = (wlo.min(h), whi.max(h));
        }
        if t <= 10.0 {
            x_settled = p.x;
        }
        t += 1.0 / 60.0;
    }
    // It rises and falls with the surface: a 0.5 m sphere on a 40 m wave.
    let ratio = (hi - lo) / (whi - wlo);
    assert!((0.85..1.15).contains(&ratio), "heave {} m for a surface swing of {} m", hi - lo, whi - wlo);
    // And it drifts the way the wave travels (+X).
    let drift = b.bodies()[0].state.position.x - x_settled;
    assert!(drift > 0.3, "drift {drift} m in 50 s");
}

#[test]
fn bad_bodies_are_refused_naming_the_key() {
    let cases: Vec<(BodySpec, &str)> = vec![
        (BodySpec::new(BodyShape::Box, &[1.0, 1.0], Vec3::ZERO), "body[0].size"),
        (BodySpec::new(BodyShape::Sphere, &[-1.0], Vec3::ZERO), "body[0].size[0]"),
        (
            {
                let mut b = BodySpec::new(BodyShape::Sphere, &[1.0], Vec3::ZERO);
                b.mass = Some(0.0);
                b
            },
            "body[0].mass",
        ),
        (
            {
                let mut b = BodySpec::new(BodyShape::Sphere, &[1.0], Vec3::ZERO);
                b.density = Some(-5.0);
                b
            },
            "body[0].density",
        ),
        (
            {
                let mut b = BodySpec::new(BodyShape::Sphere, &[1.0], Vec3::ZERO);
                b.position.x = f32::NAN;
                b
            },
            "body[0].position[0]",
        ),
        (BodySpec::new(BodyShape::Mesh, &[], Vec3::ZERO), "body[0].path"),
        (
            {
                // Foam, 3 cm: it would bob faster than the step follows.
                let mut b = BodySpec::new(BodyShape::Sphere, &[0.03], Vec3::ZERO);
                b.density = Some(20.0);
                b
            },
            "body[0].mass",
        ),
    ];
    for (spec, key) in cases {
        let e = FloatingBodies::from_specs(&[spec], RHO).unwrap_err().to_string();
        assert!(e.contains(key), "{e} should name {key}");
    }
    let twins =
        [BodySpec::new(BodyShape::Sphere, &[1.0], Vec3::ZERO), BodySpec::new(BodyShape::Sphere, &[1.0], Vec3::ZERO)];
    let mut twins = twins.to_vec();
    twins[0].name = "a".into();
    twins[1].name = "a".into();
    assert!(FloatingBodies::from_specs(&twins, RHO).unwrap_err().to_string().contains("body[1].name"));
    assert!(FloatingBodies::from_specs(&[], 2000.0).unwrap_err().to_string().contains("water.density"));
    let mut b = bodies(&three_bodies());
    assert!(b.advance(f64::NAN, &mut StillWater).is_err());
}

#[test]
fn two_crates_meeting_on_the_water_do_not_pass_through_each_other() {
    // Flat (stable) crates 1 m wide, 2 m apart, sailing at each other at 1 m/s each.
    let mut a = boxed([1.0, 0.4, 1.0], 500.0, 0.0);
    a.position.x = -1.0;
    a.velocity.x = 1.0;
    a.drag = 0.0;
    let mut b = boxed([1.0, 0.4, 1.0], 500.0, 0.0);
    b.position.x = 1.0;
    b.velocity.x = -1.0;
    b.drag = 0.0;
    let mut both = bodies(&[a, b]);
    let mut closest = f64::MAX;
    for k in 0..=600 {
        both.advance(FloatingBodies::step_time(k), &mut StillWater).unwrap();
        let (pa, pb) = (both.bodies()[0].state.position, both.bodies()[1].state.position);
        closest = closest.min(pb.x - pa.x);
    }
    // They met (without contacts they would cross) and parted again no deeper than a few
    // centimetres into each other.
    assert!(closest > 0.9, "centres came within {closest} m (1 m wide crates)");
    let (pa, pb) = (both.bodies()[0].state.position, both.bodies()[1].state.position);
    assert!(pb.x > pa.x + 0.95, "{pa} {pb}");
}
