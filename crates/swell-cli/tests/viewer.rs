//! The viewer in a real X window: `swell view` under Xvfb draws water, a scripted mouse drag
//! changes the view, and `q` quits.
//!
//! Needs `Xvfb`, `xdotool` and ImageMagick's `import` (see docs/viewer.md for the Debian packages).
//! Without them the tests print why and pass, unless the environment variable `CI` is set: CI
//! installs them, so there a missing tool is a failure.

use std::io::Read;
use std::os::unix::net::UnixStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::atomic::{AtomicU32, Ordering};
use std::time::{Duration, Instant};

use image::RgbaImage;

/// Size of the virtual screen; the viewer's window (1280x720 view + panel) fits inside.
const SCREEN: &str = "1920x1080x24";
/// The view occupies the window's top-left 1280x720 pixels; the window opens at (0, 0).
const VIEW_W: u32 = 1280;
const VIEW_H: u32 = 720;
/// How long the viewer may take to open its window on a loaded two-core machine.
const STARTUP: Duration = Duration::from_secs(180);

static NEXT_DISPLAY: AtomicU32 = AtomicU32::new(99);

/// A running Xvfb, killed on drop.
struct Xvfb {
    child: Child,
    display: String,
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        // SIGTERM, not SIGKILL: Xvfb then removes its /tmp/.X{n}-lock, which would otherwise stay
        // behind and use up the displays this test tries, one per run.
        if let Ok(pid) = i32::try_from(self.child.id()) {
            // SAFETY: kill(2) only sends a signal to our own child process.
            unsafe { libc::kill(pid, libc::SIGTERM) };
        }
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

/// Whether `/tmp/.X{n}-lock` names a live X server. A lock left by a killed server (its PID gone)
/// does not count: Xvfb removes such a stale lock itself when it starts on that display.
fn display_in_use(n: u32) -> bool {
    let Ok(text) = std::fs::read_to_string(format!("/tmp/.X{n}-lock")) else {
        return false;
    };
    match text.trim().parse::<u32>() {
        Ok(pid) => Path::new(&format!("/proc/{pid}")).exists(),
        Err(_) => true,
    }
}

fn have(tool: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {tool}")])
        .stdout(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// Starts Xvfb on a free display, or returns None (after printing why) when the tools are missing
/// outside CI. Panics in CI when they are missing.
fn start_xvfb(tools: &[&str]) -> Option<Xvfb> {
    let missing: Vec<_> = tools.iter().copied().filter(|t| !have(t)).collect();
    if !missing.is_empty() {
        let msg = format!("viewer test needs {} (apt-get install xvfb xdotool imagemagick)", missing.join(", "));
        if std::env::var_os("CI").is_some() {
            panic!("{msg}, and CI is set");
        }
        eprintln!("SKIPPED: {msg}");
        return None;
    }
    for _ in 0..40 {
        let n = NEXT_DISPLAY.fetch_add(1, Ordering::SeqCst);
        if display_in_use(n) {
            continue;
        }
        // `-noreset`: an X server resets when its last client leaves, and the readiness probe
        // below is a client that leaves; a viewer connecting during that reset could not open
        // the display (a CI flake, "Failed to open connection to X server").
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
                break; // display taken after all: try the next one
            }
            // Connect, not just look: a socket file left by an earlier server on this display
            // exists before ours listens, and a viewer started then cannot open the display.
            if UnixStream::connect(&socket).is_ok() {
                return Some(x);
            }
            std::thread::sleep(Duration::from_millis(100));
        }
        let _ = x.child.kill();
    }
    panic!("could not start Xvfb on any display :99..:139");
}

fn swell(display: &str) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_swell"));
    c.env("DISPLAY", display).env_remove("WAYLAND_DISPLAY");
    c
}

