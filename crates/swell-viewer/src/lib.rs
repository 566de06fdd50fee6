//! # swell-viewer: swell's CPU render live in a window, every scene parameter in a panel
//!
//! `swell view --preset sea` opens it. This is the only swell crate with window dependencies
//! (eframe/egui with the glow backend under X11); everything it shows is computed by the `swell`
//! library: [`swell::world::World::update`] moves the water and
//! [`swell::render::Renderer::render_size`] draws it on the CPU at the view's pixel size, on the
//! render thread, one frame ahead of the paint; the window only displays the image (a texture
//! blitted to the window).
//!
//! User documentation (keys, mouse, panel, files): `docs/viewer.md`.
//!
//! ## Layout
//!
//! | module | what |
//! |---|---|
//! | [`app`] | the eframe app: layout, keys, mouse, file requests, scripted exit |
//! | [`editor`] | draft scene (what the panel shows), last valid scene and its `World` |
//! | [`panels`] | one module per scene section or water model |
//! | [`camera_control`] | orbit, zoom and pan as pure functions on `Camera` |
//! | [`live_view`] | one frame in flight: collect the last, request the next |
//! | [`render_thread`] | simulates and renders the next frame while the UI paints this one |
//! | [`gl_view`] | upload and show the frame (one GL blit, no egui shader) |
//! | [`picking`] | a click in the view to a point on the water (spring mesh disturbances, drops) |
//! | [`body_control`] | floating bodies: a click's drop, the keys' push, what a frame reports |
//! | [`clock`], [`frame_stats`], [`files`] | time, timings, scene and PNG files |
//!
//! ## How a parameter change flows
//!
//! 1. A panel's `show` writes the new value into [`editor::SceneEditor::draft`] and returns `true`.
//! 2. [`editor::SceneEditor::apply`] validates the whole draft with the library's own checks. If it
//!    is valid it becomes the scene: a changed `[water]` rebuilds the world (models and meshes),
//!    anything else is swapped in place. If not, the previous scene keeps running, the draft keeps
//!    the refused value, and the error (key, value, valid range) is shown at the top of the panel
//!    with a "Revert" button.
//! 3. The next UI frame sees the new [`editor::SceneEditor::revision`] and sends the committed
//!    scene to the [`render_thread`], whose own world follows it (rebuilt only when `[water]` or
//!    `[terrain]` changed); the frame made from it is shown one UI frame later.
//!
//! The mouse moves the camera through [`editor::SceneEditor::set_camera`], which updates both the
//! draft and the scene, so the camera keeps working while a draft is refused.
//!
//! Floating bodies ([`body_control`]): a click that drops a crate does not edit the draft. The
//! drop travels with the next frame's request to the render thread, whose world adds the body
//! (`World::add_body`, released at the next body step); the frame brings the spec back and
//! [`editor::SceneEditor::body_dropped`] appends it to the editor's scenes, so the scene sent next
//! holds what the world holds and the world is not rebuilt (a rebuild replays the bodies from
//! t = 0). The keys' push goes with every request and is not part of the scene. Body keys edited
//! in the panel go through the draft like any key; in a scene with bodies a dragged value is
//! committed when the drag ends ([`panels::commit_now`]).
//!
//! ## Adding a panel for a water model
//!
//! Follow `panels/fft_ocean.rs` or `panels/river.rs` (or `panels/tessendorf.rs` for a list of waves,
//! which implements `panels::wave_list::ListedWave` for its wave type):
//!
//! 1. Create `panels/<model>.rs` with
//!    `pub fn show(ui: &mut Ui, spec: &mut <Model>Spec, form: &mut <Model>Form) -> bool`, using the
//!    field editors of [`panels::fields`] (one `label | editor` row each, no clamping: validation
//!    refuses bad values with the reason). Put edit operations that are more than setting a field
//!    (add a wave, regenerate, drop a disturbance) in plain functions beside it and unit-test them;
//!    `panels::test_support::commit` applies an edit the way the viewer does (draft, validate,
//!    commit or refuse) and checks that the committed scene saves and loads back unchanged.
//! 2. Add `pub mod <model>;` to `panels/mod.rs` and, if it needs one, its form to
//!    [`panels::PanelState`].
//! 3. Add one arm to the `match` at the end of [`panels::water::show`] (the compiler asks for it
//!    when a `WaterModelSpec` variant is added). The model menu lists `swell::scene::WATER_MODELS`
//!    by itself, and [`panels::water::switch_model`] starts a newly chosen model from its
//!    scene-file defaults.
//!
//! A new scene section (terrain, objects) gets its own `panels/<section>.rs` with
//! `show(ui, &mut scene.<section>) -> bool` and one `section(...)` line in [`panels::show_all`].
//! The test `showing_the_panel_changes_nothing_in_any_preset` then checks, for every preset, that
//! merely showing the panel leaves the scene as loaded.

