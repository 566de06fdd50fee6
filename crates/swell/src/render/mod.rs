//! Scene + settings -> framebuffer. One file per pass, drawn in order into the same z-buffer, every
//! lit one through the one shaded-draw path ([`shaded_draw`]):
//! [`sky_pass`] clears the depth, [`terrain_pass`] draws the terrain, [`far_land_pass`] the land
//! beyond it to the horizon, [`body_pass`] the floating bodies, [`reflection_pass`] draws the terrain
//! mirrored into its own image for the water to reflect, [`water_pass`] draws the water surface,
//! [`sky_pass`] fills what is left with the sky, [`overlay_pass`] draws the wireframe and normals
//! when asked for. Unbounded water (issue 17) is drawn from the camera-following rings of
//! [`sea_lod`] by the same [`water_pass`], then [`far_field_pass`] carries the sea from the rings'
//! edge to the horizon before the sky fills the rest.

mod body_pass;
mod far_field_pass;
mod far_land_pass;
mod mesh_pass;
// issue 10: the OBJ comparison mode's camera/light files, read in the library so they can be fuzzed.
mod mesh_view_json;
mod overlay_pass;
mod reflection_pass;
mod render_stages;
mod sea_lod;
mod shaded_draw;
mod sky_pass;
mod terrain_pass;
mod water_pass;

use crate::raster::Framebuffer;
use crate::scene::{Camera, WaterExtent};
use crate::shading::{Environment, ReflectionMap};
use crate::world::{TerrainBody, WaterBody, World};

pub use mesh_pass::{MeshLight, MeshRenderer};
pub use mesh_view_json::{parse_camera_json, parse_light_json, MeshView, MAX_VIEW_JSON_BYTES};
pub use render_stages::RenderStages;

use render_stages::Stopwatch;
use shaded_draw::ShadedDraw;

/// Renders [`World`]s, keeping its buffers from frame to frame so steady-state frames do not
/// allocate.
#[derive(Default)]
pub struct Renderer {
    framebuffer: Option<Framebuffer>,
    /// The supersampled frame, when `[render] supersample` > 1.
    supersampled: Option<Framebuffer>,
    /// The terrain's vertex buffers and colours, which its reflection draws again.
    terrain_draw: shaded_draw::ShadedDraw,
    /// The vertex buffers of the land beyond the terrain's field.
    far_land_draw: shaded_draw::ShadedDraw,
    /// The water's vertex buffers.
    water_draw: shaded_draw::ShadedDraw,
    /// The floating bodies' triangles at this frame's poses, and their vertex buffers.
    body_meshes: body_pass::BodyMeshes,
    body_draw: shaded_draw::ShadedDraw,
    /// The mirrored terrain the water reflects.
    reflection_scratch: reflection_pass::Scratch,
    /// The unbounded sea's rings as this image filters them (the rings are the world's).
    sea: sea_lod::SeaLod,
    /// The sky ready to look up, rebuilt when `[sky]` changes (a Preetham sky is tabulated).
    sky: Option<crate::shading::SkyRadiance>,
    /// The scene's lights as the sky drives them (`[sky] sun_drives_light`).
    lights: Vec<crate::scene::Light>,
    /// Where the last frame's time went.
    stages: RenderStages,
}

impl Renderer {
    /// A renderer with no buffers yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Wall time of each pass of the last render.
    pub fn last_stages(&self) -> RenderStages {
        self.stages
    }

    /// Renders `world` at its scene's `[render]` size.
    pub fn render(&mut self, world: &World) -> &Framebuffer {
        let r = world.scene.render;
        self.render_size(world, r.width, r.height)
    }

