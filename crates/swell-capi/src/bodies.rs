//! Floating bodies from C (issue 34): the `[[body]]`s of a scene handle, stepped by its
//! [`World`] on the scene's own water, so an engine floats its crates on exactly the waves it
//! queries and draws.
//!
//! The scene handle ([`SwellScene`]) is the one that holds a [`World`], the type that steps bodies
//! (`World::advance`), so the bodies live there rather than on the water handle, whose
//! [`swell_lib::Water`] has no bodies. A `SwellWater` made from the same text answers queries on
//! the same water: both build the model from the same `[water]` section.

use std::ffi::c_char;

use glam::{DVec3, Vec3};
use swell_lib::body::{BodyShape, BodySpec};
use swell_lib::error::Human;
use swell_lib::limits::MAX_TIME_S;
use swell_lib::world::World;
use swell_lib::Error;

use super::{check_len, check_null, guard, invalid, lock, non_null, text, Failure, SwellResult, SwellScene};

/// The name scene texts are known by in error messages, as for `swell_scene_from_toml`.
const SOURCE: &str = "toml";

/// Refuses a time the bodies cannot be asked for: not finite, before t = 0 (when the bodies
/// start; the library has no pose before it) or past `MAX_TIME_S`.
fn check_body_time(t: f64) -> Result<(), Failure> {
    if t.is_finite() && (0.0..=MAX_TIME_S).contains(&t) {
        return Ok(());
    }
    let range = format!("[0, {MAX_TIME_S:e}] seconds (floating bodies start at t = 0)");
    Err(Failure(SwellResult::InvalidArgument, Error::out_of_range("t", Human(t), range).to_string()))
}

/// Refuses an index that is not one of the scene's `count` bodies.
fn check_index(index: usize, count: usize) -> Result<(), Failure> {
    match count {
        _ if index < count => Ok(()),
        0 => Err(invalid("index", format!("{index}; the scene has no bodies"))),
        n => Err(invalid("index", format!("{index}; must be below {n} (the scene's bodies)"))),
    }
}

/// Moves the world to `t` (checked by [`check_body_time`]) on the handle's pool.
fn advance(scene: &SwellScene, world: &mut World, t: f64) -> Result<(), Failure> {
    scene.pool.install(|| world.advance(t))?;
    Ok(())
}

/// How many floating bodies (`[[body]]`) the scene has, added ones included: `*count`, in
/// [0, 1024].
///
/// # Safety
/// `scene` is a live handle; `count` points to a writable `size_t`.
#[no_mangle]
pub unsafe extern "C" fn swell_scene_body_count(scene: *const SwellScene, count: *mut usize) -> SwellResult {
    guard(|| {
        let s = non_null("scene", scene)?;
        check_null("count", count)?;
        let n = lock(&s.inner).world.bodies.len();
        // SAFETY: checked non-NULL; the caller promises it is writable.
        unsafe { *count = n };
        Ok(())
    })
}

/// The name of body `index` (in [0, count)), UTF-8, NUL-terminated, into `name` (`name_len`
/// bytes). `*name_size` always receives the bytes the name needs, its NUL included; a
/// `name_len` below it is refused (`SWELL_RESULT_INVALID_ARGUMENT`) and nothing is written to
/// `name`. `name` may be NULL when `name_len` is 0: a call that only asks the size. A body the
/// scene leaves unnamed is `body<index>`.
///
/// # Safety
/// `scene` is a live handle; `name` is NULL or points to `name_len` writable bytes; `name_size`
/// points to a writable `size_t`.
#[no_mangle]
pub unsafe extern "C" fn swell_scene_body_name(
    scene: *const SwellScene,
    index: usize,
    name: *mut c_char,
    name_len: usize,
    name_size: *mut usize,
) -> SwellResult {
    guard(|| {
        let s = non_null("scene", scene)?;
        check_null("name_size", name_size)?;
        if name_len > 0 {
            check_null("name", name)?;
        }
        let state = lock(&s.inner);
        let bodies = state.world.bodies.bodies();
        check_index(index, bodies.len())?;
        let bytes = bodies[index].name.as_bytes();
        let needed = bytes.len() + 1;
        // SAFETY: checked non-NULL; the caller promises it is writable.
        unsafe { *name_size = needed };
        if name.is_null() {
            return Ok(());
        }
        if name_len < needed {
            return Err(invalid(
                "name_len",
                format!("{name_len}; must be at least {needed} (the name's {} bytes and a NUL)", bytes.len()),
            ));
        }
        // SAFETY: `name` holds `name_len` >= `needed` writable bytes (the caller's contract).
        let out = unsafe { std::slice::from_raw_parts_mut(name.cast::<u8>(), needed) };
        out[..bytes.len()].copy_from_slice(bytes);
        out[bytes.len()] = 0;
        Ok(())
    })
}

