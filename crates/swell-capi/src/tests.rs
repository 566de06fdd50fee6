//! The entry points called as C would call them: results, errors and messages, agreement with
//! the library.

use std::ffi::CString;
use std::ptr::{null, null_mut};

use super::*;
use swell_lib::scene::preset;

fn last_error() -> String {
    // SAFETY: swell_last_error_message never returns NULL.
    unsafe { CStr::from_ptr(swell_last_error_message()) }.to_str().unwrap().to_string()
}

/// The `sea` preset with a small grid, as TOML text.
fn sea_text(cells: u32) -> CString {
    let mut s = preset("sea").unwrap();
    s.water.as_mut().unwrap().surface.cells = [cells, cells];
    (s.render.width, s.render.height) = (64, 36);
    CString::new(s.to_toml()).unwrap()
}

fn water(text: &CString) -> *mut SwellWater {
    let mut w = null_mut();
    assert_eq!(unsafe { swell_water_from_toml(text.as_ptr(), &mut w) }, SwellResult::Ok, "{}", last_error());
    w
}

#[test]
fn the_version_is_the_crate_s() {
    let v = unsafe { CStr::from_ptr(swell_version()) };
    assert_eq!(v.to_str().unwrap(), env!("CARGO_PKG_VERSION"));
}

#[test]
fn displaced_grid_and_heights_equal_the_library_s() {
    let text = sea_text(8);
    let w = water(&text);
    let (mut rows, mut cols) = (0, 0);
    assert_eq!(unsafe { swell_water_grid_size(w, &mut rows, &mut cols) }, SwellResult::Ok);
    assert_eq!((rows, cols), (9, 9));
    let n = rows * cols;
    let (mut p, mut q) = (vec![0.0f32; 3 * n], vec![0.0f32; 3 * n]);
    let r = unsafe { swell_water_displace(w, 1.5, p.as_mut_ptr(), p.len(), q.as_mut_ptr(), q.len()) };
    assert_eq!(r, SwellResult::Ok);
    let mut lib = Water::from_toml(text.to_str().unwrap(), "t").unwrap();
    let (mut lp, mut lq) = (vec![Vec3::ZERO; n], vec![Vec3::ZERO; n]);
    lib.displace(1.5, &mut lp, &mut lq).unwrap();
    let flat = |v: &[Vec3]| v.iter().flat_map(|v| v.to_array()).collect::<Vec<f32>>();
    assert_eq!((p, q), (flat(&lp), flat(&lq)));
    let xz = [1.0f32, 2.0, -3.0, 4.5];
    let mut h = [0.0f32; 2];
    let r = unsafe { swell_water_heights(w, 1.5, xz.as_ptr(), 4, h.as_mut_ptr(), 2) };
    assert_eq!(r, SwellResult::Ok);
    assert_eq!(h[1], lib.height_at(-3.0, 4.5, 1.5).unwrap());
    let mut nrm = [0.0f32; 6];
    let r = unsafe { swell_water_normals(w, 1.5, xz.as_ptr(), 4, nrm.as_mut_ptr(), 6) };
    assert_eq!(r, SwellResult::Ok);
    assert!(nrm[1] > 0.5 && nrm[4] > 0.5, "{nrm:?}");
    let mut foam = vec![7.0f32; n];
    let mut has = true;
    let r = unsafe { swell_water_foam(w, 1.5, foam.as_mut_ptr(), n, &mut has) };
    assert_eq!((r, has), (SwellResult::Ok, false));
    assert!(foam.iter().all(|f| *f == 7.0));
    unsafe { swell_water_destroy(w) };
}

