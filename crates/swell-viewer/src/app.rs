//! The eframe application: panel on the right, status line at the bottom, the live view in the
//! middle; keys and mouse; file requests; the scripted screenshot-and-exit mode.

use std::cell::RefCell;
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::Arc;
use std::time::Instant;

use eframe::egui::{self, Color32, Key, PointerButton, Rect, Sense, ViewportCommand};
use swell::world::TerrainBody;
use swell::{Error, Result};

use crate::body_control::{push_direction, BodyDrop, DropKind, LiveBody, Push};
use crate::camera_control::CameraRig;
use crate::clock::Clock;
use crate::editor::{FrameFailure, SceneEditor};
use crate::frame::FrameKey;
use crate::frame_stats::FrameStats;
use crate::live_view::LiveView;
use crate::panels::bodies::ClickMode;
use crate::panels::files::{FileMessage, FileRequest};
use crate::panels::{self, PanelOutput, PanelState};
use crate::ViewerOptions;

/// Width of the parameter panel, points: wide enough for its widest row (a label and three
/// values, e.g. the water's absorption). A narrower panel let that row spill past the window's
/// right edge, and egui then laid the panel out that much further right, so the view grew under it
/// (1344 px for 1280 asked) and the panel's labels were hidden behind the view.
pub const PANEL_WIDTH: f32 = 500.0;

/// Height of the status line, points.
pub const STATUS_HEIGHT: f32 = 24.0;

/// Frames to wait for the window's screenshot before falling back to the last rendered view.
const SCREENSHOT_PATIENCE_FRAMES: u32 = 60;

/// What a key does (paper 002's keys plus space and `r`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shortcut {
    /// `q`: close the viewer.
    Quit,
    /// Space: play or pause.
    TogglePlay,
    /// `t`: wireframe overlay on or off.
    ToggleWireframe,
    /// `n`: normals overlay on or off.
    ToggleNormals,
    /// `r`: back to the scene's camera.
    ResetCamera,
}

/// The key bindings, also listed in `docs/viewer.md`.
pub const SHORTCUTS: &[(Key, Shortcut)] = &[
    (Key::Q, Shortcut::Quit),
    (Key::Space, Shortcut::TogglePlay),
    (Key::T, Shortcut::ToggleWireframe),
    (Key::N, Shortcut::ToggleNormals),
    (Key::R, Shortcut::ResetCamera),
];

/// The keys that push the selected floating body while held, each with how much it pushes
/// forward (along the camera's view laid flat) and to the right: I, J, K, L sit under the right
/// hand like arrow keys, and none of them is a shortcut. Arrow keys themselves step the panel's
/// focused number.
pub const PUSH_KEYS: &[(Key, f32, f32)] =
    &[(Key::I, 1.0, 0.0), (Key::K, -1.0, 0.0), (Key::J, 0.0, -1.0), (Key::L, 0.0, 1.0)];

/// Whether a click in this frame's `events` was made with Shift held: the modifiers of the
/// primary button's own press or release (Shift may be let go within the same frame), else
/// those held now.
pub fn shift_click(events: &[egui::Event], now: egui::Modifiers) -> bool {
    now.shift
        || events.iter().any(|e| {
            matches!(e, egui::Event::PointerButton { button: PointerButton::Primary, modifiers, .. } if modifiers.shift)
        })
}

/// Why a screenshot was asked for, sent back with the image by egui's screenshot callback.
#[derive(Clone, Debug)]
enum ScreenshotPurpose {
    /// The panel's "Save window PNG".
    Panel(PathBuf),
    /// `--screenshot FILE` at the end of `--exit-after-frames`.
    Exit(PathBuf),
}

/// Progress of `--exit-after-frames`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ExitState {
    /// Rendering frames.
    Running,
    /// Screenshot asked for this many frames ago.
    WaitingForScreenshot(u32),
    /// Close sent.
    Closing,
}

