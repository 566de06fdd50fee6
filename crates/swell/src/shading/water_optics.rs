//! The colour of a water surface point (paper 003 §2): the sky and sun it reflects, the bottom it
//! lets through (refracted, absorbed per colour channel), the light scattered by the water body,
//! the sun glitter and the foam, weighted by Fresnel.

use glam::{Vec2, Vec3};

use super::slope_variance::{mean_fresnel_lanes, pixel_footprint_lanes, spread_normals_lanes, widened_lobe_lanes};
use super::sun_glitter::SunGlitter;
use super::{
    fresnel_dielectric, Environment, FoamPattern, Lobe, ReflectionMap, SurfaceVarying, Texture, FOAM_PATTERN_SIDE,
};
use crate::math::{fast_exp2, fast_pow, Isa, Lanes, Vec3Lanes};
use crate::scene::{Light, WaterMaterial};

/// What lies under the water: the height and colour of the bottom below each horizontal point.
///
/// Implemented by [`FlatBottom`], [`NoBottom`], and by terrain (in the renderer) for scenes with one.
pub trait Seabed: Sync {
    /// Bottom height (world y, metres) and linear RGB albedo under world (`x`, `z`), or `None`
    /// where no bottom is seen (deep water).
    fn sample(&self, x: f32, z: f32) -> Option<(f32, Vec3)>;

    /// False when [`Self::sample`] is `None` everywhere, so the shading can skip the refracted
    /// ray's search for a bottom.
    fn anywhere(&self) -> bool {
        true
    }
}

/// A horizontal bottom at world height `height` with one albedo.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatBottom {
    /// World y of the bottom, metres (negative below water at rest).
    pub height: f32,
    /// Linear RGB albedo, [0, 1].
    pub albedo: Vec3,
}

impl Seabed for FlatBottom {
    fn sample(&self, _x: f32, _z: f32) -> Option<(f32, Vec3)> {
        Some((self.height, self.albedo))
    }
}

/// Deep water: no bottom anywhere.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NoBottom;

impl Seabed for NoBottom {
    fn sample(&self, _x: f32, _z: f32) -> Option<(f32, Vec3)> {
        None
    }
    fn anywhere(&self) -> bool {
        false
    }
}

/// Everything about one water body that its shading needs, resolved once per frame.
#[derive(Clone, Copy)]
pub struct WaterLook<'a> {
    /// The material keys.
    pub material: &'a WaterMaterial,
    /// What is under the water.
    pub seabed: &'a dyn Seabed,
    /// The material's texture, if any.
    pub texture: Option<&'a Texture>,
    /// Texture coordinates of world (x, z) are `(x, z) / texture_scale + texture_offset` (tiles);
    /// the offset slides the texture with the flow.
    pub texture_offset: Vec2,
    /// The terrain above the water, mirrored ([`ReflectionMap`]); `None` reflects only the sky.
    pub reflection: Option<&'a ReflectionMap<'a>>,
    /// The structure foam shows ([`FoamPattern`]); `None` blends towards foam by its coverage.
    pub foam: Option<&'a FoamPattern>,
    /// Foam streaks: the unit world direction (x, z) the wind blows towards and how many times
    /// longer than wide the pattern's cells are drawn along it (>= 1); `None` keeps them round.
    pub foam_streaks: Option<(Vec2, f32)>,
    /// Angle one pixel of the image spans, radians (the supersampled image's when supersampling),
    /// at least 0: the foam pattern is filtered to each pixel's footprint. 0 (the default, no camera)
    /// shows it at full detail at every distance.
    pub pixel_angle: f32,
    /// Foam gathered on the crests: the height of the water at rest (world y, m) and `1 / σ`,
    /// σ the spread of the surface's height (m, `sqrt(m0)`); `None` spreads the coverage the
    /// wave model reports evenly over the surface ([`crest_weight_lanes`]).
    pub foam_crests: Option<(f32, f32)>,
    /// The lights' reflection through the surface's slope distribution
    /// ([`GlitterModel::CoxMunk`](crate::scene::GlitterModel::CoxMunk)): its micro-roughness also
    /// blurs the reflected sky and averages the Fresnel factor. `None` draws the material's
    /// Phong or Blinn-Phong lobe instead. Either way the sun disc is mirrored in the sky only
    /// when no directional light stands for the sun.
    pub glitter: Option<SunGlitter>,
}

impl<'a> WaterLook<'a> {
    /// The look of `material` over `seabed` at time `t` (s): the texture slides by
    /// `flow_velocity * t`, so a point of the pattern moves with the water (paper 004).
    pub fn new(material: &'a WaterMaterial, seabed: &'a dyn Seabed, texture: Option<&'a Texture>, t: f64) -> Self {
        // Reduce modulo one tile in f64 so that hours of flow keep full f32 precision.
        let tiles = |v: f32| (-(v as f64) * t / material.texture_scale as f64).rem_euclid(1.0) as f32;
        let texture_offset = Vec2::new(tiles(material.flow_velocity.x), tiles(material.flow_velocity.y));
        Self {
            material,
            seabed,
            texture,
            texture_offset,
            reflection: None,
            foam: None,
            foam_streaks: None,
            pixel_angle: 0.0,
            foam_crests: None,
            glitter: None,
        }
    }

    /// The same look, reflecting the lights through `glitter`'s slope distribution (see
    /// [`Self::glitter`]).
    pub fn with_glitter(self, glitter: Option<SunGlitter>) -> Self {
        Self { glitter, ..self }
    }

    /// The same look, also reflecting the terrain of `reflection`.
    pub fn with_reflection(self, reflection: Option<&'a ReflectionMap<'a>>) -> Self {
        Self { reflection, ..self }
    }

    /// The same look, its foam structured by `pattern`.
    pub fn with_foam(self, pattern: Option<&'a FoamPattern>) -> Self {
        Self { foam: pattern, ..self }
    }

    /// The same look, for an image whose pixels span `pixel_angle` radians each (>= 0; see
    /// [`Self::pixel_angle`]).
    pub fn with_pixel_angle(self, pixel_angle: f32) -> Self {
        Self { pixel_angle: pixel_angle.max(0.0), ..self }
    }

    /// The same look, its foam gathered on the crests of a surface at rest at height `rest` (world
    /// y, m) whose height spreads `spread` m about it (the standard deviation, `sqrt(m0)`); no
    /// gathering for a spread that is not positive and finite.
    pub fn with_foam_crests(self, rest: f32, spread: f32) -> Self {
        let foam_crests = (spread.is_finite() && spread > 0.0 && rest.is_finite()).then(|| (rest, 1.0 / spread));
        Self { foam_crests, ..self }
    }

    /// The same look, its foam's cells drawn out `ratio` (>= 1) times longer than wide along the
    /// wind blowing towards `wind` (world x, z; any length, none for a zero vector).
    pub fn with_foam_streaks(self, wind: Option<Vec2>, ratio: f32) -> Self {
        let foam_streaks = wind.and_then(|w| w.try_normalize()).filter(|_| ratio > 1.0).map(|w| (w, ratio));
        Self { foam_streaks, ..self }
    }

