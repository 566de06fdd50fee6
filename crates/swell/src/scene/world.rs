//! A scene made runnable: its models built and its meshes allocated, updated frame by frame.

use super::{Scene, TerrainBody, WaterMaterial};
use crate::error::Result;
use crate::mesh::SurfaceMesh;
use crate::shading::Texture;
use crate::water::WaveModel;

/// The water of a [`World`]: the model, the mesh it displaces and the material it is drawn with.
pub struct WaterBody {
    /// The wave model, built from the scene.
    pub model: Box<dyn WaveModel>,
    /// The displaced grid, updated by [`World::update`].
    pub mesh: SurfaceMesh,
    /// How it looks.
    pub material: WaterMaterial,
    /// The material's texture, loaded or generated, if it names one.
    pub texture: Option<Texture>,
}

/// Refuses a mesh holding NaN or infinity, so it never reaches the rasterizer or a file. Validation
/// bounds every parameter, so this only fires on combinations the bounds do not foresee.
fn check_finite_mesh(mesh: &SurfaceMesh, t: f64) -> Result<()> {
    use rayon::prelude::*;
    let finite = |v: &glam::Vec3| v.is_finite();
    if mesh.positions.par_iter().all(finite) && mesh.normals.par_iter().all(finite) {
        Ok(())
    } else {
        Err(crate::Error::Unstable(format!(
            "the water model produced non-finite positions or normals at time {t} s; \
             reduce the wave amplitudes, wavelengths or speeds in [water]"
        )))
    }
}

/// A [`Scene`] with its models built; [`World::update`] moves it to a time.
pub struct World {
    /// The scene it was built from.
    pub scene: Scene,
    /// The water, if the scene has any.
    pub water: Option<WaterBody>,
    /// The terrain, if the scene has any (static: built once, not changed by updates).
    pub terrain: Option<TerrainBody>,
    time: f64,
}

impl World {
    /// Validates `scene`, builds its models and allocates its meshes (the only allocation: updates
    /// reuse these buffers).
    pub fn new(scene: Scene) -> Result<Self> {
        scene.validate()?;
        // Terrain first: the depth under the water is known before the water model is built
        // (`TerrainBody::median_water_depth` for models that take one depth).
        let mut terrain = match &scene.terrain {
            Some(spec) => Some(TerrainBody::new(spec)?),
            None => None,
        };
        if let (Some(t), Some(w)) = (&mut terrain, &scene.water) {
            t.measure_water_depths(&w.surface.grid()?);
        }
        let water = match &scene.water {
            Some(spec) => {
                let model = spec.model.build()?;
                let mesh = SurfaceMesh::new(spec.surface.grid()?);
                let texture = spec.material.load_texture()?;
                Some(WaterBody { model, mesh, material: spec.material.clone(), texture })
            }
            None => None,
        };
        let mut world = Self { scene, water, terrain, time: f64::NAN };
        world.update(0.0)?;
        Ok(world)
    }

    /// Moves every model to time `t` (s) and displaces the meshes.
    ///
    /// Fails only when a time-stepped model became unstable; the meshes then keep the last good
    /// frame.
    pub fn update(&mut self, t: f64) -> Result<()> {
        if let Some(w) = &mut self.water {
            w.model.advance(t)?;
            w.mesh.displace(w.model.as_ref(), t);
            check_finite_mesh(&w.mesh, t)?;
        }
        self.time = t;
        Ok(())
    }

    /// Depth (m) of the ground below the water at rest (y = 0) at world (x, z): positive under
    /// water, negative on dry land, `None` where there is no terrain below (deep water).
    pub fn depth_at(&self, x: f32, z: f32) -> Option<f32> {
        self.terrain.as_ref().and_then(|t| t.depth_at(x, z))
    }

    /// The time of the last [`World::update`], seconds.
    pub fn time(&self) -> f64 {
        self.time
    }
}
