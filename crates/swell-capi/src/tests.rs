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

// Floating bodies (issue 34).

/// A sines sea (1000 kg/m³) with a crate of pine, a buoy and a falling log, over a patch of
/// 40 m: the scene of the bodies' tests and of the Python package's reference poses.
const BODIES_SCENE: &str = "version = 1\n\
[water]\nmodel = 'sines'\nsize = [40.0, 40.0]\ncells = [16, 16]\ndensity = 1000.0\n\
[[water.waves]]\namplitude = 0.2\nwavelength = 12.0\nspeed = 4.3\ndirection = [1.0, 0.2]\n\
[[body]]\nname = 'crate'\nshape = 'box'\nsize = [1.0, 0.5, 2.0]\ndensity = 500.0\nposition = [0.0, 0.3, 0.0]\nrotation_deg = [20.0, 0.0, 0.0]\n\
[[body]]\nname = 'buoy'\nshape = 'sphere'\nsize = [0.4]\nmass = 40.0\nposition = [-4.0, 0.5, 2.0]\n\
[[body]]\nname = 'log'\nshape = 'capsule'\nsize = [0.25, 2.0]\nposition = [3.0, 1.0, -1.0]\nvelocity = [0.0, -1.0, 0.0]\n";

fn scene(text: &str) -> *mut SwellScene {
    let text = CString::new(text).unwrap();
    let mut s = null_mut();
    assert_eq!(unsafe { swell_scene_from_toml(text.as_ptr(), &mut s) }, SwellResult::Ok, "{}", last_error());
    s
}

fn body_count(s: *const SwellScene) -> usize {
    let mut n = usize::MAX;
    assert_eq!(unsafe { swell_scene_body_count(s, &mut n) }, SwellResult::Ok, "{}", last_error());
    n
}

/// Every body's position and rotation at `t` through the C entry point, flat.
fn c_poses(s: *mut SwellScene, t: f64) -> (Vec<f64>, Vec<f64>) {
    let n = body_count(s);
    let (mut p, mut r) = (vec![f64::NAN; 3 * n], vec![f64::NAN; 4 * n]);
    let code = unsafe { swell_scene_body_poses(s, t, p.as_mut_ptr(), p.len(), r.as_mut_ptr(), r.len()) };
    assert_eq!(code, SwellResult::Ok, "{}", last_error());
    (p, r)
}

/// The library's poses after `World::update(t)`, flat as C has them.
fn world_poses(w: &mut World, t: f64) -> (Vec<f64>, Vec<f64>) {
    w.update(t).unwrap();
    let p = w.body_poses().iter().flat_map(|p| p.position.to_array()).collect();
    let r = w.body_poses().iter().flat_map(|p| p.rotation.to_array()).collect();
    (p, r)
}

fn c_name(s: *const SwellScene, k: usize) -> String {
    let mut size = 0;
    assert_eq!(unsafe { swell_scene_body_name(s, k, null_mut(), 0, &mut size) }, SwellResult::Ok);
    let mut buf = vec![0x55u8; size];
    let r = unsafe { swell_scene_body_name(s, k, buf.as_mut_ptr().cast(), buf.len(), &mut size) };
    assert_eq!(r, SwellResult::Ok, "{}", last_error());
    CStr::from_bytes_with_nul(&buf).unwrap().to_str().unwrap().to_string()
}

