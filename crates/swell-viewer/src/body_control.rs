//! Floating bodies in the viewer (issue 34): what a click drops (a crate, a buoy) and where it
//! lands, the push the keys give the selected body, and what each frame reports of the bodies.
//!
//! All of it acts on the render thread's [`World`], the one simulated and shown: a drop is added
//! there with [`World::add_body`] (which also writes it into that world's scene, its release time
//! the next body step's), and the spec it added goes back to the UI with the frame, where the
//! editor appends the very same spec to its scenes ([`crate::editor::SceneEditor::body_dropped`]).
//! The next scene the UI sends then has the bodies the world has, so the world is not rebuilt
//! ([`World::needs_rebuild_for`]) and the saved scene replays the drop. A push is a force
//! ([`swell::body::FloatingBody::thrust`]), not part of the scene: it is set again with every
//! frame's request and gone when the keys are let go.

use glam::{DQuat, DVec3, EulerRot, Vec2, Vec3};
use swell::body::{BodyShape, BodySpec};
use swell::scene::Camera;
use swell::world::World;
use swell::{Error, Result};

use crate::picking::{surface_point, Ray};

/// What a click on the water or an *Add* button of the bodies panel drops.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DropKind {
    /// A wooden crate: a [`CRATE_SIZE_M`] cube at the default density (500 kg/m³), floating half
    /// under water.
    Crate,
    /// A buoy: a sphere of [`BUOY_RADIUS_M`] at [`BUOY_DENSITY`], in [`BUOY_COLOR`].
    Buoy,
}

/// Side of a dropped crate, m: a cube, so that it floats level whichever way it lands.
pub const CRATE_SIZE_M: f32 = 1.0;

/// Radius of a dropped buoy, m.
pub const BUOY_RADIUS_M: f32 = 0.4;

/// Density of a dropped buoy, kg/m³: a hollow float riding high (about a third under water).
pub const BUOY_DENSITY: f32 = 300.0;

/// A buoy's colour (linear RGB): international orange, to tell it from crates at a distance.
pub const BUOY_COLOR: Vec3 = Vec3::new(0.8, 0.12, 0.02);

/// How far above the surface under it (m) a dropped body's lowest point starts: it falls about
/// half a second, enough to see it drop and splash, not so long that it lands far from a moving
/// crest.
pub const DROP_CLEARANCE_M: f32 = 1.0;

/// How far ahead of the eye (m, horizontally) a body is dropped when the ray meets no water (it
/// points at the sky): the *Add* buttons with the camera looking up.
pub const DROP_AHEAD_M: f32 = 10.0;

/// Acceleration (m/s²) a push gives its body: the force is this times the body's mass, so a
/// crate and a ship answer the keys alike (before the water's drag, which slows the larger less).
pub const PUSH_ACCELERATION: f64 = 2.0;

impl DropKind {
    /// Both kinds, in the order the panel offers them.
    pub const ALL: [DropKind; 2] = [DropKind::Crate, DropKind::Buoy];

    /// Its name: the panel's label and the prefix of the names of the bodies it drops.
    pub fn name(self) -> &'static str {
        match self {
            DropKind::Crate => "crate",
            DropKind::Buoy => "buoy",
        }
    }

    /// The body it drops, named `name`, at `position` (its centre of mass).
    pub fn spec(self, name: String, position: Vec3) -> BodySpec {
        let mut spec = match self {
            DropKind::Crate => BodySpec::new(BodyShape::Box, &[CRATE_SIZE_M; 3], position),
            DropKind::Buoy => {
                let mut s = BodySpec::new(BodyShape::Sphere, &[BUOY_RADIUS_M], position);
                s.density = Some(BUOY_DENSITY);
                s.color = BUOY_COLOR;
                s
            }
        };
        spec.name = name;
        spec
    }
}

/// `prefix` followed by the smallest number from 1 that no body of `bodies` is called (a body
/// without a name is called `body<k>`, k its index): `crate1`, `crate2`, ...
pub fn free_name(prefix: &str, bodies: &[BodySpec]) -> String {
    let taken = |n: &str| {
        bodies.iter().enumerate().any(|(i, b)| if b.name.is_empty() { format!("body{i}") == n } else { b.name == n })
    };
    (1..).map(|k| format!("{prefix}{k}")).find(|n| !taken(n)).expect("a free name")
}

