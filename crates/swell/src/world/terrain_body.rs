//! The terrain of a [`super::World`]: its height field placed in the world, as a mesh to draw and
//! as ground heights to measure water depth against.

use glam::{Mat4, Vec2, Vec3};
use rayon::prelude::*;

use super::terrain_far_land::FarLand;
use crate::error::Result;
use crate::math::Transform;
use crate::mesh::SurfaceMesh;
use crate::scene::TerrainMaterial;
use crate::scene::TerrainSpec;
use crate::shading::Seabed;
use crate::terrain::HeightField;

/// Terrain built from a [`TerrainSpec`]: the model-space field, its placement, the world-space mesh
/// and the look.
pub struct TerrainBody {
    /// Heights in model space, as generated or loaded.
    pub field: HeightField,
    /// Placement in the world.
    pub transform: Transform,
    /// The field in world space (positions and unit normals transformed), drawn by the renderer.
    pub mesh: SurfaceMesh,
    /// How it looks.
    pub material: TerrainMaterial,
    /// The land beyond the field to the horizon, when `[terrain.far_land]` asks for it. It is
    /// drawn, but [`Self::ground_height`] answers for the field alone (water beyond it is deep).
    pub far_land: Option<FarLand>,
    model_from_world: Mat4,
    /// World-space ground heights for transforms that tilt the field (rotation about X or Z),
    /// where a vertical world line no longer maps to a vertical model line.
    tilted_ground: Option<GroundMap>,
}

impl TerrainBody {
    /// Builds the field (running the generator or reading the heightmap) and its world mesh.
    pub fn new(spec: &TerrainSpec) -> Result<Self> {
        let field = spec.build()?;
        let transform = spec.transform;
        let mut mesh = SurfaceMesh::new(field.grid());
        field.write_vertices(&mut mesh.positions, &mut mesh.normals);
        let world_from_model = transform.world_from_model();
        let normal_matrix = transform.world_from_model_normals();
        mesh.positions.par_iter_mut().zip(mesh.normals.par_iter_mut()).for_each(|(p, n)| {
            *p = world_from_model.transform_point3(*p);
            *n = (normal_matrix * *n).normalize_or(Vec3::Y);
        });
        let tilted_ground = (!transform.keeps_up()).then(|| GroundMap::from_mesh(&mesh, field.cols(), field.rows()));
        let far_land = spec.far_land.as_ref().map(|p| FarLand::new(&field, p, &transform)).transpose()?;
        Ok(Self {
            field,
            transform,
            mesh,
            material: spec.material,
            far_land,
            model_from_world: transform.model_from_world(),
            tilted_ground,
        })
    }

    /// World height (m) of the top of the terrain above world (x, z), or `None` outside it.
    ///
    /// Exact (bilinear in the field) when the transform keeps vertical lines vertical; otherwise
    /// the field is resampled once, top-down, onto a world grid as fine as the field, and this
    /// interpolates that grid.
    pub fn ground_height(&self, x: f32, z: f32) -> Option<f32> {
        if let Some(g) = &self.tilted_ground {
            return g.height_at(x, z);
        }
        let m = self.model_from_world.transform_point3(Vec3::new(x, 0.0, z));
        if !self.field.contains(m.x, m.z) {
            return None;
        }
        // Without tilt the model y axis is the world y axis scaled: world y = ty + sy * h.
        Some(self.transform.translate.y + self.transform.scale.y * self.field.height_at(m.x, m.z))
    }

    /// Whether some of the terrain's border lies under the water at rest (y = 0): water there
    /// runs on past the terrain's edge (an island, a coast), rather than being held by it (a
    /// lake, whose rim stands above the water all round). Decides the water's default extent
    /// ([`crate::scene::WaterExtent::default_for`]); one row of the mesh's world positions, once.
    pub fn border_under_water(&self) -> bool {
        let (cols, rows) = (self.field.cols(), self.field.rows());
        let wet = |i: usize| self.mesh.positions[i].y < 0.0;
        (0..cols).any(|c| wet(c) || wet((rows - 1) * cols + c))
            || (0..rows).any(|r| wet(r * cols) || wet(r * cols + cols - 1))
    }

