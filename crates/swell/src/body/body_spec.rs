//! A floating body as a scene describes it (`[[body]]`): its shape, mass, starting pose and how
//! the water drags it; [`BodySpec::build`] turns it into a [`super::FloatingBody`].

use std::path::{Path, PathBuf};

use glam::{DMat3, DQuat, DVec3, EulerRot, Vec3};
use serde::{Deserialize, Serialize};

use super::{FloatingBody, Hull};
use crate::error::{check_finite_vec, check_range, Error, Result};

crate::closed_set! {
    /// The shape of a floating body's hull.
    pub enum BodyShape: "a body shape" {
        /// A box of full extents `size = [x, y, z]`, m.
        Box = "box",
        /// A sphere, `size = [radius]`, m.
        Sphere = "sphere",
        /// A capsule along the body's X axis, `size = [radius, length]`, m (`length` between the
        /// centres of its round ends).
        Capsule = "capsule",
        /// A closed triangle mesh read from the OBJ file `path` (metres, +Y up).
        Mesh = "mesh",
    }
}

/// Most bodies a scene may have: 256 bodies of every key take about 4,600 list items, well within
/// the scene text's [`crate::limits::MAX_LIST_ITEMS`], so a saved scene always loads again.
pub const MAX_BODIES: usize = 256;

/// Smallest and largest size (m) of any extent of a body: below a few centimetres the 120 Hz step
/// cannot follow the body's bobbing; above a kilometre it is no longer a body on the water.
pub const BODY_SIZE_RANGE_M: (f32, f32) = (0.02, 1000.0);

/// Density range (kg/m³) of a body: from foam to steel.
pub const BODY_DENSITY_RANGE: (f32, f32) = (10.0, 20_000.0);

/// Largest coordinate (m) of a body's starting position, and speed (m/s) of its starting velocity.
pub const MAX_BODY_POSITION_M: f32 = 100_000.0;
/// See [`MAX_BODY_POSITION_M`].
pub const MAX_BODY_SPEED: f32 = 1000.0;

/// Longest edge (m) of the squares a box's faces are split into: the water is sampled at the
/// hull's vertices, so a long box needs some along its length to feel a wave shorter than
/// itself, while a crate of a metre keeps its 8 corners (12 triangles), the cheapest hull.
pub const BOX_CELL_M: f32 = 1.0;

/// One `[[body]]` of a scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Name, unique in the scene; names the body in `bodies.json`, glTF nodes and errors. Empty:
    /// `body<k>`, k its index.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub name: String,
    /// Shape of the hull.
    pub shape: BodyShape,
    /// Dimensions (m), as [`BodyShape`] says for each shape; not used by `mesh`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub size: Vec<f32>,
    /// The hull's OBJ file for `shape = "mesh"`: a closed triangle mesh in metres, +Y up, in the
    /// body's frame (its centroid need not be at the origin).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub path: Option<PathBuf>,
    /// Density of the solid, kg/m³, in [`BODY_DENSITY_RANGE`]; exclusive with `mass`. Neither
    /// given: 500 (pine wood), so a body floats at half its volume.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<f32>,
    /// Mass, kg (> 0); gives the density mass / volume, which must be in [`BODY_DENSITY_RANGE`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f32>,
    /// Centre of mass in the body's frame relative to the hull's centroid, m (a keel's ballast
    /// below it); default the centroid. Must stay inside the hull's bounding box.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub center_of_mass: Option<Vec3>,
    /// Principal moments of inertia about the body's X, Y and Z axes through the centre of mass,
    /// kg·m², each > 0; default those of the solid hull at its density.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<Vec3>,
    /// Centre of mass at t = 0, world metres.
    #[serde(default)]
    pub position: Vec3,
    /// Orientation at t = 0: yaw about +Y, then pitch about the turned +X, then roll about the
    /// turned +Z, degrees, each in [-360, 360].
    #[serde(default)]
    pub rotation_deg: Vec3,
    /// Velocity of the centre of mass at t = 0, m/s.
    #[serde(default)]
    pub velocity: Vec3,
    /// Angular velocity at t = 0, rad/s, world axes.
    #[serde(default)]
    pub angular_velocity: Vec3,
    /// Time (s, in [0, 1e6]) until which the body hangs still at its initial pose and velocity,
    /// then falls free: a crate dropped into a running scene (the viewer's click writes the time
    /// of the click). Default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub release_time: f64,
    /// Pressure-drag coefficient of the faces the body pushes into the water (dimensionless,
    /// [0, 10]; 1 for a blunt face): each submerged face moving into the water at normal speed u
    /// feels ½ ρ C u² per m².
    #[serde(default = "default_drag", skip_serializing_if = "is_default_drag")]
    pub drag: f32,
    /// Linear (skin) drag, N·s/m³ ([0, 10,000]): each m² of wetted hull feels this force per m/s
    /// of the water's speed past it.
    #[serde(default = "default_linear_drag", skip_serializing_if = "is_default_linear_drag")]
    pub linear_drag: f32,
    /// Coulomb friction coefficient against the terrain, [0, 2].
    #[serde(default = "default_friction", skip_serializing_if = "is_default_friction")]
    pub friction: f32,
    /// Albedo the renderer draws the body in, linear RGB, each in [0, 1] (default a weathered
    /// wood).
    #[serde(default = "default_color", skip_serializing_if = "is_default_color")]
    pub color: Vec3,
}