/// The index of the body named `name` (UTF-8, NUL-terminated) into `*index`; a name no body has
/// is refused (`SWELL_RESULT_INVALID_ARGUMENT`) and `*index` left as it was.
///
/// # Safety
/// `scene` is a live handle; `name` is a NUL-terminated string; `index` points to a writable
/// `size_t`.
#[no_mangle]
pub unsafe extern "C" fn swell_scene_body_index(
    scene: *const SwellScene,
    name: *const c_char,
    index: *mut usize,
) -> SwellResult {
    guard(|| {
        let s = non_null("scene", scene)?;
        check_null("index", index)?;
        // SAFETY: the caller promises a NUL-terminated string.
        let wanted = unsafe { text("name", name)? };
        let state = lock(&s.inner);
        let bodies = state.world.bodies.bodies();
        let Some(k) = bodies.iter().position(|b| b.name == wanted) else {
            // The message is made printable (escapes, length) where it is stored.
            return Err(invalid("name", format!("\"{wanted}\" names none of the scene's {} bodies", bodies.len())));
        };
        // SAFETY: checked non-NULL; the caller promises it is writable.
        unsafe { *index = k };
        Ok(())
    })
}

/// Moves the scene to time `t` (s, in [0, 1e7]): its floating bodies step at 120 Hz up to `t`,
/// each step on the water at that step's time, and the water model moves to `t` (the drawn surface
/// is moved by the next `swell_scene_render_rgba8`). The steps are the fixed 120 Hz ones whatever
/// times are asked, so a pose does not depend on the frame rate: `t` reached in one call or in 60
/// fps steps gives the same numbers. A `t` before the scene's time replays from t = 0 (the bodies
/// added later held until their release, the thrusts as they are now), which costs the steps from
/// 0 to `t`; going forward costs the steps from the scene's time. Each step moves the water model
/// to its time (for the FFT ocean, one synthesis a step). Fails with `SWELL_RESULT_UNSTABLE` if a
/// body left the finite numbers; the bodies are then back at t = 0.
///
/// # Safety
/// `scene` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn swell_scene_advance(scene: *mut SwellScene, t: f64) -> SwellResult {
    guard(|| {
        let s = non_null("scene", scene)?;
        check_body_time(t)?;
        let mut state = lock(&s.inner);
        advance(s, &mut state.world, t)
    })
}

