//! The whole renderer: every shading model, overlays and supersampling give bit-identical images on
//! 1, 2 and 3 threads, and shading models differ where they should.

use swell::render::Renderer;
use swell::scene::preset;
use swell::scene::{GlitterModel, Shading};
use swell::world::World;

fn render(shading: Shading, glitter: GlitterModel, threads: usize) -> Vec<[u32; 3]> {
    let mut scene = preset("sea").unwrap();
    scene.render.width = 200;
    scene.render.height = 120;
    scene.render.supersample = 2;
    scene.render.wireframe = shading == Shading::Flat;
    scene.render.normals = shading == Shading::Gouraud;
    let w = scene.water.as_mut().unwrap();
    w.surface.cells = [64, 64];
    w.material.shading = shading;
    w.material.glitter = glitter;
    w.material.bottom_depth = Some(4.0);
    w.material.texture = Some("procedural".into());
    let mut world = World::new(scene).unwrap();
    world.update(2.0).unwrap();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| Renderer::new().render(&world).color.iter().map(|c| c.to_array().map(f32::to_bits)).collect())
}

#[test]
fn every_shading_model_is_bit_identical_on_one_two_and_three_threads() {
    for glitter in GlitterModel::ALL.iter().copied() {
        let mut images = Vec::new();
        for shading in [Shading::Flat, Shading::Gouraud, Shading::Phong, Shading::BlinnPhong] {
            let one = render(shading, glitter, 1);
            for n in [2, 3] {
                assert!(one == render(shading, glitter, n), "{shading:?}, {glitter:?} differs on {n} threads");
            }
            let finite = one.iter().flatten().all(|&b| f32::from_bits(b).is_finite());
            assert!(finite, "{shading:?}, {glitter:?} has non-finite pixels");
            images.push(one);
        }
        // Phong's and Blinn's lobes differ only where the glitter is a lobe; through the slope
        // distribution both per-pixel models draw the same water.
        let per_pixel_alike = glitter == GlitterModel::CoxMunk;
        for i in 0..images.len() {
            for j in i + 1..images.len() {
                if per_pixel_alike && (i, j) == (2, 3) {
                    assert!(images[i] == images[j], "{glitter:?}: phong and blinn-phong differ");
                } else {
                    assert!(images[i] != images[j], "{glitter:?}: shading models {i} and {j} render the same image");
                }
            }
        }
    }
}

/// The viewer's frame, RGBA8 bytes included (the encoding table is kept between frames and read
/// eight channels at a time where the CPU has AVX2): identical on 1 and 2 threads, frame after
/// frame, and following a change of exposure.
#[test]
fn encoded_ocean_frames_are_byte_identical_on_one_and_two_threads() {
    let frames = |threads: usize| {
        let mut world = World::new(preset("ocean").unwrap()).unwrap();
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let mut renderer = Renderer::new();
            let mut frames = Vec::new();
            for (k, exposure) in [1.0, 1.0, 1.6].into_iter().enumerate() {
                world.update(2.0 + k as f64 / 30.0).unwrap();
                let mut rgba = Vec::new();
                let encoding = world.scene.render.display_encoding();
                renderer.render_size(&world, 240, 135).encode_rgba8(&encoding.with_exposure(exposure), &mut rgba);
                frames.push(rgba);
            }
            frames
        })
    };
    let one = frames(1);
    assert!(one == frames(2), "the encoded frames differ on 2 threads");
    assert!(one[0] != one[1] && one[1] != one[2], "the frames should move and brighten");
}

#[test]
fn a_reused_renderer_draws_the_same_frame_as_a_fresh_one() {
    let mut scene = preset("sea").unwrap();
    scene.render.width = 96;
    scene.render.height = 64;
    scene.water.as_mut().unwrap().surface.cells = [32, 32];
    let mut world = World::new(scene).unwrap();
    let mut reused = Renderer::new();
    world.update(0.0).unwrap();
    reused.render(&world);
    world.update(3.0).unwrap();
    let again = reused.render(&world).color.clone();
    let fresh = Renderer::new().render(&world).color.clone();
    assert!(again == fresh, "state from the previous frame leaked into the next");
}

/// A calm lake at the foot of a slope rising out of it, seen from 2 m above the water.
const LAKE_UNDER_A_HILL: &str = r#"
version = 1

[camera]
eye = [-100.0, 2.0, 0.0]
target = [0.0, 0.0, 0.0]
fov_y_deg = 40.0
near = 0.5
far = 2000.0

[[light]]
type = "directional"
direction = [0.3, -0.8, 0.2]
color = [1.0, 1.0, 1.0]
intensity = 1.0

[render]
width = 320
height = 200

[terrain]
generator = "slope"
size = 129
extent = [200.0, 200.0]
start_height = -40.0
end_height = 40.0

[terrain.material]
shading = "gouraud"

