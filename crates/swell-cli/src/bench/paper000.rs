//! Paper 000's experiments (section 4.2, tables 4.1-4.3): the time of one frame (simulation and
//! rendering of a Gerstner sea) against the grid extent, the number of polygons and the number of
//! added waves.
//!
//! The paper's scene (section 4.1, figure 4.1): main wave of amplitude 40, speed 20, wavelength 50,
//! steepness 0.02, direction (1, 1), plus added waves, over a square grid of 100 x 100 quads. The
//! paper gives no unit of length (its grid is 100 to 800 "units" wide, drawn in a window of a few
//! hundred pixels); swell takes one paper unit as 0.1 m and scales every length and speed alike.
//! The paper's amplitude is not physical: A = 40 on L = 50 (A/L = 0.8) is ten times steeper than
//! water can stand (waves break near H/L = 1/7, A/L = 0.07), and drawn with swell it is a field of
//! spikes. swell keeps A/L = 0.07, the steepest real sea; the cost of a frame does not depend on
//! the amplitude beyond the few pixels the crests cover.
//!
//! The paper reports "ticks" without saying of which clock, so only the growth relative to the
//! first row is compared; swell reports milliseconds.

use glam::{Vec2, Vec3};
use swell::render::Renderer;
use swell::scene::{
    Camera, GerstnerSpec, Light, RenderSettings, Scene, Sky, WaterMaterial, WaterModelSpec, WaterSpec, WaterSurface,
    SCENE_VERSION,
};
use swell::water::GerstnerWave;
use swell::world::World;
use swell::Result;

use super::report::{PaperUnit, PlotKind, Point, Report, Series};
use super::timing::{measure, Stats};
use super::Context;

/// Metres per paper unit of length.
const METRES_PER_UNIT: f32 = 0.1;
/// Amplitude / wavelength of every wave: the steepest sea that does not break (see the module doc).
const AMPLITUDE_PER_WAVELENGTH: f32 = 0.07;
/// Image size of every frame, pixels (the paper does not give its window size).
pub const IMAGE: (u32, u32) = (800, 600);
/// Simulated time between frames, s.
const FRAME_DT: f64 = 1.0 / 30.0;

/// Table 4.1: grid extent (paper units) and mean frame time (ticks); 10 000 polygons, 3 waves.
const GRID_SIZE: [(u32, f64); 8] = [
    (100, 42782.0),
    (200, 43284.0),
    (300, 45594.0),
    (400, 47417.0),
    (500, 48903.0),
    (600, 50219.0),
    (700, 53101.0),
    (800, 56732.0),
];

/// Table 4.2: polygons and mean frame time (ticks); grid 400, 3 waves.
const POLYGONS: [(u32, f64); 16] = [
    (100, 14775.0),
    (400, 15180.0),
    (900, 17946.0),
    (1200, 20605.0),
    (1600, 21182.0),
    (2500, 23760.0),
    (3600, 25367.0),
    (4900, 28089.0),
    (6400, 34606.0),
    (8100, 39220.0),
    (10000, 47151.0),
    (12100, 55233.0),
    (14400, 65147.0),
    (16000, 74444.0),
    (19600, 86878.0),
    (22500, 95676.0),
];

/// Table 4.3: added waves and mean frame time (ticks); grid 400, 10 000 polygons.
const WAVES: [(u32, f64); 13] = [
    (0, 39753.0),
    (1, 41244.0),
    (2, 41453.0),
    (3, 44749.0),
    (4, 47229.0),
    (5, 47883.0),
    (6, 50893.0),
    (7, 52283.0),
    (8, 55608.0),
    (9, 57292.0),
    (10, 60908.0),
    (11, 61400.0),
    (12, 65104.0),
];

/// Directions of the added waves, as (x, z): the paper's figures 4.1 ((1, 0), (0, 1)), 4.3
/// ((-1, 2)), 4.4 ((1, 1.2), (1, 1.5), (1, 0.8)) and 4.5 ((-1, -1), (-1, 1.2)), then four more
/// spread around the compass for the 12 of table 4.3.
const ADDED_DIRECTIONS: [[f32; 2]; 12] = [
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 2.0],
    [1.0, 1.2],
    [1.0, 1.5],
    [1.0, 0.8],
    [-1.0, -1.0],
    [-1.0, 1.2],
    [2.0, 1.0],
    [1.0, -1.0],
    [-2.0, 1.0],
    [1.0, 2.0],
];