/// The viewer's whole state.
pub struct ViewerApp {
    editor: SceneEditor,
    panels: PanelState,
    clock: Clock,
    rig: CameraRig,
    view: LiveView,
    stats: FrameStats,
    options: ViewerOptions,
    exit: ExitState,
    last_frame: Option<Instant>,
    /// When the window showed the last rendered frame (the start of the next frame interval).
    last_shown: Option<Instant>,
    /// Rendered frames the window has shown since start (what `--exit-after-frames` counts).
    rendered: u32,
    /// The last simulation or rendering error, shown in the status line.
    run_error: Option<String>,
    /// A hint about the last click (what it did not do and how to), shown in the status line.
    notice: Option<String>,
    /// The view's rectangle in the last frame, points: where *Add* buttons drop (its centre).
    view_rect: Option<Rect>,
    /// The body the keys push this frame, by index (shown in the status line).
    pushing: Option<usize>,
    /// Where the scripted run's outcome goes, read by [`crate::run`] after the window closes.
    outcome: Rc<RefCell<Option<Error>>>,
    /// Window screenshots: egui hands each to a callback once the backend has read the pixels
    /// (possibly on another thread); it waits here for the next frame's [`Self::handle_screenshots`].
    shots: (Sender<Screenshot>, Receiver<Screenshot>),
}

/// A window screenshot and why it was taken.
type Screenshot = (ScreenshotPurpose, Arc<egui::ColorImage>);

impl ViewerApp {
    /// The viewer for `options.scene`; `outcome` receives any error of the scripted exit.
    pub fn new(options: ViewerOptions, outcome: Rc<RefCell<Option<Error>>>) -> Result<Self> {
        let editor = SceneEditor::new(options.scene.clone())?;
        let rig = CameraRig::new(options.scene.camera);
        Ok(Self {
            editor,
            panels: PanelState::default(),
            clock: Clock::default(),
            rig,
            view: LiveView::new(),
            stats: FrameStats::default(),
            options,
            exit: ExitState::Running,
            last_frame: None,
            last_shown: None,
            rendered: 0,
            run_error: None,
            notice: None,
            view_rect: None,
            pushing: None,
            outcome,
            shots: channel(),
        })
    }

    /// The scene being shown (the last valid one): what is saved, and what scripted checks read.
    pub fn scene(&self) -> &swell::scene::Scene {
        self.editor.scene()
    }

    /// The simulation time, seconds (what the next frame is rendered at).
    pub fn time(&self) -> f64 {
        self.clock.time
    }

    /// Every floating body as the last frame received showed it, in scene order.
    pub fn live_bodies(&self) -> &[LiveBody] {
        &self.panels.bodies.live
    }

    /// The push the held keys give the selected body this frame, if any (none while a text field
    /// has the keyboard, or without bodies).
    fn push_from_keys(&self, ctx: &egui::Context) -> Option<Push> {
        if ctx.egui_wants_keyboard_input() {
            return None;
        }
        let (mut forward, mut right) = (0.0, 0.0);
        for &(key, f, r) in PUSH_KEYS {
            if ctx.input(|i| i.key_down(key)) {
                forward += f;
                right += r;
            }
        }
        let scene = self.editor.scene();
        let body = self.panels.bodies.pushed(scene.bodies.len())?;
        Some(Push { body, direction: push_direction(&scene.camera, forward, right)? })
    }

    fn handle_keys(&mut self, ctx: &egui::Context) {
        if ctx.egui_wants_keyboard_input() {
            return;
        }
        for &(key, action) in SHORTCUTS {
            if !ctx.input(|i| i.key_pressed(key)) {
                continue;
            }
            match action {
                Shortcut::Quit => ctx.send_viewport_cmd(ViewportCommand::Close),
                Shortcut::TogglePlay => self.clock.toggle(),
                Shortcut::ToggleWireframe => self.toggle_overlay(|r| &mut r.wireframe),
                Shortcut::ToggleNormals => self.toggle_overlay(|r| &mut r.normals),
                Shortcut::ResetCamera => self.move_camera(self.rig.home),
            }
        }
    }

    /// Flips an overlay switch of the scene's render settings (`t`, `n`) and applies it at once.
    fn toggle_overlay(&mut self, flag: fn(&mut swell::scene::RenderSettings) -> &mut bool) {
        *flag(&mut self.editor.draft.render) ^= true;
        if let Err(e) = self.editor.apply() {
            self.run_error = Some(swell::error::printable(&e.to_string()));
        }
    }

    fn move_camera(&mut self, camera: swell::scene::Camera) {
        if let Err(e) = self.editor.set_camera(camera) {
            self.run_error = Some(swell::error::printable(&e.to_string()));
        }
    }

