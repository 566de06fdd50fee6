//! The C ABI of swell: `libswell.so`, `libswell.a` and `include/swell.h` (generated from this file
//! by cbindgen; the header's preamble states the conventions, errors and thread rules).
//!
//! Every entry point:
//! - checks its pointers (NULL is refused with [`SwellResult::NullPointer`]) and buffer lengths
//!   (refused with [`SwellResult::InvalidArgument`]) before touching them;
//! - runs inside `catch_unwind`, so no panic crosses the boundary ([`SwellResult::Panic`]);
//! - on failure stores the error's message, the text the CLI prints after `error: `, for
//!   [`swell_last_error_message`] on the calling thread.
//!
//! Handles are `Box`es of a `Mutex` around the library's [`swell_lib::Water`] or a
//! [`swell_lib::world::World`] (rendered, and stepping its floating bodies: `bodies.rs`); the lock serialises calls on one handle. All live handles run
//! their work on one shared rayon pool (one thread per core, however many handles: 200 handles
//! once meant 400 threads on 2 cores), whose threads are joined when the last handle is
//! destroyed: the library leaves no thread behind (rayon's global pool, never joined, would still
//! be running at exit, which valgrind reports as possibly lost thread memory).

#![allow(clippy::missing_safety_doc)] // Each function's doc comment states its safety contract.

use std::cell::RefCell;
use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Arc, Mutex, MutexGuard, Weak};
use std::thread::JoinHandle;

use glam::{DVec2, DVec3, Vec2, Vec3};
use swell_lib::render::Renderer;
use swell_lib::scene::Scene;
use swell_lib::world::{World, MAX_QUERY_COORDINATE_M};
use swell_lib::{Error, Water};

/// What a call did: `SWELL_RESULT_OK` (0) or the kind of failure; the message is
/// `swell_last_error_message()`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SwellResult {
    /// Success.
    Ok = 0,
    /// A required pointer argument was NULL.
    NullPointer = 1,
    /// An argument was out of range: a buffer length, a non-finite time, text that is not UTF-8.
    InvalidArgument = 2,
    /// The scene text was refused: TOML syntax, an unknown key, a value out of range (the message
    /// names the key path, the value and the valid range).
    Scene = 3,
    /// The simulation became unstable (e.g. a spring mesh blowing up) or was asked too far ahead.
    Unstable = 4,
    /// A bug in swell: a panic was caught at the boundary. The handle may be used again; its next
    /// query recomputes the state from scratch where needed.
    Panic = 5,
    /// The progress callback (`swell_water_set_progress`) asked a long call to stop. Nothing is
    /// wrong: the same call made again continues from where this one stopped.
    Cancelled = 6,
}

/// Told the progress of a long call on a water handle (a spring mesh asked far ahead), about
/// every million node updates (10-50 ms of work): `fraction` done in [0, 1), and `user_data` as
/// given to `swell_water_set_progress`. Return 0 to go on, any other value to stop the call, which
/// then returns `SWELL_RESULT_CANCELLED`. It is called on one of swell's worker threads while the
/// call waits, never concurrently with itself for one handle; it must not call swell on the same
/// handle (its lock is held) and must return (no `longjmp` out of it).
pub type SwellProgress = Option<unsafe extern "C" fn(fraction: f64, user_data: *mut c_void) -> c_int>;

/// The water of a scene: its model, grid and placement, answering queries about any time.
/// Created by `swell_water_from_toml`, freed by `swell_water_destroy`.
pub struct SwellWater {
    water: Mutex<Water>,
    pool: Arc<Pool>,
}

/// A whole scene (water, terrain, camera, lights, sky, floating bodies), ready to render and to
/// step its floating bodies (`swell_scene_body_poses`).
/// Created by `swell_scene_from_toml`, freed by `swell_scene_destroy`.
pub struct SwellScene {
    inner: Mutex<SceneState>,
    pool: Arc<Pool>,
}

struct SceneState {
    world: World,
    renderer: Renderer,
    rgba: Vec<u8>,
}

/// The handles' worker threads: a rayon pool whose threads it spawned itself, so that it can join
/// them when the last handle using it is destroyed.
struct Pool {
    pool: Option<rayon::ThreadPool>,
    threads: Arc<Mutex<Vec<JoinHandle<()>>>>,
}