#[test]
fn every_bad_input_is_a_code_and_a_message_naming_the_parameter() {
    let text = sea_text(4);
    let w = water(&text);
    let mut buf = vec![0.0f32; 75];
    let cases: Vec<(SwellResult, SwellResult, &str)> = unsafe {
        vec![
            (
                swell_water_displace(w, 0.0, buf.as_mut_ptr(), 74, buf.as_mut_ptr(), 75),
                SwellResult::InvalidArgument,
                "positions_len: 74; must be 75 (3 floats per vertex x 5 rows x 5 columns)",
            ),
            (
                swell_water_displace(w, f64::NAN, buf.as_mut_ptr(), 75, buf.as_mut_ptr(), 75),
                SwellResult::InvalidArgument,
                "t = NaN is outside finite seconds",
            ),
            (
                swell_water_displace(null_mut(), 0.0, buf.as_mut_ptr(), 75, buf.as_mut_ptr(), 75),
                SwellResult::NullPointer,
                "water: is NULL",
            ),
            (
                swell_water_displace(w, 0.0, null_mut(), 75, buf.as_mut_ptr(), 75),
                SwellResult::NullPointer,
                "positions: is NULL",
            ),
            (
                swell_water_heights(w, 0.0, buf.as_ptr(), 3, buf.as_mut_ptr(), 1),
                SwellResult::InvalidArgument,
                "xz_len: 3; must be even (pairs of x, z)",
            ),
            (
                swell_water_heights(w, 0.0, buf.as_ptr(), 4, buf.as_mut_ptr(), 3),
                SwellResult::InvalidArgument,
                "heights_len: 3; must be 2 (one height per (x, z) pair: xz_len / 2)",
            ),
            (
                swell_water_normals(w, 0.0, buf.as_ptr(), 4, buf.as_mut_ptr(), 3),
                SwellResult::InvalidArgument,
                "normals_len: 3; must be 6 (3 floats per (x, z) pair: 3 * xz_len / 2)",
            ),
            (swell_water_foam(w, 0.0, buf.as_mut_ptr(), 24, null_mut()), SwellResult::NullPointer, "has_foam: is NULL"),
            (swell_water_grid_size(w, null_mut(), null_mut()), SwellResult::NullPointer, "rows: is NULL"),
        ]
    };
    for (got, code, message) in cases {
        assert_eq!(got, code, "{message}");
        // Each failure set the message; check the last one below and each code here.
    }
    // Messages, one call at a time.
    let r = unsafe { swell_water_heights(w, 0.0, buf.as_ptr(), 4, buf.as_mut_ptr(), 3) };
    assert_eq!(r, SwellResult::InvalidArgument);
    assert_eq!(last_error(), "heights_len: 3; must be 2 (one height per (x, z) pair: xz_len / 2)");
    let r = unsafe { swell_water_displace(w, f64::INFINITY, buf.as_mut_ptr(), 75, buf.as_mut_ptr(), 75) };
    assert_eq!(r, SwellResult::InvalidArgument);
    assert_eq!(last_error(), "t = inf is outside finite seconds");
    // A success leaves the message alone.
    let mut other = vec![0.0f32; 75];
    let r = unsafe { swell_water_displace(w, 0.0, buf.as_mut_ptr(), 75, other.as_mut_ptr(), 75) };
    assert_eq!(r, SwellResult::Ok);
    assert_eq!(last_error(), "t = inf is outside finite seconds");
    unsafe { swell_water_destroy(w) };
    unsafe { swell_water_destroy(null_mut()) };
}

#[test]
fn bad_scenes_are_scene_errors_with_the_cli_s_message() {
    let mut out = null_mut();
    let bad = CString::new(
        "version = 1\n[camera]\neye = [0.0, 5.0, 10.0]\ntarget = [0.0, 0.0, 0.0]\n\
         [water]\nmodel = 'gerstner'\n[[water.waves]]\namplitude = 1.0\nwavelength = 10.0\nspeed = 3.0\n\
         direction = [1.0, 0.0]\nsteepness = 1.7\n",
    )
    .unwrap();
    assert_eq!(unsafe { swell_water_from_toml(bad.as_ptr(), &mut out) }, SwellResult::Scene);
    assert!(out.is_null());
    assert_eq!(last_error(), "toml: water.waves[0].steepness = 1.7 is outside [0, 1]");
    let syntax = CString::new("version = 1\n[camera\n").unwrap();
    assert_eq!(unsafe { swell_water_from_toml(syntax.as_ptr(), &mut out) }, SwellResult::Scene);
    assert!(last_error().starts_with("toml: TOML parse error"), "{}", last_error());
    assert_eq!(unsafe { swell_water_from_toml(null(), &mut out) }, SwellResult::NullPointer);
    assert_eq!(last_error(), "toml: is NULL");
    let not_utf8 = [0xffu8, 0xfe, 0];
    assert_eq!(
        unsafe { swell_scene_from_toml(not_utf8.as_ptr().cast(), &mut out.cast()) },
        SwellResult::InvalidArgument
    );
    assert!(last_error().starts_with("toml: is not UTF-8 text"), "{}", last_error());
    let sea = sea_text(4);
    assert_eq!(unsafe { swell_scene_from_toml(sea.as_ptr(), null_mut()) }, SwellResult::NullPointer);
    assert_eq!(last_error(), "out: is NULL");
}