    fn handle_mouse(&mut self, ui: &egui::Ui, response: &egui::Response) {
        let cam = self.editor.scene().camera;
        let d = response.drag_delta();
        let moved = if response.dragged_by(PointerButton::Primary) {
            Some(self.rig.drag_orbit(&cam, d.x, d.y))
        } else if response.dragged_by(PointerButton::Secondary) {
            Some(self.rig.drag_zoom(&cam, d.y))
        } else if response.dragged_by(PointerButton::Middle) {
            let ppp = ui.ctx().pixels_per_point();
            let height_px = response.rect.height() * ppp;
            Some(crate::camera_control::pan(&cam, d.x * ppp, d.y * ppp, height_px))
        } else {
            None
        };
        let scroll = if response.hovered() { ui.input(|i| i.smooth_scroll_delta.y) } else { 0.0 };
        let moved = match (moved, scroll != 0.0) {
            (m, true) => Some(self.rig.wheel_zoom(&m.unwrap_or(cam), scroll)),
            (m, false) => m,
        };
        if let Some(c) = moved.filter(|c| *c != cam) {
            self.move_camera(c);
        }
        if response.clicked_by(PointerButton::Primary) {
            if let Some(pos) = response.interact_pointer_pos() {
                let shift = ui.input(|i| shift_click(&i.events, i.modifiers));
                let mode = if shift { ClickMode::Drop(DropKind::Crate) } else { self.panels.bodies.click };
                match mode {
                    ClickMode::Disturb => self.disturb_at_click(response.rect, pos),
                    ClickMode::Drop(kind) => self.drop_body_at(kind, response.rect, pos),
                }
            }
        }
    }

    /// A click on the water drops a disturbance there (models with state: the spring mesh).
    fn disturb_at_click(&mut self, rect: Rect, pos: egui::Pos2) {
        let cam = self.editor.scene().camera;
        let local = pos - rect.min;
        let Some(at) = crate::picking::water_point(&cam, rect.width(), rect.height(), local.x, local.y) else {
            return;
        };
        let click = self.panels.click_drop;
        if let Err(e) = click.validate() {
            self.run_error = Some(swell::error::printable(&e.to_string()));
        } else if self.editor.disturb_water() {
            // The render thread's world, the one shown, takes the dent.
            let d = crate::render_thread::Disturbance { x: at.x, z: at.y, depth: click.depth, radius: click.radius };
            self.view.disturb(d);
            self.run_error = None;
            self.notice = None;
        } else {
            self.notice = Some("this water takes no dents: Shift+click drops a crate (Bodies: left click)".into());
        }
    }

    /// Drops a body of `kind` where the ray through `pos` (in the view `rect`) meets the water:
    /// the render thread's world adds it, and the frame brings its spec back to the scene.
    fn drop_body_at(&mut self, kind: DropKind, rect: Rect, pos: egui::Pos2) {
        let cam = self.editor.scene().camera;
        let local = pos - rect.min;
        match crate::picking::view_ray(&cam, rect.width(), rect.height(), local.x, local.y) {
            Some(ray) if ray.direction.y < 0.0 => {
                self.view.drop_body(BodyDrop { kind, ray });
                self.notice = None;
            }
            _ => self.notice = Some(format!("no {} dropped: the click is above the horizon", kind.name())),
        }
    }

    /// Takes what the last frame said about the bodies: each drop the render thread's world added
    /// joins the editor's scenes (and becomes the pushed body), a refused one is reported in the
    /// bodies panel; the bodies' places go to the panel.
    fn handle_bodies(&mut self) {
        for outcome in self.view.take_dropped() {
            match outcome {
                Ok(spec) => {
                    let k = self.editor.body_dropped(spec);
                    self.panels.bodies.dropped(k);
                }
                Err(e) => self.panels.bodies.message = Some(format!("drop refused: {e}")),
            }
        }
        if let Some(bodies) = self.view.take_bodies() {
            self.panels.bodies.live = bodies;
        }
    }

    fn handle_panel(&mut self, ctx: &egui::Context, out: PanelOutput) {
        if out.revert {
            self.editor.revert();
        }
        if out.scene_changed {
            // A refusal is kept in the editor and shown at the top of the panel.
            let _ = self.editor.apply();
        }
        if out.reset_camera {
            self.move_camera(self.rig.home);
        }
        if let Some(kind) = out.drop {
            // At the view's centre: the camera's line of sight.
            match self.view_rect {
                Some(rect) => self.drop_body_at(kind, rect, rect.center()),
                None => self.notice = Some("no view to drop into yet".into()),
            }
        }
        if let Some(request) = out.file {
            let heightmap = matches!(request, FileRequest::SaveHeightmap(_) | FileRequest::LoadHeightmap(_));
            let message = match self.file_action(ctx, request) {
                Ok(m) => FileMessage::Done(m),
                Err(e) => FileMessage::Failed(e),
            };
            // Heightmap outcomes show under the terrain's heightmap row, the others under Files.
            if heightmap {
                self.panels.terrain.file_message = Some(message);
            } else {
                self.panels.files.message = Some(message);
            }
        }
    }

