//! A scene made runnable: its models built and its meshes allocated, updated frame by frame.

use super::world_environment::WorldEnvironment;
use super::TerrainBody;
use crate::body::{BodyPose, FloatingBodies};
use crate::error::Result;
use crate::math::GridSpec;
use crate::mesh::{Clipmap, DrawnSurface, SurfaceMesh};
use crate::scene::{Scene, WaterExtent, WaterMaterial, WaterPlacement};
use crate::shading::{FoamPattern, Texture};
use crate::water::{UnresolvedSlopes, WaveModel};

/// The water of a [`World`]: the model, the surface that is drawn and the material it is drawn
/// with.
pub struct WaterBody {
    /// The wave model, built from the scene. It works in the patch's own frame: query it through
    /// [`World::water_height_at`] for world coordinates when the patch is turned or scaled.
    pub model: Box<dyn WaveModel>,
    /// The surface a frame draws, in world coordinates, moved by [`World::update`]: the patch for
    /// `extent = "patch"`, the rings around the scene's camera for an unbounded sea. The one
    /// owner of the drawn water: the renderer and its overlays draw exactly this.
    pub surface: DrawnSurface,
    /// The patch's own (local) `size` x `cells` grid: what bakes and exports sample, whatever is
    /// drawn ([`World::sample_patch`]).
    pub patch_grid: GridSpec,
    /// Where the patch sits: the map from the model's frame to the world.
    pub placement: WaterPlacement,
    /// How it looks.
    pub material: WaterMaterial,
    /// The material's texture, loaded or generated, if it names one.
    pub texture: Option<Texture>,
    /// The structure of its foam (`foam_texture`), loaded or generated.
    pub foam_pattern: FoamPattern,
    /// How far the water reaches ([`crate::scene::Scene::water_extent`]): an unbounded sea is
    /// drawn from camera-following rings ([`crate::mesh::Clipmap`]) and a far field beyond them.
    pub extent: WaterExtent,
    /// The model's slope spectrum in world units, for filtering what a pixel cannot resolve.
    pub slopes: UnresolvedSlopes,
}

/// Refuses a mesh holding NaN or infinity, so it never reaches the rasterizer or a file. Validation
/// bounds every parameter, so this only fires on combinations the bounds do not foresee.
fn check_finite_mesh(positions: &[glam::Vec3], normals: &[glam::Vec3], t: f64) -> Result<()> {
    use rayon::prelude::*;
    let finite = |v: &glam::Vec3| v.is_finite();
    if positions.par_iter().all(finite) && normals.par_iter().all(finite) {
        Ok(())
    } else {
        Err(crate::Error::Unstable(format!(
            "the water model produced non-finite positions or normals at time {t} s; \
             reduce the wave amplitudes, wavelengths or speeds in [water]"
        )))
    }
}

/// Refuses body `i` if its centre of mass starts below the terrain's ground.
fn check_above_ground(terrain: Option<&TerrainBody>, body: &crate::body::FloatingBody, i: usize) -> Result<()> {
    let p = body.initial.position;
    let Some(g) = terrain.and_then(|t| t.ground_height(p.x as f32, p.z as f32)) else { return Ok(()) };
    if p.y >= f64::from(g) {
        return Ok(());
    }
    Err(crate::Error::invalid(
        format!("body[{i}].position"),
        format!(
            "[{}, {}, {}] starts inside the terrain, whose ground is at y = {g} m there; start it above the ground",
            p.x, p.y, p.z
        ),
    ))
}

/// A [`Scene`] with its models built; [`World::update`] moves it to a time.
pub struct World {
    /// The scene it was built from.
    pub scene: Scene,
    /// The water, if the scene has any.
    pub water: Option<WaterBody>,
    /// The terrain, if the scene has any (static: built once, not changed by updates).
    pub terrain: Option<TerrainBody>,
    /// The scene's floating bodies (`[[body]]`), stepped by every update to its time.
    pub bodies: FloatingBodies,
    /// Every body's pose at the time of the last update, in the order of [`World::bodies`].
    body_poses: Vec<BodyPose>,
    time: f64,
}