impl Pool {
    /// `threads` workers, 0 for one per core.
    fn new(threads: usize) -> Result<Self, Failure> {
        let handles: Arc<Mutex<Vec<JoinHandle<()>>>> = Arc::default();
        let spawned = Arc::clone(&handles);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(|k| format!("swell-{k}"))
            .spawn_handler(move |thread| {
                let mut b = std::thread::Builder::new();
                if let Some(name) = thread.name() {
                    b = b.name(name.to_owned());
                }
                if let Some(size) = thread.stack_size() {
                    b = b.stack_size(size);
                }
                lock(&spawned).push(b.spawn(|| thread.run())?);
                Ok(())
            })
            .build()
            .map_err(|e| {
                Failure(SwellResult::InvalidArgument, format!("threads: cannot start {threads} threads: {e}"))
            })?;
        Ok(Self { pool: Some(pool), threads: handles })
    }

    /// The pool every live handle shares, started by the first handle and stopped (its threads
    /// joined) with the last: a handle holds an `Arc`, this slot only a `Weak`.
    fn shared() -> Result<Arc<Self>, Failure> {
        static SHARED: Mutex<Weak<Pool>> = Mutex::new(Weak::new());
        let mut slot = lock(&SHARED);
        if let Some(pool) = slot.upgrade() {
            return Ok(pool);
        }
        let pool = Arc::new(Self::new(0)?);
        *slot = Arc::downgrade(&pool);
        Ok(pool)
    }

    fn install<R: Send>(&self, f: impl FnOnce() -> R + Send) -> R {
        self.pool.as_ref().expect("present until dropped").install(f)
    }
}

impl Drop for Pool {
    fn drop(&mut self) {
        // Dropping the pool tells its threads to finish; joining waits until they have.
        drop(self.pool.take());
        for t in lock(&self.threads).drain(..) {
            let _ = t.join();
        }
    }
}

/// A failure on its way to the caller: the code and the message.
struct Failure(SwellResult, String);

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        let code = match &e {
            // InSource: a key error found in the scene text ("toml: water.cells[0] = ...").
            Error::Parse { .. }
            | Error::InSource { .. }
            | Error::UnknownPreset { .. }
            | Error::Io { .. }
            | Error::Image { .. } => SwellResult::Scene,
            Error::Unstable(_) => SwellResult::Unstable,
            Error::Cancelled(_) => SwellResult::Cancelled,
            // Keys of a scene (water.cells[0]) are scene errors; the API's own parameters (t,
            // positions_len) are argument errors.
            Error::OutOfRange { key, .. } | Error::Invalid { key, .. } if is_scene_key(key) => SwellResult::Scene,
            Error::OutOfRange { .. } | Error::Invalid { .. } => SwellResult::InvalidArgument,
        };
        Failure(code, e.to_string())
    }
}

/// Whether an error key is a scene key (as opposed to a parameter of a C function).
fn is_scene_key(key: &str) -> bool {
    ["water", "terrain", "camera", "light", "sky", "render", "version", "scene", "body"]
        .iter()
        .any(|s| key == *s || key.starts_with(&format!("{s}.")) || key.starts_with(&format!("{s}[")))
}

fn invalid(key: &str, message: String) -> Failure {
    Failure(SwellResult::InvalidArgument, format!("{key}: {message}"))
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_last_error(message: &str) {
    // The message echoes user text: control characters (NUL among them, which would end the C
    // string early), bidi marks and overlong text are escaped and cut as the CLI prints them.
    let c = CString::new(swell_lib::error::printable(message)).expect("printable text has no NUL");
    LAST_ERROR.with(|e| *e.borrow_mut() = c);
}

/// Runs one entry point: catches panics, stores the message of a failure.
fn guard(f: impl FnOnce() -> Result<(), Failure>) -> SwellResult {
    let outcome = catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|payload| {
        let what = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into());
        Err(Failure(SwellResult::Panic, format!("internal error (a bug in swell, please report it): {what}")))
    });
    match outcome {
        Ok(()) => SwellResult::Ok,
        Err(Failure(code, message)) => {
            set_last_error(&message);
            code
        }
    }
}

/// Locks a handle's mutex; a lock poisoned by a caught panic is taken over (the state it guards
/// re-derives itself on the next query).
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