/// Moves the scene to time `t` (s, in [0, 1e7]) as `swell_scene_advance` does, then writes every
/// body's pose at `t`, in body order: `positions` receives the centre of mass (x, y, z, world m),
/// `rotations` the unit quaternion (x, y, z, w) turning the body's frame into the world's, so
/// `positions_len` must be `3 * count` and `rotations_len` `4 * count` (`swell_scene_body_count`).
/// The numbers are `World::body_poses()` of the Rust library, and those `swell bake` writes to
/// `bodies.json`. Nothing is written on failure, and never a NaN: a non-finite pose is refused
/// with `SWELL_RESULT_UNSTABLE`.
///
/// # Safety
/// `scene` is a live handle; `positions` and `rotations` point to `positions_len` and
/// `rotations_len` writable doubles, not overlapping.
#[no_mangle]
pub unsafe extern "C" fn swell_scene_body_poses(
    scene: *mut SwellScene,
    t: f64,
    positions: *mut f64,
    positions_len: usize,
    rotations: *mut f64,
    rotations_len: usize,
) -> SwellResult {
    guard(|| {
        let s = non_null("scene", scene)?;
        check_null("positions", positions)?;
        check_null("rotations", rotations)?;
        check_body_time(t)?;
        let mut state = lock(&s.inner);
        let n = state.world.bodies.len();
        check_len("positions_len", positions_len, 3 * n, &format!("3 doubles per body x {n} bodies"))?;
        check_len("rotations_len", rotations_len, 4 * n, &format!("4 doubles per body x {n} bodies"))?;
        advance(s, &mut state.world, t)?;
        let poses = state.world.body_poses();
        // The library checks the state at every step; the pose between steps is integrated on
        // from it, and is checked here so that no NaN ever reaches the caller's buffers.
        if poses.len() != n || !poses.iter().all(|p| p.position.is_finite() && p.rotation.is_finite()) {
            return Err(Failure(
                SwellResult::Unstable,
                format!("simulation unstable: the bodies' poses at t = {} s are not finite numbers", Human(t)),
            ));
        }
        // SAFETY: lengths checked; the caller promises the buffers hold them.
        let (p, r) = unsafe {
            (
                std::slice::from_raw_parts_mut(positions, positions_len),
                std::slice::from_raw_parts_mut(rotations, rotations_len),
            )
        };
        for ((pose, p), r) in poses.iter().zip(p.chunks_exact_mut(3)).zip(r.chunks_exact_mut(4)) {
            p.copy_from_slice(&pose.position.to_array());
            r.copy_from_slice(&pose.rotation.to_array());
        }
        Ok(())
    })
}

/// Adds a floating body described by `toml`, the text of one `[[body]]` table as a scene file
/// holds it, header included (`"[[body]]\nshape = 'box'\nsize = [1.0, 0.5, 2.0]\n..."`, every key
/// of docs/scene-format.md; a mesh's relative `path` is relative to the working directory). It
/// joins the scene as its last body, held still at its initial pose until the next body step
/// after the scene's time (later if its `release_time` says so), then free; `*index` (if `index`
/// is not NULL) receives its index. Refused with `SWELL_RESULT_SCENE` and a message naming the key
/// as the scene numbers the new body (`toml: body[3].size[0] = -1 is outside [0.02, 1000]`): bad
/// keys, a name another body has, text holding anything but one `[[body]]` table, a body starting
/// inside the terrain.
///
/// # Safety
/// `scene` is a live handle; `toml` is a NUL-terminated UTF-8 string; `index` is NULL or points to
/// a writable `size_t`.
#[no_mangle]
pub unsafe extern "C" fn swell_scene_add_body_toml(
    scene: *mut SwellScene,
    toml: *const c_char,
    index: *mut usize,
) -> SwellResult {
    guard(|| {
        let s = non_null("scene", scene)?;
        // SAFETY: the caller promises a NUL-terminated string.
        let snippet = unsafe { text("toml", toml)? };
        let mut state = lock(&s.inner);
        // Released at the next body step after the world's time (World::add_body).
        let spec = state.world.scene.body_from_toml(snippet, SOURCE)?;
        let k = state.world.add_body(spec).map_err(|e| e.in_source(SOURCE))?;
        if !index.is_null() {
            // SAFETY: not NULL; the caller promises it is writable.
            unsafe { *index = k };
        }
        Ok(())
    })
}