#[test]
fn a_rendered_frame_is_the_library_s() {
    let text = sea_text(16);
    let mut scene = null_mut();
    assert_eq!(unsafe { swell_scene_from_toml(text.as_ptr(), &mut scene) }, SwellResult::Ok);
    let (mut w, mut h) = (0, 0);
    assert_eq!(unsafe { swell_scene_image_size(scene, &mut w, &mut h) }, SwellResult::Ok);
    assert_eq!((w, h), (64, 36));
    let mut rgba = vec![0u8; 4 * 64 * 36];
    assert_eq!(unsafe { swell_scene_render_rgba8(scene, 2.0, rgba.as_mut_ptr(), rgba.len()) }, SwellResult::Ok);
    let mut world = World::new(Scene::from_toml(text.to_str().unwrap(), "t").unwrap()).unwrap();
    world.update(2.0).unwrap();
    let mut expected = Vec::new();
    let r = world.scene.render;
    Renderer::new().render(&world).encode_rgba8(&r.display_encoding(), &mut expected);
    assert_eq!(rgba, expected);
    let r = unsafe { swell_scene_render_rgba8(scene, 2.0, rgba.as_mut_ptr(), rgba.len() - 1) };
    assert_eq!(r, SwellResult::InvalidArgument);
    assert_eq!(last_error(), "rgba_len: 9215; must be 9216 (4 bytes x 64 x 36 pixels)");
    unsafe { swell_scene_destroy(scene) };
}

#[test]
fn a_panic_inside_becomes_a_code_not_an_unwind() {
    let r = guard(|| panic!("boom"));
    assert_eq!(r, SwellResult::Panic);
    assert!(last_error().ends_with("boom"), "{}", last_error());
}

#[test]
fn the_message_is_per_thread() {
    set_last_error("main thread");
    std::thread::spawn(|| {
        assert_eq!(last_error(), "");
        set_last_error("other thread");
    })
    .join()
    .unwrap();
    assert_eq!(last_error(), "main thread");
}

/// Issue 37: a NaN or infinite coordinate is an argument error naming `xz[k]`, never calm water,
/// and nothing is written.
#[test]
fn non_finite_points_are_refused_naming_the_coordinate() {
    let text = sea_text(4);
    let w = water(&text);
    for (k, bad) in [(1, f32::NAN), (2, f32::INFINITY), (3, f32::NEG_INFINITY)] {
        let mut xz = [1.0f32, 2.0, -3.0, 4.5];
        xz[k] = bad;
        let mut h = [7.0f32; 2];
        let r = unsafe { swell_water_heights(w, 0.5, xz.as_ptr(), 4, h.as_mut_ptr(), 2) };
        assert_eq!(r, SwellResult::InvalidArgument);
        assert_eq!(last_error(), format!("xz[{k}]: {bad} is not a finite coordinate (world metres)"));
        assert_eq!(h, [7.0; 2]);
        let mut n = [7.0f32; 6];
        let r = unsafe { swell_water_normals(w, 0.5, xz.as_ptr(), 4, n.as_mut_ptr(), 6) };
        assert_eq!(r, SwellResult::InvalidArgument);
        assert!(last_error().starts_with(&format!("xz[{k}]: ")), "{}", last_error());
        assert_eq!(n, [7.0; 6]);
    }
    unsafe { swell_water_destroy(w) };
}

/// Issue 37: the last error escapes control characters (NUL among them) and bidi marks, and
/// cuts an overlong key, as the CLI prints it.
#[test]
fn the_last_error_escapes_hostile_text_and_cuts_it() {
    let hostile = CString::new("[water]\nmodel = 'sines'\n\"w\u{1b}]0;pwned\u{7}\u{202e}\" = 1\n").unwrap();
    let mut out = null_mut();
    assert_eq!(unsafe { swell_water_from_toml(hostile.as_ptr(), &mut out) }, SwellResult::Scene);
    let e = last_error();
    assert!(!e.contains('\u{1b}') && !e.contains('\u{7}') && !e.contains('\u{202e}'), "{e}");
    assert!(e.contains("\\u{1b}"), "{e}");
    let long = CString::new(format!("[water]\nmodel = 'sines'\n{} = 1\n", "k".repeat(100_000))).unwrap();
    assert_eq!(unsafe { swell_water_from_toml(long.as_ptr(), &mut out) }, SwellResult::Scene);
    let e = last_error();
    assert!(e.len() < 4000 && e.contains("characters in all)"), "{} bytes", e.len());
}