/// Waits for `child` with a deadline, killing it if it overruns.
fn wait_with_timeout(mut child: Child, limit: Duration) -> Output {
    let deadline = Instant::now() + limit;
    loop {
        if child.try_wait().expect("child status").is_some() {
            return child.wait_with_output().expect("child output");
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            let out = child.wait_with_output().expect("child output");
            panic!("timed out after {limit:?}; stderr:\n{}", String::from_utf8_lossy(&out.stderr));
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// Fraction of the view's bottom half whose pixels are blue-ish (blue clearly above red), as water
/// under a sky is.
fn blue_fraction(img: &RgbaImage) -> f64 {
    let mut blue = 0usize;
    let mut total = 0usize;
    for y in VIEW_H / 2..VIEW_H.min(img.height()) {
        for x in 0..VIEW_W.min(img.width()) {
            let p = img.get_pixel(x, y);
            total += 1;
            if p[2] as i32 > p[0] as i32 + 20 {
                blue += 1;
            }
        }
    }
    blue as f64 / total.max(1) as f64
}

#[test]
fn scripted_screenshot_shows_water() {
    let Some(x) = start_xvfb(&["Xvfb"]) else { return };
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("shot.png");
    let child = swell(&x.display)
        .args(["view", "--preset", "sea", "--exit-after-frames", "30", "--screenshot"])
        .arg(&shot)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let out = wait_with_timeout(child, STARTUP + Duration::from_secs(60));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "swell view failed: {stderr}");
    assert!(stderr.contains("fps | sim"), "no timing summary: {stderr}");
    let img = image::open(&shot).unwrap().to_rgba8();
    // The whole window: view plus panel.
    assert!(img.width() > VIEW_W && img.height() >= VIEW_H, "{}x{}", img.width(), img.height());
    let f = blue_fraction(&img);
    assert!(f > 0.8, "only {:.0} % of the lower view is water-blue", f * 100.0);
}

fn xdotool(display: &str, args: &[&str]) {
    let s = Command::new("xdotool").env("DISPLAY", display).args(args).status().unwrap();
    assert!(s.success(), "xdotool {args:?} failed");
}

/// Captures the whole X screen.
fn capture(display: &str, path: &Path) -> RgbaImage {
    let s = Command::new("import")
        .env("DISPLAY", display)
        .args(["-window", "root"])
        .arg(format!("png:{}", path.display()))
        .status()
        .unwrap();
    assert!(s.success(), "import failed");
    image::open(path).unwrap().to_rgba8()
}

/// Mean absolute difference per channel over the view, 0..255.
fn view_difference(a: &RgbaImage, b: &RgbaImage) -> f64 {
    let mut sum = 0u64;
    for y in 0..VIEW_H {
        for x in 0..VIEW_W {
            let (p, q) = (a.get_pixel(x, y), b.get_pixel(x, y));
            sum += (0..3).map(|c| (p[c] as i32 - q[c] as i32).unsigned_abs() as u64).sum::<u64>();
        }
    }
    sum as f64 / (3.0 * VIEW_W as f64 * VIEW_H as f64)
}

/// Starts `swell view --preset PRESET` and waits until its window is mapped and at least
/// `min_blue` of the view's lower half is water-blue; returns the process and the window id.
fn open_viewer(d: &str, dir: &Path, preset: &str, min_blue: f64) -> (Child, String) {
    let mut child =
        swell(d).args(["view", "--preset", preset]).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    // Wait until the window is mapped and has drawn water.
    let deadline = Instant::now() + STARTUP;
    let window = loop {
        let found =
            Command::new("xdotool").env("DISPLAY", d).args(["search", "--onlyvisible", "--name", "^swell"]).output();
        let id = found
            .ok()
            .filter(|o| o.status.success())
            .and_then(|o| String::from_utf8_lossy(&o.stdout).split_whitespace().next().map(str::to_owned));
        let blue = id.as_ref().map(|_| blue_fraction(&capture(d, &dir.join("probe.png"))));
        if let (Some(id), Some(b)) = (&id, blue) {
            if b > min_blue {
                break id.clone();
            }
        }
        // A viewer that exited will not show a window: say why now instead of at the deadline.
        if let Ok(Some(status)) = child.try_wait() {
            let mut err = String::new();
            child.stderr.take().map(|mut e| e.read_to_string(&mut err));
            panic!("the viewer exited before showing water ({status}): {err}");
        }
        assert!(
            Instant::now() < deadline,
            "the viewer window did not show water within {STARTUP:?} (window {id:?}, blue fraction {blue:?})"
        );
        std::thread::sleep(Duration::from_millis(500));
    };
    (child, window)
}

#[test]
fn a_mouse_drag_turns_the_view_and_q_quits() {
    let Some(x) = start_xvfb(&["Xvfb", "xdotool", "import"]) else { return };
    let d = x.display.clone();
    let dir = tempfile::tempdir().unwrap();
    let (child, window) = open_viewer(&d, dir.path(), "sea", 0.8);
    // Without a window manager nobody gives the window the keyboard: do it, then pause with space
    // so that only the camera can change the picture.
    xdotool(&d, &["windowfocus", "--sync", &window]);
    xdotool(&d, &["mousemove", "640", "360"]);
    xdotool(&d, &["key", "space"]);
    std::thread::sleep(Duration::from_millis(1500));
    let before = capture(&d, &dir.path().join("before.png"));
    std::thread::sleep(Duration::from_millis(500));
    let still = capture(&d, &dir.path().join("still.png"));
    let noise = view_difference(&before, &still);
    assert!(noise < 0.5, "paused view still changes: {noise}");

    xdotool(&d, &["mousedown", "1"]);
    for k in 1..=10 {
        std::thread::sleep(Duration::from_millis(60));
        let (px, py) = (640 + 20 * k, 360 + 4 * k);
        xdotool(&d, &["mousemove", &px.to_string(), &py.to_string()]);
    }
    std::thread::sleep(Duration::from_millis(200));
    xdotool(&d, &["mouseup", "1"]);
    std::thread::sleep(Duration::from_millis(1500));
    let after = capture(&d, &dir.path().join("after.png"));
    let change = view_difference(&before, &after);
    assert!(change > 5.0, "a 200-pixel orbit drag changed the view by only {change:.2} per channel");
    assert!(blue_fraction(&after) > 0.5, "the turned view lost the water");

    xdotool(&d, &["key", "q"]);
    let out = wait_with_timeout(child, Duration::from_secs(30));
    assert!(out.status.success(), "viewer exit: {}", String::from_utf8_lossy(&out.stderr));
}

/// Whether the viewer process is still running.
fn alive(child: &mut Child) -> bool {
    child.try_wait().expect("child status").is_none()
}

#[test]
fn the_viewer_survives_resizing_to_nothing_minimising_and_rapid_changes() {
    let Some(x) = start_xvfb(&["Xvfb", "xdotool", "import"]) else { return };
    let d = x.display.clone();
    let dir = tempfile::tempdir().unwrap();
    let (mut child, window) = open_viewer(&d, dir.path(), "sea", 0.8);
    xdotool(&d, &["windowfocus", "--sync", &window]);
    // Shrink to a single pixel (X has no zero-sized windows; the view then gets 0 x 0 points
    // beside the fixed-width panel), and try zero anyway: xdotool may refuse it, the viewer must not care.
    xdotool(&d, &["windowsize", "--sync", &window, "1", "1"]);
    std::thread::sleep(Duration::from_millis(800));
    let _ = Command::new("xdotool").env("DISPLAY", &d).args(["windowsize", &window, "0", "0"]).status();
    std::thread::sleep(Duration::from_millis(800));
    assert!(alive(&mut child), "the viewer died at 1x1");
    // Minimise (iconify request) and hide the window entirely, then bring it back.
    let _ = Command::new("xdotool").env("DISPLAY", &d).args(["windowminimize", &window]).status();
    xdotool(&d, &["windowunmap", "--sync", &window]);
    std::thread::sleep(Duration::from_millis(800));
    xdotool(&d, &["windowmap", "--sync", &window]);
    assert!(alive(&mut child), "the viewer died while hidden");
    // Rapid resizes through odd sizes, interleaved with overlay and pause keys and wheel zooms.
    for (k, (w, h)) in
        [(300, 200), (1, 700), (1900, 1), (733, 411), (1711, 901), (2, 2), (1700, 800)].into_iter().enumerate()
    {
        xdotool(&d, &["windowsize", &window, &w.to_string(), &h.to_string()]);
        xdotool(&d, &["windowfocus", &window]);
        xdotool(&d, &["key", "--delay", "5", "t", "n", "space", "t", "n", "space"]);
        xdotool(
            &d,
            &["mousemove", "200", "200", "click", "--repeat", "5", "--delay", "5", if k % 2 == 0 { "4" } else { "5" }],
        );
        std::thread::sleep(Duration::from_millis(150));
    }
    std::thread::sleep(Duration::from_millis(2000));
    assert!(alive(&mut child), "the viewer died during rapid resizing");
    // Back at a normal size it still draws water.
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let b = blue_fraction(&capture(&d, &dir.path().join("back.png")));
        if b > 0.5 {
            break;
        }
        assert!(Instant::now() < deadline, "after resizing the view shows no water (blue fraction {b})");
        std::thread::sleep(Duration::from_millis(500));
    }
    xdotool(&d, &["windowfocus", "--sync", &window]);
    xdotool(&d, &["key", "q"]);
    let out = wait_with_timeout(child, Duration::from_secs(30));
    assert!(out.status.success(), "viewer exit: {}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn a_click_on_the_spring_mesh_drops_a_disturbance_there() {
    let Some(x) = start_xvfb(&["Xvfb", "xdotool", "import"]) else { return };
    let d = x.display.clone();
    let dir = tempfile::tempdir().unwrap();
    let (child, window) = open_viewer(&d, dir.path(), "springs", 0.2);
    xdotool(&d, &["windowfocus", "--sync", &window]);
    xdotool(&d, &["mousemove", "640", "560"]);
    xdotool(&d, &["key", "space"]);
    std::thread::sleep(Duration::from_millis(1500));
    let before = capture(&d, &dir.path().join("before.png"));
    xdotool(&d, &["click", "1"]);
    std::thread::sleep(Duration::from_millis(1500));
    let after = capture(&d, &dir.path().join("after.png"));
    // The dent changes pixels near the click and leaves the far corner of the view alone.
    let region = |img: &RgbaImage, x0: u32, y0: u32| {
        let mut v = Vec::new();
        for y in y0..y0 + 60 {
            for x in x0..x0 + 60 {
                v.extend_from_slice(&img.get_pixel(x, y).0[..3]);
            }
        }
        v
    };
    let diff = |a: &[u8], b: &[u8]| {
        a.iter().zip(b).map(|(p, q)| (*p as i32 - *q as i32).unsigned_abs() as u64).sum::<u64>() as f64 / a.len() as f64
    };
    let near = diff(&region(&before, 610, 530), &region(&after, 610, 530));
    let far = diff(&region(&before, 0, 0), &region(&after, 0, 0));
    assert!(near > 2.0, "the click changed the water under it by only {near:.2} per channel");
    assert!(far < 0.5, "the sky changed by {far:.2} per channel");
    xdotool(&d, &["key", "q"]);
    let out = wait_with_timeout(child, Duration::from_secs(30));
    assert!(out.status.success(), "viewer exit: {}", String::from_utf8_lossy(&out.stderr));
}

/// The summary `--exit-after-frames` prints: frames, fps, sim and render (ms).
fn summary(stderr: &str) -> (u32, f64, f64, f64) {
    let line = stderr.lines().find(|l| l.contains(" frames at ")).unwrap_or_else(|| panic!("no summary: {stderr}"));
    let number_before = |marker: &str| -> f64 {
        let head = &line[..line.find(marker).unwrap_or_else(|| panic!("no `{marker}` in {line}"))];
        head.trim_end()
            .rsplit(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap_or_else(|_| panic!("bad number before {marker}: {line}"))
    };
    let number_after = |marker: &str| -> f64 {
        let tail = &line[line.find(marker).unwrap_or_else(|| panic!("no `{marker}` in {line}")) + marker.len()..];
        tail.trim_start()
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap_or_else(|_| panic!("bad number after {marker}: {line}"))
    };
    let frames = number_before(" frames at ") as u32;
    (frames, number_before(" fps"), number_after("| sim "), number_after("| render "))
}

/// `--exit-after-frames 60` renders and shows exactly 60 frames, with or without a screenshot, and
/// the rate it reports is one the render thread can reach: frames are simulated and rendered one
/// after the other there, so no more than 1 / (sim + render) of them per second (issue 22: the
/// count was of UI repaints, 61 frames and more fps than that).
#[test]
fn exit_after_frames_counts_exactly_the_frames_rendered_and_shown() {
    let Some(x) = start_xvfb(&["Xvfb"]) else { return };
    let dir = tempfile::tempdir().unwrap();
    for screenshot in [false, true] {
        let shot = dir.path().join("ocean.png");
        let mut cmd = swell(&x.display);
        cmd.args(["view", "--preset", "ocean", "--exit-after-frames", "60"]);
        if screenshot {
            cmd.arg("--screenshot").arg(&shot);
        }
        let child = cmd.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
        let out = wait_with_timeout(child, STARTUP + Duration::from_secs(120));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "swell view failed: {stderr}");
        let (frames, fps, sim, render) = summary(&stderr);
        eprintln!("ocean, screenshot {screenshot}: {}", stderr.lines().last().unwrap_or(""));
        assert_eq!(frames, 60, "screenshot {screenshot}: {stderr}");
        let ceiling = 1000.0 / (sim + render);
        assert!(fps <= ceiling * 1.05, "{fps} fps reported, but sim + render allow at most {ceiling:.1}: {stderr}");
        assert!(fps > 0.0, "{stderr}");
        assert_eq!(shot.exists(), screenshot);
    }
}

/// Runs `swell view ARGS` in `dir` without a display (nothing may get as far as a window).
fn view_refused(dir: &Path, args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_swell"))
        .current_dir(dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .arg("view")
        .args(args)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success(), "swell view {args:?} was accepted: {stderr}");
    stderr
}

/// Hostile values of the viewer's flags: each is refused before any window or file, with a
/// message naming the flag (and, for `--screenshot`, the value and the valid choice).
#[test]
fn hostile_viewer_flags_are_refused_by_name_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("folder.png")).unwrap();
    let cases: &[(&[&str], &str, &[&str])] = &[
        (&["--exit-after-frames", "0"], "--exit-after-frames", &["0", "[1, 4294967295]"]),
        // `--exit-after-frames -3` (a space) is clap's "unexpected argument '-3'", before the flag
        // is known; with `=` the value reaches the flag.
        (&["--exit-after-frames=-3"], "--exit-after-frames", &["-3"]),
        (&["--exit-after-frames", "lots"], "--exit-after-frames", &["lots"]),
        (&["--exit-after-frames", "99999999999"], "--exit-after-frames", &["99999999999"]),
        (&["--exit-after-frames", ""], "--exit-after-frames", &[]),
        (&["--screenshot", "shot.jpg", "--exit-after-frames", "5"], "--screenshot", &["shot.jpg", ".png"]),
        (&["--screenshot", "shot.PNG.gif", "--exit-after-frames", "5"], "--screenshot", &["shot.PNG.gif", ".png"]),
        (&["--screenshot", "shot", "--exit-after-frames", "5"], "--screenshot", &["shot", ".png"]),
        (&["--screenshot", "", "--exit-after-frames", "5"], "--screenshot", &[]),
        (&["--screenshot", "no/such/dir/shot.png", "--exit-after-frames", "5"], "--screenshot", &["no/such/dir"]),
        (&["--screenshot", "folder.png", "--exit-after-frames", "5"], "--screenshot", &["folder.png", "directory"]),
        (&["--screenshot", "shot.png"], "--exit-after-frames", &[]),
        (&["--screenshot", "shot.png", "--exit-after-frames", "0"], "--exit-after-frames", &["0"]),
    ];
    for (args, flag, also) in cases {
        let mut full = vec!["--preset", "sea"];
        full.extend_from_slice(args);
        let stderr = view_refused(dir.path(), &full);
        assert!(stderr.contains(flag), "{args:?}: the message does not name {flag}: {stderr}");
        for a in *also {
            assert!(stderr.contains(a), "{args:?}: the message does not say `{a}`: {stderr}");
        }
        assert!(!stderr.contains("DISPLAY"), "{args:?} got as far as opening a window: {stderr}");
        let mut left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
        left.retain(|n| n != "folder.png");
        assert!(left.is_empty(), "{args:?} left {left:?} behind");
    }
}