/// Adds a floating body from parameters, as `swell_scene_add_body_toml` does with the keys
/// `name` (NULL or "" for `body<index>`), `shape` ("box", "sphere" or "capsule"; a mesh needs its
/// file: use the TOML form), `size` (`size_len` doubles, m: box [x, y, z] full extents, sphere
/// [radius], capsule [radius, length], each in [0.02, 1000]), `density` (kg/m³, in [10, 20000];
/// 500 floats half under) and the centre of mass at (`x`, `y`, `z`) (world m, each within 1e5),
/// unturned and at rest; every other key at its default. The numbers are narrowed to the scene's
/// floats. `*index` (if `index` is not NULL) receives the new body's index. Refused with
/// `SWELL_RESULT_INVALID_ARGUMENT` and a message naming the key (`body[3].density = 0 is outside
/// [10, 20000]`).
///
/// # Safety
/// `scene` is a live handle; `name` is NULL or a NUL-terminated string; `shape` is a
/// NUL-terminated string; `size` points to `size_len` readable doubles; `index` is NULL or points
/// to a writable `size_t`.
#[no_mangle]
#[allow(clippy::too_many_arguments)] // A C signature: the parameters of a body, flat.
pub unsafe extern "C" fn swell_scene_add_body(
    scene: *mut SwellScene,
    name: *const c_char,
    shape: *const c_char,
    size: *const f64,
    size_len: usize,
    density: f64,
    x: f64,
    y: f64,
    z: f64,
    index: *mut usize,
) -> SwellResult {
    guard(|| {
        let s = non_null("scene", scene)?;
        check_null("size", size)?;
        // SAFETY: the caller promises a NUL-terminated string.
        let shape_name = unsafe { text("shape", shape)? };
        let name = if name.is_null() { "" } else { unsafe { text("name", name)? } };
        let shape = BodyShape::parse("shape", shape_name)?;
        if shape == BodyShape::Mesh {
            return Err(invalid(
                "shape",
                "\"mesh\" reads its hull from an OBJ file: add it with swell_scene_add_body_toml and its path".into(),
            ));
        }
        // Checked before the buffer is read: at most 3 values, whatever the pointer holds.
        if size_len > 3 {
            return Err(invalid("size_len", format!("{size_len}; must be 3 (box), 1 (sphere) or 2 (capsule)")));
        }
        // SAFETY: the caller promises `size_len` readable doubles (at most 3, checked).
        let size: Vec<f32> = unsafe { std::slice::from_raw_parts(size, size_len) }.iter().map(|&v| v as f32).collect();
        let mut spec = BodySpec::new(shape, &size, Vec3::new(x as f32, y as f32, z as f32));
        spec.name = name.to_string();
        spec.density = Some(density as f32);
        let mut state = lock(&s.inner);
        let k = state.world.add_body(spec).map_err(|e| {
            // The keys of this body are this function's arguments, not a scene's text.
            let Failure(code, message) = Failure::from(e);
            Failure(if code == SwellResult::Scene { SwellResult::InvalidArgument } else { code }, message)
        })?;
        if !index.is_null() {
            // SAFETY: not NULL; the caller promises it is writable.
            unsafe { *index = k };
        }
        Ok(())
    })
}

/// Sets the thrust of body `index`: a force (`fx`, `fy`, `fz`) in newtons, world axes, applied at
/// its centre of mass from the next body step on, on top of gravity's, the water's and the
/// ground's (an engine's propeller, a player's push); (0, 0, 0) removes it. It is not part of the
/// scene: a time before the scene's replays from t = 0 with the thrust as it is now. A force so
/// strong that a body leaves the finite numbers fails the next advance with
/// `SWELL_RESULT_UNSTABLE`.
///
/// # Safety
/// `scene` is a live handle.
#[no_mangle]
pub unsafe extern "C" fn swell_scene_set_body_thrust(
    scene: *mut SwellScene,
    index: usize,
    fx: f64,
    fy: f64,
    fz: f64,
) -> SwellResult {
    guard(|| {
        let s = non_null("scene", scene)?;
        for (key, v) in [("fx", fx), ("fy", fy), ("fz", fz)] {
            if !v.is_finite() {
                return Err(invalid(key, format!("{v} is not a finite force (newtons)")));
            }
        }
        let mut state = lock(&s.inner);
        let bodies = state.world.bodies.bodies_mut();
        check_index(index, bodies.len())?;
        bodies[index].thrust = DVec3::new(fx, fy, fz);
        Ok(())
    })
}
