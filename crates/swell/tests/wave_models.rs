//! The conformance test every wave model runs: zero amplitude is the plane at rest, the grid is
//! identical on one and two threads, `height_at` agrees with the evaluated grid, positions and
//! normals are finite and normals unit length. The list of models is checked against the scene
//! format's one list (`swell::scene::WATER_MODELS`), so a new model fails here until it is added.

use glam::{Vec2, Vec3};
use swell::math::GridSpec;
use swell::spectrum::Dispersion;
use swell::water::*;

/// Every model, with waves (`calm = false`) or with all amplitudes zero (`calm = true`), ready to
/// be evaluated at time `t` (s): the FFT ocean synthesised for `t`, the spring lattice stepped to
/// 7 s (after its first drops; its surface is its state, whatever `t`).
fn models(calm: bool, t: f64) -> Vec<(&'static str, Box<dyn WaveModel>)> {
    let a = |x: f32| if calm { 0.0 } else { x };
    let gerstner = |amp: f32, l: f32, dir: Vec2| GerstnerWave {
        amplitude: a(amp),
        wavelength: l,
        speed: Dispersion::Deep.phase_speed(std::f32::consts::TAU / l),
        direction: dir,
        steepness: 0.8,
    };
    let mut springs = SpringMesh::new(SpringMeshParams {
        lattice: [24, 24],
        spacing: 1.0,
        vertical_only: false,
        drops: Some(DropSchedule { interval: 3.0, radius: 2.5, depth: a(0.5), seed: 2 }),
        ..Default::default()
    })
    .unwrap();
    springs.advance(7.0).unwrap();
    // A small two-cascade ocean; calm through Blender's wave_scale = 0, which scales every height.
    let fft = if calm {
        let blender = BlenderOcean { wave_scale: 0.0, spatial_size: 40.0, resolution: 5, ..Default::default() };
        FftOceanParams { blender: Some(blender), ..Default::default() }
    } else {
        FftOceanParams { grid: 32, patch_size: 40.0, cascades: 2, ..Default::default() }
    };
    let mut fft = fft.build().unwrap();
    fft.advance(t).unwrap();
    vec![
        ("fft", fft),
        (
            "gerstner",
            Box::new(
                Gerstner::new(vec![gerstner(0.6, 18.0, Vec2::X), gerstner(0.2, 6.0, Vec2::new(0.3, 1.0))]).unwrap(),
            ),
        ),
        (
            "wave-set",
            Box::new(
                Gerstner::new(
                    wave_set(&WaveSetParams { median_amplitude: a(0.2), count: 8, ..Default::default() }).unwrap(),
                )
                .unwrap(),
            ),
        ),
        (
            "tessendorf",
            Box::new(
                GerstnerTessendorf::new(TessendorfParams {
                    waves: vec![
                        TessendorfWave { amplitude: a(1.0), wavelength: 20.0, direction: Vec2::X, phase: 0.0 },
                        TessendorfWave {
                            amplitude: a(0.3),
                            wavelength: 7.0,
                            direction: Vec2::new(1.0, 1.0),
                            phase: 1.0,
                        },
                    ],
                    dispersion: Dispersion::FiniteDepth { depth: 5.0 },
                    loop_period: Some(30.0),
                })
                .unwrap(),
            ),
        ),
        (
            "sines",
            Box::new(
                SumOfSines::new(vec![SineWave { amplitude: a(0.4), wavelength: 9.0, speed: 3.0, direction: Vec2::Y }])
                    .unwrap(),
            ),
        ),
        (
            "airy",
            Box::new(
                Airy::new(AiryParams {
                    waves: vec![AiryWave { amplitude: a(0.4), wavelength: 9.0, direction: Vec2::Y, phase: 0.5 }],
                    dispersion: Dispersion::Capillary { depth: 3.0 },
                })
                .unwrap(),
            ),
        ),
        (
            "steep-sines",
            Box::new(
                SteepSines::new(SteepSinesParams {
                    waves: vec![SteepSineWave {
                        amplitude: a(0.5),
                        frequency: 0.6,
                        velocity: 2.0,
                        direction: Vec2::new(1.0, -0.4),
                        exponent: 2.5,
                    }],
                })
                .unwrap(),
            ),
        ),
        (
            "radial",
            Box::new(
                RadialWave::new(RadialWaveParams { amplitude: a(0.3), wavenumber: 1.3, ..Default::default() }).unwrap(),
            ),
        ),
        ("noise", Box::new(NoiseWaves::new(NoiseParams { amplitude: a(0.5), ..Default::default() }).unwrap())),
        ("springs", Box::new(springs)),
        // Ripples from 2.5 m, so the 0.5 m grid holds them all (shorter ones leave the mesh, not the query).
        (
            "river",
            Box::new(
                River::new(RiverParams { ripple_amplitude: a(0.02), ripple_wavelength: 2.5, ..Default::default() })
                    .unwrap(),
            ),
        ),
    ]
}

fn grid() -> GridSpec {
    GridSpec::centered(Vec2::new(24.0, 20.0), 48, 40).unwrap()
}

fn evaluate(m: &dyn WaveModel, threads: usize, t: f64) -> (Vec<Vec3>, Vec<Vec3>) {
    let g = grid();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    let mut p = vec![Vec3::ZERO; g.vertex_count()];
    let mut n = p.clone();
    pool.install(|| m.evaluate(&g, t, &mut p, &mut n));
    (p, n)
}

#[test]
fn every_model_of_the_scene_format_is_tested() {
    let names: Vec<&str> = models(false, 0.0).iter().map(|(n, _)| *n).collect();
    for name in swell::scene::WATER_MODELS {
        assert!(names.contains(name), "water model {name} has no entry in this conformance test");
    }
    assert_eq!(names.len(), swell::scene::WATER_MODELS.len(), "{names:?}");
}

#[test]
fn zero_amplitude_is_the_plane_at_rest() {
    for (name, m) in models(true, 3.3) {
        let (p, n) = evaluate(m.as_ref(), 2, 3.3);
        assert!(p.iter().all(|v| v.y == 0.0), "{name}: not flat");
        assert!(n.iter().all(|v| (*v - Vec3::Y).length() < 1e-6), "{name}: normals not +Y");
        assert!(m.height_at(1.3, -2.2, 3.3) == 0.0, "{name}: height_at not 0");
    }
}

#[test]
fn output_is_identical_on_one_and_two_threads_and_finite() {
    for (name, m) in models(false, 2.7) {
        let one = evaluate(m.as_ref(), 1, 2.7);
        let two = evaluate(m.as_ref(), 2, 2.7);
        assert!(one == two, "{name}: thread count changed the output");
        assert!(one.0.iter().all(|p| p.is_finite()), "{name}: non-finite position");
        assert!(one.1.iter().all(|n| (n.length() - 1.0).abs() < 1e-4), "{name}: normal not unit");
        assert!(one.0.iter().any(|p| p.y.abs() > 1e-3), "{name}: no waves");
    }
}

#[test]
fn height_at_agrees_with_the_evaluated_grid() {
    for (name, m) in models(false, 1.9) {
        let (p, _) = evaluate(m.as_ref(), 2, 1.9);
        for v in p.iter().step_by(13) {
            let h = m.height_at(v.x, v.z, 1.9);
            assert!((h - v.y).abs() < 2e-4, "{name}: height_at({}, {}) = {h}, grid {}", v.x, v.z, v.y);
        }
    }
}