    /// Does what a file button asked; the outcome names the path: what was written or read, or
    /// what failed and why.
    fn file_action(&mut self, ctx: &egui::Context, request: FileRequest) -> std::result::Result<String, String> {
        let failed = |what: &str, p: &std::path::Path, e: Error| format!("could not {what} {}: {e}", p.display());
        match request {
            FileRequest::SaveScene(p) => self
                .editor
                .save(&p)
                .map(|()| format!("saved the scene to {}", p.display()))
                .map_err(|e| failed("save the scene to", &p, e)),
            FileRequest::LoadScene(p) => match self.editor.load(&p) {
                Ok(()) => {
                    self.rig = CameraRig::new(self.editor.scene().camera);
                    Ok(format!("loaded the scene {}", p.display()))
                }
                Err(e) => Err(failed("load the scene", &p, e)),
            },
            FileRequest::SaveView(p) => match self.view.save_png(&p) {
                Ok(()) => {
                    let [w, h] = self.view.size();
                    Ok(format!("saved the {w}x{h} view to {}", p.display()))
                }
                Err(e) => Err(failed("save the view to", &p, e)),
            },
            // Generators are deterministic: the spec rebuilds the very field on screen.
            FileRequest::SaveHeightmap(p) => match &self.editor.scene().terrain {
                Some(spec) => TerrainBody::new(spec)
                    .and_then(|t| swell::terrain::write_heightmap(&p, &t.field))
                    .map(|s| format!("saved the heightmap to {} ({} m per grey range)", p.display(), s.height_scale))
                    .map_err(|e| failed("save the heightmap to", &p, e)),
                None => {
                    Err(failed("save the heightmap to", &p, Error::invalid("terrain", "there is no terrain to save")))
                }
            },
            FileRequest::LoadHeightmap(p) => match self.editor.load_heightmap(&p) {
                Ok([cols, rows]) => Ok(format!("loaded the heightmap {} ({cols} x {rows} vertices)", p.display())),
                Err(e) => Err(failed("load the heightmap", &p, e)),
            },
            FileRequest::SaveWindow(p) => {
                self.request_screenshot(ctx, ScreenshotPurpose::Panel(p));
                Ok("taking a screenshot of the window...".into())
            }
        }
    }

    /// Asks egui for a screenshot of the next frame, to arrive in [`Self::shots`].
    fn request_screenshot(&self, ctx: &egui::Context, purpose: ScreenshotPurpose) {
        let (tx, wake) = (self.shots.0.clone(), ctx.clone());
        ctx.request_screenshot(move |image| {
            // Fails only once the viewer is gone, when nobody wants the image any more.
            let _ = tx.send((purpose, image));
            // egui does not repaint for a screenshot by itself; a paused view would wait for input.
            wake.request_repaint();
        });
    }

    /// Saves window screenshots that arrived since the last frame.
    fn handle_screenshots(&mut self, ctx: &egui::Context) {
        let shots: Vec<Screenshot> = self.shots.1.try_iter().collect();
        for (purpose, image) in shots {
            let [w, h] = image.size;
            let result = |p: &PathBuf| crate::files::write_screenshot(p, w, h, image.as_raw());
            match purpose {
                ScreenshotPurpose::Panel(p) => {
                    self.panels.files.message = Some(match result(&p) {
                        Ok(()) => FileMessage::Done(format!("saved the {w}x{h} window to {}", p.display())),
                        Err(e) => FileMessage::Failed(format!("could not save the window to {}: {e}", p.display())),
                    });
                }
                ScreenshotPurpose::Exit(p) => {
                    if let Err(e) = result(&p) {
                        *self.outcome.borrow_mut() = Some(e);
                    } else {
                        eprintln!("swell view: saved the {w}x{h} window to {}", p.display());
                    }
                    self.close(ctx);
                }
            }
        }
    }