impl World {
    /// Validates `scene`, builds its models and allocates its meshes (the only allocation: updates
    /// reuse these buffers).
    pub fn new(scene: Scene) -> Result<Self> {
        scene.validate()?;
        let mut terrain = match &scene.terrain {
            Some(spec) => Some(TerrainBody::new(spec)?),
            None => None,
        };
        // Ground is wet only where there is water to wet it.
        if let (Some(t), None) = (terrain.as_mut(), &scene.water) {
            t.material.wet_height = 0.0;
        }
        let water = match &scene.water {
            Some(spec) => {
                let model = spec.model.build()?;
                let patch_grid = spec.surface.grid()?;
                let placement = spec.surface.placement()?;
                // Unset, the extent follows the model and whether the terrain holds the water.
                let held = terrain.as_ref().is_some_and(|t| !t.border_under_water());
                let extent = spec.surface.extent.unwrap_or_else(|| WaterExtent::default_for(&spec.model, held));
                let surface = match extent {
                    WaterExtent::Patch => DrawnSurface::Patch(SurfaceMesh::new(patch_grid)),
                    WaterExtent::Unbounded => {
                        let lod = spec.surface.lod;
                        let spacing = lod.resolved_spacing(&patch_grid);
                        DrawnSurface::Rings(Clipmap::new(lod.levels, lod.ring_cells, spacing)?)
                    }
                };
                // A flowing model (the river) slides a texture with its flow.
                let material = spec.material.with_flow(spec.model.params().surface_flow(), &placement);
                let texture = material.load_texture()?;
                let foam_pattern = material.load_foam_pattern()?;
                let mut components = Vec::new();
                model.slope_components(&mut components);
                // A uniform scale keeps slopes and divides wavenumbers: the table is in world units.
                for c in &mut components {
                    c.0 /= placement.scale;
                }
                let slopes = UnresolvedSlopes::from_components(&components);
                Some(WaterBody {
                    model,
                    surface,
                    patch_grid,
                    placement,
                    material,
                    texture,
                    foam_pattern,
                    extent,
                    slopes,
                })
            }
            None => None,
        };
        let density = scene.water.as_ref().map_or(crate::body::SEA_WATER_DENSITY, |w| w.density);
        let bodies = FloatingBodies::from_specs(&scene.bodies, density)?;
        for (i, b) in bodies.bodies().iter().enumerate() {
            check_above_ground(terrain.as_ref(), b, i)?;
        }
        let mut world = Self { scene, water, terrain, bodies, body_poses: Vec::new(), time: f64::NAN };
        world.update(0.0)?;
        Ok(world)
    }

    /// Whether showing `scene` needs a new world ([`World::new`]) rather than a swap of
    /// [`World::scene`]: water and terrain are built into the world (models, meshes, the water's
    /// state, and the depths the water model may take from the terrain below), everything else
    /// (camera, lights, sky, render settings) is read from the scene at draw time.
    pub fn needs_rebuild_for(&self, scene: &Scene) -> bool {
        scene.water != self.scene.water || scene.terrain != self.scene.terrain || scene.bodies != self.scene.bodies
    }

    /// Moves every model to time `t` (s) and the drawn water surface with it, once: the rings of
    /// an unbounded sea follow the scene's camera, then the surface is displaced, placed in the
    /// world, foamed and checked for non-finite values.
    ///
    /// Fails only when a model became unstable or produced non-finite values; the surface then
    /// keeps the last good frame's buffers.
    pub fn update(&mut self, t: f64) -> Result<()> {
        self.advance(t)?;
        if let Some(w) = &mut self.water {
            let eye = self.scene.camera.eye;
            w.surface.follow(w.placement.to_local_xz(glam::Vec2::new(eye.x, eye.z)));
            w.surface.displace(w.model.as_ref(), t);
            let (positions, normals) = w.surface.positions_and_normals_mut();
            w.placement.apply_to(positions, normals);
            check_finite_mesh(positions, normals, t)?;
        }
        Ok(())
    }