fn non_null<'a, T>(name: &str, p: *const T) -> Result<&'a T, Failure> {
    // SAFETY: the caller promises a non-NULL pointer is valid for the call (the function's contract).
    unsafe { p.as_ref() }.ok_or_else(|| Failure(SwellResult::NullPointer, format!("{name}: is NULL")))
}

fn check_null<T>(name: &str, p: *const T) -> Result<(), Failure> {
    if p.is_null() {
        Err(Failure(SwellResult::NullPointer, format!("{name}: is NULL")))
    } else {
        Ok(())
    }
}

/// Reads a NUL-terminated UTF-8 string.
unsafe fn text<'a>(name: &str, p: *const c_char) -> Result<&'a str, Failure> {
    check_null(name, p)?;
    // SAFETY: non-NULL, and the caller promises a NUL-terminated string.
    unsafe { CStr::from_ptr(p) }.to_str().map_err(|e| invalid(name, format!("is not UTF-8 text ({e})")))
}

fn check_time(t: f64) -> Result<(), Failure> {
    if t.is_finite() {
        Ok(())
    } else {
        Err(Failure(SwellResult::InvalidArgument, Error::out_of_range("t", t, "finite seconds").to_string()))
    }
}

fn check_len(name: &str, len: usize, expected: usize, what: &str) -> Result<(), Failure> {
    if len == expected {
        Ok(())
    } else {
        Err(invalid(name, format!("{len}; must be {expected} ({what})")))
    }
}

/// Refuses the first non-finite coordinate of the flattened pairs (x0, z0, x1, z1, ...), or one
/// farther than [`MAX_QUERY_COORDINATE_M`] from the origin, naming it `xz[k]` (issue 37): a NaN
/// buoy must be told with [`SwellResult::InvalidArgument`], not answered with calm water.
fn check_finite_coordinates<C: Into<f64>>(flat: impl Iterator<Item = C>) -> Result<(), Failure> {
    // Written so that NaN fails it.
    let within = |c: f64| c.abs() <= MAX_QUERY_COORDINATE_M;
    match flat.map(Into::into).enumerate().find(|(_, c)| !within(*c)) {
        None => Ok(()),
        Some((k, c)) if c.is_finite() => Err(invalid(
            &format!("xz[{k}]"),
            format!("{} m is farther than 1e9 m from the origin (MAX_QUERY_COORDINATE_M)", swell_lib::error::Human(c)),
        )),
        Some((k, c)) => Err(invalid(&format!("xz[{k}]"), format!("{c} is not a finite coordinate (world metres)"))),
    }
}

/// A caller's float buffer of `len` floats as `len / 3` vectors (`len` is checked first).
unsafe fn vec3s<'a>(p: *mut f32, len: usize) -> &'a mut [Vec3] {
    // SAFETY: Vec3 is #[repr(C)] { x, y, z: f32 } (size 12, align 4, like float[3]); the caller
    // promises `len` writable floats.
    unsafe { std::slice::from_raw_parts_mut(p.cast::<Vec3>(), len / 3) }
}

/// The words of a length error for one height per (x, z) pair.
const ONE_PER_PAIR: &str = "one height per (x, z) pair: xz_len / 2";
/// The words of a length error for one mask byte per (x, z) pair.
const ONE_BYTE_PER_PAIR: &str = "one byte per (x, z) pair: xz_len / 2";

/// A point query's output buffer as the caller passed it: its parameter name, the pointer, its
/// length in scalars, how many scalars each (x, z) pair gets, and the words of a length error.
struct OutBuffer<S> {
    name: &'static str,
    ptr: *mut S,
    len: usize,
    per_pair: usize,
    what: &'static str,
}