    /// `--exit-after-frames`: after N rendered frames, screenshot (if asked) and close.
    fn scripted_exit(&mut self, ctx: &egui::Context) {
        let Some(n) = self.options.exit_after_frames else { return };
        match self.exit {
            ExitState::Running if self.rendered >= n => match self.options.screenshot.clone() {
                Some(p) => {
                    self.request_screenshot(ctx, ScreenshotPurpose::Exit(p));
                    self.exit = ExitState::WaitingForScreenshot(0);
                }
                None => self.close(ctx),
            },
            ExitState::WaitingForScreenshot(k) if k >= SCREENSHOT_PATIENCE_FRAMES => {
                // The backend never answered: save what swell rendered instead, and say so.
                let p = self.options.screenshot.clone().expect("waiting implies a screenshot path");
                eprintln!("swell view: the window screenshot did not arrive; saving the rendered view instead");
                if let Err(e) = self.view.save_png(&p) {
                    *self.outcome.borrow_mut() = Some(e);
                }
                self.close(ctx);
            }
            ExitState::WaitingForScreenshot(k) => self.exit = ExitState::WaitingForScreenshot(k + 1),
            _ => {}
        }
    }

    fn close(&mut self, ctx: &egui::Context) {
        if self.exit == ExitState::Closing {
            return;
        }
        if let Some(m) = self.stats.mean() {
            let [w, h] = self.view.size();
            eprintln!(
                "swell view: {} frames at {w}x{h}, mean after {} warm-up frames: {}",
                self.stats.frames,
                crate::frame_stats::WARMUP_FRAMES,
                m.line()
            );
        }
        self.exit = ExitState::Closing;
        ctx.send_viewport_cmd(ViewportCommand::Close);
    }

    fn status_line(&self) -> String {
        let [w, h] = self.view.size();
        let mut s = format!(
            "{:.1} fps | sim {:.1} ms | render {:.1} ms | upload {:.1} ms | view {w}x{h} | t = {:.2} s{}",
            self.stats.fps(),
            self.stats.recent.simulate * 1e3,
            self.stats.recent.render * 1e3,
            self.stats.recent.upload * 1e3,
            self.clock.time,
            if self.clock.playing { "" } else { " (paused)" },
        );
        let bodies = self.editor.scene().bodies.len();
        if bodies > 0 {
            s.push_str(&format!(" | {bodies} {}", if bodies == 1 { "body" } else { "bodies" }));
        }
        if let Some(b) = self.pushing.and_then(|i| self.editor.scene().bodies.get(i).map(|b| (i, b))) {
            let name = if b.1.name.is_empty() { format!("body{}", b.0) } else { b.1.name.clone() };
            s.push_str(&format!(" | pushing {name}"));
        }
        let o = self.editor.scene().render;
        if o.wireframe || o.normals {
            s.push_str(" | overlays:");
            if o.wireframe {
                s.push_str(" wireframe");
            }
            if o.normals {
                s.push_str(" normals");
            }
        }
        s
    }

    /// Records the frames the last paints showed: the status line and `--exit-after-frames` count
    /// these, not UI repaints.
    fn count_shown_frames(&mut self) {
        for f in self.view.take_shown() {
            let interval = self.last_shown.map(|t| f.at.saturating_duration_since(t));
            self.last_shown = Some(f.at);
            self.stats.record(interval, f.times.simulate, f.times.render, f.times.upload);
            self.rendered = self.rendered.saturating_add(1);
        }
    }

    /// Whether another frame may be asked for: always, except in a scripted run whose N frames
    /// are all shown or on their way (so that exactly N frames are rendered and shown).
    fn frame_budget_left(&self) -> bool {
        self.options.exit_after_frames.is_none_or(|n| self.rendered.saturating_add(self.view.pending()) < n)
    }

    /// Shows the frame rendered since the last UI frame and asks for the next one if anything it
    /// depends on changed (always, in the scripted mode, until its N frames are asked for).
    fn draw_view(&mut self, ctx: &egui::Context, size: [u32; 2]) {
        match self.view.collect() {
            Some((revision, Ok(_))) => self.editor.frame_shown(revision),
            Some((revision, Err(e))) => {
                // A commit that does not build is undone and shown as a refusal in the panel, and
                // a failure of an older revision is left to the current one's frame; otherwise a
                // stateful model went unstable: stop the clock so the error stays readable.
                let failure = self.editor.frame_failed(revision, &e);
                if failure == FrameFailure::Unrecoverable {
                    self.clock.playing = false;
                    self.run_error = Some(swell::error::printable(&e.to_string()));
                }
            }
            None => {}
        }
        self.handle_bodies();
        if size[0] == 0 || size[1] == 0 || !self.frame_budget_left() {
            return;
        }
        let key = FrameKey { revision: self.editor.revision(), time: self.clock.time, size };
        if !self.view.is_stale(&key) && self.options.exit_after_frames.is_none() {
            return;
        }
        let threads = self.editor.scene().render.threads;
        if let Err(e) = self.view.request(ctx, self.editor.scene(), key, threads) {
            self.run_error = Some(swell::error::printable(&e.to_string()));
        }
    }
}

