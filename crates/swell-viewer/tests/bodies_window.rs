//! Floating bodies in a real X window (issue 34): under Xvfb, a Shift+click on the `ocean` preset's
//! FFT sea drops a crate into the scene, which falls and then rides the waves at the surface, and
//! holding `l` pushes it to the camera's right.
//!
//! The viewer runs in this process (eframe needs the main thread, hence `harness = false`) behind
//! a thin app that records, every frame, the viewer's scene, clock and bodies, while a second
//! thread plays the user with `xdotool`. Needs `Xvfb` and `xdotool` (docs/viewer.md); without
//! them it prints why and passes, unless the environment variable `CI` is set (CI installs them).

use std::cell::RefCell;
use std::os::unix::net::UnixStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::rc::Rc;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use eframe::egui;
use glam::Vec2;
use swell::body::{BodyShape, BodySpec};
use swell_viewer::app::ViewerApp;
use swell_viewer::body_control::{LiveBody, CRATE_SIZE_M};
use swell_viewer::ViewerOptions;

/// Size of the virtual screen.
const SCREEN: &str = "1600x900x24";
/// The view: small, so the FFT sea renders fast on a loaded two-core machine.
const VIEW: [f32; 2] = [640.0, 360.0];
/// Where the test clicks, in the view (the window opens at the screen's top-left corner, the
/// view at the window's): below the centre, on the sea some 40 m ahead.
const CLICK: [f32; 2] = [320.0, 250.0];
/// How long the window may take to show its first frames.
const STARTUP: Duration = Duration::from_secs(180);
/// Longest the whole run may take before the test gives up and closes the window.
const DEADLINE: Duration = Duration::from_secs(420);
const TITLE: &str = "swell bodies window test";

/// What the app saw, shared with the user thread.
#[derive(Default)]
struct Seen {
    /// UI frames run.
    frames: u64,
    /// The scene's bodies at the last frame.
    bodies: Vec<BodySpec>,
    /// Body 0 as each rendered frame showed it, with the simulation time it was asked for (one
    /// entry per new frame; the view is one frame behind the clock).
    samples: Vec<(f64, LiveBody)>,
    /// The user thread is done (or gave up): close the window.
    done: bool,
    /// Why the user thread gave up, if it did.
    failure: Option<String>,
}

/// The viewer, recording what it shows into [`Seen`] after every frame.
struct Recorder {
    viewer: ViewerApp,
    seen: Arc<Mutex<Seen>>,
    start: Instant,
}

impl eframe::App for Recorder {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.viewer.ui(ui, frame);
        let mut seen = self.seen.lock().unwrap();
        seen.frames += 1;
        seen.bodies.clone_from(&self.viewer.scene().bodies);
        if let Some(&live) = self.viewer.live_bodies().first() {
            if seen.samples.last().is_none_or(|(_, l)| *l != live) {
                let t = self.viewer.time();
                seen.samples.push((t, live));
            }
        }
        if self.start.elapsed() > DEADLINE && !seen.done {
            seen.failure.get_or_insert_with(|| format!("the run took over {DEADLINE:?}"));
            seen.done = true;
        }
        if seen.done {
            ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
        }
        // Keep frames coming while the user thread works, paused or not.
        ui.ctx().request_repaint();
    }

    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        self.viewer.clear_color(visuals)
    }

    fn on_exit(&mut self, gl: Option<&eframe::glow::Context>) {
        self.viewer.on_exit(gl);
    }
}