    /// The water-body colour at world (`x`, `z`): `color`, or its blend with the texture.
    pub fn body_color(&self, x: f32, z: f32) -> Vec3 {
        let m = self.material;
        match self.texture {
            Some(tex) => {
                let uv = Vec2::new(x, z) / m.texture_scale + self.texture_offset;
                m.color.lerp(tex.sample(uv), m.texture_mix)
            }
            None => m.color,
        }
    }
}

/// Refracts the unit direction `incident` (travelling towards the surface) through unit normal
/// `n` (on the incident side) with `eta` = n_incident / n_transmitted, by Snell's law
/// `n1 sin θ1 = n2 sin θ2` in vector form; `None` on total internal reflection.
pub fn refract(incident: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = -n.dot(incident);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(eta * incident + (eta * cos_i - cos_t) * n)
}

/// Fixed-point steps that find where a refracted ray meets a bottom that is not flat.
const SEABED_ITERATIONS: usize = 4;

/// Most the crest factor of the subsurface scattering may be (`1 + y / scatter_height`, three at
/// twice the height): a tall spike does not glow without bound.
const MAX_CREST_FACTOR: f32 = 3.0;

/// Foam coverage below which the pattern is not drawn, only its mean ([`foam_cover_lanes`]).
const FOAM_SPECK_COVERAGE: f32 = 1.0 / 256.0;

/// How strongly foam gathers on the crests: the weight of a point `z` standard deviations above
/// the water at rest is `exp(a z - a² / 2)` with this `a` ([`crest_weight_lanes`]).
const FOAM_CREST_CONTRAST: f32 = 1.5;

/// Depth of water (m) over which the surface's reflection and glitter give way to the bottom at
/// the water's edge: a film a few centimetres thick shows the wet sand under it, so the edge has
/// the land's colour on both sides and draws no line (no stair steps where the water's triangles
/// cut the terrain's).
const SOFT_EDGE_DEPTH: f32 = 0.3;
/// Breaker index γ: a wave breaks in water shallower than its height over γ (McCowan 1894, the
/// solitary wave's limit H_b = 0.78 d_b, the usual rule for depth-limited breaking).
const BREAKER_INDEX: f32 = 0.78;
/// Fraction of the breaking height at which a crest starts to whiten (white water spreads down
/// the front of a wave before the crest is at the limit).
const BREAKING_ONSET: f32 = 0.6;

/// `smoothstep(a, b, x)` per lane (0 below a, 1 above b, C1 between); infinite x saturates.
#[inline(always)]
fn smoothstep_lanes(a: f32, b: f32, x: Lanes) -> Lanes {
    let t = ((x - a) * (1.0 / (b - a))).max(0.0).min(1.0);
    t * t * (3.0 - 2.0 * t)
}

/// How much of the surface shows over `depth` metres of water, per lane: 0 at the water's edge,
/// rising to 1 over [`SOFT_EDGE_DEPTH`] (infinite depth, no bottom in sight, gives 1).
#[inline(always)]
fn edge_lanes(depth: Lanes) -> Lanes {
    smoothstep_lanes(0.0, SOFT_EDGE_DEPTH, depth)
}

/// Foam that shallow water makes, [0, 1] per lane, for surface points at height `y` (m, water at
/// rest is 0) over `depth` metres of water (infinite where no bottom is in sight): crests whiten
/// where their height, taken as half the wave height, passes [`BREAKING_ONSET`] of the
/// depth-limited breaking height `γ d0 / 2` (d0 the depth at rest, [`BREAKER_INDEX`]). So the
/// foam follows the waves: crests break as they run into the shallows, and the water a crest
/// pushes up the beach (over ground above the rest level, d0 <= 0) is all swash foam, moving up
/// and down with each wave; troughs and calm shallows stay clear. It fades out over the last
/// [`SOFT_EDGE_DEPTH`] of water with the surface itself (`edge`, [`edge_lanes`] of `depth`, passed
/// in because the shading has it already). Scaled by `strength`.
#[inline(always)]
fn shore_foam_lanes(strength: f32, y: Lanes, depth: Lanes, edge: Lanes) -> Lanes {
    // In deep water, or with no bottom in sight (infinite depth), the ratio is 0.
    let rest_depth = (depth - y).max(1e-3);
    let height_ratio = y.max(0.0) * (2.0 / BREAKER_INDEX) / rest_depth;
    let breaking = smoothstep_lanes(BREAKING_ONSET, 1.0, height_ratio);
    breaking * edge * strength
}

/// Radiance leaving water point `p` (world m) with unit normal `n` towards the eye; `foam` in
/// [0, 1] whitens it.
///
/// `L = F L_r + (1 − F) L_t + specular + foam`, with F the exact Fresnel reflectance
/// ([`fresnel_dielectric`]) and `L_r` what the mirrored view ray r sees: the terrain above the
/// water where [`WaterLook::reflection`] has it along r, the sky elsewhere; and where the transmitted radiance
/// `L_t = L_bottom e^(−a s) + L_body (1 − e^(−a s)) + L_sss` is the refracted bottom attenuated by
/// Beer-Lambert absorption `a` (per channel, 1/m) over the underwater path s, plus light
/// scattered by the water body along it (`color` lit by the light that enters the water,
/// [`light_in_water_lanes`]), plus the light scattered through thin backlit crests (`L_sss`);
/// with no bottom in sight only the body remains (deep water). The bottom is lit by the lights
/// after their own refraction and absorption down to it. A reflected ray below the horizon would
/// hit the water again; it is bent back to the horizon, whose colour is what such a ray would
/// eventually see. Foam covers the water where the wave model reports it, structured by the
/// look's [`FoamPattern`] so that the foam shown has the reported coverage.
pub fn shade_water(env: &Environment, look: &WaterLook, lobe: Lobe, p: Vec3, n: Vec3, foam: f32) -> Vec3 {
    shade_water_filtered(env, look, lobe, p, n, foam, 0.0)
}

/// [`shade_water`] with the slope variance `unresolved` (both axes summed, >= 0) of the waves
/// too short for the mesh or the pixel that sampled `n`, shaded statistically
/// (`shading/slope_variance.rs`, Bruneton et al. 2010): the Fresnel factor is their mean over the
/// slopes, the reflected sky is averaged over normals spread by the slopes' deviation and the
/// specular lobe is widened with its energy kept. `unresolved = 0` is [`shade_water`].
///
/// One point is one lane of [`shade_water_lanes`], the one definition of the water's colour.
pub fn shade_water_filtered(
    env: &Environment,
    look: &WaterLook,
    lobe: Lobe,
    p: Vec3,
    n: Vec3,
    foam: f32,
    unresolved: f32,
) -> Vec3 {
    let points = WaterPoints {
        position: Vec3Lanes::splat(p),
        normal: Vec3Lanes::splat(n),
        foam: Lanes::splat(foam),
        unresolved: Lanes::splat(unresolved),
    };
    shade_water_lanes(env, look, lobe, &points, 1).lane(0)
}

/// Up to [`crate::math::LANES`] water surface points shaded together (see [`shade_water_lanes`]).
#[derive(Clone, Copy, Debug)]
pub struct WaterPoints {
    /// World positions, m.
    pub position: Vec3Lanes,
    /// Unit normals (any side: the one facing the eye is shaded).
    pub normal: Vec3Lanes,
    /// Foam coverage, [0, 1].
    pub foam: Lanes,
    /// Unresolved slope variance, >= 0 (0: a point-sampled surface).
    pub unresolved: Lanes,
}