/// Counts calls through `user_data` and stops the third.
unsafe extern "C" fn stop_at_the_third(fraction: f64, user_data: *mut c_void) -> c_int {
    let seen = unsafe { &*user_data.cast::<Mutex<Vec<f64>>>() };
    let mut seen = lock(seen);
    seen.push(fraction);
    c_int::from(seen.len() >= 3)
}

/// A spring mesh asked far ahead reports progress and stops when the callback says so
/// (`SWELL_RESULT_CANCELLED`); asked again without it, it finishes to the answer of a handle never
/// stopped (issue 37).
#[test]
fn a_progress_callback_sees_long_calls_and_can_cancel_them() {
    let mut s = preset("springs").unwrap();
    s.water.as_mut().unwrap().surface.cells = [8, 8];
    let text = CString::new(s.to_toml()).unwrap();
    let (w, plain) = (water(&text), water(&text));
    let seen = Mutex::new(Vec::<f64>::new());
    let user = (&seen as *const Mutex<Vec<f64>>).cast_mut().cast::<c_void>();
    assert_eq!(unsafe { swell_water_set_progress(w, Some(stop_at_the_third), user) }, SwellResult::Ok);
    // 1000 steps of 0.4 s on a 129² lattice: some 16 parts.
    let (t, xz) = (400.0, [1.0f32, 2.0]);
    let mut h = [0.0f32];
    let r = unsafe { swell_water_heights(w, t, xz.as_ptr(), 2, h.as_mut_ptr(), 1) };
    assert_eq!(r, SwellResult::Cancelled, "{}", last_error());
    assert!(last_error().starts_with("cancelled: stopped at the caller's request"), "{}", last_error());
    assert_eq!(lock(&seen).len(), 3);
    assert_eq!(unsafe { swell_water_set_progress(w, None, null_mut()) }, SwellResult::Ok);
    let mut expected = [0.0f32];
    assert_eq!(unsafe { swell_water_heights(plain, t, xz.as_ptr(), 2, expected.as_mut_ptr(), 1) }, SwellResult::Ok);
    assert_eq!(unsafe { swell_water_heights(w, t, xz.as_ptr(), 2, h.as_mut_ptr(), 1) }, SwellResult::Ok);
    assert_eq!(h, expected);
    assert_eq!(unsafe { swell_water_set_progress(null_mut(), None, null_mut()) }, SwellResult::NullPointer);
    unsafe { (swell_water_destroy(w), swell_water_destroy(plain)) };
}

/// Threads of this process, from /proc (Linux).
fn threads() -> usize {
    std::fs::read_dir("/proc/self/task").map_or(0, |d| d.count())
}

/// Many handles share one pool: 40 handles add at most one thread per core (issue 37: each handle
/// used to start its own pool, 80 threads here). That the pool's threads end with the last handle
/// is valgrind's check on the C examples (no thread left behind).
#[test]
fn forty_handles_share_one_pool() {
    if !std::path::Path::new("/proc/self/task").is_dir() {
        return;
    }
    // Other tests run beside this one and hold handles of their own: serialise through a lock.
    let _one_at_a_time = lock(&POOL_TEST);
    let text = sea_text(4);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let before = threads();
    let handles: Vec<_> = (0..40).map(|_| water(&text)).collect();
    let during = threads();
    assert!(during <= before + cores + 2, "{before} threads before, {during} with 40 handles ({cores} cores)");
    let mut h = [0.0f32];
    for &w in &handles {
        assert_eq!(
            unsafe { swell_water_heights(w, 1.0, [0.0f32, 0.0].as_ptr(), 2, h.as_mut_ptr(), 1) },
            SwellResult::Ok
        );
    }
    for w in handles {
        unsafe { swell_water_destroy(w) };
    }
}

static POOL_TEST: Mutex<()> = Mutex::new(());