[water]
model = "gerstner"
size = [200.0, 200.0]
cells = [64, 64]

[water.material]
shading = "phong"
specular = 0.0
"#;

/// Paper 003 §2: calm water mirrors the terrain above it. The slope rises through the water at
/// x = 0; its point P = (40, 16, 0) shows in the image, and the water at the pixel of P mirrored
/// about the waterline, (40, -16, 0), must show P's colour weighted by Fresnel, where the sky
/// alone would give the sky's.
#[test]
fn calm_water_mirrors_the_hill_above_it_weighted_by_fresnel() {
    use glam::{Vec3, Vec4};
    use swell::scene::Scene;
    use swell::shading::{fresnel_dielectric, shade_water, Environment, Lobe, WaterLook};

    let scene = Scene::from_toml(LAKE_UNDER_A_HILL, "test").unwrap();
    let (width, height) = (scene.render.width, scene.render.height);
    let mut world = World::new(scene).unwrap();
    world.update(0.0).unwrap();
    let image = Renderer::new().render(&world).color.clone();
    let scene = &world.scene;
    let clip_from_world = scene.camera.clip_from_world(width as f32 / height as f32);
    let pixel_of = |q: Vec3| {
        let c = clip_from_world * Vec4::from((q, 1.0));
        let x = ((0.5 * c.x / c.w + 0.5) * width as f32) as usize;
        let y = ((0.5 - 0.5 * c.y / c.w) * height as f32) as usize;
        (x, y)
    };
    let (hx, hy) = pixel_of(Vec3::new(40.0, 16.0, 0.0));
    let (mx, my) = pixel_of(Vec3::new(40.0, -16.0, 0.0));
    assert_eq!(hx, mx);
    let hill = image[hy * width as usize + hx];
    let mirrored = image[my * width as usize + mx];

    // The water point seen at the mirror pixel's centre: the pixel's view ray meets y = 0.
    let world_from_clip = clip_from_world.inverse();
    let ndc = |x: usize, y: usize| {
        (2.0 * (x as f32 + 0.5) / width as f32 - 1.0, 1.0 - 2.0 * (y as f32 + 0.5) / height as f32)
    };
    let (nx, ny) = ndc(mx, my);
    let far = world_from_clip.project_point3(Vec3::new(nx, ny, 1.0));
    let eye = scene.camera.eye;
    let p = eye + (far - eye) * (eye.y / (eye.y - far.y));
    let env = Environment {
        lights: &scene.lights,
        ambient: scene.render.ambient,
        sky: &swell::shading::SkyRadiance::new(&scene.sky),
        sun: scene.sky.sun(&scene.lights),
        eye,
        time: world.time(),
    };
    let water = world.water.as_ref().unwrap();
    let terrain = world.terrain.as_ref().unwrap();
    let look = WaterLook::new(&water.material, terrain, None, world.time());
    // What the water would show reflecting only the sky, and the same with the hill in its place.
    let sky_only = shade_water(&env, &look, Lobe::Phong, p, Vec3::Y, 0.0);
    let to_eye = (eye - p).normalize();
    let f = fresnel_dielectric(to_eye.y, water.material.refractive_index);
    let sky = env.sky_radiance(2.0 * to_eye.y * Vec3::Y - to_eye);
    let with_hill = sky_only + f * (hill - sky);
    assert!(f > 0.3, "a grazing view reflects much of the light: F = {f}");
    assert!((hill - sky).abs().max_element() > 0.2, "the hill {hill} must differ from the sky {sky}");
    let off_hill = (mirrored - with_hill).abs().max_element();
    let off_sky = (mirrored - sky_only).abs().max_element();
    assert!(
        off_hill < 0.03 && off_hill * 5.0 < off_sky,
        "water {mirrored}: hill reflected {with_hill} (off {off_hill}), sky reflected {sky_only} (off {off_sky})"
    );
}

/// The reflection pass keeps the image bit-identical for any thread count, whichever model
/// shades the water (per face, per vertex or per pixel, each reading the reflection).
#[test]
fn terrain_reflections_are_bit_identical_on_one_and_two_threads() {
    let mut scene = swell::scene::Scene::from_toml(LAKE_UNDER_A_HILL, "test").unwrap();
    scene.render.width = 160;
    scene.render.height = 100;
    for shading in [Shading::Flat, Shading::Gouraud, Shading::BlinnPhong] {
        scene.water.as_mut().unwrap().material.shading = shading;
        let mut world = World::new(scene.clone()).unwrap();
        world.update(0.0).unwrap();
        let render = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| Renderer::new().render(&world).color.clone())
        };
        let one = render(1);
        assert!(one == render(2), "{shading:?} differs on 2 threads");
        assert!(one.iter().all(|c| c.is_finite()), "{shading:?} has non-finite pixels");
    }
}
