//! Draws the water surface with its material's shading model, through the one shaded-draw path:
//! the water's optics ([`shade_water`]: Fresnel sky and terrain reflection, refraction to the
//! bottom with absorption, sun glitter, foam) are its [`SurfaceShader`].

use glam::{Vec3, Vec4};

use super::sea_lod::FootprintFilter;
use super::shaded_draw::{ShadedDraw, ShadedMesh, SurfaceShader};
use super::FrameContext;
use crate::math::{Lanes, Vec3Lanes};
use crate::raster::Fragment;
use crate::raster::Framebuffer;
use crate::scene::{TerrainBody, WaterBody};
use crate::shading::{
    shade_water, shade_water_filtered, shade_water_run, Environment, FlatBottom, Lobe, NoBottom, ReflectionMap, Seabed,
    SurfaceVarying, WaterLook, WaterRun,
};

/// Water as [`shade_water`] sees it, with the specular lobe of its shading model; with a
/// `filter` (the unbounded sea's) the slope variance each point's pixel cannot resolve is shaded
/// statistically ([`shade_water_filtered`]).
struct WaterShader<'a> {
    env: &'a Environment<'a>,
    look: WaterLook<'a>,
    lobe: Lobe,
    filter: Option<&'a FootprintFilter<'a>>,
}

impl SurfaceShader for WaterShader<'_> {
    fn shade(&self, position: Vec3, normal: Vec3, foam: f32) -> Vec3 {
        match self.filter {
            Some(f) => {
                let unresolved = f.variance(position, normal);
                shade_water_filtered(self.env, &self.look, self.lobe, position, normal, foam, unresolved)
            }
            None => shade_water(self.env, &self.look, self.lobe, position, normal, foam),
        }
    }

    /// A row's pixels many at a time ([`shade_water_run`]), each with the unresolved slope
    /// variance interpolated from the mesh's vertices (the unbounded sea's; 0 on a patch).
    fn shade_pixels(&self, pixels: &[Fragment<SurfaceVarying>], out: &mut [Vec3]) {
        shade_water_run(self.env, &self.look, self.lobe, &Pixels { pixels }, out);
    }

    /// Many vertices or faces at a time ([`shade_water_run`]).
    fn shade_points(&self, points: &[(Vec3, Vec3, f32)], out: &mut [Vec3]) {
        shade_water_run(self.env, &self.look, self.lobe, &Points { points, filter: self.filter }, out);
    }
}

/// A run of water vertices or faces, with the unbounded sea's filter when there is one.
struct Points<'a> {
    points: &'a [(Vec3, Vec3, f32)],
    filter: Option<&'a FootprintFilter<'a>>,
}

impl WaterRun for Points<'_> {
    fn len(&self) -> usize {
        self.points.len()
    }
    #[inline(always)]
    fn point(&self, i: usize) -> (Vec3, Vec3, f32) {
        self.points[i]
    }
    #[inline(always)]
    fn unresolved(&self, _: usize, _: usize, position: Vec3Lanes, normal: Vec3Lanes) -> Lanes {
        unresolved(self.filter, position, normal)
    }
}

/// A row's run of water pixels, whose unresolved slope variance the rasterizer interpolated.
struct Pixels<'a> {
    pixels: &'a [Fragment<SurfaceVarying>],
}

impl WaterRun for Pixels<'_> {
    fn len(&self) -> usize {
        self.pixels.len()
    }
    #[inline(always)]
    fn point(&self, i: usize) -> (Vec3, Vec3, f32) {
        let v = &self.pixels[i].varying;
        (v.position, v.normal, v.foam)
    }
    #[inline(always)]
    fn unresolved(&self, first: usize, live: usize, _: Vec3Lanes, _: Vec3Lanes) -> Lanes {
        Lanes::from_fn(|l| self.pixels[first + if l < live { l } else { 0 }].varying.unresolved)
    }
}

/// Draws `mesh` (the patch's or the unbounded sea's, world positions) with `water`'s material
/// into `fb` through `draw`; `terrain` is the bottom where the material sets none, `reflection`
/// the terrain the surface mirrors, `filter` the unbounded sea's footprint filter.
#[allow(clippy::too_many_arguments)]
pub fn draw(
    fb: &mut Framebuffer,
    frame: &FrameContext,
    water: &WaterBody,
    mesh: ShadedMesh,
    filter: Option<&FootprintFilter>,
    draw: &mut ShadedDraw,
    terrain: Option<&TerrainBody>,
    reflection: Option<&ReflectionMap>,
) {
    let material = &water.material;
    let flat_bottom;
    // An explicit flat bottom in the material wins; otherwise the scene's terrain is the bottom.
    let seabed: &dyn Seabed = match (material.bottom_depth, terrain) {
        (Some(depth), _) => {
            flat_bottom = FlatBottom { height: -depth, albedo: material.bottom_color };
            &flat_bottom
        }
        (None, Some(t)) => t,
        (None, None) => &NoBottom,
    };
    let look = WaterLook::new(material, seabed, water.texture.as_ref(), frame.env.time)
        .with_reflection(reflection)
        .with_foam(Some(&water.foam_pattern));
    let shader = WaterShader { env: &frame.env, look, lobe: Lobe::of(material.shading), filter };
    let clip_from_world = frame.clip_from_world;
    draw.draw(fb, mesh, &|p| clip_from_world * Vec4::from((p, 1.0)), material.shading, &shader);
}

/// The slope variance the unbounded sea's `filter` leaves unresolved at these points; none
/// without one (a patch is point-sampled).
#[inline(always)]
fn unresolved(filter: Option<&FootprintFilter>, position: Vec3Lanes, normal: Vec3Lanes) -> Lanes {
    match filter {
        Some(f) => f.variance_lanes(position, normal),
        None => Lanes::splat(0.0),
    }
}