/// Off a finite patch there is no water: the mask says 0 and heights and normals are NaN
/// (issue 37), where an unbounded sea covers every point.
#[test]
fn points_off_finite_water_are_masked_and_nan() {
    for (name, finite) in [("pool", true), ("sea", false)] {
        let mut s = preset(name).unwrap();
        s.water.as_mut().unwrap().surface.cells = [8, 8];
        let text = CString::new(s.to_toml()).unwrap();
        let w = water(&text);
        let c = s.water.as_ref().unwrap().surface.center;
        let xz = [c.x, c.y, 1.0e5, -2.0e4];
        let (mut mask, mut h, mut n) = ([9u8; 2], [0.0f32; 2], [0.0f32; 6]);
        assert_eq!(unsafe { swell_water_coverage(w, xz.as_ptr(), 4, mask.as_mut_ptr(), 2) }, SwellResult::Ok);
        assert_eq!(mask, [1, u8::from(!finite)], "{name}");
        assert_eq!(unsafe { swell_water_heights(w, 1.0, xz.as_ptr(), 4, h.as_mut_ptr(), 2) }, SwellResult::Ok);
        assert_eq!(unsafe { swell_water_normals(w, 1.0, xz.as_ptr(), 4, n.as_mut_ptr(), 6) }, SwellResult::Ok);
        assert!(h[0].is_finite() && n[..3].iter().all(|v| v.is_finite()), "{name}");
        assert_eq!(h[1].is_nan(), finite, "{name}");
        assert!(n[3..].iter().all(|v| v.is_nan() == finite), "{name}");
        assert_eq!(
            unsafe { swell_water_coverage(w, xz.as_ptr(), 4, mask.as_mut_ptr(), 3) },
            SwellResult::InvalidArgument
        );
        assert!(last_error().starts_with("mask_len: 3; must be 2"), "{}", last_error());
        unsafe { swell_water_destroy(w) };
    }
}

/// Issue 37: a scene naming a FIFO that no process writes to (a heightmap, a water texture) is
/// refused at once with `SwellResult::Scene` and a message naming the FIFO; a plain open would
/// block the caller for good, beyond the reach of any signal handler of the host program.
#[cfg(unix)]
#[test]
fn a_fifo_without_a_writer_is_an_error_at_once_not_a_hang() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("map.png");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let sea = "version = 1\n[camera]\neye = [0.0, 6.0, 14.0]\ntarget = [0.0, 0.0, 0.0]\n[render]\nwidth = 16\n\
               height = 9\n[water]\nmodel = 'sines'\ncells = [8, 8]\n[[water.waves]]\namplitude = 0.3\n\
               wavelength = 8.0\nspeed = 3.0\ndirection = [1.0, 0.0]\n";
    let f = fifo.display();
    let scenes = [
        format!("{sea}[terrain]\ngenerator = 'heightmap'\npath = '{f}'\nheight_scale = 2.0\n"),
        format!("{sea}[water.material]\ntexture = '{f}'\n"),
    ];
    for text in scenes {
        // On another thread, so that a hang fails the test instead of blocking the run.
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let toml = CString::new(text).unwrap();
            let mut scene = null_mut();
            let r = unsafe { swell_scene_from_toml(toml.as_ptr(), &mut scene) };
            tx.send((r, scene.is_null(), last_error())).unwrap();
        });
        let (r, null, message) = rx.recv_timeout(std::time::Duration::from_secs(30)).expect("blocked on the FIFO");
        assert_eq!(r, SwellResult::Scene, "{message}");
        assert!(null);
        assert!(message.contains(&format!("{f}: is a FIFO or pipe that no process writes to")), "{message}");
    }
}

