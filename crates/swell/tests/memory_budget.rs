//! Issue 21: a scene over the memory budget is refused before anything large is allocated, and a
//! scene within it builds each model once.
//!
//! A counting global allocator measures the peak of live heap bytes while the scene is read and
//! validated. It is this binary's own allocator, so the test runs alone in its process.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use swell::scene::Scene;
use swell::world::World;

/// The system allocator, counting live bytes and their peak.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Peak live bytes above the live bytes at the start, while `f` runs.
fn peak_while<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let base = LIVE.load(Ordering::Relaxed);
    PEAK.store(base, Ordering::Relaxed);
    let out = f();
    (out, PEAK.load(Ordering::Relaxed) - base)
}

/// Four 2048² FFT cascades (about 1.6 GB of spectra and fields), a 4096² water grid and an 8192²
/// image: each key in range, together over the 4 GiB budget.
const OVER_BUDGET: &str = "[water]\nmodel = 'fft'\ngrid = 2048\ncascades = 4\ncells = [4096, 4096]\n\
                           [render]\nwidth = 8192\nheight = 8192\n";

/// One test: the counters are global, and tests in one binary run in parallel threads.
#[test]
fn memory_is_checked_before_building_and_each_model_is_built_once() {
    an_over_budget_scene_is_refused_before_any_large_allocation();
    validating_builds_nothing_and_a_world_builds_each_model_once();
}

fn an_over_budget_scene_is_refused_before_any_large_allocation() {
    let scene: Scene = toml_scene("[water]\nmodel = 'fft'\ngrid = 2048\ncascades = 4\n");
    assert!(scene.estimate_bytes() > 1 << 30, "four 2048² cascades are counted: {}", scene.estimate_bytes());

    let (result, peak) = peak_while(|| Scene::from_toml(OVER_BUDGET, "big.toml"));
    let e = result.expect_err("over the budget").to_string();
    assert!(e.starts_with("big.toml: scene (water grid + terrain + framebuffer): needs about"), "{e}");
    assert!(e.contains("over the memory budget of 4096 MiB"), "{e}");
    // Parsing and validating a few hundred bytes of TOML: well under a megabyte, where building
    // the first cascade alone would take 400 MB.
    eprintln!("refusing the over-budget scene peaked at {peak} bytes of heap");
    assert!(peak < 1 << 20, "peak {peak} bytes while refusing");
}

fn validating_builds_nothing_and_a_world_builds_each_model_once() {
    // A scene within the budget whose FFT ocean takes tens of megabytes once built.
    let text =
        "[water]\nmodel = 'fft'\ngrid = 512\ncascades = 2\ncells = [16, 16]\n[render]\nwidth = 64\nheight = 64\n";
    let (scene, peak) = peak_while(|| Scene::from_toml(text, "t").unwrap());
    assert!(peak < 1 << 20, "validation allocated {peak} bytes");
    let model_bytes = scene.water.as_ref().unwrap().model.estimate_bytes() as usize;
    let (world, peak) = peak_while(|| World::new(scene).unwrap());
    eprintln!("World::new peaked at {peak} bytes; the model's estimate is {model_bytes}");
    // One build: within the estimate's factor of 1.5 of one model, not two or three of them.
    assert!(peak < model_bytes * 3 / 2 + (8 << 20), "World::new peaked at {peak} bytes, one model is ~{model_bytes}");
    assert!(peak > model_bytes / 2, "the estimate ({model_bytes}) is within a factor of 2 of the build ({peak})");
    drop(world);
}

fn toml_scene(text: &str) -> Scene {
    Scene::from_toml(text, "t").unwrap()
}