#![warn(missing_docs)]

pub mod app;
pub mod body_control;
pub mod camera_control;
pub mod clock;
pub mod editor;
pub mod files;
pub mod frame;
pub mod frame_stats;
pub mod gl_view;
pub mod live_view;
pub mod panels;
pub mod picking;
pub mod render_thread;

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use eframe::egui;
use swell::scene::Scene;
use swell::{Error, Result};

/// Largest initial view, pixels: the scene's `[render]` size is scaled down to fit.
pub const MAX_INITIAL_VIEW: [f32; 2] = [1280.0, 720.0];

/// What to open and, for scripted runs, when to stop.
#[derive(Clone, Debug)]
pub struct ViewerOptions {
    /// The scene to show first (already validated).
    pub scene: Scene,
    /// Window title suffix: the preset or file the scene came from.
    pub source: String,
    /// Save the window's content as PNG here before exiting (needs `exit_after_frames`).
    pub screenshot: Option<PathBuf>,
    /// Close after this many rendered frames (at least 1).
    pub exit_after_frames: Option<u32>,
}

/// The view size the window opens with: the scene's image size, scaled down to fit
/// [`MAX_INITIAL_VIEW`] with its aspect ratio kept.
pub fn initial_view_size(scene: &Scene) -> [f32; 2] {
    let (w, h) = (scene.render.width as f32, scene.render.height as f32);
    let scale = (MAX_INITIAL_VIEW[0] / w).min(MAX_INITIAL_VIEW[1] / h).min(1.0);
    [(w * scale).round().max(64.0), (h * scale).round().max(64.0)]
}

/// Checks the scripted-run flags before anything is loaded, opened or written: `--exit-after-frames`
/// at least 1, and `--screenshot` (which needs it) a `.png` path in an existing directory. The
/// screenshot is always PNG: any other extension is refused rather than written as PNG bytes
/// under a misleading name.
pub fn check_flags(screenshot: Option<&Path>, exit_after_frames: Option<u32>) -> Result<()> {
    if exit_after_frames == Some(0) {
        return Err(Error::out_of_range("--exit-after-frames", 0, "[1, 4294967295]"));
    }
    let Some(path) = screenshot else { return Ok(()) };
    if exit_after_frames.is_none() {
        return Err(Error::invalid("--screenshot", "needs --exit-after-frames N (when to take it)"));
    }
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if ext.as_deref() != Some("png") {
        return Err(Error::invalid(
            "--screenshot",
            format!("\"{}\" must end in .png (the only screenshot format)", path.display()),
        ));
    }
    if path.is_dir() {
        return Err(Error::invalid("--screenshot", format!("\"{}\" is a directory", path.display())));
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        return Err(Error::invalid(
            "--screenshot",
            format!("\"{}\": directory {} does not exist", path.display(), dir.display()),
        ));
    }
    Ok(())
}

/// The window [`run`] opens: titled `title`, at the screen's top-left corner, sized for a view of
/// `view` points beside the panel and above the status line. Public so that a program running
/// [`app::ViewerApp`] itself (the real-window tests) gets the same window.
pub fn native_options(title: &str, view: [f32; 2]) -> eframe::NativeOptions {
    let [vw, vh] = view;
    eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title(title)
            .with_inner_size([vw + app::PANEL_WIDTH, vh + app::STATUS_HEIGHT])
            .with_position([0.0, 0.0]),
        // The view is blitted, not shaded (gl_view.rs); egui's dithering only touches the panel.
        // No vsync: frames are paced by the render, and Xvfb has no display refresh to wait for.
        glow_options: eframe::egui_glow::GlowConfiguration { vsync: false, ..Default::default() },
        dithering: false,
        multisampling: 0,
        depth_buffer: 0,
        stencil_buffer: 0,
        ..Default::default()
    }
}

/// Opens the viewer window and runs until it is closed (`q`, the window's close button, or the end
/// of `exit_after_frames`). Errors: no display to open a window on, or a failed scripted
/// screenshot.
pub fn run(options: ViewerOptions) -> Result<()> {
    check_flags(options.screenshot.as_deref(), options.exit_after_frames)?;
    let outcome = Rc::new(RefCell::new(None));
    let app = app::ViewerApp::new(options.clone(), outcome.clone())?;
    let native = native_options(&format!("swell: {}", options.source), initial_view_size(&options.scene));
    eframe::run_native("swell", native, Box::new(move |_cc| Ok(Box::new(app)))).map_err(|e| {
        Error::invalid("window", format!("cannot run the viewer window ({e}); is DISPLAY set to a running X server?"))
    })?;
    let scripted = outcome.borrow_mut().take();
    match scripted {
        Some(e) => Err(e),
        None => Ok(()),
    }
}