/// [`shade_water_filtered`] for the first `live` lanes of `points` at once (the rest are computed
/// and ignored): the per-pixel shading of water runs this over each row's pixels, [`LANES`](crate::math::LANES) at a time.
/// Each lane's result is what the scalar formula gives for that point alone; the vector part is
/// plain arithmetic on [`Lanes`] with [`fast_pow`] for the powers (relative error < 1e-4), and the
/// parts that read scene data (the sky, the mirrored terrain, the texture, the seabed) run per
/// lane.
#[inline(always)]
pub fn shade_water_lanes(
    env: &Environment,
    look: &WaterLook,
    lobe: Lobe,
    points: &WaterPoints,
    live: usize,
) -> Vec3Lanes {
    let m = look.material;
    let p = points.position;
    let to_eye = (Vec3Lanes::splat(env.eye) - p).normalize_or(Vec3::Y);
    // Seen from behind (a fold, or the far side of a steep crest), shade the side facing the eye.
    let n = points.normal.dot(to_eye).lt(0.0).select3(-points.normal, points.normal);
    let cos_i = n.dot(to_eye);
    let unresolved = points.unresolved.max(0.0);
    let (transmitted, depth) = transmitted_lanes(env, look, p, n, to_eye, live);
    // At the water's edge the surface fades into the bottom it covers (1 away from the shore).
    let shore = depth.lt(f32::INFINITY).any();
    let edge = if shore { edge_lanes(depth) } else { Lanes::splat(1.0) };
    // The micro-roughness below the unresolved waves blurs the sky's reflection and averages
    // its Fresnel factor as they do. The sun reaches the eye through the glitter (or the lobe),
    // not as a disc in the mirrored sky, unless no directional light stands for it: the disc
    // carries the sunlight's whole irradiance, so mirroring both would count the sun twice.
    let rough = match &look.glitter {
        Some(g) => unresolved + g.micro_total(),
        None => unresolved,
    };
    let disc_in_sky = !env.lights.iter().any(|l| matches!(l, Light::Directional { .. }));
    let f = fresnel_over_slopes_lanes(m, cos_i, rough) * edge;
    let sky = reflected_lanes(env, look, p, n, to_eye, cos_i, rough, disc_in_sky, live);

    let mut water = sky.scale(f) + transmitted.scale(1.0 - f);
    if m.specular > 0.0 {
        let glitter = match &look.glitter {
            Some(g) => g.radiance_lanes(env, p, n, to_eye, unresolved, m.refractive_index),
            None => {
                let (shininess, weight) = widened_lobe_lanes(m.shininess, unresolved);
                specular_lanes(env, p, n, to_eye, lobe, shininess).scale(weight)
            }
        };
        water = water + glitter.scale(edge * m.specular);
    }
    // The wave model's whitecaps gather on the crests; the shore's foam has its own place (where
    // crests reach their breaking height, and the swash).
    let whitecaps = on_crests_lanes(look, p, points.foam);
    let foam = if shore && m.shore_foam > 0.0 {
        whitecaps.max(shore_foam_lanes(m.shore_foam, p.y, depth, edge))
    } else {
        whitecaps
    };
    if foam.gt(0.0).any() {
        let foam_light = lambert_lanes(env, p, Vec3Lanes::splat(Vec3::Y)) * m.foam_color;
        let cover = foam_cover_lanes(env, look, p, cos_i, foam.min(1.0));
        water = foam.gt(0.0).select3(water.lerp(foam_light, cover), water);
    }
    // Aerial perspective: distant water fades into the horizon's haze (unchanged without haze).
    // Lanes past `live` are computed and dropped by the caller.
    env.sky.aerial_perspective_lanes(env.eye, p, water)
}

/// The Fresnel reflectance of the water at `cos_i` to the mean normal: exact where the surface is
/// point-sampled, Bruneton's mean over the `unresolved` slopes elsewhere. Each only where some
/// lane needs it: near water has no unresolved slopes, far water little else.
#[inline(always)]
fn fresnel_over_slopes_lanes(m: &WaterMaterial, cos_i: Lanes, unresolved: Lanes) -> Lanes {
    let rough = unresolved.gt(0.0);
    if !rough.any() {
        fresnel_dielectric_lanes(cos_i, m.refractive_index)
    } else if !unresolved.le(0.0).any() {
        mean_fresnel_lanes(cos_i, unresolved, fresnel_dielectric(1.0, m.refractive_index))
    } else {
        rough.select(
            mean_fresnel_lanes(cos_i, unresolved, fresnel_dielectric(1.0, m.refractive_index)),
            fresnel_dielectric_lanes(cos_i, m.refractive_index),
        )
    }
}

/// What the water reflects towards the eye: the sky (and the sun disc, with `disc`) averaged over
/// two normals tilted by the slopes' deviation towards and away from the eye (one normal, twice,
/// when nothing is unresolved), replaced by the mirrored terrain where the reflected ray meets it.
#[allow(clippy::too_many_arguments)] // the lanes of one batch, passed apart so each stays a register set
#[inline(always)]
fn reflected_lanes(
    env: &Environment,
    look: &WaterLook,
    p: Vec3Lanes,
    n: Vec3Lanes,
    to_eye: Vec3Lanes,
    cos_i: Lanes,
    unresolved: Lanes,
    disc: bool,
    live: usize,
) -> Vec3Lanes {
    let mut sky = Vec3Lanes::splat(Vec3::ZERO);
    for s in spread_normals_lanes(n, to_eye, unresolved, live) {
        let c = s.dot(to_eye).max(0.0);
        let mut r = s.scale(2.0 * c) - to_eye;
        // A reflected ray below the horizon would meet the water again: bent back to it.
        r.y = r.y.max(0.0);
        let r = r.normalize_or(Vec3::Y);
        let seen = if disc { env.sky_radiance_lanes(r) } else { env.sky.radiance_lanes(r) };
        sky = sky + seen.scale(0.5);
    }
    if let Some(map) = look.reflection {
        // The terrain above the water, where the mirrored view ray meets it, replaces the sky.
        let reflected = (n.scale(2.0 * cos_i) - to_eye).normalize_or(Vec3::Y);
        for i in 0..live {
            let r = reflected.lane(i);
            if r.y > 0.0 {
                if let Some(t) = map.sample(p.lane(i), r) {
                    sky.set_lane(i, t);
                }
            }
        }
    }
    sky
}