fn default_drag() -> f32 {
    1.0
}
fn is_default_drag(v: &f32) -> bool {
    *v == default_drag()
}
fn default_linear_drag() -> f32 {
    20.0
}
fn is_default_linear_drag(v: &f32) -> bool {
    *v == default_linear_drag()
}
fn is_zero(v: &f64) -> bool {
    *v == 0.0
}
fn default_color() -> Vec3 {
    Vec3::new(0.36, 0.22, 0.11)
}
fn is_default_color(v: &Vec3) -> bool {
    *v == default_color()
}
fn default_friction() -> f32 {
    0.6
}
fn is_default_friction(v: &f32) -> bool {
    *v == default_friction()
}

/// Density (kg/m³) of a body that gives neither `density` nor `mass`.
pub const DEFAULT_BODY_DENSITY: f32 = 500.0;

impl BodySpec {
    /// A body of `shape` and `size` at `position`, everything else default.
    pub fn new(shape: BodyShape, size: &[f32], position: Vec3) -> Self {
        Self {
            name: String::new(),
            shape,
            size: size.to_vec(),
            path: None,
            density: None,
            mass: None,
            center_of_mass: None,
            inertia: None,
            position,
            rotation_deg: Vec3::ZERO,
            velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            release_time: 0.0,
            drag: default_drag(),
            linear_drag: default_linear_drag(),
            friction: default_friction(),
            color: default_color(),
        }
    }

