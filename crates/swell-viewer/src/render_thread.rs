//! The render thread: simulates and renders frame N+1 while the UI thread lets egui and OpenGL
//! paint frame N.
//!
//! On two cores the UI thread's paint (egui's panel through Mesa's llvmpipe) and swell's render
//! each take a large share of a frame; done one after the other they add up, overlapped they do
//! not. The thread owns the [`Renderer`], its rayon pool and its own [`World`], built from the
//! scene the UI sends whenever the editor's revision changes: rebuilt when `[water]` or
//! `[terrain]` changed (as the editor does), otherwise only its scene is swapped. Clicks on the
//! water are forwarded as [`Disturbance`]s, so the spring mesh's state lives here, and as
//! [`BodyDrop`]s, which add a body to this world; the frame hands back the specs it added (for the
//! editor's scene) and every body's place ([`LiveBody`]). The push the keys give a body comes with
//! every request ([`Push`]). The UI sees each frame one frame late.

use std::sync::mpsc::{channel, Receiver, Sender};
use std::thread::JoinHandle;
use std::time::Instant;

use swell::render::Renderer;
use swell::scene::{Scene, MAX_IMAGE_SIDE};
use swell::world::World;
use swell::{Error, Result};

use crate::body_control::{apply_push, drop_into, live_bodies, BodyDrop, LiveBody, Push};
use crate::frame::{FrameKey, StageTimes};

/// A dent dropped on the water at world (x, z): `depth` and `radius` in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disturbance {
    /// World x, m.
    pub x: f32,
    /// World z, m.
    pub z: f32,
    /// Depth of the dent, m.
    pub depth: f32,
    /// Radius of the dent, m.
    pub radius: f32,
}

/// One frame to make.
pub struct Request {
    /// What to render; `key.size` is clamped to [1, `MAX_IMAGE_SIDE`] per side.
    pub key: FrameKey,
    /// The editor's scene, when its revision changed since the last request.
    pub scene: Option<Box<Scene>>,
    /// Clicks on the water since the last request, applied before the update.
    pub disturbances: Vec<Disturbance>,
    /// Bodies dropped since the last request, added before the update.
    pub drops: Vec<BodyDrop>,
    /// The push the keys give a body during this frame's update (none: every push taken away).
    pub push: Option<Push>,
    /// Worker threads of the render (`render.threads`, 0 = one per core).
    pub threads: u32,
    /// A buffer to encode into (recycled: the frame shown before the last one).
    pub buffer: Vec<u8>,
}

/// A finished frame.
pub struct Frame {
    /// The request's key.
    pub key: FrameKey,
    /// RGBA8, rows top first, `size[0] * size[1] * 4` bytes.
    pub pixels: Vec<u8>,
    /// Its size in pixels (the key's, clamped).
    pub size: [u32; 2],
    /// Simulation and render times (upload is the UI's).
    pub times: StageTimes,
    /// Every floating body at the frame's time, in scene order.
    pub bodies: Vec<LiveBody>,
    /// What became of each of the request's drops, in order: the body's spec as the world's scene
    /// now holds it, or why it was refused.
    pub dropped: Vec<std::result::Result<swell::body::BodySpec, String>>,
}

/// What a frame found besides its pixels.
struct FrameReport {
    size: [u32; 2],
    times: StageTimes,
    bodies: Vec<LiveBody>,
    dropped: Vec<std::result::Result<swell::body::BodySpec, String>>,
}

/// The answer to a request: the frame, or the error with the request's buffer back.
pub type Outcome = std::result::Result<Frame, (Error, Vec<u8>)>;

/// The thread and its two channels; dropping it stops the thread after its current frame.
pub struct RenderThread {
    requests: Option<Sender<Request>>,
    frames: Receiver<Outcome>,
    handle: Option<JoinHandle<()>>,
}

impl RenderThread {
    /// Starts the thread; `on_frame` is called after each finished frame (to wake the UI).
    pub fn start(on_frame: impl Fn() + Send + 'static) -> Result<Self> {
        let (requests, inbox) = channel::<Request>();
        let (outbox, frames) = channel::<Outcome>();
        let handle = std::thread::Builder::new()
            .name("swell-render".into())
            .spawn(move || {
                let mut worker = Worker::default();
                for request in inbox {
                    if outbox.send(worker.frame(request)).is_err() {
                        break;
                    }
                    on_frame();
                }
            })
            .map_err(|e| Error::invalid("render thread", format!("cannot start it: {e}")))?;
        Ok(Self { requests: Some(requests), frames, handle: Some(handle) })
    }