    /// Depth (m) below the water at rest (y = 0) of the ground at world (x, z): positive under
    /// water, negative on dry land, `None` outside the terrain.
    pub fn depth_at(&self, x: f32, z: f32) -> Option<f32> {
        self.ground_height(x, z).map(|g| -g)
    }
}

/// Ground heights on a regular world (x, z) grid, `NEG_INFINITY` where no terrain lies below.
struct GroundMap {
    origin: Vec2,
    spacing: Vec2,
    cols: usize,
    rows: usize,
    heights: Vec<f32>,
}

impl GroundMap {
    /// Rasterises the mesh's triangles from above onto a `cols` x `rows` grid over their bounding
    /// box, keeping the highest surface at each grid point.
    fn from_mesh(mesh: &SurfaceMesh, cols: usize, rows: usize) -> Self {
        let (lo, hi) =
            mesh.positions.iter().fold((Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY)), |(lo, hi), p| {
                (lo.min(Vec2::new(p.x, p.z)), hi.max(Vec2::new(p.x, p.z)))
            });
        let spacing = ((hi - lo) / Vec2::new((cols - 1) as f32, (rows - 1) as f32)).max(Vec2::splat(1e-6));
        let mut map = Self { origin: lo, spacing, cols, rows, heights: vec![f32::NEG_INFINITY; cols * rows] };
        for t in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[t[k] as usize]);
            map.cover(a, b, c);
        }
        map
    }

    fn cover(&mut self, a: Vec3, b: Vec3, c: Vec3) {
        let g = |p: Vec3| (Vec2::new(p.x, p.z) - self.origin) / self.spacing;
        let (pa, pb, pc) = (g(a), g(b), g(c));
        let area = (pb - pa).perp_dot(pc - pa);
        if area.abs() < 1e-12 {
            return; // seen edge-on from above: covers nothing
        }
        let min = pa.min(pb).min(pc).ceil().max(Vec2::ZERO);
        let max = pa.max(pb).max(pc).floor().min(Vec2::new((self.cols - 1) as f32, (self.rows - 1) as f32));
        for j in min.y as usize..=max.y.max(-1.0) as usize {
            for i in min.x as usize..=max.x.max(-1.0) as usize {
                let q = Vec2::new(i as f32, j as f32);
                let wa = (pc - pb).perp_dot(q - pb) / area;
                let wb = (pa - pc).perp_dot(q - pc) / area;
                let wc = 1.0 - wa - wb;
                // A small tolerance so grid points on shared edges are covered by either triangle.
                if wa >= -1e-5 && wb >= -1e-5 && wc >= -1e-5 {
                    let y = wa * a.y + wb * b.y + wc * c.y;
                    let h = &mut self.heights[j * self.cols + i];
                    *h = h.max(y);
                }
            }
        }
    }

    fn height_at(&self, x: f32, z: f32) -> Option<f32> {
        let q = (Vec2::new(x, z) - self.origin) / self.spacing;
        let max = Vec2::new((self.cols - 1) as f32, (self.rows - 1) as f32);
        if q.x < 0.0 || q.y < 0.0 || q.x > max.x || q.y > max.y {
            return None;
        }
        let (i, j) = ((q.x as usize).min(self.cols - 2), (q.y as usize).min(self.rows - 2));
        let (tx, tz) = (q.x - i as f32, q.y - j as f32);
        let h = |di: usize, dj: usize| self.heights[(j + dj) * self.cols + i + di];
        let corners = [h(0, 0), h(1, 0), h(0, 1), h(1, 1)];
        if corners.iter().any(|c| !c.is_finite()) {
            return None; // at the terrain's border
        }
        let bottom = corners[0] + (corners[1] - corners[0]) * tx;
        let top = corners[2] + (corners[3] - corners[2]) * tx;
        Some(bottom + (top - bottom) * tz)
    }
}