/// The main wave of figure 4.1 and `added` more, in metres.
///
/// The paper does not list the added waves' amplitudes, lengths or speeds (figure 4.5 says only
/// "different wavelengths and speeds"), so swell derives them: added wave k has wavelength
/// `50 * 0.85^(k+1)` units, the main wave's amplitude/wavelength ratio (paper 000 section 2.4 keeps
/// that ratio equal across waves; 0.07 rather than the paper's 0.8, see the module doc), speed scaled as `sqrt(L)` like deep-water waves, and the main
/// wave's steepness. Frame time depends only on how many waves there are.
pub fn paper_waves(added: usize) -> Vec<GerstnerWave> {
    let s = METRES_PER_UNIT;
    let main = GerstnerWave {
        amplitude: AMPLITUDE_PER_WAVELENGTH * 50.0 * s,
        wavelength: 50.0 * s,
        speed: 20.0 * s,
        direction: Vec2::new(1.0, 1.0),
        steepness: 0.02,
    };
    let mut waves = vec![main];
    for (k, d) in ADDED_DIRECTIONS.iter().take(added).enumerate() {
        let ratio = 0.85f32.powi(k as i32 + 1);
        waves.push(GerstnerWave {
            amplitude: main.amplitude * ratio,
            wavelength: main.wavelength * ratio,
            speed: main.speed * ratio.sqrt(),
            direction: Vec2::from_array(*d),
            ..main
        });
    }
    waves
}

/// Quads along x and z making exactly `polygons` quads, as square as possible (1200 = 30 x 40).
pub fn cells_for(polygons: u32) -> (u32, u32) {
    let root = (polygons as f64).sqrt().floor() as u32;
    let a = (1..=root.max(1)).rev().find(|a| polygons.is_multiple_of(*a)).unwrap_or(1);
    (a, polygons / a)
}

/// The paper's scene: a square grid `extent_units` wide of `cells` quads with the main wave and
/// `added` more, seen from a fixed camera that frames the largest (800-unit) grid.
pub fn scene(extent_units: u32, cells: (u32, u32), added: usize) -> Scene {
    let extent = extent_units as f32 * METRES_PER_UNIT;
    Scene {
        terrain: None,
        version: SCENE_VERSION,
        // Fixed for every row, as in the paper: a larger grid covers more of the image.
        camera: Camera {
            eye: Vec3::new(0.0, 55.0, 75.0),
            target: Vec3::new(0.0, -4.0, 0.0),
            up: Vec3::Y,
            fov_y_deg: 50.0,
            near: 0.5,
            far: 1000.0,
        },
        lights: vec![Light::Directional {
            direction: Vec3::new(0.4, -0.6, 0.5),
            color: Vec3::new(1.0, 0.96, 0.88),
            intensity: 1.0,
        }],
        // Beyond the patch the eye sees distant sea (as in the `sea` preset).
        sky: Sky { ground: Vec3::new(0.30, 0.40, 0.47), ..Sky::default() },
        water: Some(WaterSpec {
            surface: WaterSurface {
                size: Vec2::splat(extent),
                cells: [cells.0, cells.1],
                extent: Some(swell::scene::WaterExtent::Patch),
                ..WaterSurface::default()
            },
            // Gouraud shading, as in the paper.
            material: WaterMaterial::default(),
            model: WaterModelSpec::Gerstner(GerstnerSpec { waves: paper_waves(added) }),
            density: swell::body::SEA_WATER_DENSITY,
        }),
        render: RenderSettings { width: IMAGE.0, height: IMAGE.1, ..RenderSettings::default() },
        bodies: Vec::new(),
    }
}

/// Times frames of `scene`: `World::update` to the next time step, then `Renderer::render`.
pub fn frame_time(ctx: &Context, scene: Scene) -> Result<Stats> {
    let mut world = World::new(scene)?;
    let mut renderer = Renderer::new();
    let mut t = 0.0;
    measure(ctx.reps, || {
        t += FRAME_DT;
        world.update(t)?;
        renderer.render(&world);
        Ok(())
    })
}