/// What every point query checks before it reads or writes, in this order: NULL pointers, pairs,
/// the output's length (`NAME_len`), then every coordinate finite and within
/// `MAX_QUERY_COORDINATE_M`. Then the buffers as slices: the points as `P` (pairs of `C`), the
/// output as `O` (`per_pair` scalars `S` each). Nothing is written when a check fails.
///
/// # Safety
/// `xz` points to `xz_len` readable `C`, `out.ptr` to `out.len` writable `S`, not overlapping (the
/// calling function's contract); `P` is laid out as `[C; 2]` and `O` as `[S; per_pair]`, which
/// glam's `#[repr(C)]` vectors (`Vec2` = float[2], `DVec3` = double[3], ...) and the scalars are.
unsafe fn query_buffers<'a, C: Copy + Into<f64>, P, S, O>(
    xz: *const C,
    xz_len: usize,
    out: OutBuffer<S>,
) -> Result<(&'a [P], &'a mut [O]), Failure> {
    check_null("xz", xz)?;
    check_null(out.name, out.ptr)?;
    check_pairs(xz_len)?;
    check_len(&format!("{}_len", out.name), out.len, out.per_pair * (xz_len / 2), out.what)?;
    debug_assert!(size_of::<P>() == 2 * size_of::<C>() && size_of::<O>() == out.per_pair * size_of::<S>());
    // SAFETY: lengths checked above; the caller promises the buffers hold them, and the layouts.
    unsafe {
        check_finite_coordinates(std::slice::from_raw_parts(xz, xz_len).iter().copied())?;
        let points = std::slice::from_raw_parts(xz.cast::<P>(), xz_len / 2);
        Ok((points, std::slice::from_raw_parts_mut(out.ptr.cast::<O>(), out.len / out.per_pair)))
    }
}

/// `swell_water_coverage` and its double variant: `covered` tells whether a point `P` (pairs of
/// `C`) has water.
///
/// # Safety
/// As `query_buffers`, with `mask` as its output of one byte per pair.
unsafe fn coverage<C: Copy + Into<f64>, P: Copy>(
    water: *const SwellWater,
    xz: *const C,
    xz_len: usize,
    mask: *mut u8,
    mask_len: usize,
    covered: fn(&Water, P) -> bool,
) -> SwellResult {
    guard(|| {
        let w = non_null("water", water)?;
        let out = OutBuffer { name: "mask", ptr: mask, len: mask_len, per_pair: 1, what: ONE_BYTE_PER_PAIR };
        // SAFETY: the calling function's contract.
        let (points, out) = unsafe { query_buffers::<C, P, u8, u8>(xz, xz_len, out)? };
        let w = lock(&w.water);
        for (m, p) in out.iter_mut().zip(points) {
            *m = u8::from(covered(&w, *p));
        }
        Ok(())
    })
}

/// Refuses an odd count of coordinates: they come in (x, z) pairs.
fn check_pairs(xz_len: usize) -> Result<(), Failure> {
    if xz_len.is_multiple_of(2) {
        Ok(())
    } else {
        Err(invalid("xz_len", format!("{xz_len}; must be even (pairs of x, z)")))
    }
}

/// The version of swell, e.g. "0.1.0": a static NUL-terminated string, never freed.
#[no_mangle]
pub extern "C" fn swell_version() -> *const c_char {
    static VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "\0");
    VERSION.as_ptr().cast()
}

/// The message of the most recent failed call on this thread ("" if none failed yet): the text
/// the swell command line prints after "error: ". Valid until the next failing call on this
/// thread; successful calls leave it unchanged. Never NULL; do not free it.
#[no_mangle]
pub extern "C" fn swell_last_error_message() -> *const c_char {
    LAST_ERROR.with(|e| e.borrow().as_ptr())
}

/// Parses a scene's TOML text (docs/scene-format.md; a `[water]` section is required) and builds
/// its water at time 0. On success `*out` is a new handle for `swell_water_destroy`; on failure
/// `*out` is set to NULL.
///
/// # Safety
/// `toml` is a NUL-terminated UTF-8 string; `out` points to writable storage for one pointer.
#[no_mangle]
pub unsafe extern "C" fn swell_water_from_toml(toml: *const c_char, out: *mut *mut SwellWater) -> SwellResult {
    guard(|| {
        check_null("out", out)?;
        // SAFETY: checked non-NULL; the caller promises it is writable.
        unsafe { *out = std::ptr::null_mut() };
        let text = unsafe { text("toml", toml)? };
        let pool = Pool::shared()?;
        let water = pool.install(|| Water::from_toml(text, "toml"))?;
        let handle = Box::new(SwellWater { water: Mutex::new(water), pool });
        unsafe { *out = Box::into_raw(handle) };
        Ok(())
    })
}

/// Frees a water handle. NULL is ignored.
///
/// # Safety
/// `water` is NULL or a handle from `swell_water_from_toml` not yet destroyed, with no other call
/// on it in progress.
#[no_mangle]
pub unsafe extern "C" fn swell_water_destroy(water: *mut SwellWater) {
    if !water.is_null() {
        let _ = catch_unwind(AssertUnwindSafe(|| {
            // SAFETY: the caller gives back a pointer from Box::into_raw, once.
            drop(unsafe { Box::from_raw(water) });
        }));
    }
}

