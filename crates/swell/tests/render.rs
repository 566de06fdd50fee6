//! The whole renderer: every shading model, overlays and supersampling give bit-identical images on
//! 1, 2 and 3 threads, and shading models differ where they should.

use swell::render::Renderer;
use swell::scene::{preset, World};
use swell::shading::Shading;

fn render(shading: Shading, threads: usize) -> Vec<[u32; 3]> {
    let mut scene = preset("sea").unwrap();
    scene.render.width = 200;
    scene.render.height = 120;
    scene.render.supersample = 2;
    scene.render.wireframe = shading == Shading::Flat;
    scene.render.normals = shading == Shading::Gouraud;
    let w = scene.water.as_mut().unwrap();
    w.surface.cells = [64, 64];
    w.material.shading = shading;
    w.material.bottom_depth = Some(4.0);
    w.material.texture = Some("procedural".into());
    let mut world = World::new(scene).unwrap();
    world.update(2.0).unwrap();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| Renderer::new().render(&world).color.iter().map(|c| c.to_array().map(f32::to_bits)).collect())
}

#[test]
fn every_shading_model_is_bit_identical_on_one_two_and_three_threads() {
    let mut images = Vec::new();
    for shading in [Shading::Flat, Shading::Gouraud, Shading::Phong, Shading::BlinnPhong] {
        let one = render(shading, 1);
        for n in [2, 3] {
            assert!(one == render(shading, n), "{shading:?} differs on {n} threads");
        }
        assert!(one.iter().flatten().all(|&b| f32::from_bits(b).is_finite()), "{shading:?} has non-finite pixels");
        images.push(one);
    }
    for i in 0..images.len() {
        for j in i + 1..images.len() {
            assert!(images[i] != images[j], "shading models {i} and {j} render the same image");
        }
    }
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