    /// Checks every key that can be checked without reading the mesh file, naming it under `key`
    /// (`body[2]`).
    pub fn validate(&self, key: &str) -> Result<()> {
        let (lo, hi) = BODY_SIZE_RANGE_M;
        let wanted = match self.shape {
            BodyShape::Box => 3,
            BodyShape::Sphere => 1,
            BodyShape::Capsule => 2,
            BodyShape::Mesh => 0,
        };
        if self.size.len() != wanted {
            let what = match self.shape {
                BodyShape::Box => "[x, y, z] (full extents, m)",
                BodyShape::Sphere => "[radius] (m)",
                BodyShape::Capsule => "[radius, length] (m)",
                BodyShape::Mesh => "nothing: a mesh's size is its OBJ's",
            };
            return Err(Error::invalid(
                format!("{key}.size"),
                format!("{:?} has {} values; shape {} takes {what}", self.size, self.size.len(), self.shape),
            ));
        }
        for (i, &s) in self.size.iter().enumerate() {
            // A capsule's length may be 0 (a sphere).
            let low = if self.shape == BodyShape::Capsule && i == 1 { 0.0 } else { lo };
            check_range(&format!("{key}.size[{i}]"), s, low, hi)?;
        }
        match (&self.path, self.shape) {
            (None, BodyShape::Mesh) => {
                return Err(Error::invalid(
                    format!("{key}.path"),
                    "is missing; shape = \"mesh\" reads its hull from an OBJ file",
                ))
            }
            (Some(p), BodyShape::Mesh) if p.as_os_str().is_empty() => {
                return Err(Error::invalid(format!("{key}.path"), "is empty; give the hull's OBJ file"))
            }
            (Some(_), s) if s != BodyShape::Mesh => {
                return Err(Error::invalid(
                    format!("{key}.path"),
                    format!("is only read for shape = \"mesh\", not \"{s}\""),
                ))
            }
            _ => {}
        }
        match (self.density, self.mass) {
            (Some(_), Some(_)) => {
                return Err(Error::invalid(format!("{key}.mass"), "give density or mass, not both"));
            }
            (Some(d), None) => check_range(&format!("{key}.density"), d, BODY_DENSITY_RANGE.0, BODY_DENSITY_RANGE.1)?,
            (None, Some(m)) => {
                if !(m > 0.0 && m.is_finite()) {
                    return Err(Error::out_of_range(format!("{key}.mass"), m, "(0, inf) kg"));
                }
            }
            (None, None) => {}
        }
        if let Some(c) = self.center_of_mass {
            check_finite_vec(&format!("{key}.center_of_mass"), &c.to_array())?;
        }
        if let Some(i) = self.inertia {
            for (k, v) in i.to_array().into_iter().enumerate() {
                if !(v > 0.0 && v.is_finite()) {
                    return Err(Error::out_of_range(format!("{key}.inertia[{k}]"), v, "(0, inf) kg·m²"));
                }
            }
        }
        for (k, v) in self.position.to_array().into_iter().enumerate() {
            check_range(&format!("{key}.position[{k}]"), v, -MAX_BODY_POSITION_M, MAX_BODY_POSITION_M)?;
        }
        for (k, v) in self.rotation_deg.to_array().into_iter().enumerate() {
            check_range(&format!("{key}.rotation_deg[{k}]"), v, -360.0, 360.0)?;
        }
        for (k, v) in self.velocity.to_array().into_iter().enumerate() {
            check_range(&format!("{key}.velocity[{k}]"), v, -MAX_BODY_SPEED, MAX_BODY_SPEED)?;
        }
        for (k, v) in self.angular_velocity.to_array().into_iter().enumerate() {
            check_range(&format!("{key}.angular_velocity[{k}]"), v, -100.0, 100.0)?;
        }
        if !(0.0..=1e6).contains(&self.release_time) {
            return Err(Error::out_of_range(format!("{key}.release_time"), self.release_time, "[0, 1000000]"));
        }
        check_range(&format!("{key}.drag"), self.drag, 0.0, 10.0)?;
        check_range(&format!("{key}.linear_drag"), self.linear_drag, 0.0, 10_000.0)?;
        check_range(&format!("{key}.friction"), self.friction, 0.0, 2.0)?;
        for (k, v) in self.color.to_array().into_iter().enumerate() {
            check_range(&format!("{key}.color[{k}]"), v, 0.0, 1.0)?;
        }
        Ok(())
    }

    /// Makes a relative `path` relative to `dir` (the scene file's directory).
    pub fn resolve_paths(&mut self, dir: &Path) {
        if let Some(p) = &mut self.path {
            if p.is_relative() {
                *p = dir.join(&*p);
            }
        }
    }

    /// The hull in the body's frame, as the shape gives it (a mesh read from its file).
    pub fn hull(&self, key: &str) -> Result<Hull> {
        Ok(match self.shape {
            BodyShape::Box => {
                let size = Vec3::new(self.size[0], self.size[1], self.size[2]);
                Hull::cuboid(size, (size / BOX_CELL_M).ceil().as_uvec3().to_array())
            }
            BodyShape::Sphere => Hull::sphere(self.size[0]),
            BodyShape::Capsule => Hull::capsule(self.size[0], self.size[1]),
            BodyShape::Mesh => {
                let path = self.path.as_deref().unwrap_or(Path::new(""));
                let bytes = crate::io::read_input(path, crate::mesh::MAX_OBJ_BYTES)
                    .map_err(|e| Error::invalid(format!("{key}.path"), e.to_string()))?;
                let source = path.display().to_string();
                let text = String::from_utf8(bytes)
                    .map_err(|_| Error::invalid(format!("{key}.path"), format!("{source} is not UTF-8 OBJ text")))?;
                let mesh = crate::mesh::parse_obj(&text, &source)?;
                Hull::from_mesh(&mesh.positions, &mesh.indices, &source)
                    .map_err(|e| Error::invalid(format!("{key}.path"), e.to_string()))?
            }
        })
    }