/// Sets (or, with a NULL `callback`, removes) the progress callback of long calls on `water`
/// (see `SwellProgress`): a spring mesh asked minutes ahead reports how far it has got and stops
/// when the callback returns non-zero. Closed-form and spectral models never call it.
///
/// # Safety
/// `water` is a live handle with no other call on it in progress; `callback`, if not NULL, is
/// callable with `user_data` from any thread until it is replaced or the handle destroyed.
#[no_mangle]
pub unsafe extern "C" fn swell_water_set_progress(
    water: *mut SwellWater,
    callback: SwellProgress,
    user_data: *mut c_void,
) -> SwellResult {
    /// The caller's pointer, passed back untouched: the caller promised it may be used from any
    /// thread.
    struct UserData(*mut c_void);
    // SAFETY: swell never dereferences it; the caller's contract covers the threads.
    unsafe impl Send for UserData {}
    guard(|| {
        let water = non_null("water", water)?;
        let watch = callback.map(|f| {
            let user = UserData(user_data);
            Box::new(move |fraction: f64| {
                let user = &user;
                // SAFETY: the caller promised `f` is callable with `user_data` (see above).
                unsafe { f(fraction, user.0) == 0 }
            }) as swell_lib::world::Watch
        });
        lock(&water.water).set_watch(watch);
        Ok(())
    })
}

/// The grid's size: `*rows` vertices along +Z, `*cols` vertices along +X. Position and normal
/// buffers hold `3 * rows * cols` floats, foam buffers `rows * cols`.
///
/// # Safety
/// `water` is a live handle; `rows` and `cols` point to writable `size_t`s.
#[no_mangle]
pub unsafe extern "C" fn swell_water_grid_size(
    water: *const SwellWater,
    rows: *mut usize,
    cols: *mut usize,
) -> SwellResult {
    guard(|| {
        let w = non_null("water", water)?;
        check_null("rows", rows)?;
        check_null("cols", cols)?;
        let w = lock(&w.water);
        // SAFETY: checked non-NULL; the caller promises they are writable.
        unsafe { (*rows, *cols) = (w.rows(), w.cols()) };
        Ok(())
    })
}

/// Writes the displaced world positions (m) and unit normals of every grid vertex at time `t`
/// (s, finite): `x, y, z` per vertex, row-major. `positions_len` and `normals_len` count floats
/// and must both be `3 * rows * cols`. The numbers are those `swell export` writes (and, in the
/// patch's frame, `swell bake`'s displacement plus the rest position).
///
/// # Safety
/// `water` is a live handle; `positions` and `normals` point to `positions_len` and
/// `normals_len` writable floats.
#[no_mangle]
pub unsafe extern "C" fn swell_water_displace(
    water: *mut SwellWater,
    t: f64,
    positions: *mut f32,
    positions_len: usize,
    normals: *mut f32,
    normals_len: usize,
) -> SwellResult {
    guard(|| {
        let water = non_null("water", water)?;
        check_null("positions", positions)?;
        check_null("normals", normals)?;
        check_time(t)?;
        let mut guard = lock(&water.water);
        let w = &mut *guard;
        let what = format!("3 floats per vertex x {} rows x {} columns", w.rows(), w.cols());
        let n = 3 * w.vertex_count();
        check_len("positions_len", positions_len, n, &what)?;
        check_len("normals_len", normals_len, n, &what)?;
        // SAFETY: lengths checked; the caller promises the buffers hold them.
        let (p, q) = unsafe { (vec3s(positions, positions_len), vec3s(normals, normals_len)) };
        water.pool.install(|| w.displace(t, p, q))?;
        Ok(())
    })
}