/// egui's frame for a side or bottom panel, without its fill: the window is cleared to the same
/// colour (`clear_color`), which llvmpipe does as a memory fill, while a filled panel is one more
/// pass of egui's shader (an sRGB decode and a `pow` per channel and pixel) over some 0.35 M
/// pixels every frame. Same pixels on screen.
fn panel_frame(ctx: &egui::Context) -> egui::Frame {
    egui::Frame::side_top_panel(&ctx.global_style()).fill(Color32::TRANSPARENT)
}

impl eframe::App for ViewerApp {
    fn on_exit(&mut self, gl: Option<&eframe::glow::Context>) {
        if let Some(gl) = gl {
            self.view.destroy(gl);
        }
    }

    /// The panels' colour, so that the panels need no fill of their own (see [`panel_frame`]).
    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        visuals.panel_fill.to_normalized_gamma_f32()
    }

    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = &ui.ctx().clone();
        let now = Instant::now();
        let frame_dt = self.last_frame.map(|t| now - t).unwrap_or_default();
        self.last_frame = Some(now);
        self.count_shown_frames();
        self.handle_screenshots(ctx);
        self.handle_keys(ctx);
        let push = self.push_from_keys(ctx);
        self.pushing = push.map(|p| p.body);
        self.view.set_push(push);
        self.clock.tick(frame_dt.as_secs_f64());

        egui::Panel::bottom("status").exact_size(STATUS_HEIGHT).frame(panel_frame(ctx)).show(ui, |ui| {
            ui.horizontal_centered(|ui| {
                ui.monospace(self.status_line());
                if let Some(e) = &self.run_error {
                    ui.colored_label(ui.visuals().error_fg_color, e);
                }
                if let Some(n) = &self.notice {
                    ui.weak(n);
                }
            });
        });
        egui::Panel::right("panel").exact_size(PANEL_WIDTH).frame(panel_frame(ctx)).show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                let error = self.editor.error().map(str::to_owned);
                let out =
                    panels::show_all(ui, &mut self.editor.draft, &mut self.panels, &mut self.clock, error.as_deref());
                self.handle_panel(ctx, out);
            });
        });
        // No fill behind the view: it would be one more full-view pass of egui's shader on
        // llvmpipe; black is painted only until the first frame exists.
        egui::CentralPanel::no_frame().show(ui, |ui| {
            let (rect, response) = ui.allocate_exact_size(ui.available_size(), Sense::click_and_drag());
            self.view_rect = Some(rect);
            self.handle_mouse(ui, &response);
            let ppp = ctx.pixels_per_point();
            let size = [(rect.width() * ppp).round() as u32, (rect.height() * ppp).round() as u32];
            self.draw_view(ctx, size);
            if self.view.has_frame() {
                self.view.paint(ui.painter(), rect);
            } else {
                ui.painter().rect_filled(rect, 0.0, Color32::BLACK);
            }
        });

        self.scripted_exit(ctx);
        if self.clock.playing || self.exit != ExitState::Running || self.options.exit_after_frames.is_some() {
            ctx.request_repaint();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn push_keys_are_not_shortcuts_and_shift_is_read_from_the_click_itself() {
        for (key, f, r) in PUSH_KEYS {
            assert!(!SHORTCUTS.iter().any(|(k, _)| k == key), "{key:?} is a shortcut too");
            assert_eq!(f.abs() + r.abs(), 1.0, "{key:?} pushes one way");
        }
        let click = |shift: bool| egui::Event::PointerButton {
            pos: egui::Pos2::ZERO,
            button: PointerButton::Primary,
            pressed: false,
            modifiers: if shift { egui::Modifiers::SHIFT } else { egui::Modifiers::NONE },
        };
        // Shift let go within the same frame as the click still counts; none held, none counted.
        assert!(shift_click(&[click(true)], egui::Modifiers::NONE));
        assert!(!shift_click(&[click(false)], egui::Modifiers::NONE));
        assert!(shift_click(&[], egui::Modifiers::SHIFT));
        let middle = egui::Event::PointerButton {
            pos: egui::Pos2::ZERO,
            button: PointerButton::Middle,
            pressed: true,
            modifiers: egui::Modifiers::SHIFT,
        };
        assert!(!shift_click(&[middle, click(false)], egui::Modifiers::NONE));
    }
}