/// The light that leaves the water body towards the eye: the lit body colour (or its texture),
/// where a seabed is in reach the bottom seen through the water with Beer-Lambert absorption, and
/// the backlit crests' scattering; and the depth of water over that bottom (the point's height
/// less the bottom's where the refracted ray meets it, m; infinite where none is in sight).
#[inline(always)]
fn transmitted_lanes(
    env: &Environment,
    look: &WaterLook,
    p: Vec3Lanes,
    n: Vec3Lanes,
    to_eye: Vec3Lanes,
    live: usize,
) -> (Vec3Lanes, Lanes) {
    let m = look.material;
    let (lit, scatter) = light_in_water_lanes(env, m, p, n, to_eye);
    let body = match look.texture {
        Some(_) => Vec3Lanes::from_fn(|i| look.body_color(p.x.0[i], p.z.0[i])) * lit,
        None => lit * m.color,
    };
    let mut transmitted = body;
    let mut depth = Lanes::splat(f32::INFINITY);
    // Open water has no bottom to refract to.
    if look.seabed.anywhere() {
        let refracted = refract_lanes(-to_eye, n, 1.0 / m.refractive_index);
        for i in 0..live {
            let t = refracted.lane(i);
            // Beyond the critical angle `refract` gives no ray (a NaN lane here): only the body shows.
            if t.y.is_nan() || t.y >= -1e-4 {
                continue;
            }
            if let Some((path, height, albedo)) = bottom_hit(look.seabed, p.lane(i), t) {
                depth.0[i] = p.y.0[i] - height;
                let bottom = albedo * bottom_irradiance(env, m, p.y.0[i].max(0.0) - height);
                let transmittance = (-m.absorption * path).exp();
                let v = bottom * transmittance + body.lane(i) * (Vec3::ONE - transmittance);
                transmitted.set_lane(i, v);
            }
        }
    }

    if m.scatter_strength > 0.0 {
        transmitted = transmitted + scatter;
    }
    (transmitted, depth)
}

/// A run of water points to shade together ([`shade_water_run`]): point `i` of `len`, with its
/// world position (m), normal (any length), foam in [0, 1] and unresolved slope variance (>= 0).
pub trait WaterRun: Sync {
    /// Number of points.
    fn len(&self) -> usize;
    /// Whether there are none.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Point `i`, `i < len()`.
    fn point(&self, i: usize) -> SurfaceVarying;
    /// Points `start..start + live` (`live` in 1..=[`LANES`](crate::math::LANES), within `len()`)
    /// as lanes, the lanes past `live` repeating the first, normals as given.
    #[inline(always)]
    fn gather(&self, start: usize, live: usize) -> WaterPoints {
        let mut points = empty_points();
        for i in 0..crate::math::LANES {
            points.set_lane(i, &self.point(start + if i < live { i } else { 0 }));
        }
        points
    }
}

impl WaterRun for &[SurfaceVarying] {
    fn len(&self) -> usize {
        <[SurfaceVarying]>::len(self)
    }
    #[inline(always)]
    fn point(&self, i: usize) -> SurfaceVarying {
        self[i]
    }
    /// The slice's points read in order, one bounds check per batch (per point, the checks and
    /// the lane choice were a twentieth of a `sea` frame's instructions).
    #[inline(always)]
    fn gather(&self, start: usize, live: usize) -> WaterPoints {
        let batch = &self[start..start + live];
        let mut points = empty_points();
        for (i, p) in batch.iter().enumerate() {
            points.set_lane(i, p);
        }
        for i in live..crate::math::LANES {
            points.set_lane(i, &batch[0]);
        }
        points
    }
}

/// Lanes of zeros to gather into.
#[inline(always)]
fn empty_points() -> WaterPoints {
    let zero = Vec3Lanes::splat(Vec3::ZERO);
    WaterPoints { position: zero, normal: zero, foam: Lanes::splat(0.0), unresolved: Lanes::splat(0.0) }
}

impl WaterPoints {
    /// Sets lane `i` to point `p`.
    #[inline(always)]
    fn set_lane(&mut self, i: usize, p: &SurfaceVarying) {
        self.position.set_lane(i, p.position);
        self.normal.set_lane(i, p.normal);
        self.foam.0[i] = p.foam;
        self.unresolved.0[i] = p.unresolved;
    }
}

/// Shades every point of `run` into `out` (as many), a batch at a time through
/// [`shade_water_lanes`] compiled for the widest vector instructions the CPU has ([`Isa`]): the
/// same IEEE operations lane by lane whichever, so the image does not depend on the CPU.
pub fn shade_water_run(env: &Environment, look: &WaterLook, lobe: Lobe, run: &impl WaterRun, out: &mut [Vec3]) {
    shade_water_run_with(Isa::widest(), env, look, lobe, run, out);
}

/// [`shade_water_run`] compiled for `isa` (the baseline where the CPU lacks it).
pub(crate) fn shade_water_run_with(
    isa: Isa,
    env: &Environment,
    look: &WaterLook,
    lobe: Lobe,
    run: &impl WaterRun,
    out: &mut [Vec3],
) {
    isa.run(
        #[inline(always)]
        || shade_water_run_lanes(env, look, lobe, run, out),
    );
}

#[inline(always)]
fn shade_water_run_lanes(env: &Environment, look: &WaterLook, lobe: Lobe, run: &impl WaterRun, out: &mut [Vec3]) {
    let n = run.len().min(out.len());
    for (start, out) in (0..n).step_by(crate::math::LANES).zip(out[..n].chunks_mut(crate::math::LANES)) {
        let live = out.len();
        // Lanes past the run repeat its first point of the batch and are dropped.
        let mut points = run.gather(start, live);
        points.normal = points.normal.normalize_or(Vec3::Y);
        let c = shade_water_lanes(env, look, lobe, &points, live);
        for (i, o) in out.iter_mut().enumerate() {
            *o = c.lane(i);
        }
    }
}

/// The light that enters the water at each lane's point with unit normal `n`, and the light its
/// thin crests scatter towards the eye (`to_eye`, unit), both linear RGB.
///
/// Entering light: the ambient light plus each light's irradiance `E cos θ_l` less its Fresnel
/// reflection (Schlick's approximation, Schlick 1994, of [`fresnel_dielectric`]): a low sun or
/// a wave face turned from it puts less light into the water, and the body colour follows.
///
/// Subsurface scattering: the approximation of the Atlas talk (Tcheblokov and others, "Wakes,
/// Explosions and Lighting: Interactive Water Simulation in Atlas", GDC 2019) as GodotOceanWaves
/// writes it (`assets/shaders/spatial/water.gdshader`, `light()`): light crossing a crest towards
/// the eye, `k H max(0, −l·v)^4 ((1 − n·l) / 2)^3`, strongest looking into the light (`−l·v`)
/// through a face turned away from it (`1 − n·l`, the thin back of a crest) and growing with the
/// crest's height H; here `H = clamp(1 + y / scatter_height, 0, 3)`, `k = scatter_strength`,
/// tinted by `scatter_color`. Everything is per lane; the lights are few.
#[inline(always)]
fn light_in_water_lanes(
    env: &Environment,
    m: &WaterMaterial,
    p: Vec3Lanes,
    n: Vec3Lanes,
    to_eye: Vec3Lanes,
) -> (Vec3Lanes, Vec3Lanes) {
    let r0 = fresnel_dielectric(1.0, m.refractive_index);
    let scatters = m.scatter_strength > 0.0;
    let crest = (1.0 + p.y * (1.0 / m.scatter_height)).max(0.0).min(MAX_CREST_FACTOR) * m.scatter_strength;
    let mut entering = Vec3Lanes::splat(env.ambient);
    let mut scatter = Vec3Lanes::splat(Vec3::ZERO);
    for light in env.lights {
        let (l, radiance) = incident_lanes(light, p);
        let cos_l = n.dot(l);
        let c = cos_l.max(0.0);
        let x = 1.0 - c;
        let x2 = x * x;
        let transmitted = (1.0 - r0) * (1.0 - x2 * x2 * x);
        entering = entering + radiance.scale(c * transmitted);
        if scatters {
            let towards = (-l.dot(to_eye)).max(0.0);
            let towards2 = towards * towards;
            let thin = 0.5 - 0.5 * cos_l;
            scatter = scatter + radiance.scale(crest * towards2 * towards2 * (thin * thin * thin));
        }
    }
    (entering, scatter * m.scatter_color)
}