/// Writes foam coverage in [0, 1] of every grid vertex at time `t` (s, finite) and sets
/// `*has_foam` to true, or sets it to false and leaves `foam` untouched if the model has no foam
/// (only the FFT ocean with `foam = true` has). `foam_len` must be `rows * cols`.
///
/// # Safety
/// `water` is a live handle; `foam` points to `foam_len` writable floats; `has_foam` to a
/// writable bool.
#[no_mangle]
pub unsafe extern "C" fn swell_water_foam(
    water: *mut SwellWater,
    t: f64,
    foam: *mut f32,
    foam_len: usize,
    has_foam: *mut bool,
) -> SwellResult {
    guard(|| {
        let water = non_null("water", water)?;
        check_null("foam", foam)?;
        check_null("has_foam", has_foam)?;
        check_time(t)?;
        let mut guard = lock(&water.water);
        let w = &mut *guard;
        let what = format!("1 float per vertex x {} rows x {} columns", w.rows(), w.cols());
        check_len("foam_len", foam_len, w.vertex_count(), &what)?;
        // SAFETY: length checked; the caller promises the buffer holds it.
        let out = unsafe { std::slice::from_raw_parts_mut(foam, foam_len) };
        let has = water.pool.install(|| w.foam(t, out))?;
        unsafe { *has_foam = has };
        Ok(())
    })
}

/// Heights (m above the water at rest) of the surface above world points at time `t` (s,
/// finite). `xz` holds `xz_len` floats, pairs (x, z) in metres; `heights` receives one float per
/// pair, so `heights_len` must be `xz_len / 2` and `xz_len` even. Points are computed in parallel;
/// a million take well under 2 s on 2 cores (docs/embedding.md). A NaN or infinite coordinate is
/// refused (`SWELL_RESULT_INVALID_ARGUMENT`, the message naming `xz[k]`) and `heights` left as it was.
/// A point where there is no water (off a finite patch: a pool, a spring lattice, a river, or
/// `extent = "patch"`) gets NaN; `swell_water_coverage` tells which points have water.
///
/// # Safety
/// `water` is a live handle; `xz` points to `xz_len` readable floats, `heights` to `heights_len`
/// writable floats, not overlapping.
#[no_mangle]
pub unsafe extern "C" fn swell_water_heights(
    water: *mut SwellWater,
    t: f64,
    xz: *const f32,
    xz_len: usize,
    heights: *mut f32,
    heights_len: usize,
) -> SwellResult {
    guard(|| {
        let w = non_null("water", water)?;
        check_time(t)?;
        let out = OutBuffer { name: "heights", ptr: heights, len: heights_len, per_pair: 1, what: ONE_PER_PAIR };
        // SAFETY: the function's contract; Vec2 is laid out as float[2].
        let (points, out) = unsafe { query_buffers::<f32, Vec2, f32, f32>(xz, xz_len, out)? };
        w.pool.install(|| lock(&w.water).heights_at(t, points, out))?;
        Ok(())
    })
}

/// Unit normals of the surface above world points at time `t` (s, finite). `xz` holds `xz_len`
/// floats, pairs (x, z); `normals` receives (x, y, z) per pair, so `normals_len` must be
/// `3 * xz_len / 2`. Central differences of the height over 2 cm (five height queries a point). A
/// NaN or infinite coordinate is refused as by `swell_water_heights`; a point with no water gets
/// three NaN.
///
/// # Safety
/// `water` is a live handle; `xz` points to `xz_len` readable floats, `normals` to `normals_len`
/// writable floats, not overlapping.
#[no_mangle]
pub unsafe extern "C" fn swell_water_normals(
    water: *mut SwellWater,
    t: f64,
    xz: *const f32,
    xz_len: usize,
    normals: *mut f32,
    normals_len: usize,
) -> SwellResult {
    guard(|| {
        let w = non_null("water", water)?;
        check_time(t)?;
        let what = "3 floats per (x, z) pair: 3 * xz_len / 2";
        let out = OutBuffer { name: "normals", ptr: normals, len: normals_len, per_pair: 3, what };
        // SAFETY: the function's contract; Vec2 and Vec3 are laid out as float[2] and float[3].
        let (points, out) = unsafe { query_buffers::<f32, Vec2, f32, Vec3>(xz, xz_len, out)? };
        w.pool.install(|| lock(&w.water).normals_at(t, points, out))?;
        Ok(())
    })
}