#[test]
fn body_poses_from_c_are_the_world_s_however_the_time_is_reached() {
    let s = scene(BODIES_SCENE);
    assert_eq!(body_count(s), 3);
    assert_eq!((0..3).map(|k| c_name(s, k)).collect::<Vec<_>>(), ["crate", "buoy", "log"]);
    let mut k = usize::MAX;
    let log = CString::new("log").unwrap();
    assert_eq!(unsafe { swell_scene_body_index(s, log.as_ptr(), &mut k) }, SwellResult::Ok);
    assert_eq!(k, 2);
    let mut world = World::new(Scene::from_toml(BODIES_SCENE, "t").unwrap()).unwrap();
    // Straight to 2.5 s, at t = 0, and back to an earlier time (a replay from t = 0).
    for t in [2.5, 0.0, 1.2345] {
        assert_eq!(c_poses(s, t), world_poses(&mut world, t), "t = {t}");
    }
    // 60 fps steps through swell_scene_advance on a second handle reach the same numbers.
    let stepped = scene(BODIES_SCENE);
    for f in 0..=150 {
        assert_eq!(unsafe { swell_scene_advance(stepped, f64::from(f) / 60.0) }, SwellResult::Ok);
    }
    assert_eq!(c_poses(stepped, 2.5), c_poses(s, 2.5));
    let (p, r) = c_poses(s, 2.5);
    // The quaternions are unit and the bodies afloat near the water at rest.
    for (pos, q) in p.chunks(3).zip(r.chunks(4)) {
        assert!((q.iter().map(|v| v * v).sum::<f64>().sqrt() - 1.0).abs() < 1e-9, "{q:?}");
        assert!(pos[1].abs() < 0.6, "{pos:?}");
    }
    // Rendering moves the same world: the poses at the render's time are unchanged by it.
    let (mut width, mut height) = (0, 0);
    assert_eq!(unsafe { swell_scene_image_size(s, &mut width, &mut height) }, SwellResult::Ok);
    let mut rgba = vec![0u8; 4 * width as usize * height as usize];
    assert_eq!(unsafe { swell_scene_render_rgba8(s, 2.5, rgba.as_mut_ptr(), rgba.len()) }, SwellResult::Ok);
    assert_eq!(c_poses(s, 2.5), world_poses(&mut world, 2.5));
    unsafe { (swell_scene_destroy(s), swell_scene_destroy(stepped)) };
}

#[test]
fn a_scene_without_bodies_has_none_and_takes_one_at_its_time() {
    let s = scene(sea_text(4).to_str().unwrap());
    assert_eq!(body_count(s), 0);
    let (mut p, mut r) = ([7.0f64; 1], [7.0f64; 1]);
    assert_eq!(unsafe { swell_scene_body_poses(s, 1.0, p.as_mut_ptr(), 0, r.as_mut_ptr(), 0) }, SwellResult::Ok);
    assert_eq!((p, r), ([7.0], [7.0]));
    let mut size = 0;
    let code = unsafe { swell_scene_body_name(s, 0, null_mut(), 0, &mut size) };
    assert_eq!((code, last_error().as_str()), (SwellResult::InvalidArgument, "index: 0; the scene has no bodies"));
    // A body added at t = 3 s is dropped then, not at t = 0 (a world without bodies still counts their steps).
    assert_eq!(unsafe { swell_scene_advance(s, 3.0) }, SwellResult::Ok);
    let (shape, size) = (CString::new("box").unwrap(), [2.0, 0.5, 2.0]);
    let r =
        unsafe { swell_scene_add_body(s, null(), shape.as_ptr(), size.as_ptr(), 3, 500.0, 0.0, 2.0, 0.0, null_mut()) };
    assert_eq!(r, SwellResult::Ok, "{}", last_error());
    assert_eq!(c_poses(s, 3.0), (vec![0.0, 2.0, 0.0], vec![0.0, 0.0, 0.0, 1.0]));
    // About g t² / 2 = 0.2 m fallen in 0.2 s, not three seconds' worth.
    let y = c_poses(s, 3.2).0[1];
    assert!((1.7..1.85).contains(&y), "{y}");
    unsafe { swell_scene_destroy(s) };
}

/// The body the reference protocol adds from TOML (at `ADD_FRAME`) and the one it adds from
/// parameters (`BALL_*`, at the same frame), and the thrust it then gives the crate.
const ADDED_BODY: &str = "[[body]]\nname = 'barrel'\nshape = 'capsule'\nsize = [0.3, 0.8]\ndensity = 400.0\n\
                          position = [1.0, 1.5, 3.0]\nrotation_deg = [0.0, 0.0, 90.0]\n";
const BALL_SIZE: f64 = 0.3;
const BALL_DENSITY: f64 = 300.0;
const BALL_POSITION: [f64; 3] = [-1.0, 2.0, 0.5];
const THRUST: [f64; 3] = [300.0, 0.0, -50.0];
/// Frames at 60 fps: the bodies are added at frame `ADD_FRAME` (1 s), the thrust set at
/// `THRUST_FRAME`, and every `RECORD_EVERY`th frame's poses kept, up to `LAST_FRAME` (3 s).
const ADD_FRAME: u32 = 60;
const THRUST_FRAME: u32 = 90;
const RECORD_EVERY: u32 = 15;
const LAST_FRAME: u32 = 180;