    /// Validates and builds the body (reading its mesh, if any) as body number `index` of its
    /// scene, `key` naming it in errors (`body[2]`).
    pub fn build(&self, index: usize, key: &str) -> Result<FloatingBody> {
        self.validate(key)?;
        let hull = self.hull(key)?;
        let props = hull.mass_properties();
        let density = match (self.density, self.mass) {
            (_, Some(m)) => {
                let d = f64::from(m) / props.volume;
                let (lo, hi) = BODY_DENSITY_RANGE;
                if !(f64::from(lo)..=f64::from(hi)).contains(&d) {
                    return Err(Error::out_of_range(
                        format!("{key}.mass"),
                        m,
                        format!(
                            "[{:.4}, {:.4}] kg for this {:.4} m³ hull (density {lo} to {hi} kg/m³)",
                            f64::from(lo) * props.volume,
                            f64::from(hi) * props.volume,
                            props.volume
                        ),
                    ));
                }
                d
            }
            (Some(d), None) => f64::from(d),
            (None, None) => f64::from(DEFAULT_BODY_DENSITY),
        };
        let (lo, hi) = hull.bounds();
        let offset = self.center_of_mass.unwrap_or(Vec3::ZERO);
        let com = props.centroid.as_vec3() + offset;
        if !(com.cmpge(lo).all() && com.cmple(hi).all()) {
            return Err(Error::invalid(
                format!("{key}.center_of_mass"),
                format!("{offset} puts the centre of mass outside the hull's box {lo} to {hi} (m, body frame)"),
            ));
        }
        let mass = density * props.volume;
        // The hull's inertia about its centroid, carried to the centre of mass (parallel axes).
        let d = offset.as_dvec3();
        let shifted =
            props.inertia * density + (DMat3::from_diagonal(DVec3::splat(d.length_squared())) - outer(d)) * mass;
        let inertia = match self.inertia {
            Some(i) => DMat3::from_diagonal(i.as_dvec3()),
            None => shifted,
        };
        let name = if self.name.is_empty() { format!("body{index}") } else { self.name.clone() };
        let r = self.rotation_deg.as_dvec3() * (std::f64::consts::PI / 180.0);
        let orientation = DQuat::from_euler(EulerRot::YXZ, r.x, r.y, r.z);
        let mut body = FloatingBody::new(
            name,
            hull.translated(-com),
            super::BodyMaterial {
                mass,
                inertia,
                drag: f64::from(self.drag),
                linear_drag: f64::from(self.linear_drag),
                friction: f64::from(self.friction),
            },
            super::BodyState {
                position: self.position.as_dvec3(),
                orientation,
                velocity: self.velocity.as_dvec3(),
                angular_velocity: self.angular_velocity.as_dvec3(),
            },
            key,
        )?;
        body.release_time = self.release_time;
        Ok(body)
    }
}

/// d dᵀ.
fn outer(d: DVec3) -> DMat3 {
    DMat3::from_cols(d * d.x, d * d.y, d * d.z)
}

/// Checks a scene's bodies together: each one's keys, at most [`MAX_BODIES`], names unique.
pub fn validate_bodies(bodies: &[BodySpec]) -> Result<()> {
    if bodies.len() > MAX_BODIES {
        return Err(Error::out_of_range(
            "body",
            format!("{} bodies", bodies.len()),
            format!("[0, {MAX_BODIES}] bodies"),
        ));
    }
    let mut names = std::collections::HashSet::new();
    for (i, b) in bodies.iter().enumerate() {
        b.validate(&format!("body[{i}]"))?;
        let name = if b.name.is_empty() { format!("body{i}") } else { b.name.clone() };
        if !names.insert(name.clone()) {
            return Err(Error::invalid(
                format!("body[{i}].name"),
                format!("\"{name}\" names an earlier body too; names must be unique"),
            ));
        }
    }
    Ok(())
}