/// Whether there is water above each world point (x, z) (m): `mask` receives 1 or 0 per pair,
/// so `mask_len` must be `xz_len / 2`. Unbounded water covers every point; a finite patch (a pool,
/// a spring lattice, a river, or `extent = "patch"`) only its rectangle, edges included. Where it
/// is 0, `swell_water_heights` and `swell_water_normals` answer NaN. Non-finite coordinates are
/// refused as by `swell_water_heights`.
///
/// # Safety
/// `water` is a live handle; `xz` points to `xz_len` readable floats, `mask` to `mask_len`
/// writable bytes.
#[no_mangle]
pub unsafe extern "C" fn swell_water_coverage(
    water: *const SwellWater,
    xz: *const f32,
    xz_len: usize,
    mask: *mut u8,
    mask_len: usize,
) -> SwellResult {
    // SAFETY: the function's contract; Vec2 is laid out as float[2].
    unsafe { coverage::<f32, Vec2>(water, xz, xz_len, mask, mask_len, Water::has_water_at) }
}

/// `swell_water_heights` in double precision, for engines whose coordinates run far from the
/// origin (at 10^6 m a float moves in 6 cm steps): `xz` holds `xz_len` doubles, pairs (x, z) in
/// metres; `heights` receives one double per pair (`heights_len` = `xz_len / 2`). The point is
/// carried into the water's frame in double precision and, for water that repeats in space (the
/// FFT ocean), whole periods are taken off before the model (which computes in float) is asked,
/// so such water answers at 10^6 m as precisely as near the origin; other models are asked at the
/// point narrowed to float. Non-finite coordinates are refused and points with no water get NaN,
/// as by `swell_water_heights`.
///
/// # Safety
/// `water` is a live handle; `xz` points to `xz_len` readable doubles, `heights` to
/// `heights_len` writable doubles, not overlapping.
#[no_mangle]
pub unsafe extern "C" fn swell_water_heights_f64(
    water: *mut SwellWater,
    t: f64,
    xz: *const f64,
    xz_len: usize,
    heights: *mut f64,
    heights_len: usize,
) -> SwellResult {
    guard(|| {
        let w = non_null("water", water)?;
        check_time(t)?;
        let out = OutBuffer { name: "heights", ptr: heights, len: heights_len, per_pair: 1, what: ONE_PER_PAIR };
        // SAFETY: the function's contract; DVec2 is laid out as double[2].
        let (points, out) = unsafe { query_buffers::<f64, DVec2, f64, f64>(xz, xz_len, out)? };
        w.pool.install(|| lock(&w.water).heights_at_f64(t, points, out))?;
        Ok(())
    })
}

/// `swell_water_normals` in double precision, as `swell_water_heights_f64`: `xz` holds `xz_len`
/// doubles, pairs (x, z); `normals` receives (x, y, z) doubles per pair (`normals_len` =
/// `3 * xz_len / 2`), three NaN where there is no water.
///
/// # Safety
/// `water` is a live handle; `xz` points to `xz_len` readable doubles, `normals` to
/// `normals_len` writable doubles, not overlapping.
#[no_mangle]
pub unsafe extern "C" fn swell_water_normals_f64(
    water: *mut SwellWater,
    t: f64,
    xz: *const f64,
    xz_len: usize,
    normals: *mut f64,
    normals_len: usize,
) -> SwellResult {
    guard(|| {
        let w = non_null("water", water)?;
        check_time(t)?;
        let what = "3 doubles per (x, z) pair: 3 * xz_len / 2";
        let out = OutBuffer { name: "normals", ptr: normals, len: normals_len, per_pair: 3, what };
        // SAFETY: the function's contract; DVec2 and DVec3 are laid out as double[2] and double[3].
        let (points, out) = unsafe { query_buffers::<f64, DVec2, f64, DVec3>(xz, xz_len, out)? };
        w.pool.install(|| lock(&w.water).normals_at_f64(t, points, out))?;
        Ok(())
    })
}

/// `swell_water_coverage` of points given in double precision (`xz`: `xz_len` doubles, pairs
/// (x, z) in metres; `mask`: `mask_len` = `xz_len / 2` bytes, 1 where there is water).
///
/// # Safety
/// `water` is a live handle; `xz` points to `xz_len` readable doubles, `mask` to `mask_len`
/// writable bytes.
#[no_mangle]
pub unsafe extern "C" fn swell_water_coverage_f64(
    water: *const SwellWater,
    xz: *const f64,
    xz_len: usize,
    mask: *mut u8,
    mask_len: usize,
) -> SwellResult {
    // SAFETY: the function's contract; DVec2 is laid out as double[2].
    unsafe { coverage::<f64, DVec2>(water, xz, xz_len, mask, mask_len, Water::has_water_at_f64) }
}