/// `text` as a JSON string.
fn json_string(text: &str) -> String {
    let mut out = String::from('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Numbers as a JSON array: `{:?}` writes the shortest decimal that reads back to the same f64
/// (Python's `json` reads it so), in a form JSON accepts (`0.5`, `1e-7`, `-0.0`).
fn json_numbers(v: &[f64]) -> String {
    format!("[{}]", v.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(", "))
}

/// The reference protocol run through the C entry points and, beside it, through the library's
/// `World` (bodies added into the running scene from TOML and from parameters, a thrust, 60 fps
/// steps): every frame's poses must agree bit for bit. Its records are the reference the Python
/// package's tests hold their poses to (`crates/swell-py/tests/bodies_reference.json`, compared
/// with what this test writes; `SWELL_BLESS=1 cargo test -p swell-capi` rewrites it), so C, Rust
/// and Python float the same bodies the same way.
#[test]
fn added_bodies_and_thrust_are_the_library_s_and_the_python_reference() {
    let s = scene(BODIES_SCENE);
    let mut world = World::new(Scene::from_toml(BODIES_SCENE, "t").unwrap()).unwrap();
    let mut records = Vec::new();
    for f in 0..=LAST_FRAME {
        let t = f64::from(f) / 60.0;
        let poses = c_poses(s, t);
        assert_eq!(poses, world_poses(&mut world, t), "t = {t}");
        if f % RECORD_EVERY == 0 {
            records.push((f, t, poses));
        }
        if f == ADD_FRAME {
            let text = CString::new(ADDED_BODY).unwrap();
            let mut k = usize::MAX;
            let r = unsafe { swell_scene_add_body_toml(s, text.as_ptr(), &mut k) };
            assert_eq!((r, k), (SwellResult::Ok, 3), "{}", last_error());
            let spec = Scene::from_toml(ADDED_BODY, "t").unwrap().bodies.remove(0);
            assert_eq!(world.add_body(spec).unwrap(), 3);
            let (shape, [x, y, z]) = (CString::new("sphere").unwrap(), BALL_POSITION);
            let r = unsafe {
                swell_scene_add_body(s, null(), shape.as_ptr(), &BALL_SIZE, 1, BALL_DENSITY, x, y, z, &mut k)
            };
            assert_eq!((r, k), (SwellResult::Ok, 4), "{}", last_error());
            let position = Vec3::new(x as f32, y as f32, z as f32);
            let mut ball =
                swell_lib::body::BodySpec::new(swell_lib::body::BodyShape::Sphere, &[BALL_SIZE as f32], position);
            ball.density = Some(BALL_DENSITY as f32);
            assert_eq!(world.add_body(ball).unwrap(), 4);
        }
        if f == THRUST_FRAME {
            let [x, y, z] = THRUST;
            assert_eq!(unsafe { swell_scene_set_body_thrust(s, 0, x, y, z) }, SwellResult::Ok);
            world.bodies.bodies_mut()[0].thrust = DVec3::from_array(THRUST);
        }
    }
    let names: Vec<String> = (0..body_count(s)).map(|k| c_name(s, k)).collect();
    assert_eq!(names, ["crate", "buoy", "log", "barrel", "body4"]);
    // Held until released, then fallen onto the water; the crate pushed along +X.
    let (p, _) = &records.last().unwrap().2;
    assert!(p[3 * 3 + 1] < 1.0 && p[3 * 4 + 1] < 1.0, "{p:?}");
    let mut unpushed = World::new(Scene::from_toml(BODIES_SCENE, "t").unwrap()).unwrap();
    unpushed.update(f64::from(LAST_FRAME) / 60.0).unwrap();
    assert!(p[0] > unpushed.body_poses()[0].position.x + 0.2, "{} vs {}", p[0], unpushed.body_poses()[0].position);
    unsafe { swell_scene_destroy(s) };

    let mut json = String::from("{\n");
    json.push_str(
        "  \"about\": \"Reference poses of floating bodies for the Python tests (test_bodies.py), written by \
         crates/swell-capi/src/tests.rs (added_bodies_and_thrust_are_the_library_s_and_the_python_reference) from the \
         C API and the Rust library, which agree bit for bit. Do not edit: SWELL_BLESS=1 cargo test -p swell-capi \
         rewrites it.\",\n",
    );
    json.push_str(&format!("  \"scene\": {},\n", json_string(BODIES_SCENE)));
    json.push_str(&format!("  \"add_frame\": {ADD_FRAME},\n  \"add_toml\": {},\n", json_string(ADDED_BODY)));
    json.push_str(&format!(
        "  \"add_keys\": {{\"shape\": \"sphere\", \"size\": [{BALL_SIZE:?}], \"density\": {BALL_DENSITY:?}, \"position\": {}}},\n",
        json_numbers(&BALL_POSITION)
    ));
    json.push_str(&format!(
        "  \"thrust_frame\": {THRUST_FRAME},\n  \"thrust_body\": 0,\n  \"thrust\": {},\n",
        json_numbers(&THRUST)
    ));
    json.push_str(&format!("  \"last_frame\": {LAST_FRAME},\n  \"record_every\": {RECORD_EVERY},\n"));
    let quoted: Vec<String> = names.iter().map(|n| json_string(n)).collect();
    json.push_str(&format!("  \"names\": [{}],\n  \"records\": [\n", quoted.join(", ")));
    let lines: Vec<String> = records
        .iter()
        .map(|(f, t, (p, r))| {
            let p: Vec<String> = p.chunks(3).map(json_numbers).collect();
            let r: Vec<String> = r.chunks(4).map(json_numbers).collect();
            format!(
                "    {{\"frame\": {f}, \"t\": {t:?}, \"positions\": [{}], \"rotations\": [{}]}}",
                p.join(", "),
                r.join(", ")
            )
        })
        .collect();
    json.push_str(&lines.join(",\n"));
    json.push_str("\n  ]\n}\n");
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../swell-py/tests/bodies_reference.json");
    if std::env::var_os("SWELL_BLESS").is_some() {
        std::fs::write(&path, &json).unwrap();
        return;
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == json,
        "{} is stale: run `SWELL_BLESS=1 cargo test -p swell-capi` and commit it",
        path.display()
    );
}

#[test]
fn bad_body_inputs_are_refused_with_a_code_and_a_message_naming_the_argument() {
    let s = scene(BODIES_SCENE);
    let (mut p, mut r) = (vec![7.0f64; 9], vec![7.0f64; 12]);
    let poses = |s: *mut SwellScene, t: f64, pl: usize, rl: usize, p: &mut Vec<f64>, r: &mut Vec<f64>| unsafe {
        swell_scene_body_poses(s, t, p.as_mut_ptr(), pl, r.as_mut_ptr(), rl)
    };
    let cases: Vec<(SwellResult, SwellResult, &str)> = vec![
        (poses(null_mut(), 1.0, 9, 12, &mut p, &mut r), SwellResult::NullPointer, "scene: is NULL"),
        (
            poses(s, f64::NAN, 9, 12, &mut p, &mut r),
            SwellResult::InvalidArgument,
            "t = NaN is outside [0, 1e7] seconds (floating bodies start at t = 0)",
        ),
        (
            poses(s, -0.5, 9, 12, &mut p, &mut r),
            SwellResult::InvalidArgument,
            "t = -0.5 is outside [0, 1e7] seconds (floating bodies start at t = 0)",
        ),
        (
            poses(s, 1.0, 8, 12, &mut p, &mut r),
            SwellResult::InvalidArgument,
            "positions_len: 8; must be 9 (3 doubles per body x 3 bodies)",
        ),
        (
            poses(s, 1.0, 9, 9, &mut p, &mut r),
            SwellResult::InvalidArgument,
            "rotations_len: 9; must be 12 (4 doubles per body x 3 bodies)",
        ),
        (
            unsafe { swell_scene_body_poses(s, 1.0, null_mut(), 9, r.as_mut_ptr(), 12) },
            SwellResult::NullPointer,
            "positions: is NULL",
        ),
        (
            unsafe { swell_scene_advance(s, f64::INFINITY) },
            SwellResult::InvalidArgument,
            "t = inf is outside [0, 1e7] seconds (floating bodies start at t = 0)",
        ),
        (unsafe { swell_scene_advance(null_mut(), 1.0) }, SwellResult::NullPointer, "scene: is NULL"),
        (unsafe { swell_scene_body_count(s, null_mut()) }, SwellResult::NullPointer, "count: is NULL"),
        (
            unsafe { swell_scene_set_body_thrust(s, 3, 1.0, 0.0, 0.0) },
            SwellResult::InvalidArgument,
            "index: 3; must be below 3 (the scene's bodies)",
        ),
        (
            unsafe { swell_scene_set_body_thrust(s, 0, 1.0, f64::NAN, 0.0) },
            SwellResult::InvalidArgument,
            "fy: NaN is not a finite force (newtons)",
        ),
        (
            unsafe { swell_scene_body_index(s, CString::new("raft").unwrap().as_ptr(), &mut 0) },
            SwellResult::InvalidArgument,
            "name: \"raft\" names none of the scene's 3 bodies",
        ),
        (unsafe { swell_scene_body_name(s, 0, null_mut(), 4, &mut 0) }, SwellResult::NullPointer, "name: is NULL"),
    ];
    for (got, code, message) in cases {
        assert_eq!(got, code, "{message}");
    }
    // The messages, one call at a time, and nothing written by a refused call.
    assert_eq!(poses(s, f64::NAN, 9, 12, &mut p, &mut r), SwellResult::InvalidArgument);
    assert_eq!(last_error(), "t = NaN is outside [0, 1e7] seconds (floating bodies start at t = 0)");
    assert_eq!(poses(s, 1.0, 9, 13, &mut p, &mut r), SwellResult::InvalidArgument);
    assert_eq!(last_error(), "rotations_len: 13; must be 12 (4 doubles per body x 3 bodies)");
    assert!(p.iter().chain(&r).all(|v| *v == 7.0));
    assert_eq!(unsafe { swell_scene_set_body_thrust(s, 7, 0.0, 0.0, 0.0) }, SwellResult::InvalidArgument);
    assert_eq!(last_error(), "index: 7; must be below 3 (the scene's bodies)");
    assert_eq!(unsafe { swell_scene_set_body_thrust(s, 0, 0.0, 0.0, f64::NEG_INFINITY) }, SwellResult::InvalidArgument);
    assert_eq!(last_error(), "fz: -inf is not a finite force (newtons)");
    // A name buffer too short gets nothing but the size it needs.
    let (mut buf, mut size) = ([0x55u8; 4], 0);
    let code = unsafe { swell_scene_body_name(s, 0, buf.as_mut_ptr().cast(), 4, &mut size) };
    assert_eq!((code, size, buf), (SwellResult::InvalidArgument, 6, [0x55; 4]));
    assert_eq!(last_error(), "name_len: 4; must be at least 6 (the name's 5 bytes and a NUL)");
    unsafe { swell_scene_destroy(s) };
}

/// A body added from TOML is refused naming its key as the scene numbers the new body
/// (`body[3]`, not the snippet's `body[0]`), with the snippet's own line numbers for a syntax error;
/// from parameters, as an argument error.
#[test]
fn bad_added_bodies_are_refused_naming_the_key() {
    let s = scene(BODIES_SCENE);
    let add_toml = |text: &str| {
        let text = CString::new(text).unwrap();
        let mut k = 99;
        let r = unsafe { swell_scene_add_body_toml(s, text.as_ptr(), &mut k) };
        assert_eq!(k, 99, "the index is written only on success");
        (r, last_error())
    };
    for (text, code, message) in [
        (
            "[[body]]\nshape = 'box'\nsize = [1.0, 0.5]\n",
            SwellResult::Scene,
            "toml: body[3].size: [1.0, 0.5] has 2 values; shape box takes [x, y, z] (full extents, m)",
        ),
        (
            "[[body]]\nshape = 'boat'\nsize = [1.0]\n",
            SwellResult::Scene,
            "toml: body[3].shape: unknown variant `boat`, expected one of `box`, `sphere`, `capsule`, `mesh`",
        ),
        (
            "[[body]]\nname = 'buoy'\nshape = 'sphere'\nsize = [0.5]\n",
            SwellResult::Scene,
            "toml: body[3].name: \"buoy\" names an earlier body too; names must be unique",
        ),
        (
            "[[body]]\nshape = 'sphere'\nsize = [0.5]\n[[body]]\nshape = 'sphere'\nsize = [0.5]\n",
            SwellResult::Scene,
            "toml: holds 2 [[body]] tables; give exactly one [[body]] table (its header and keys) and nothing else",
        ),
        (
            "[[body]]\nshape = 'sphere'\nsize = [0.5]\n[render]\nwidth = 64\n",
            SwellResult::Scene,
            "toml: holds 1 [[body]] table and other sections; give exactly one [[body]] table (its header and keys) and nothing else",
        ),
    ] {
        let (r, e) = add_toml(text);
        assert_eq!(r, code, "{text}: {e}");
        assert!(e.starts_with(message), "{text}: {e}");
    }
    // A syntax error counts the snippet's lines, not those of the scene's bodies read before it.
    let (r, e) = add_toml("[[body]]\nshape = 'sphere'\nsize = [0.5\n");
    assert_eq!(r, SwellResult::Scene);
    assert!(e.starts_with("toml: TOML parse error at line 3"), "{e}");
    assert_eq!(unsafe { swell_scene_add_body_toml(s, null(), null_mut()) }, SwellResult::NullPointer);
    assert_eq!(last_error(), "toml: is NULL");

    let add = |shape: &str, size: &[f64], density: f64| {
        let shape = CString::new(shape).unwrap();
        let r = unsafe {
            swell_scene_add_body(
                s,
                null(),
                shape.as_ptr(),
                size.as_ptr(),
                size.len(),
                density,
                0.0,
                1.0,
                0.0,
                null_mut(),
            )
        };
        (r, last_error())
    };
    for ((shape, size, density), message) in [
        (("box", &[1.0, 1.0, 1.0][..], 0.0), "body[3].density = 0 is outside [10, 20000]"),
        (("sphere", &[f64::NAN][..], 500.0), "body[3].size[0] = NaN is outside [0.02, 1000]"),
        (("boat", &[1.0][..], 500.0), "shape: `boat` is not a body shape; valid: box, sphere, capsule, mesh"),
        (("mesh", &[][..], 500.0), "shape: \"mesh\" reads its hull from an OBJ file"),
        (("box", &[1.0, 1.0, 1.0, 1.0][..], 500.0), "size_len: 4; must be 3 (box), 1 (sphere) or 2 (capsule)"),
    ] {
        let (r, e) = add(shape, size, density);
        assert_eq!(r, SwellResult::InvalidArgument, "{e}");
        assert!(e.starts_with(message), "{e}");
    }
    // Nothing refused was added; a good body still is.
    assert_eq!(body_count(s), 3);
    assert_eq!(add("box", &[1.0, 1.0, 1.0], 500.0).0, SwellResult::Ok);
    assert_eq!(body_count(s), 4);
    unsafe { swell_scene_destroy(s) };
}

/// A force that throws a body out of the finite numbers fails the call and writes nothing: no
/// NaN ever reaches the caller's buffers. Taking the force away lets the replay from t = 0 go on.
#[test]
fn a_body_thrown_out_of_the_finite_numbers_is_an_error_not_a_nan() {
    let s = scene(BODIES_SCENE);
    assert_eq!(unsafe { swell_scene_set_body_thrust(s, 1, 0.0, -1e300, 0.0) }, SwellResult::Ok);
    let (mut p, mut r) = (vec![7.0f64; 9], vec![7.0f64; 12]);
    let code = unsafe { swell_scene_body_poses(s, 2.0, p.as_mut_ptr(), 9, r.as_mut_ptr(), 12) };
    assert_eq!(code, SwellResult::Unstable, "{}", last_error());
    assert!(last_error().contains("\"buoy\" left the finite numbers"), "{}", last_error());
    assert!(p.iter().chain(&r).all(|v| *v == 7.0));
    assert_eq!(unsafe { swell_scene_set_body_thrust(s, 1, 0.0, 0.0, 0.0) }, SwellResult::Ok);
    let mut world = World::new(Scene::from_toml(BODIES_SCENE, "t").unwrap()).unwrap();
    assert_eq!(c_poses(s, 2.0), world_poses(&mut world, 2.0));
    unsafe { swell_scene_destroy(s) };
}