/// A body to drop where `ray` (from a click, or the view's centre) meets the surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyDrop {
    /// What to drop.
    pub kind: DropKind,
    /// The ray it drops along (world).
    pub ray: Ray,
}

/// Height (m) of what a body lands on at world (x, z): the drawn water or, where it is higher,
/// the ground; `None` where there is neither.
pub fn surface_height(world: &World, x: f32, z: f32) -> Option<f32> {
    let water = world.water_height_at(x, z).filter(|h| h.is_finite());
    let ground = world.terrain.as_ref().and_then(|t| t.ground_height(x, z));
    match (water, ground) {
        (Some(w), Some(g)) => Some(w.max(g)),
        (w, g) => w.or(g),
    }
}

/// How far (m) the lowest point of `spec`'s hull lies below its centre of mass in the starting
/// orientation. Refused, naming the key, for a spec that is not valid or whose mesh cannot be
/// read.
pub fn depth_below_centre(spec: &BodySpec, key: &str) -> Result<f32> {
    spec.validate(key)?;
    let hull = spec.hull(key)?;
    let com = hull.mass_properties().centroid + spec.center_of_mass.unwrap_or(Vec3::ZERO).as_dvec3();
    let r = spec.rotation_deg.as_dvec3() * (std::f64::consts::PI / 180.0);
    let turn = DQuat::from_euler(EulerRot::YXZ, r.x, r.y, r.z);
    let lowest = hull.positions.iter().map(|p| (turn * (p.as_dvec3() - com)).y).fold(f64::INFINITY, f64::min);
    Ok((-lowest).max(0.0) as f32)
}

/// Drops `drop` into `world` at the point its ray first meets the water or the ground (a point
/// [`DROP_AHEAD_M`] ahead of the eye if it meets neither), its lowest point
/// [`DROP_CLEARANCE_M`] above the surface there, named by [`free_name`]. Returns the spec as the
/// world's scene now holds it (with the release time [`World::add_body`] gave it). Refused,
/// changing nothing, like any body the world refuses (too many bodies, inside the terrain).
pub fn drop_into(world: &mut World, drop: &BodyDrop) -> Result<BodySpec> {
    let ray = &drop.ray;
    let at = surface_point(ray, |x, z| surface_height(world, x, z)).unwrap_or_else(|| {
        let ahead = Vec3::new(ray.direction.x, 0.0, ray.direction.z).normalize_or_zero();
        ray.origin + ahead * DROP_AHEAD_M
    });
    if !at.is_finite() {
        return Err(Error::invalid("drop", format!("the point {at} under the pointer is not finite")));
    }
    let k = world.scene.bodies.len();
    let key = format!("body[{k}]");
    let mut spec = drop.kind.spec(free_name(drop.kind.name(), &world.scene.bodies), Vec3::ZERO);
    let below = depth_below_centre(&spec, &key)?;
    let surface = surface_height(world, at.x, at.z).unwrap_or(0.0);
    spec.position = Vec3::new(at.x, surface + DROP_CLEARANCE_M + below, at.z);
    // Released at the next body step after the world's time, even into a world that had no body.
    let k = world.add_body(spec)?;
    Ok(world.scene.bodies[k].clone())
}

/// A push on body `body` (its index in the scene) along `direction`, a horizontal unit vector
/// (world x, z), with [`PUSH_ACCELERATION`] times the body's mass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Push {
    /// Index of the body in the scene's `[[body]]` list.
    pub body: usize,
    /// Direction in the world's horizontal plane (x, z), unit length.
    pub direction: Vec2,
}

/// The horizontal direction (world x, z, unit) of a push `forward` along the camera's view and
/// `right` to its right, as the camera looks now (each usually -1, 0 or 1: the keys held); `None`
/// when they cancel or the camera gives no horizontal heading.
///
/// Forward is the view direction laid flat; looking straight down, where that vanishes, it is
/// the camera's `up` laid flat (what is up on the screen).
pub fn push_direction(camera: &Camera, forward: f32, right: f32) -> Option<Vec2> {
    let flat = |v: Vec3| Vec2::new(v.x, v.z).try_normalize();
    let view = camera.target - camera.eye;
    let ahead = flat(view).filter(|_| view.normalize_or_zero().y.abs() < 0.9999).or_else(|| flat(camera.up))?;
    // Right of the heading with +Y up: (x, z) -> (-z, x).
    let side = Vec2::new(-ahead.y, ahead.x);
    (ahead * forward + side * right).try_normalize()
}