/// The scene's terrain is the bottom the water refracts to where the material sets none.
impl Seabed for TerrainBody {
    fn sample(&self, x: f32, z: f32) -> Option<(f32, glam::Vec3)> {
        // The albedo uses an upward normal: under water the bands are chosen by height (sand), and
        // the refracted view is too blurred by absorption for slope-dependent rock to matter.
        self.ground_height(x, z).map(|y| (y, self.material.albedo(y, glam::Vec3::Y)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::TerrainGenerator;
    use crate::terrain::{FlatParams, SlopeParams};

    fn spec(generator: TerrainGenerator, transform: Transform) -> TerrainSpec {
        TerrainSpec {
            size: Some(65),
            extent: Some(Vec2::new(100.0, 60.0)),
            transform,
            material: TerrainMaterial::default(),
            generator,
            far_land: None,
        }
    }

    #[test]
    fn depth_follows_a_moved_scaled_and_turned_slope() {
        // Floor rising along model +X from -10 m to +2 m over 100 m, scaled by 2 vertically,
        // turned 90 degrees about Y (model +X -> world -Z) and lowered 1 m.
        let slope = TerrainGenerator::Slope(SlopeParams {
            start_height: -10.0,
            end_height: 2.0,
            direction: Vec2::X,
            exponent: 1.0,
        });
        let t = Transform {
            translate: Vec3::new(5.0, -1.0, 0.0),
            rotate_deg: Vec3::new(0.0, 90.0, 0.0),
            scale: Vec3::new(1.0, 2.0, 1.0),
        };
        let body = TerrainBody::new(&spec(slope, t)).unwrap();
        // World (5, z): model x = -z. Model height at x: -4 + 0.12 x; world y = -1 + 2 h.
        for z in [-40.0f32, -10.0, 0.0, 25.0, 50.0] {
            let expected = -(-1.0 + 2.0 * (-4.0 + 0.12 * -z));
            let d = body.depth_at(5.0, z).unwrap();
            assert!((d - expected).abs() < 1e-3, "z = {z}: depth {d}, expected {expected}");
        }
        // The shore (depth 0) is where -1 + 2 (-4 - 0.12 z) = 0: z = -37.5.
        assert!(body.depth_at(5.0, -37.5).unwrap().abs() < 1e-3);
        assert_eq!(body.depth_at(5.0, 51.0), None);
        assert_eq!(body.depth_at(36.0, 0.0), None);
    }

    #[test]
    fn tilted_terrain_is_measured_from_above() {
        // A flat floor at y = 0 in model space, tilted 10 degrees about X and lowered 3 m: model
        // (0, 0, m) goes to world (0, -3 - m sin 10°, m cos 10°), so world y = -3 - z tan 10°.
        let floor = TerrainGenerator::Flat(FlatParams { height: 0.0 });
        let t = Transform {
            translate: Vec3::new(0.0, -3.0, 0.0),
            rotate_deg: Vec3::new(10.0, 0.0, 0.0),
            ..Transform::IDENTITY
        };
        let body = TerrainBody::new(&spec(floor, t)).unwrap();
        let s = 10f32.to_radians().tan();
        for z in [-20.0f32, 0.0, 13.0] {
            let d = body.depth_at(0.0, z).unwrap();
            assert!((d - (3.0 + z * s)).abs() < 1e-3, "z = {z}: {d}");
        }
        assert_eq!(body.depth_at(0.0, 40.0), None);
    }

    #[test]
    fn a_world_knows_the_depth_under_the_water() {
        // A pool: flat floor 0.2 m below the water (paper 002), 4 m x 4 m, under a 6 m x 6 m patch.
        let text = "version = 1\n[camera]\neye = [0.0, 5.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\n\
                    [water]\nmodel = 'sines'\nsize = [6.0, 6.0]\ncells = [6, 6]\n\
                    [terrain]\ngenerator = 'flat'\nsize = 9\nextent = [4.0, 4.0]\nheight = -0.2\n";
        let world = crate::world::World::new(crate::scene::Scene::from_toml(text, "t").unwrap()).unwrap();
        assert!((world.depth_at(0.5, -1.5).unwrap() - 0.2).abs() < 1e-6);
        assert_eq!(world.depth_at(2.5, 0.0), None);
        // Water vertices at x, z in {-3, ..., 3}: inside |x|, |z| <= 2 the floor is 0.2 m down.
        for (x, z) in (0..49).map(|k| ((k % 7) as f32 - 3.0, (k / 7) as f32 - 3.0)) {
            let inside = x.abs() <= 2.0 && z.abs() <= 2.0;
            assert_eq!(world.depth_at(x, z), inside.then_some(0.2), "vertex ({x}, {z})");
        }
    }
}