/// How much of each lane foam covers, [0, 1], for the wave model's coverage `coverage` there:
/// the look's [`FoamPattern`] at the point (tiles of `foam_scale`) revealed down to the coverage
/// (its mean over a tile is the coverage), at the level of detail the pixel's footprint resolves
/// ([`FoamPattern::filtered_alpha_lanes`]) and handing over to the coverage itself where even the
/// coarsest level would be finer than a pixel; drawn out along the wind when the look has
/// [`WaterLook::foam_streaks`]. `cos_i` is the cosine between the normal and the view (the
/// footprint is the slope filter's, [`pixel_footprint_lanes`]).
/// Without a pattern, the coverage.
#[inline(always)]
fn foam_cover_lanes(env: &Environment, look: &WaterLook, p: Vec3Lanes, cos_i: Lanes, coverage: Lanes) -> Lanes {
    let Some(pattern) = look.foam else { return coverage };
    // A batch whose coverage stays below a 256th shows at most a scatter of specks a pixel's
    // grey level would not tell from their mean: drawn as the mean, and the pattern (most of the
    // foam's cost) is not read where the sea barely breaks.
    if !coverage.gt(FOAM_SPECK_COVERAGE).any() {
        return coverage;
    }
    let m = look.material;
    let per_tile = 1.0 / m.foam_scale;
    // Texels per metre of the round pattern: streaks squeeze it across the wind and stretch it
    // along by the same factor, so a footprint keeps its area in texels, and the level is chosen
    // by that area (taking the finer axis instead blurred the foam seen from above a fifth below
    // the solid share of a 4 x 4 supersampled frame, `tests/foam_coverage.rs`).
    let texels_per_m = per_tile * FOAM_PATTERN_SIDE as f32;
    let distance = (Vec3Lanes::splat(env.eye) - p).length();
    let texels = pixel_footprint_lanes(distance, look.pixel_angle, cos_i) * texels_per_m;
    let (u, v) = match look.foam_streaks {
        // The pattern in axes along and across the wind, stretched along it and squeezed across
        // by the square root of the ratio each, so that a cell keeps its area and the foam its
        // coverage.
        Some((wind, ratio)) => {
            let (along, across) = (per_tile / ratio.sqrt(), per_tile * ratio.sqrt());
            ((p.x * wind.x + p.z * wind.y) * along, (p.z * wind.x - p.x * wind.y) * across)
        }
        None => (p.x * per_tile, p.z * per_tile),
    };
    pattern.filtered_alpha_lanes(u, v, coverage, m.foam_feather, texels)
}

/// The wave model's foam coverage `coverage` at points `p`, gathered on the crests when the look
/// has [`WaterLook::foam_crests`] ([`crest_weight_lanes`]), in [0, 1].
#[inline(always)]
fn on_crests_lanes(look: &WaterLook, p: Vec3Lanes, coverage: Lanes) -> Lanes {
    match look.foam_crests {
        Some((rest, inv_spread)) => (coverage * crest_weight_lanes((p.y - rest) * inv_spread)).min(1.0),
        None => coverage,
    }
}

/// How much more foam than the wave model's coverage a point `z` standard deviations of the
/// sea's height above the water at rest shows: `exp(a z - a² / 2)`, a = [`FOAM_CREST_CONTRAST`]
/// (z clamped to ±4).
///
/// Why: the model's coverage is a probability per sample, and where most of the breaking is
/// below the grid (the FFT ocean's `σ` of the unresolved Jacobian, `water/foam.rs`) it is nearly
/// the same everywhere, which drawn as it is makes an even lace over the whole sea. Waves break
/// at the crests of the long waves and their groups (Donelan, Longuet-Higgins and Turner 1972,
/// "Periodicity in whitecaps", Nature 239; the short waves are steepest on the long waves' crests,
/// Longuet-Higgins and Stewart 1960): the weight moves the foam there, so whitecaps have bodies on
/// the crests and thin out into the troughs. Its mean over a Gaussian sea is exactly 1
/// (`E[exp(a Z)] = exp(a² / 2)`), so the foam an image shows keeps the coverage the model reports
/// (the cap at full cover and the sea's small skewness aside).
#[inline(always)]
fn crest_weight_lanes(z: Lanes) -> Lanes {
    const A: f32 = FOAM_CREST_CONTRAST;
    let z = z.max(-4.0).min(4.0);
    // exp(x) = 2^(x log2 e).
    Lanes::from_fn(|i| fast_exp2((A * z.0[i] - 0.5 * A * A) * std::f32::consts::LOG2_E))
}

/// [`fresnel_dielectric`] per lane.
#[inline(always)]
pub(super) fn fresnel_dielectric_lanes(cos_incident: Lanes, ior: f32) -> Lanes {
    let cos_i = cos_incident.max(0.0).min(1.0);
    let sin_t2 = (1.0 - cos_i * cos_i) / (ior * ior);
    let cos_t = (1.0 - sin_t2).max(0.0).sqrt();
    let rs = (cos_i - ior * cos_t) / (cos_i + ior * cos_t);
    let rp = (ior * cos_i - cos_t) / (ior * cos_i + cos_t);
    // Total internal reflection (from inside water) reflects everything.
    sin_t2.lt(1.0).select(0.5 * (rs * rs + rp * rp), 1.0)
}

/// [`refract`] per lane; lanes past the critical angle get NaN.
#[inline(always)]
fn refract_lanes(incident: Vec3Lanes, n: Vec3Lanes, eta: f32) -> Vec3Lanes {
    let cos_i = -n.dot(incident);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    let cos_t = (1.0 - sin2_t).sqrt(); // NaN past the critical angle
    incident.scale(eta) + n.scale(eta * cos_i - cos_t)
}

/// [`super::lambert`] per lane.
#[inline(always)]
fn lambert_lanes(env: &Environment, p: Vec3Lanes, n: Vec3Lanes) -> Vec3Lanes {
    let mut acc = Vec3Lanes::splat(env.ambient);
    for light in env.lights {
        let (to_light, radiance) = incident_lanes(light, p);
        acc = acc + radiance.scale(n.dot(to_light).max(0.0));
    }
    acc
}

/// [`super::specular`] per lane.
#[inline(always)]
fn specular_lanes(
    env: &Environment,
    p: Vec3Lanes,
    n: Vec3Lanes,
    to_eye: Vec3Lanes,
    lobe: Lobe,
    shininess: Lanes,
) -> Vec3Lanes {
    let mut acc = Vec3Lanes::splat(Vec3::ZERO);
    for light in env.lights {
        let (l, radiance) = incident_lanes(light, p);
        let n_dot_l = n.dot(l);
        let c = match lobe {
            Lobe::Phong => (n.scale(2.0 * n_dot_l) - l).dot(to_eye),
            Lobe::BlinnPhong => n.dot((l + to_eye).normalize_or(Vec3::ZERO)),
        };
        let lit = n_dot_l.gt(0.0).and(c.gt(0.0));
        let power = Lanes::from_fn(|i| fast_pow(c.0[i].max(0.0), shininess.0[i]));
        acc = acc + radiance.scale(lit.select(power, 0.0));
    }
    acc
}