    /// Renders `world` at `width` x `height` pixels (each at least 1, checked by the caller against
    /// [`crate::scene::MAX_IMAGE_SIDE`]), supersampled per the scene's `[render] supersample`.
    pub fn render_size(&mut self, world: &World, width: u32, height: u32) -> &Framebuffer {
        let ss = world.scene.render.supersample.max(1);
        let target = if ss > 1 { &mut self.supersampled } else { &mut self.framebuffer };
        let (w, h) = (width * ss, height * ss);
        let fb = target.get_or_insert_with(|| Framebuffer::new(w, h));
        if (fb.width(), fb.height()) != (w, h) {
            fb.resize(w, h);
        }
        let scene = &world.scene;
        let sky = self.sky.get_or_insert_with(|| crate::shading::SkyRadiance::new(&scene.sky));
        sky.update(&scene.sky);
        scene.sky.drive_lights(&scene.lights, &mut self.lights);
        let frame = FrameContext {
            env: Environment {
                lights: &self.lights,
                ambient: scene.render.ambient,
                sky,
                sun: scene.sky.sun(&self.lights),
                eye: scene.camera.eye,
                time: world.time(),
            },
            clip_from_world: scene.camera.clip_from_world(width as f32 / height as f32),
            camera: &scene.camera,
            size: (w, h),
        };
        let mut stages = RenderStages::default();
        let mut watch = Stopwatch::start();
        sky_pass::clear_depth(fb);
        watch.lap(&mut stages.sky);
        let mut reflection = None;
        if let Some(terrain) = &world.terrain {
            let draws = (&mut self.terrain_draw, &mut self.far_land_draw, &mut self.reflection_scratch);
            reflection = draw_terrain(fb, &frame, world, terrain, draws);
            watch.lap(&mut stages.terrain);
        }
        if !world.body_poses().is_empty() {
            body_pass::draw(fb, &frame, world, &mut self.body_meshes, &mut self.body_draw);
            watch.lap(&mut stages.terrain);
        }
        if let Some(water) = &world.water {
            let buffers = (&mut self.sea, &mut self.water_draw);
            draw_water(fb, &frame, world, water, buffers, reflection.as_ref(), (&mut stages, &mut watch));
        }
        // After every geometry pass: the sky fills only what they left at the far plane.
        sky_pass::draw(fb, &scene.camera, frame.env.sky, frame.env.sun.as_ref());
        watch.lap(&mut stages.sky);
        if let Some(water) = &world.water {
            let scale = water.placement.scale;
            overlay_pass::draw(fb, &frame, &water.surface, scale, scene.render.wireframe, scene.render.normals);
        }
        if ss > 1 {
            let hi = self.supersampled.as_ref().expect("rendered above");
            let out = self.framebuffer.get_or_insert_with(|| Framebuffer::new(width, height));
            out.downsample_from(hi, ss);
        }
        watch.lap(&mut stages.finish);
        self.stages = stages;
        self.framebuffer.as_ref().expect("rendered above")
    }
}

/// Draws `terrain`, the land beyond it and, for a finite water patch in the scene, the terrain's
/// mirror image, which it returns for the water to reflect.
fn draw_terrain<'a>(
    fb: &mut Framebuffer,
    frame: &FrameContext,
    world: &World,
    terrain: &TerrainBody,
    (terrain_draw, far_land_draw, scratch): (&mut ShadedDraw, &mut ShadedDraw, &'a mut reflection_pass::Scratch),
) -> Option<ReflectionMap<'a>> {
    terrain_pass::draw(fb, frame, terrain, terrain_draw);
    let sea = world.water.as_ref().is_some_and(|w| w.extent == WaterExtent::Unbounded);
    far_land_pass::draw(fb, frame, terrain, far_land_draw, sea);
    let water = world.water.as_ref()?;
    let water_box =
        (!sea).then(|| reflection_pass::water_screen_box(water.surface.positions(), frame.clip_from_world)).flatten();
    reflection_pass::draw(scratch, frame, terrain, terrain_draw, water_box)
}

/// Draws `water` as the world holds it (the patch, or the rings with the footprint filter of this
/// image, then the far field to the horizon), timing each stage.
fn draw_water(
    fb: &mut Framebuffer,
    frame: &FrameContext,
    world: &World,
    water: &WaterBody,
    (sea_lod, water_draw): (&mut sea_lod::SeaLod, &mut ShadedDraw),
    reflection: Option<&ReflectionMap>,
    (stages, watch): (&mut RenderStages, &mut Stopwatch),
) {
    let surface = &water.surface;
    let mesh = match surface.rings() {
        // Only what depends on the image is done here: the footprint filter.
        Some(rings) => {
            let rows = frame.size.1;
            let sea = sea_lod.filter(rings, &water.slopes, water.placement.scale, frame.camera, rows);
            watch.lap(&mut stages.sea_filter);
            shaded_draw::ShadedMesh {
                positions: &rings.positions,
                normals: sea.normals,
                foam: surface.foam(),
                unresolved: Some(sea.unresolved),
                indices: &rings.indices,
            }
        }
        None => shaded_draw::ShadedMesh {
            positions: surface.positions(),
            normals: surface.normals(),
            foam: surface.foam(),
            unresolved: None,
            indices: surface.indices(),
        },
    };
    water_pass::draw(fb, frame, water, mesh, water_draw, world.terrain.as_ref(), reflection);
    watch.lap(&mut stages.water);
    if water.extent == WaterExtent::Unbounded {
        let lobe = crate::shading::Lobe::of(water.material.shading);
        far_field_pass::draw(fb, frame, frame.camera, water, &water.slopes, lobe);
        watch.lap(&mut stages.far_field);
    }
}

/// What every pass of one frame shares.
pub(crate) struct FrameContext<'a> {
    /// Lights, ambient, sky and eye.
    pub env: Environment<'a>,
    /// World to clip transform of the frame's camera and aspect ratio.
    pub clip_from_world: glam::Mat4,
    /// The frame's camera.
    pub camera: &'a Camera,
    /// Pixels drawn, width x height (the supersampled size when supersampling).
    pub size: (u32, u32),
}