/// Issue 37: the double variants refuse what the float ones refuse, name the bad coordinate, mask
/// and NaN points off finite water, and answer as the library's `_f64` queries do.
#[test]
fn double_variants_check_as_the_float_ones_and_answer_as_the_library() {
    let mut s = preset("pool").unwrap();
    s.water.as_mut().unwrap().surface.cells = [8, 8];
    let text = CString::new(s.to_toml()).unwrap();
    let w = water(&text);
    let c = s.water.as_ref().unwrap().surface.center.as_dvec2();
    let xz = [c.x, c.y, 1.0e6, -2.0e4];
    let (mut mask, mut h, mut n) = ([9u8; 2], [0.0f64; 2], [0.0f64; 6]);
    assert_eq!(unsafe { swell_water_coverage_f64(w, xz.as_ptr(), 4, mask.as_mut_ptr(), 2) }, SwellResult::Ok);
    assert_eq!(mask, [1, 0]);
    assert_eq!(unsafe { swell_water_heights_f64(w, 1.0, xz.as_ptr(), 4, h.as_mut_ptr(), 2) }, SwellResult::Ok);
    assert_eq!(unsafe { swell_water_normals_f64(w, 1.0, xz.as_ptr(), 4, n.as_mut_ptr(), 6) }, SwellResult::Ok);
    let mut lib = Water::from_toml(&s.to_toml(), "test").unwrap();
    let mut expected = [0.0f64; 2];
    lib.heights_at_f64(1.0, &[glam::DVec2::new(c.x, c.y), glam::DVec2::new(1.0e6, -2.0e4)], &mut expected).unwrap();
    assert_eq!(h[0], expected[0]);
    assert!(h[1].is_nan() && n[3..].iter().all(|v| v.is_nan()) && n[..3].iter().all(|v| v.is_finite()));
    // A NaN coordinate is named by its index in the flat array, the output left as it was.
    let bad = [0.0, 0.0, 1.0, f64::NAN];
    h = [7.0; 2];
    assert_eq!(
        unsafe { swell_water_heights_f64(w, 1.0, bad.as_ptr(), 4, h.as_mut_ptr(), 2) },
        SwellResult::InvalidArgument
    );
    assert!(last_error().starts_with("xz[3]: NaN is not a finite coordinate"), "{}", last_error());
    assert_eq!(h, [7.0; 2]);
    // Finite, but past the models' arithmetic.
    let far = [0.0, 0.0, 1.0, 2.0e196];
    assert_eq!(
        unsafe { swell_water_heights_f64(w, 1.0, far.as_ptr(), 4, h.as_mut_ptr(), 2) },
        SwellResult::InvalidArgument
    );
    assert!(last_error().starts_with("xz[3]: 2e196 m is farther than 1e9 m from the origin"), "{}", last_error());
    assert_eq!(
        unsafe { swell_water_normals_f64(w, 1.0, bad.as_ptr(), 3, n.as_mut_ptr(), 3) },
        SwellResult::InvalidArgument
    );
    assert!(last_error().starts_with("xz_len: 3; must be even"), "{}", last_error());
    assert_eq!(
        unsafe { swell_water_coverage_f64(w, bad.as_ptr(), 4, mask.as_mut_ptr(), 2) },
        SwellResult::InvalidArgument
    );
    unsafe { swell_water_destroy(w) };
}

/// Issue 36 from C: a measured sea written in the scene text (`spectrum = "table"`) is the same
/// water as the library's, and a bad table is a scene error naming the field.
#[test]
fn a_measured_sea_in_the_scene_text_is_the_library_s() {
    let table = "[water]\nmodel = 'fft'\nspectrum = 'table'\ngrid = 32\npatch_size = 400.0\nsize = [40.0, 40.0]\ncells = [8, 8]\n\
                 [[water.spectrum_table]]\nfreq_hz = [0.06, 0.1, 0.15, 0.25]\ndir_deg = [0.0, 90.0, 180.0, 270.0]\n\
                 efth = [[0.0, 0.0, 0.0, 0.0], [0.5, 2.0, 0.5, 0.0], [0.1, 0.4, 0.1, 0.0], [0.0, 0.0, 0.0, 0.0]]\n";
    let text = CString::new(table).unwrap();
    let w = water(&text);
    let xz = [3.0f32, -7.0];
    let mut h = [0.0f32; 1];
    assert_eq!(unsafe { swell_water_heights(w, 2.0, xz.as_ptr(), 2, h.as_mut_ptr(), 1) }, SwellResult::Ok);
    let mut lib = Water::from_toml(table, "t").unwrap();
    assert_eq!(h[0], lib.height_at(3.0, -7.0, 2.0).unwrap());
    assert!(h[0].abs() > 0.0 && h[0].abs() < 5.0, "{h:?}");
    unsafe { swell_water_destroy(w) };
    let bad = CString::new(table.replace("[0.5, 2.0", "[-0.5, 2.0")).unwrap();
    let mut out = null_mut();
    assert_eq!(unsafe { swell_water_from_toml(bad.as_ptr(), &mut out) }, SwellResult::Scene);
    assert!(last_error().contains("water.spectrum_table[0].efth[1][0] = -0.5 is outside [0, "), "{}", last_error());
}