    /// Moves every model to time `t` (s) without touching the drawn surface: for bakes and
    /// exports, which sample the patch ([`World::sample_patch`]) and draw nothing. The drawn
    /// surface keeps the time of the last [`World::update`] until the next one.
    ///
    /// The floating bodies are stepped first, at their fixed rate up to `t`, each step with the
    /// water model at that step's time; then the model moves to `t` and the bodies' poses at `t`
    /// are taken ([`World::body_poses`]).
    pub fn advance(&mut self, t: f64) -> Result<()> {
        // Without bodies this only counts the steps (no model is advanced), so that a body added
        // later joins at this time's step.
        let mut env = WorldEnvironment { water: self.water.as_mut(), terrain: self.terrain.as_ref() };
        self.bodies.advance(t, &mut env)?;
        if let Some(w) = &mut self.water {
            w.model.advance(t)?;
        }
        self.body_poses = self.bodies.poses_at(t).unwrap_or_default();
        self.time = t;
        Ok(())
    }

    /// Adds a floating body to the running world and to its scene (`[[body]]`), as the viewer's
    /// click drops a crate: its `release_time` becomes at least the next body step's time, so
    /// the scene saved afterwards replays the drop exactly; an empty name becomes `body<k>`.
    /// Returns the body's index. Refused like a scene's body (naming `body[k]`), and when it
    /// starts inside the terrain.
    pub fn add_body(&mut self, mut spec: crate::body::BodySpec) -> Result<usize> {
        let k = self.scene.bodies.len();
        let next = FloatingBodies::step_time(self.bodies.steps() + 1);
        spec.release_time = spec.release_time.max(next);
        if spec.name.is_empty() {
            let taken = |n: &str| self.scene.bodies.iter().any(|b| b.name == n);
            spec.name = (k..).map(|i| format!("body{i}")).find(|n| !taken(n)).expect("a free name");
        }
        let mut all = self.scene.bodies.clone();
        all.push(spec.clone());
        crate::body::validate_bodies(&all)?;
        let body = spec.build(k, &format!("body[{k}]"))?;
        check_above_ground(self.terrain.as_ref(), &body, k)?;
        self.bodies.push(body)?;
        self.scene.bodies.push(spec);
        // The new body hangs at its initial pose until the next step: it has a pose now.
        if let Some(poses) = self.bodies.poses_at(self.time) {
            self.body_poses = poses;
        }
        Ok(k)
    }

    /// Every floating body's pose at the time of the last [`World::update`] or
    /// [`World::advance`], in the order of the scene's `[[body]]`s.
    pub fn body_poses(&self) -> &[BodyPose] {
        &self.body_poses
    }

    /// A mesh over the water's patch ([`WaterBody::patch_grid`]), at rest: the buffer
    /// [`World::sample_patch`] fills. `None` without water.
    pub fn new_patch_mesh(&self) -> Option<SurfaceMesh> {
        self.water.as_ref().map(|w| SurfaceMesh::new(w.patch_grid))
    }

    /// The water's patch at the time of the last [`World::update`] or [`World::advance`], in a new
    /// mesh ([`World::sample_patch`] refills one); `None` without water.
    pub fn patch_mesh(&self) -> Result<Option<SurfaceMesh>> {
        let Some(mut mesh) = self.new_patch_mesh() else { return Ok(None) };
        self.sample_patch(&mut mesh)?;
        Ok(Some(mesh))
    }

    /// Displaces `mesh` (made by [`World::new_patch_mesh`]; another grid is replaced by the
    /// patch's) as the water's patch at the time of the last [`World::update`] or
    /// [`World::advance`], placed in the world, with foam, and checked for non-finite values:
    /// what bakes and exports write, whatever extent is drawn. Without water, nothing changes.
    pub fn sample_patch(&self, mesh: &mut SurfaceMesh) -> Result<()> {
        let Some(w) = &self.water else { return Ok(()) };
        if mesh.grid != w.patch_grid {
            *mesh = SurfaceMesh::new(w.patch_grid);
        }
        mesh.displace(w.model.as_ref(), self.time);
        w.placement.apply(mesh);
        check_finite_mesh(&mesh.positions, &mesh.normals, self.time)
    }