/// A running Xvfb, stopped on drop.
struct Xvfb {
    child: Child,
    display: String,
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        // SIGTERM, so that Xvfb removes its lock file; SIGKILL if it does not stop.
        let _ = Command::new("kill").args(["-TERM", &self.child.id().to_string()]).status();
        let deadline = Instant::now() + Duration::from_secs(5);
        while Instant::now() < deadline {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn have(tool: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {tool}")])
        .stdout(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// Whether `/tmp/.X{n}-lock` names a live X server (a lock whose process is gone does not count:
/// Xvfb removes it itself).
fn display_in_use(n: u32) -> bool {
    let Ok(text) = std::fs::read_to_string(format!("/tmp/.X{n}-lock")) else { return false };
    text.trim().parse::<u32>().map_or(true, |pid| Path::new(&format!("/proc/{pid}")).exists())
}

/// Starts Xvfb on a free display from :150 (the CLI's viewer tests take :99 upwards).
fn start_xvfb() -> Xvfb {
    for n in 150..200 {
        if display_in_use(n) {
            continue;
        }
        // `-noreset`: the readiness probe is a client that leaves, which would reset the server.
        let child = Command::new("Xvfb")
            .args([format!(":{n}").as_str(), "-screen", "0", SCREEN, "-nolisten", "tcp", "-noreset"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("Xvfb starts");
        let mut x = Xvfb { child, display: format!(":{n}") };
        let socket = PathBuf::from(format!("/tmp/.X11-unix/X{n}"));
        let deadline = Instant::now() + Duration::from_secs(20);
        while Instant::now() < deadline {
            if let Ok(Some(_)) = x.child.try_wait() {
                break; // taken after all: the next one
            }
            if UnixStream::connect(&socket).is_ok() {
                return x;
            }
            std::thread::sleep(Duration::from_millis(100));
        }
        let _ = x.child.kill();
    }
    panic!("could not start Xvfb on any display :150..:199");
}

fn xdotool(display: &str, args: &[&str]) -> Result<String, String> {
    let out = Command::new("xdotool").env("DISPLAY", display).args(args).output().map_err(|e| e.to_string())?;
    if out.status.success() {
        Ok(String::from_utf8_lossy(&out.stdout).into_owned())
    } else {
        Err(format!("xdotool {args:?}: {}", String::from_utf8_lossy(&out.stderr)))
    }
}

/// Waits until `ready` holds of what the app saw, for at most `limit`.
fn wait_for(seen: &Mutex<Seen>, limit: Duration, what: &str, ready: impl Fn(&Seen) -> bool) -> Result<(), String> {
    let deadline = Instant::now() + limit;
    while Instant::now() < deadline {
        if ready(&seen.lock().unwrap()) {
            return Ok(());
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    Err(format!("waited {limit:?} for {what}"))
}

/// The simulation time of the last frame shown with a body, if any.
fn last_time(seen: &Mutex<Seen>) -> Option<f64> {
    seen.lock().unwrap().samples.last().map(|(t, _)| *t)
}

/// The user: Shift+click on the sea, wait for the crate to settle, hold `l`. Returns the
/// simulation times the push started and ended.
fn play_the_user(display: &str, seen: &Mutex<Seen>) -> Result<(f64, f64), String> {
    let window = {
        let deadline = Instant::now() + STARTUP;
        loop {
            let found = xdotool(display, &["search", "--onlyvisible", "--name", TITLE]);
            if let Some(id) = found.ok().and_then(|o| o.split_whitespace().next().map(str::to_owned)) {
                if seen.lock().unwrap().frames > 10 {
                    break id;
                }
            }
            if Instant::now() > deadline {
                return Err(format!("no window after {STARTUP:?}"));
            }
            std::thread::sleep(Duration::from_millis(300));
        }
    };
    // Without a window manager nobody gives the window the keyboard.
    xdotool(display, &["windowfocus", "--sync", &window])?;
    let (x, y) = (CLICK[0].to_string(), CLICK[1].to_string());
    xdotool(display, &["mousemove", "--sync", &x, &y])?;
    std::thread::sleep(Duration::from_millis(400));
    xdotool(display, &["keydown", "shift"])?;
    std::thread::sleep(Duration::from_millis(300));
    xdotool(display, &["click", "1"])?;
    std::thread::sleep(Duration::from_millis(300));
    xdotool(display, &["keyup", "shift"])?;
    wait_for(seen, Duration::from_secs(60), "the dropped crate in the scene", |s| !s.bodies.is_empty())?;
    // Six simulated seconds to fall and settle.
    let dropped = last_time(seen).ok_or("no frame shows the crate")?;
    wait_for(seen, Duration::from_secs(120), "six simulated seconds", |s| {
        s.samples.last().is_some_and(|(t, _)| *t > dropped + 6.0)
    })?;
    let start = last_time(seen).expect("samples above");
    xdotool(display, &["keydown", "l"])?;
    std::thread::sleep(Duration::from_millis(2500));
    xdotool(display, &["keyup", "l"])?;
    // The push lasts until the frame after the key is let go.
    std::thread::sleep(Duration::from_millis(500));
    let end = last_time(seen).expect("samples above");
    Ok((start, end))
}

fn main() {
    let missing: Vec<_> = ["Xvfb", "xdotool"].into_iter().filter(|t| !have(t)).collect();
    if !missing.is_empty() {
        let msg = format!("the bodies window test needs {} (apt-get install xvfb xdotool)", missing.join(", "));
        assert!(std::env::var_os("CI").is_none(), "{msg}, and CI is set");
        eprintln!("SKIPPED: {msg}");
        return;
    }
    let x = start_xvfb();
    // No other thread runs yet, so none reads the environment while it changes.
    std::env::set_var("DISPLAY", &x.display);
    std::env::remove_var("WAYLAND_DISPLAY");

    let scene = swell::scene::preset("ocean").unwrap();
    let camera = scene.camera;
    let hit = swell_viewer::picking::water_point(&camera, VIEW[0], VIEW[1], CLICK[0], CLICK[1])
        .expect("the test's click is on the sea");
    let options = ViewerOptions { scene, source: "ocean".into(), screenshot: None, exit_after_frames: None };
    let viewer = ViewerApp::new(options, Rc::new(RefCell::new(None))).unwrap();
    let seen = Arc::new(Mutex::new(Seen::default()));
    let user = {
        let (seen, display) = (seen.clone(), x.display.clone());
        std::thread::spawn(move || {
            let result = play_the_user(&display, &seen);
            let mut s = seen.lock().unwrap();
            if let Err(e) = &result {
                s.failure = Some(e.clone());
            }
            s.done = true;
            result
        })
    };
    let app = Recorder { viewer, seen: seen.clone(), start: Instant::now() };
    let native = swell_viewer::native_options(TITLE, VIEW);
    eframe::run_native("swell", native, Box::new(move |_cc| Ok(Box::new(app)))).expect("the window runs");
    let pushed = user.join().expect("the user thread");
    let seen = seen.lock().unwrap();
    if let Some(f) = &seen.failure {
        panic!("{f}");
    }
    let (push_start, push_end) = pushed.expect("failures reported above");

    // One crate in the scene, dropped at the click's time (held until then, so a saved scene
    // replays the drop), under the click.
    assert_eq!(seen.bodies.len(), 1, "{:?}", seen.bodies);
    let spec = &seen.bodies[0];
    assert_eq!(
        (spec.name.as_str(), spec.shape, spec.size.as_slice()),
        ("crate1", BodyShape::Box, &[CRATE_SIZE_M; 3][..])
    );
    let first = seen.samples.first().expect("frames with the crate");
    // Released at the body step after the frame the click landed in, at most that frame's time
    // plus one step.
    let step = 1.0 / f64::from(swell::body::BODY_STEP_HZ);
    assert!(spec.release_time > 0.1 && spec.release_time <= first.0 + step + 1e-9, "released at {}", spec.release_time);
    let landed = Vec2::new(spec.position.x, spec.position.z);
    // The rest-plane point and the crest under the pointer differ by the waves' reach along the ray.
    assert!((landed - hit).length() < 15.0, "dropped at {landed}, the click's rest-plane point is {hit}");
    assert!(first.1.water_height.is_some_and(|h| first.1.position.y > h + 0.5), "it did not start above the water");

    // Afloat from two simulated seconds after the drop to the push: the centre at the surface.
    let afloat: Vec<f32> = seen
        .samples
        .iter()
        .filter(|(t, _)| *t > spec.release_time + 2.0 && *t <= push_start)
        .map(|(_, l)| l.position.y - l.water_height.expect("the sea is everywhere"))
        .collect();
    assert!(afloat.len() >= 10, "only {} frames afloat before the push", afloat.len());
    let mean = afloat.iter().sum::<f32>() / afloat.len() as f32;
    assert!(mean.abs() < 0.25 && afloat.iter().all(|d| d.abs() < 1.0), "centre above the water: {afloat:?}");

    // The push: to the camera's right on the horizontal plane, well beyond the waves' drift.
    let at = |t: f64| seen.samples.iter().rev().find(|(s, _)| *s <= t).expect("a sample").1.position;
    let (a, b) = (at(push_start), at(push_end));
    let view = (camera.target - camera.eye).normalize();
    let forward = Vec2::new(view.x, view.z).normalize();
    let right = Vec2::new(-forward.y, forward.x);
    let moved = Vec2::new(b.x - a.x, b.z - a.z);
    let pushed_for = push_end - push_start;
    eprintln!(
        "crate released at {:.2} s, afloat mean {mean:+.3} m over {} frames; pushed {pushed_for:.2} s: {:.2} m right, {:.2} m ahead",
        spec.release_time,
        afloat.len(),
        moved.dot(right),
        moved.dot(forward)
    );
    assert!(pushed_for > 0.8, "the push lasted only {pushed_for:.2} simulated seconds (a very slow machine?)");
    assert!(
        moved.dot(right) > 0.5 && moved.dot(right) > 2.0 * moved.dot(forward).abs(),
        "moved {moved} while pushed right"
    );
    eprintln!("test bodies_window ... ok");
}