/// Parses a scene's TOML text and builds it (water, terrain, meshes) for rendering, with its
/// floating bodies (`[[body]]`) at t = 0 (`swell_scene_body_poses` steps them). On success
/// `*out` is a new handle for `swell_scene_destroy`; on failure `*out` is set to NULL. Relative
/// heightmap and mesh paths in the text are relative to the working directory.
///
/// # Safety
/// `toml` is a NUL-terminated UTF-8 string; `out` points to writable storage for one pointer.
#[no_mangle]
pub unsafe extern "C" fn swell_scene_from_toml(toml: *const c_char, out: *mut *mut SwellScene) -> SwellResult {
    guard(|| {
        check_null("out", out)?;
        // SAFETY: checked non-NULL; the caller promises it is writable.
        unsafe { *out = std::ptr::null_mut() };
        let text = unsafe { text("toml", toml)? };
        // Parsing builds the models (validation), which already runs on the pool. One thread per
        // core: images do not depend on the count.
        let pool = Pool::shared()?;
        let world = pool.install(|| World::new(Scene::from_toml(text, "toml")?))?;
        let state = SceneState { world, renderer: Renderer::new(), rgba: Vec::new() };
        unsafe { *out = Box::into_raw(Box::new(SwellScene { inner: Mutex::new(state), pool })) };
        Ok(())
    })
}

/// Frees a scene handle. NULL is ignored.
///
/// # Safety
/// `scene` is NULL or a handle from `swell_scene_from_toml` not yet destroyed, with no other call
/// on it in progress.
#[no_mangle]
pub unsafe extern "C" fn swell_scene_destroy(scene: *mut SwellScene) {
    if !scene.is_null() {
        let _ = catch_unwind(AssertUnwindSafe(|| {
            // SAFETY: the caller gives back a pointer from Box::into_raw, once.
            drop(unsafe { Box::from_raw(scene) });
        }));
    }
}

/// The size in pixels of the images `swell_scene_render_rgba8` draws (`[render] width` and
/// `height` of the scene).
///
/// # Safety
/// `scene` is a live handle; `width` and `height` point to writable `uint32_t`s.
#[no_mangle]
pub unsafe extern "C" fn swell_scene_image_size(
    scene: *const SwellScene,
    width: *mut u32,
    height: *mut u32,
) -> SwellResult {
    guard(|| {
        let s = non_null("scene", scene)?;
        check_null("width", width)?;
        check_null("height", height)?;
        let s = lock(&s.inner);
        let r = &s.world.scene.render;
        // SAFETY: checked non-NULL; the caller promises they are writable.
        unsafe { (*width, *height) = (r.width, r.height) };
        Ok(())
    })
}

/// Renders the scene at time `t` (s, finite) into `rgba`: `width * height` pixels of 4 bytes (R,
/// G, B, A; sRGB-encoded as the scene says; A = 255), top row first, so `rgba_len` must be
/// `4 * width * height` (see `swell_scene_image_size`). The pixels are those of
/// `swell render --time t` of the same text.
///
/// # Safety
/// `scene` is a live handle; `rgba` points to `rgba_len` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn swell_scene_render_rgba8(
    scene: *mut SwellScene,
    t: f64,
    rgba: *mut u8,
    rgba_len: usize,
) -> SwellResult {
    guard(|| {
        let s = non_null("scene", scene)?;
        check_null("rgba", rgba)?;
        check_time(t)?;
        let mut locked = lock(&s.inner);
        let state = &mut *locked;
        let r = state.world.scene.render;
        let expected = 4 * r.width as usize * r.height as usize;
        check_len("rgba_len", rgba_len, expected, &format!("4 bytes x {} x {} pixels", r.width, r.height))?;
        s.pool.install(|| -> swell_lib::Result<()> {
            state.world.update(t)?;
            state.renderer.render(&state.world).encode_rgba8(&r.display_encoding(), &mut state.rgba);
            Ok(())
        })?;
        // SAFETY: length checked; the caller promises the buffer holds it.
        unsafe { std::slice::from_raw_parts_mut(rgba, rgba_len) }.copy_from_slice(&state.rgba);
        Ok(())
    })
}

mod bodies;
pub use bodies::*;

#[cfg(test)]
mod tests;