/// A light's direction and radiance at each lane's point ([`Light::incident`]).
#[inline(always)]
pub(super) fn incident_lanes(light: &Light, p: Vec3Lanes) -> (Vec3Lanes, Vec3Lanes) {
    match *light {
        Light::Directional { .. } => {
            let inc = light.incident(Vec3::ZERO);
            (Vec3Lanes::splat(inc.to_light), Vec3Lanes::splat(inc.radiance))
        }
        Light::Point { position, color, intensity } => {
            let d = Vec3Lanes::splat(position) - p;
            let r2 = d.dot(d).max(1e-6);
            (d.scale(1.0 / r2.sqrt()), Vec3Lanes::splat(color * intensity).scale(1.0 / r2))
        }
    }
}

/// Where the refracted ray from `p` along unit `t` (downwards) meets the seabed: (path length m,
/// bottom height, albedo). Exact for a flat bottom after the first step; for a varying one each
/// step re-reads the height where the previous estimate landed.
fn bottom_hit(seabed: &dyn Seabed, p: Vec3, t: Vec3) -> Option<(f32, f32, Vec3)> {
    let (mut height, mut albedo) = seabed.sample(p.x, p.z)?;
    let mut s = 0.0;
    for _ in 0..SEABED_ITERATIONS {
        if height >= p.y {
            return Some((0.0, height, albedo));
        }
        let next = (height - p.y) / t.y;
        if (next - s).abs() < 1e-3 {
            break;
        }
        s = next;
        let q = p + t * s;
        (height, albedo) = seabed.sample(q.x, q.z)?;
    }
    Some((s.max(0.0), height, albedo))
}