fn setup(fixed: &str) -> Vec<String> {
    vec![
        format!(
            "Frame = `World::update` (Gerstner displacement and normals) + `Renderer::render` (sky, Gouraud-shaded \
             water) at {}x{} pixels, all threads.",
            IMAGE.0, IMAGE.1
        ),
        "Scene of the paper's figure 4.1 with 1 paper unit = 0.1 m: main wave L = 50, speed 20, steepness \
         0.02, direction (1, 1), amplitude 3.5 (A/L = 0.07, not the paper's unphysical 40); added waves derived \
         from it (see `bench/paper000.rs`)."
            .into(),
        format!("{fixed}."),
        "A paper \"polygon\" is a grid quad; swell draws it as two triangles.".into(),
        "The paper's unit, \"ticks\", is not defined: compare the growth columns (each curve divided by its \
         first row); growth ratio = swell's growth / the paper's."
            .into(),
    ]
}

fn report(ctx: &Context, experiment: &'static str, title: &str, table: &str, x_label: &str, fixed: &str) -> Report {
    Report {
        experiment,
        title: title.into(),
        source: format!("paper 000, table {table}"),
        setup: setup(fixed),
        x_label: x_label.into(),
        paper_unit: PaperUnit::Ticks,
        plot: PlotKind::Relative,
        series: vec![],
        machine: ctx.machine.clone(),
        repetitions: ctx.reps,
    }
}

/// `grid-size`: table 4.1.
pub fn grid_size(ctx: &Context) -> Result<Report> {
    let mut points = Vec::new();
    for (extent, paper) in GRID_SIZE {
        ctx.progress(&format!("grid {extent}x{extent}"));
        let swell = frame_time(ctx, scene(extent, (100, 100), 3))?;
        points.push(Point { x: extent as f64, label: format!("{extent}x{extent}"), swell, paper: Some(paper) });
    }
    let mut r = report(
        ctx,
        "grid-size",
        "frame time against grid extent",
        "4.1",
        "grid extent (paper units; x 0.1 m)",
        "10 000 polygons (100 x 100 quads), main wave + 3 added waves",
    );
    r.series.push(Series { name: String::new(), points });
    Ok(r)
}

/// `polygons`: table 4.2.
pub fn polygons(ctx: &Context) -> Result<Report> {
    let mut points = Vec::new();
    for (n, paper) in POLYGONS {
        let cells = cells_for(n);
        ctx.progress(&format!("{n} polygons"));
        let swell = frame_time(ctx, scene(400, cells, 3))?;
        points.push(Point { x: n as f64, label: format!("{n} ({}x{})", cells.0, cells.1), swell, paper: Some(paper) });
    }
    let mut r = report(
        ctx,
        "polygons",
        "frame time against polygon count",
        "4.2",
        "polygons (quads)",
        "Grid 400 x 400 units (40 m), main wave + 3 added waves; 1200 and 16 000 polygons are 30 x 40 and \
         125 x 128 quads",
    );
    r.series.push(Series { name: String::new(), points });
    Ok(r)
}

/// `waves`: table 4.3.
pub fn waves(ctx: &Context) -> Result<Report> {
    let mut points = Vec::new();
    for (n, paper) in WAVES {
        ctx.progress(&format!("{n} added waves"));
        let swell = frame_time(ctx, scene(400, (100, 100), n as usize))?;
        points.push(Point { x: n as f64, label: n.to_string(), swell, paper: Some(paper) });
    }
    let mut r = report(
        ctx,
        "waves",
        "frame time against added waves",
        "4.3",
        "added waves (besides the main wave)",
        "Grid 400 x 400 units (40 m), 10 000 polygons (100 x 100 quads)",
    );
    r.series.push(Series { name: String::new(), points });
    Ok(r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygon_counts_are_exact_and_nearly_square() {
        for (n, _) in POLYGONS {
            let (a, b) = cells_for(n);
            assert_eq!(a * b, n);
            assert!(a <= b && b <= a * 2, "{n} = {a} x {b}");
        }
        assert_eq!(cells_for(10_000), (100, 100));
        assert_eq!(cells_for(1200), (30, 40));
    }

    #[test]
    fn every_scene_of_the_tables_is_valid() {
        for added in 0..=12 {
            scene(400, (100, 100), added).validate().unwrap();
        }
        scene(800, cells_for(22_500), 3).validate().unwrap();
        assert_eq!(paper_waves(12).len(), 13);
    }
}