    /// Sends a request; false if the thread has stopped.
    pub fn send(&self, request: Request) -> bool {
        self.requests.as_ref().is_some_and(|r| r.send(request).is_ok())
    }

    /// Waits for the answer to the oldest request; None if the thread has stopped.
    pub fn receive(&self) -> Option<Outcome> {
        self.frames.recv().ok()
    }
}

impl Drop for RenderThread {
    fn drop(&mut self) {
        self.requests = None;
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
    }
}

/// What lives on the render thread.
#[derive(Default)]
struct Worker {
    renderer: Renderer,
    world: Option<World>,
    pool: Option<(u32, rayon::ThreadPool)>,
}

impl Worker {
    fn frame(&mut self, mut r: Request) -> Outcome {
        let mut buffer = std::mem::take(&mut r.buffer);
        match self.frame_into(r, &mut buffer) {
            Ok((key, f)) => {
                Ok(Frame { key, pixels: buffer, size: f.size, times: f.times, bodies: f.bodies, dropped: f.dropped })
            }
            Err(e) => Err((e, buffer)),
        }
    }

    fn frame_into(&mut self, r: Request, rgba: &mut Vec<u8>) -> Result<(FrameKey, FrameReport)> {
        let Request { key, scene, disturbances, drops, push, threads, buffer: _ } = r;
        let [w, h] = key.size.map(|s| s.clamp(1, MAX_IMAGE_SIDE));
        if self.pool.as_ref().map(|(n, _)| *n) != Some(threads) {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads as usize)
                .thread_name(|i| format!("swell-render-{i}"))
                .build()
                .map_err(|e| Error::invalid("render.threads", format!("cannot start {threads} threads: {e}")))?;
            self.pool = Some((threads, pool));
        }
        let pool = &self.pool.as_ref().expect("built above").1;
        let (world_slot, renderer) = (&mut self.world, &mut self.renderer);
        let mut times = StageTimes::default();
        let mut dropped = Vec::with_capacity(drops.len());
        let mut bodies = Vec::new();
        pool.install(|| -> Result<()> {
            let t0 = Instant::now();
            if let Some(scene) = scene {
                follow(world_slot, *scene)?;
            }
            let world = world_slot.as_mut().ok_or_else(|| Error::invalid("view", "no scene received yet"))?;
            for d in &disturbances {
                world.disturb_water(d.x, d.z, d.depth, d.radius)?;
            }
            // Added after the scene is followed, so the scene sent does not hold them yet and the
            // world is not rebuilt without them; the editor then appends the same specs.
            for d in &drops {
                dropped.push(drop_into(world, d).map_err(|e| swell::error::printable(&e.to_string())));
            }
            apply_push(world, push);
            world.update(key.time)?;
            bodies = live_bodies(world);
            let t1 = Instant::now();
            let r = world.scene.render;
            renderer.render_size(world, w, h).encode_rgba8(&r.display_encoding(), rgba);
            times.simulate = t1 - t0;
            times.render = t1.elapsed();
            Ok(())
        })?;
        Ok((key, FrameReport { size: [w, h], times, bodies, dropped }))
    }
}