/// Irradiance on a horizontal bottom `depth` metres under the surface: each light enters through
/// the flat surface (losing its Fresnel reflection), refracts towards the vertical and is absorbed
/// over its slant path; ambient light is absorbed over the depth.
fn bottom_irradiance(env: &Environment, m: &WaterMaterial, depth: f32) -> Vec3 {
    let depth = depth.max(0.0);
    let eta = 1.0 / m.refractive_index;
    env.lights.iter().fold(env.ambient * (-m.absorption * depth).exp(), |acc, light| {
        let inc = light.incident(Vec3::ZERO);
        let cos_l = inc.to_light.y;
        if cos_l <= 0.0 {
            return acc;
        }
        let sin2_t = eta * eta * (1.0 - cos_l * cos_l);
        let cos_t = (1.0 - sin2_t).max(1e-3).sqrt();
        let entering = 1.0 - fresnel_dielectric(cos_l, m.refractive_index);
        acc + inc.radiance * (cos_t * entering) * (-m.absorption * (depth / cos_t)).exp()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Light, Sky};

    #[test]
    fn refraction_obeys_snells_law() {
        let n = Vec3::Y;
        for deg in [0.0f32, 10.0, 30.0, 60.0, 89.0] {
            let a = deg.to_radians();
            let incident = Vec3::new(a.sin(), -a.cos(), 0.0);
            let t = refract(incident, n, 1.0 / 1.333).unwrap();
            assert!((t.length() - 1.0).abs() < 1e-5);
            let sin_t = t.x;
            assert!((a.sin() - 1.333 * sin_t).abs() < 1e-5, "{deg}°: sin θ1 {} vs n sin θ2 {}", a.sin(), 1.333 * sin_t);
            assert!(t.y < 0.0, "the ray goes on downwards");
        }
        // From inside water past the critical angle (48.6°): total internal reflection.
        let a = 50f32.to_radians();
        assert!(refract(Vec3::new(a.sin(), a.cos(), 0.0), -Vec3::Y, 1.333).is_none());
        let a = 45f32.to_radians();
        assert!(refract(Vec3::new(a.sin(), a.cos(), 0.0), -Vec3::Y, 1.333).is_some());
    }

    fn env<'a>(lights: &'a [Light], sky: &'a Sky) -> Environment<'a> {
        let sky = Box::leak(Box::new(crate::shading::SkyRadiance::new(sky)));
        Environment { lights, ambient: Vec3::splat(0.1), sky, sun: None, eye: Vec3::new(0.0, 10.0, 0.0), time: 0.0 }
    }

    #[test]
    fn a_shallow_bottom_shows_through_and_fades_with_depth_reddest_first() {
        let lights = [Light::Directional { direction: Vec3::new(0.0, -1.0, 0.0), color: Vec3::ONE, intensity: 1.0 }];
        let sky = Sky::default();
        let env = env(&lights, &sky);
        let material = WaterMaterial { specular: 0.0, bottom_color: Vec3::ONE, ..WaterMaterial::default() };
        let look_at = |depth: f32| {
            let bottom = FlatBottom { height: -depth, albedo: Vec3::ONE };
            let look = WaterLook::new(&material, &bottom, None, 0.0);
            shade_water(&env, &look, Lobe::BlinnPhong, Vec3::ZERO, Vec3::Y, 0.0)
        };
        let deep = shade_water(
            &env,
            &WaterLook::new(&material, &NoBottom, None, 0.0),
            Lobe::BlinnPhong,
            Vec3::ZERO,
            Vec3::Y,
            0.0,
        );
        let (shallow, mid, far) = (look_at(0.5), look_at(5.0), look_at(500.0));
        assert!(shallow.x > mid.x && mid.x > far.x, "red fades with depth: {shallow} {mid} {far}");
        // Red is absorbed fastest, so a bright bottom turns blue-green with depth.
        assert!(mid.x / shallow.x < mid.z / shallow.z);
        // Far below, nothing of the bottom is left: the water looks deep.
        assert!((far - deep).abs().max_element() < 1e-3, "{far} vs {deep}");
    }

    #[test]
    fn shallow_water_foams_at_breaking_crests_and_along_the_edge_and_nowhere_deep() {
        let shore = |strength: f32, y: f32, depth: f32| {
            let depth = Lanes::splat(depth);
            shore_foam_lanes(strength, Lanes::splat(y), depth, edge_lanes(depth)).0[0]
        };
        let foam = |y: f32, depth: f32| shore(1.0, y, depth);
        // Deep water, or no bottom in sight: none, whatever the crest.
        assert_eq!(foam(1.0, 11.0), 0.0);
        assert_eq!(foam(0.0, f32::INFINITY), 0.0);
        assert_eq!(foam(3.0, f32::INFINITY), 0.0);
        // A crest 1 m up over 1.5 m of water at rest (wave height 2 m > 0.78 x 1.5 m) breaks;
        // the same crest over 4 m does not (2 m < 0.6 x 0.78 x 4 m... just under the onset).
        assert_eq!(foam(1.0, 2.5), 1.0);
        assert_eq!(foam(0.9, 0.9 + 4.0), 0.0);
        // A trough over the same shallows does not, nor calm shallow water (a wading pool).
        assert_eq!(foam(-0.5, 1.0), 0.0);
        assert_eq!(foam(0.0, 0.4), 0.0);
        // Swash: a crest 0.3 m up running over a beach 0.1 m above the rest level foams...
        assert_eq!(foam(0.3, 0.3 - 0.1 + 0.1), 1.0);
        // ...and gives way over the last few centimetres of water, with the surface.
        assert_eq!(foam(0.3, 0.0), 0.0);
        assert_eq!(foam(0.3, -0.2), 0.0);
        assert!(foam(0.3, 0.05) < foam(0.3, 0.15) && foam(0.3, 0.15) < foam(0.3, 0.3));
        // Strength scales it, 0 turns it off.
        assert_eq!(shore(0.5, 1.0, 2.5), 0.5);
        assert_eq!(shore(0.0, 1.0, 2.5), 0.0);
    }

    #[test]
    fn at_the_waters_edge_the_surface_shows_only_the_bottom_it_covers() {
        let lights = [Light::Directional { direction: Vec3::new(0.3, -1.0, 0.0), color: Vec3::ONE, intensity: 1.0 }];
        let (blue, red) = (Sky::default(), Sky { horizon: Vec3::new(1.0, 0.0, 0.0), ..Sky::default() });
        let material = WaterMaterial { shore_foam: 0.0, ..WaterMaterial::default() };
        let shade_over = |sky: &Sky, depth: f32| {
            let mut env = env(&lights, sky);
            env.eye = Vec3::new(0.0, 2.0, 20.0);
            let bottom = FlatBottom { height: -depth, albedo: Vec3::new(0.5, 0.4, 0.3) };
            let look = WaterLook::new(&material, &bottom, None, 0.0);
            shade_water(&env, &look, Lobe::BlinnPhong, Vec3::ZERO, Vec3::Y, 0.0)
        };
        // At the edge the water reflects nothing of the sky: the same colour under any sky, and
        // next to nothing a millimetre out...
        assert_eq!(shade_over(&blue, 0.0), shade_over(&red, 0.0));
        assert!((shade_over(&blue, 0.001) - shade_over(&red, 0.001)).abs().max_element() < 1e-4);
        // ...while a metre of it mirrors the sky's horizon.
        assert!((shade_over(&red, 1.0) - shade_over(&blue, 1.0)).x > 0.05);
        // The hand-over is gradual: no step in the colour with depth.
        let steps: Vec<Vec3> = (0..=40).map(|k| shade_over(&red, k as f32 * 0.01)).collect();
        for pair in steps.windows(2) {
            assert!((pair[1] - pair[0]).abs().max_element() < 0.02, "{pair:?}");
        }
    }

    #[test]
    fn grazing_views_reflect_the_sky_and_foam_whitens() {
        let lights = [Light::Directional { direction: Vec3::new(0.3, -1.0, 0.0), color: Vec3::ONE, intensity: 1.0 }];
        let sky = Sky::default();
        let mut env = env(&lights, &sky);
        let material = WaterMaterial { specular: 0.0, ..WaterMaterial::default() };
        let look = WaterLook::new(&material, &NoBottom, None, 0.0);
        env.eye = Vec3::new(0.0, 0.01, 100.0);
        let grazing = shade_water(&env, &look, Lobe::BlinnPhong, Vec3::ZERO, Vec3::Y, 0.0);
        assert!((grazing - sky.horizon).length() < 0.05, "{grazing} should be near the horizon {}", sky.horizon);
        env.eye = Vec3::new(0.0, 10.0, 0.0);
        let water = shade_water(&env, &look, Lobe::BlinnPhong, Vec3::ZERO, Vec3::Y, 0.0);
        let foamy = shade_water(&env, &look, Lobe::BlinnPhong, Vec3::ZERO, Vec3::Y, 1.0);
        assert!(foamy.min_element() > water.max_element());
    }

    /// The glow a crest at height `y` with normal `n` gains from scattering, seen from `eye` with
    /// the sun's light travelling along `sun_travel`.
    fn crest_glow(eye: Vec3, sun_travel: Vec3, y: f32, n: Vec3) -> Vec3 {
        let lights = [Light::Directional { direction: sun_travel, color: Vec3::ONE, intensity: 1.0 }];
        let sky = Sky::default();
        let mut env = env(&lights, &sky);
        env.eye = eye;
        let with = WaterMaterial { specular: 0.0, ..WaterMaterial::default() };
        let without = WaterMaterial { scatter_strength: 0.0, ..with.clone() };
        let p = Vec3::new(0.0, y, 0.0);
        let shade = |m: &WaterMaterial| {
            shade_water(&env, &WaterLook::new(m, &NoBottom, None, 0.0), Lobe::BlinnPhong, p, n.normalize(), 0.0)
        };
        shade(&with) - shade(&without)
    }

    #[test]
    fn backlit_crests_glow_green_and_frontlit_ones_do_not() {
        // The eye looks along -z towards a low sun through a crest whose face is turned to it.
        let eye = Vec3::new(0.0, 4.0, 30.0);
        let into_the_eye = Vec3::new(0.0, -0.1, 1.0);
        let face = Vec3::new(0.0, 0.8, 0.6);
        let glow = crest_glow(eye, into_the_eye, 1.5, face);
        assert!(glow.y > 0.1, "a backlit crest glows: {glow}");
        assert!(glow.y > glow.x && glow.y > glow.z, "in the scattering colour: {glow}");
        // Higher crests glow more, troughs well below rest not at all.
        assert!(crest_glow(eye, into_the_eye, 0.0, face).y < glow.y);
        assert_eq!(crest_glow(eye, into_the_eye, -3.0, face), Vec3::ZERO);
        // With the sun behind the eye nothing shines through.
        assert_eq!(crest_glow(eye, Vec3::new(0.0, -0.1, -1.0), 1.5, face), Vec3::ZERO);
    }

    #[test]
    fn the_body_colour_follows_the_light_that_enters_the_water() {
        // Deep water seen from above under a high and a low sun: the low sun puts less light in
        // than its cosine alone (Fresnel reflects more of it at grazing incidence).
        let body = |elevation_deg: f32| {
            let e = elevation_deg.to_radians();
            let lights = [Light::Directional {
                direction: Vec3::new(0.0, -e.sin(), -e.cos()),
                color: Vec3::ONE,
                intensity: 1.0,
            }];
            let sky = Sky { zenith: Vec3::ZERO, horizon: Vec3::ZERO, ground: Vec3::ZERO, ..Sky::default() };
            let mut env = env(&lights, &sky);
            env.ambient = Vec3::ZERO;
            let material = WaterMaterial { specular: 0.0, scatter_strength: 0.0, ..WaterMaterial::default() };
            let look = WaterLook::new(&material, &NoBottom, None, 0.0);
            shade_water(&env, &look, Lobe::BlinnPhong, Vec3::ZERO, Vec3::Y, 0.0)
        };
        let (high, low) = (body(60.0), body(5.0));
        let cosines = 5f32.to_radians().sin() / 60f32.to_radians().sin();
        assert!(low.z < 0.8 * cosines * high.z, "{low} vs {high}");
        assert!(low.z > 0.0);
    }

    #[test]
    fn the_texture_slides_with_the_flow() {
        let material =
            WaterMaterial { flow_velocity: Vec2::new(2.0, 0.0), texture_scale: 8.0, ..WaterMaterial::default() };
        let tex = Texture::procedural_water(material.color);
        let at = |t: f64, x: f32| WaterLook::new(&material, &NoBottom, Some(&tex), t).body_color(x, 1.3);
        // What was at x = 1 at t = 0 is at x = 1 + 2 * 1.5 at t = 1.5.
        assert!((at(0.0, 1.0) - at(1.5, 4.0)).length() < 1e-4);
        assert!((at(0.0, 1.0) - at(1.5, 1.0)).length() > 1e-4);
    }

    /// Water shaded through every vector build this CPU has gives the same bits: rough and
    /// smooth points, foam with its pattern near and far, a point light, a textured body over a
    /// seabed and haze, in runs that end mid-batch.
    #[test]
    fn isa_builds_agree() {
        let lights = [
            Light::Directional {
                direction: Vec3::new(0.4, -0.5, -1.0),
                color: Vec3::new(1.0, 0.9, 0.8),
                intensity: 3.0,
            },
            Light::Point { position: Vec3::new(5.0, 8.0, -20.0), color: Vec3::ONE, intensity: 40.0 },
        ];
        let sky = Sky { haze_distance: 2000.0, ..Sky::default() };
        let mut env = env(&lights, &sky);
        env.eye = Vec3::new(0.0, 6.0, 0.0);
        let material = WaterMaterial {
            flow_velocity: Vec2::new(0.5, 0.2),
            texture_scale: 4.0,
            texture_mix: 0.3,
            ..WaterMaterial::default()
        };
        let texture = Texture::procedural_water(material.color);
        let pattern = FoamPattern::procedural();
        let bottom = FlatBottom { height: -3.0, albedo: Vec3::new(0.8, 0.7, 0.5) };
        let look = WaterLook::new(&material, &bottom, Some(&texture), 1.25).with_foam(Some(&pattern));
        // A deterministic scatter of points from 1 m to 2 km away, some tilted past the eye.
        let points: Vec<SurfaceVarying> = (0..203u32)
            .map(|k| {
                let h = |s: u32| {
                    ((k.wrapping_mul(2_654_435_761) ^ s).wrapping_mul(2_246_822_519) >> 8) as f32 / 16_777_216.0
                };
                let distance = 1.0 + 2000.0 * h(1) * h(1);
                let angle = std::f32::consts::TAU * h(2);
                SurfaceVarying {
                    position: Vec3::new(distance * angle.cos(), 2.0 * h(3) - 1.0, distance * angle.sin()),
                    normal: Vec3::new(h(4) - 0.5, 0.3 + h(5), h(6) - 0.5) * (0.5 + h(7)),
                    foam: if k % 4 == 0 { 0.0 } else { h(8) },
                    unresolved: if k % 3 == 0 { 0.0 } else { 0.05 * h(9) },
                }
            })
            .collect();
        for lobe in [Lobe::BlinnPhong, Lobe::Phong] {
            let shade = |isa: Isa, n: usize| {
                let mut out = vec![Vec3::ZERO; n];
                shade_water_run_with(isa, &env, &look, lobe, &&points[..n], &mut out);
                out.iter().flat_map(|c| c.to_array().map(f32::to_bits)).collect::<Vec<_>>()
            };
            for n in [1, 64, 203] {
                let portable = shade(Isa::Portable, n);
                for isa in Isa::ALL.into_iter().filter(|isa| isa.is_available()) {
                    assert_eq!(shade(isa, n), portable, "{isa:?}, {n} points, {lobe:?}");
                }
            }
        }
    }

    /// Streaks draw the foam pattern out along the wind: with the wind along +z and a ratio of 4
    /// the pattern at (x, z) is the round pattern at (z / 2, -2 x), a quarter turn with the axis
    /// along the wind stretched twice and the one across squeezed twice (so the cells keep their
    /// area and the foam its coverage); no wind, or a ratio of 1, leaves it round.
    #[test]
    fn foam_streaks_draw_the_pattern_out_along_the_wind() {
        let lights = [Light::Directional { direction: Vec3::new(0.0, -1.0, 0.0), color: Vec3::ONE, intensity: 1.0 }];
        let sky = Sky::default();
        let env = env(&lights, &sky);
        // A 4 m tile: a quarter tile a metre, and the square roots of 4 exact, so both lookups
        // land on the same texels bit for bit.
        let material = WaterMaterial { foam_scale: 4.0, ..WaterMaterial::default() };
        let pattern = FoamPattern::procedural();
        let round = WaterLook::new(&material, &NoBottom, None, 0.0).with_foam(Some(&pattern));
        let streaked = round.with_foam_streaks(Some(Vec2::new(0.0, 3.0)), 4.0);
        let cover = |look: &WaterLook, x: f32, z: f32| {
            let p = Vec3Lanes::splat(Vec3::new(x, 0.0, z));
            foam_cover_lanes(&env, look, p, Lanes::splat(1.0), Lanes::splat(0.3)).0[0]
        };
        let (mut differ, mut foamy) = (0, 0);
        for i in -40..40 {
            for j in -40..40 {
                // At full detail: the look has no pixel angle, so nothing is filtered.
                let (x, z) = (i as f32 * 0.375, j as f32 * 0.375);
                let c = cover(&streaked, x, z);
                assert_eq!(c, cover(&round, z / 2.0, -2.0 * x), "at ({x}, {z})");
                differ += usize::from(c != cover(&round, x, z));
                foamy += usize::from(c > 0.5);
            }
        }
        assert!(differ > 1000 && foamy > 100, "the streaks change the pattern: {differ} differ, {foamy} foamy");
        for unstreaked in [round.with_foam_streaks(None, 4.0), round.with_foam_streaks(Some(Vec2::X), 1.0)] {
            assert!(unstreaked.foam_streaks.is_none());
            assert_eq!(cover(&unstreaked, 1.3, -2.7), cover(&round, 1.3, -2.7));
        }
    }

    /// Foam gathers on the crests: with the sea's height spread σ, a point σ above the water at
    /// rest shows e^(2a) = 20 times the foam of a point σ below it (a = 1.5), and over a Gaussian
    /// sea the weight averages to 1, so the coverage the model reports is kept; a spread that is
    /// not positive gathers nothing.
    #[test]
    fn foam_gathers_on_the_crests_and_keeps_its_coverage() {
        let material = WaterMaterial::default();
        let (rest, sigma) = (2.0f32, 0.8f32);
        let look = WaterLook::new(&material, &NoBottom, None, 0.0).with_foam_crests(rest, sigma);
        let cover = |y: f32| on_crests_lanes(&look, Vec3Lanes::splat(Vec3::new(0.0, y, 0.0)), Lanes::splat(0.01)).0[0];
        let ratio = cover(rest + sigma) / cover(rest - sigma);
        assert!((ratio / (2.0 * FOAM_CREST_CONTRAST).exp() - 1.0).abs() < 0.02, "crest over trough {ratio}");
        // The mean over a Gaussian sea, by the midpoint rule over ±6 σ.
        let steps = 2400;
        let mut mean = 0.0f64;
        for i in 0..steps {
            let z = -6.0 + 12.0 * (i as f64 + 0.5) / steps as f64;
            let density = (-0.5 * z * z).exp() / (2.0 * std::f64::consts::PI).sqrt();
            mean += f64::from(cover(rest + sigma * z as f32)) * density * 12.0 / steps as f64;
        }
        assert!((mean / 0.01 - 1.0).abs() < 0.02, "mean foam {mean} for a coverage of 0.01");
        for flat in [0.0, -1.0, f32::NAN] {
            assert!(WaterLook::new(&material, &NoBottom, None, 0.0).with_foam_crests(rest, flat).foam_crests.is_none());
        }
    }
}