/// Sets every body's thrust in `world`: [`PUSH_ACCELERATION`] times its mass along the push for
/// the pushed body, none for the others (a push from an earlier frame is taken away). A push
/// naming no body of the world does nothing.
pub fn apply_push(world: &mut World, push: Option<Push>) {
    for (i, b) in world.bodies.bodies_mut().iter_mut().enumerate() {
        b.thrust = match push {
            Some(p) if p.body == i => {
                let d = p.direction.as_dvec2();
                DVec3::new(d.x, 0.0, d.y) * (PUSH_ACCELERATION * b.material.mass)
            }
            _ => DVec3::ZERO,
        };
    }
}

/// One body as the last frame showed it, for the panel (and scripted checks).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LiveBody {
    /// Centre of mass at the frame's time, world m.
    pub position: Vec3,
    /// Velocity of the centre of mass at the last body step, m/s.
    pub velocity: Vec3,
    /// Height (m) of the water under the centre of mass at the frame's time; `None` without water.
    pub water_height: Option<f32>,
    /// Mass, kg.
    pub mass: f32,
}

/// Every body of `world` at the time of its last update, in scene order.
pub fn live_bodies(world: &World) -> Vec<LiveBody> {
    world
        .bodies
        .bodies()
        .iter()
        .zip(world.body_poses())
        .map(|(b, pose)| {
            let position = pose.position.as_vec3();
            LiveBody {
                position,
                velocity: b.state.velocity.as_vec3(),
                water_height: world.water_height_at(position.x, position.z),
                mass: b.material.mass as f32,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use swell::scene::preset;

    use super::*;

    /// The `ocean` preset (the FFT sea) at `t` s, on a coarse grid to keep the test quick.
    fn ocean(t: f64) -> World {
        let mut scene = preset("ocean").unwrap();
        let w = scene.water.as_mut().unwrap();
        w.surface.cells = [64, 64];
        let mut world = World::new(scene).unwrap();
        world.update(t).unwrap();
        world
    }

    fn down_at(world: &World, x: f32, z: f32) -> Ray {
        let eye = world.scene.camera.eye;
        Ray { origin: eye, direction: Vec3::new(x, 0.0, z) - eye }
    }

    #[test]
    fn a_dropped_crate_falls_from_above_the_waves_and_floats_on_the_fft_sea() {
        let mut world = ocean(2.0);
        let ray = down_at(&world, 0.0, 60.0);
        let spec = drop_into(&mut world, &BodyDrop { kind: DropKind::Crate, ray }).unwrap();
        assert_eq!(spec.name, "crate1");
        assert_eq!(world.scene.bodies, vec![spec.clone()], "the world's scene holds what was returned");
        // Held until the next 120 Hz step after the drop, so that a saved scene replays it.
        assert!(spec.release_time > 2.0 && spec.release_time <= 2.0 + 1.0 / 120.0 + 1e-9, "{}", spec.release_time);
        // Where the ray meets the water, a metre above the surface there (plus half the cube).
        let h = world.water_height_at(spec.position.x, spec.position.z).unwrap();
        let gap = spec.position.y - 0.5 * CRATE_SIZE_M - h;
        assert!((gap - DROP_CLEARANCE_M).abs() < 0.05, "dropped {gap} m above the water");
        let along = Vec2::new(spec.position.x, spec.position.z) - Vec2::new(ray.origin.x, ray.origin.z);
        let aim = Vec2::new(ray.direction.x, ray.direction.z);
        assert!(along.perp_dot(aim).abs() < 1e-3 * aim.length() * along.length(), "not under the ray");
        // Four seconds later it bobs at the surface: afloat, neither sunk nor flung away.
        let mut off = Vec::new();
        for k in 1..=240 {
            world.update(2.0 + f64::from(k) / 60.0).unwrap();
            let live = live_bodies(&world)[0];
            if k > 120 {
                off.push(live.position.y - live.water_height.unwrap());
            }
        }
        let mean = off.iter().sum::<f32>() / off.len() as f32;
        // (Measured: mean -0.02 m, at most 0.33 m on this 3 m sea.)
        assert!(mean.abs() < 0.15 && off.iter().all(|d| d.abs() < 0.8), "centre above the water: {off:?}");
        // A second drop gets the next free name, and a buoy its own.
        let b = drop_into(&mut world, &BodyDrop { kind: DropKind::Crate, ray }).unwrap();
        let c = drop_into(&mut world, &BodyDrop { kind: DropKind::Buoy, ray }).unwrap();
        assert_eq!((b.name.as_str(), c.name.as_str()), ("crate2", "buoy1"));
        assert_eq!((c.shape, c.density, c.color), (BodyShape::Sphere, Some(BUOY_DENSITY), BUOY_COLOR));
    }

    #[test]
    fn a_ray_into_the_sky_drops_ahead_and_land_is_landed_on() {
        let mut world = ocean(0.5);
        let eye = world.scene.camera.eye;
        let up = Ray { origin: eye, direction: Vec3::new(0.0, 1.0, -1.0) };
        let spec = drop_into(&mut world, &BodyDrop { kind: DropKind::Buoy, ray: up }).unwrap();
        let ahead = Vec2::new(spec.position.x - eye.x, spec.position.z - eye.z);
        assert!((ahead - Vec2::new(0.0, -DROP_AHEAD_M)).length() < 1e-4, "{ahead}");
        // On land the body starts above the ground rather than inside it.
        let mut scene = preset("valley-lake").unwrap();
        scene.water.as_mut().unwrap().surface.cells = [32, 32];
        let mut lake = World::new(scene).unwrap();
        let t = lake.terrain.as_ref().unwrap();
        let (x, z) = (0..400)
            .map(|i| (i as f32 - 200.0, 0.0))
            .find(|&(x, z)| t.ground_height(x, z).is_some_and(|g| g > 1.0))
            .expect("land above the water somewhere along x");
        let g = t.ground_height(x, z).unwrap();
        let ray = Ray { origin: Vec3::new(x, g + 50.0, z + 1.0), direction: Vec3::new(0.0, -50.0, -1.0) };
        let spec = drop_into(&mut lake, &BodyDrop { kind: DropKind::Crate, ray }).unwrap();
        let t = lake.terrain.as_ref().unwrap();
        let under = t.ground_height(spec.position.x, spec.position.z).unwrap();
        let gap = spec.position.y - 0.5 * CRATE_SIZE_M - under;
        assert!((gap - DROP_CLEARANCE_M).abs() < 0.05, "{} over ground at {under}", spec.position);
    }

    #[test]
    fn a_refused_drop_changes_nothing_and_says_why() {
        let bad = BodySpec::new(BodyShape::Sphere, &[-1.0], Vec3::ZERO);
        assert!(depth_below_centre(&bad, "body[0]").unwrap_err().to_string().contains("body[0].size"));
        // A scene already holding the most bodies there may be: the library refuses one more.
        let mut scene = preset("sea").unwrap();
        scene.water = None;
        scene.bodies = (0..swell::body::MAX_BODIES)
            .map(|i| BodySpec::new(BodyShape::Sphere, &[0.5], Vec3::new(i as f32 * 2.0, 0.0, 0.0)))
            .collect();
        let mut world = World::new(scene.clone()).unwrap();
        let ray = Ray { origin: Vec3::new(0.0, 10.0, 10.0), direction: Vec3::new(0.0, -1.0, -1.0) };
        let e = drop_into(&mut world, &BodyDrop { kind: DropKind::Crate, ray }).unwrap_err().to_string();
        assert!(e.contains(&format!("[0, {}] bodies", swell::body::MAX_BODIES)), "{e}");
        assert_eq!(world.scene.bodies, scene.bodies);
        assert_eq!(world.bodies.len(), swell::body::MAX_BODIES);
    }

    #[test]
    fn names_skip_taken_ones_and_unnamed_bodies_by_their_index() {
        let mut bodies = vec![BodySpec::new(BodyShape::Sphere, &[0.5], Vec3::ZERO)];
        assert_eq!(free_name("body", &bodies), "body1");
        bodies[0].name = "crate1".into();
        bodies.push(BodySpec::new(BodyShape::Sphere, &[0.5], Vec3::ZERO));
        assert_eq!(free_name("crate", &bodies), "crate2");
        // The unnamed second body is `body1`.
        assert_eq!(free_name("body", &bodies), "body2");
    }

    #[test]
    fn pushes_follow_the_camera_s_heading_on_the_horizontal_plane() {
        let mut cam = Camera { eye: Vec3::new(0.0, 10.0, 20.0), target: Vec3::ZERO, ..Camera::default() };
        let close = |a: Option<Vec2>, b: Vec2| a.is_some_and(|a| (a - b).length() < 1e-5);
        // Looking along -z: forward is -z, right is +x.
        assert!(close(push_direction(&cam, 1.0, 0.0), Vec2::new(0.0, -1.0)));
        assert!(close(push_direction(&cam, 0.0, 1.0), Vec2::new(1.0, 0.0)));
        assert!(close(push_direction(&cam, -1.0, -1.0), Vec2::new(-1.0, 1.0).normalize()));
        assert_eq!(push_direction(&cam, 0.0, 0.0), None);
        assert_eq!(
            push_direction(&cam, 1.0, 0.0).zip(push_direction(&cam, -1.0, 0.0)).map(|(a, b)| a + b),
            Some(Vec2::ZERO)
        );
        // Turned to look along +x: forward +x, right +z.
        cam.eye = Vec3::new(-20.0, 10.0, 0.0);
        assert!(close(push_direction(&cam, 1.0, 0.0), Vec2::new(1.0, 0.0)));
        assert!(close(push_direction(&cam, 0.0, 1.0), Vec2::new(0.0, 1.0)));
        // Straight down, the screen's up (the camera's up) is forward.
        cam = Camera { eye: Vec3::new(0.0, 30.0, 0.0), target: Vec3::ZERO, up: Vec3::NEG_Z, ..Camera::default() };
        assert!(close(push_direction(&cam, 1.0, 0.0), Vec2::new(0.0, -1.0)));
    }

    #[test]
    fn a_push_moves_the_pushed_body_and_only_while_it_lasts() {
        let mut scene = preset("sea").unwrap();
        scene.water.as_mut().unwrap().surface.cells = [32, 32];
        let mut specs = [
            DropKind::Crate.spec("a".into(), Vec3::new(0.0, 0.0, 0.0)),
            DropKind::Crate.spec("b".into(), Vec3::new(10.0, 0.0, 0.0)),
        ];
        for s in &mut specs {
            s.linear_drag = 0.0;
        }
        scene.bodies = specs.to_vec();
        let run = |push: Option<Push>| {
            let mut w = World::new(scene.clone()).unwrap();
            for k in 0..=120 {
                apply_push(&mut w, push);
                w.update(f64::from(k) / 60.0).unwrap();
            }
            apply_push(&mut w, None);
            assert!(w.bodies.bodies().iter().all(|b| b.thrust == DVec3::ZERO), "the push was not taken away");
            live_bodies(&w)
        };
        let free = run(None);
        let pushed = run(Some(Push { body: 1, direction: Vec2::new(0.0, 1.0) }));
        // Two seconds at 2 m/s²: at most ½ a t² = 4 m along +z for the pushed body, less the
        // water's drag (measured 3.15 m), and the other exactly where it drifts without.
        let dz = pushed[1].position.z - free[1].position.z;
        assert!(dz > 2.0 && dz < 4.0, "pushed {dz} m");
        assert!((pushed[1].position.x - free[1].position.x).abs() < 0.2 * dz);
        assert_eq!(pushed[0], free[0]);
        // The force scales with the mass: the live mass is the body's.
        assert!((free[0].mass - 500.0).abs() < 1.0, "{}", free[0].mass);
        // A push naming no body changes nothing.
        assert_eq!(run(Some(Push { body: 7, direction: Vec2::X })), free);
    }
}