    /// Depth (m) of the ground below the water at rest (y = 0) at world (x, z): positive under
    /// water, negative on dry land, `None` where there is no terrain below (deep water).
    pub fn depth_at(&self, x: f32, z: f32) -> Option<f32> {
        self.terrain.as_ref().and_then(|t| t.depth_at(x, z))
    }

    /// Height (m above rest) of the water surface over world (x, z) at the time of the last
    /// [`World::update`], with the patch's turn and scale applied (the model is asked at the local
    /// point that lands there; heights scale with the patch). `None` without water. Like the
    /// models' own [`WaveModel::height_at`], it covers the whole plane, not only the patch.
    pub fn water_height_at(&self, x: f32, z: f32) -> Option<f32> {
        let w = self.water.as_ref()?;
        let l = w.placement.to_local_xz(glam::Vec2::new(x, z));
        Some(w.placement.to_world_height(w.model.height_at(l.x, l.y, self.time)))
    }

    /// The local (x, z) of the water's frame under world (x, z): where to apply a model-frame
    /// operation such as a drop on the spring mesh. The identity without water.
    pub fn water_local_xz(&self, x: f32, z: f32) -> glam::Vec2 {
        let p = glam::Vec2::new(x, z);
        self.water.as_ref().map_or(p, |w| w.placement.to_local_xz(p))
    }

    /// Drops a dent `depth` m deep and `radius` m wide on the water at world (x, z) (a click, a
    /// stone), for models with state (the spring mesh). A turned or scaled patch gets it at the
    /// model-frame point under (x, z), sized so that it is `depth` x `radius` in the world. Returns
    /// false, changing nothing, without water or for a closed-form model. The mesh shows the dent
    /// after the next [`World::update`].
    pub fn disturb_water(&mut self, x: f32, z: f32, depth: f32, radius: f32) -> Result<bool> {
        let local = self.water_local_xz(x, z);
        let Some(w) = &mut self.water else { return Ok(false) };
        let s = w.placement.scale;
        w.model.disturb(local.x, local.y, depth / s, radius / s)
    }