/// Makes `world` follow `scene`: rebuilt when the water or the terrain changed
/// ([`World::needs_rebuild_for`]), otherwise only the scene (camera, lights, sky, render settings)
/// swapped. A scene that fails to build leaves the previous world in place.
fn follow(world: &mut Option<World>, scene: Scene) -> Result<()> {
    match world {
        Some(w) if !w.needs_rebuild_for(&scene) => w.scene = scene,
        _ => *world = Some(World::new(scene)?),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use swell::scene::preset;

    const SIZE: [u32; 2] = [96, 54];

    fn request(scene: Option<&Scene>, revision: u64, time: f64, disturbances: Vec<Disturbance>) -> Request {
        Request {
            key: FrameKey { revision, time, size: SIZE },
            scene: scene.map(|s| Box::new(s.clone())),
            disturbances,
            drops: Vec::new(),
            push: None,
            threads: 2,
            buffer: Vec::new(),
        }
    }

    fn frame(t: &RenderThread, r: Request) -> Frame {
        assert!(t.send(r));
        t.receive().expect("the thread answers").unwrap_or_else(|(e, _)| panic!("{e}"))
    }

    /// What the UI thread would have rendered itself before the render thread existed.
    fn direct(scene: &Scene, time: f64, threads: usize) -> Vec<u8> {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let mut world = World::new(scene.clone()).unwrap();
            world.update(time).unwrap();
            let mut rgba = Vec::new();
            let r = scene.render;
            Renderer::new().render_size(&world, SIZE[0], SIZE[1]).encode_rgba8(&r.display_encoding(), &mut rgba);
            rgba
        })
    }

    #[test]
    fn frames_are_the_scenes_render_and_follow_scene_changes() {
        let t = RenderThread::start(|| {}).unwrap();
        let mut scene = preset("sea").unwrap();
        let f = frame(&t, request(Some(&scene), 0, 1.5, vec![]));
        assert_eq!(f.size, SIZE);
        assert_eq!(f.pixels, direct(&scene, 1.5, 1), "render thread and a direct 1-thread render differ");

        // A camera change (same water) swaps the scene in place; a water change rebuilds.
        scene.camera.eye.x += 5.0;
        let f = frame(&t, request(Some(&scene), 1, 2.0, vec![]));
        assert_eq!(f.pixels, direct(&scene, 2.0, 2));
        scene.water.as_mut().unwrap().surface.cells = [64, 64];
        let f = frame(&t, request(Some(&scene), 2, 2.0, vec![]));
        assert_eq!(f.pixels, direct(&scene, 2.0, 2));
        // No scene sent: the thread keeps the one it has.
        let f = frame(&t, request(None, 2, 2.5, vec![]));
        assert_eq!(f.pixels, direct(&scene, 2.5, 2));
    }

    #[test]
    fn forwarded_clicks_dent_the_spring_mesh_and_errors_return_the_buffer() {
        let t = RenderThread::start(|| {}).unwrap();
        let scene = preset("springs").unwrap();
        let calm = frame(&t, request(Some(&scene), 0, 0.5, vec![])).pixels;
        let d = Disturbance { x: 0.0, z: 0.0, depth: 0.5, radius: 2.0 };
        let dented = frame(&t, request(None, 1, 0.5, vec![d])).pixels;
        assert_ne!(calm, dented, "the dent changed nothing on screen");

        let bad = Disturbance { radius: -1.0, ..d };
        assert!(t.send(Request { buffer: vec![7; 12], ..request(None, 2, 0.5, vec![bad]) }));
        match t.receive().expect("the thread answers") {
            Err((_, buffer)) => assert_eq!(buffer, vec![7; 12]),
            Ok(_) => panic!("a negative radius was accepted"),
        }
    }

    #[test]
    fn a_drop_joins_the_thread_s_world_and_the_scene_holding_it_does_not_rebuild_it() {
        use crate::body_control::{BodyDrop, DropKind, Push};
        use crate::picking::Ray;
        let t = RenderThread::start(|| {}).unwrap();
        let mut scene = preset("sea").unwrap();
        scene.water.as_mut().unwrap().surface.cells = [32, 32];
        let f = frame(&t, request(Some(&scene), 0, 1.0, vec![]));
        assert!(f.bodies.is_empty() && f.dropped.is_empty());
        let eye = scene.camera.eye;
        let ray = Ray { origin: eye, direction: scene.camera.target - eye };
        let drop = BodyDrop { kind: DropKind::Crate, ray };
        let f = frame(&t, Request { drops: vec![drop], ..request(None, 0, 1.05, vec![]) });
        let spec = match &f.dropped[..] {
            [Ok(spec)] => spec.clone(),
            other => panic!("{other:?}"),
        };
        assert_eq!(f.bodies.len(), 1);
        assert!(f.bodies[0].position.y > spec.position.y - 0.05, "it only just started falling");
        // The editor's scene with the body, sent back: the world keeps the body's motion (a
        // rebuild would replay it from t = 0 to the same place, so push it first to tell).
        let pushed = Push { body: 0, direction: glam::Vec2::X };
        for time in [1.1, 1.3, 1.5, 1.7] {
            frame(&t, Request { push: Some(pushed), ..request(None, 0, time, vec![]) });
        }
        let before = frame(&t, request(None, 0, 1.8, vec![])).bodies[0];
        scene.bodies.push(spec);
        let after = frame(&t, request(Some(&scene), 1, 1.8, vec![])).bodies[0];
        assert_eq!(before, after, "the world was rebuilt: the push's effect is gone");
        let mut replayed = World::new(scene.clone()).unwrap();
        replayed.update(1.8).unwrap();
        let unpushed = replayed.body_poses()[0].position.as_vec3();
        assert!(after.position.x > unpushed.x + 0.05, "pushed {} vs replayed {}", after.position, unpushed);
    }
}