    /// The time of the last [`World::update`], seconds.
    pub fn time(&self) -> f64 {
        self.time
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    /// A small sines sea (no horizontal motion, so heights at mesh vertices are exact), placed by
    /// the given keys.
    fn sea(placement: &str) -> World {
        let text = format!(
            "version = 1\n[camera]\neye = [0.0, 30.0, 30.0]\ntarget = [0.0, 0.0, 0.0]\n\
             [water]\nmodel = 'sines'\nsize = [20.0, 12.0]\ncells = [10, 6]\n{placement}\n\
             [[water.waves]]\namplitude = 0.4\nwavelength = 9.0\nspeed = 3.0\ndirection = [1.0, 0.3]\n\
             [[water.waves]]\namplitude = 0.2\nwavelength = 4.0\nspeed = 2.0\ndirection = [-0.2, 1.0]\n"
        );
        let mut w = World::new(Scene::from_toml(&text, "t").unwrap()).unwrap();
        w.update(1.3).unwrap();
        w
    }

    #[test]
    fn a_turned_sea_has_the_unturned_sea_s_height_at_the_turned_point() {
        let plain = sea("");
        let turned = sea("yaw_deg = 90.0");
        // Ry(90 deg) carries local +X to world -Z, so world (x, z) shows local (-z, x).
        for (x, z) in [(1.0, 2.0), (-3.5, 0.7), (7.0, -4.0)] {
            let (a, b) = (turned.water_height_at(x, z).unwrap(), plain.water_height_at(-z, x).unwrap());
            assert!((a - b).abs() < 1e-5, "({x}, {z}): {a} vs {b}");
        }
        assert!(plain.water_height_at(1.0, 2.0) != turned.water_height_at(1.0, 2.0));
    }

    #[test]
    fn the_mesh_is_turned_and_scaled_about_the_centre_and_agrees_with_the_height_query() {
        let plain = sea("center = [4.0, -2.0]");
        let placed = sea("center = [4.0, -2.0]\nyaw_deg = 90.0\nuniform_scale = 2.0");
        let (a, b) = (plain.patch_mesh().unwrap().unwrap(), placed.patch_mesh().unwrap().unwrap());
        let c = Vec3::new(4.0, 0.0, -2.0);
        for k in 0..a.positions.len() {
            let d = a.positions[k] - c;
            // Quarter turn (local +X to -Z, +Z to +X), then twice the size, heights included.
            let expected = c + 2.0 * Vec3::new(d.z, d.y, -d.x);
            assert!((b.positions[k] - expected).length() < 1e-4, "vertex {k}: {} vs {expected}", b.positions[k]);
            let n = a.normals[k];
            assert!((b.normals[k] - Vec3::new(n.z, n.y, -n.x)).length() < 1e-5);
            let p = b.positions[k];
            let h = placed.water_height_at(p.x, p.z).unwrap();
            assert!((h - p.y).abs() < 1e-4, "vertex {k}: query {h} vs mesh {}", p.y);
        }
        // The drop point of a click maps back into the model's frame.
        let l = placed.water_local_xz(4.0, -4.0);
        assert!((l - glam::Vec2::new(5.0, -2.0)).length() < 1e-5, "{l}");
    }

    #[test]
    fn placement_keys_round_trip_and_bad_values_name_the_key() {
        let w = sea("yaw_deg = -30.0\nuniform_scale = 0.5");
        let back = Scene::from_toml(&w.scene.to_toml(), "again").unwrap();
        assert_eq!(back, w.scene);
        let s = &back.water.as_ref().unwrap().surface;
        assert_eq!((s.yaw_deg, s.uniform_scale), (-30.0, 0.5));
        // Scenes without a transform save without the keys.
        assert!(!sea("").scene.to_toml().contains("yaw_deg"));
        for (keys, message) in [
            ("yaw_deg = 400.0", "water.yaw_deg = 400 is outside [-360, 360]"),
            ("uniform_scale = -1.0", "water.uniform_scale = -1 is outside (0, 10000]"),
        ] {
            let text = format!(
                "version = 1\n[camera]\neye = [0.0, 30.0, 30.0]\ntarget = [0.0, 0.0, 0.0]\n\
                 [water]\nmodel = 'noise'\nscale = 3.0\n{keys}\n"
            );
            let e = Scene::from_toml(&text, "t").err().unwrap();
            assert_eq!(e.to_string(), format!("t: {message}"));
        }
    }

    #[test]
    fn a_dent_on_a_turned_and_scaled_spring_mesh_lands_under_the_world_point() {
        let mut scene = crate::scene::preset("springs").unwrap();
        let s = &mut scene.water.as_mut().unwrap().surface;
        (s.yaw_deg, s.uniform_scale) = (90.0, 2.0);
        let mut w = World::new(scene).unwrap();
        w.update(1.0).unwrap();
        let before = w.water_height_at(2.0, -3.0).unwrap();
        assert!(w.disturb_water(2.0, -3.0, 0.5, 1.0).unwrap());
        w.update(1.0).unwrap();
        let after = w.water_height_at(2.0, -3.0).unwrap();
        assert!((before - after - 0.5).abs() < 2e-3, "{before} -> {after}");
        // The mesh shows it: its lowest vertex is at least the dent deep.
        let surface = &w.water.as_ref().unwrap().surface;
        let lowest = surface.positions().iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
        assert!(lowest <= after + 1e-4);
        assert!(w.disturb_water(0.0, 0.0, -1.0, 1.0).is_err());
        // Closed-form water has no state to dent.
        let mut sea = World::new(crate::scene::preset("sea").unwrap()).unwrap();
        assert!(!sea.disturb_water(0.0, 0.0, 0.5, 1.0).unwrap());
    }
}
