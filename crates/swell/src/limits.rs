//! Resource limits: the one place that says how large anything a user asks for may be, and how much
//! memory it will take, so that oversized requests fail with a clear error *before* allocating.
//!
//! Every size a user gives has two checks:
//!
//! 1. a per-key limit (image side, grid cells, terrain side, frames, waves...), checked where the key
//!    is validated and named in its error (`render.width = 20000 is outside [1, 16384]`);
//! 2. a whole-job memory estimate (`Scene::estimate_bytes`, [`estimate_frame_bytes`]) compared with
//!    [`MEMORY_BUDGET_BYTES`] by [`check_memory`], because keys that are each within their limit can
//!    still add up to more than a machine holds (a 4096² water grid *and* a 4097² terrain *and* a
//!    16384² image).
//!
//! The estimates count the buffers swell itself allocates, per element, rounded up; they are meant
//! to be within a factor of 1.5 of the real peak, which is enough to refuse a job that would exhaust
//! memory while never refusing one that fits comfortably.
//!
//! The per-key limits live beside the keys they limit (`MAX_IMAGE_SIDE` in `scene/render_settings.rs`,
//! `MAX_GERSTNER_WAVES` in `water/gerstner.rs`...); `docs/ROBUSTNESS.md` lists them all with their
//! reasons. This module is the bottom layer: it imports nothing of swell but its error type and the
//! input opening of `io` (for [`read_text_limited`]), so every layer may use it.

use crate::error::{Error, Result};

/// Most memory (bytes) one job may plan to use: 4 GiB.
///
/// Chosen so that any accepted scene runs on an 8 GiB laptop with room for the operating system,
/// while every realistic scene (a 1024² grid at 4K is about 0.3 GiB) is far below it.
pub const MEMORY_BUDGET_BYTES: u64 = 4 << 30;

/// Most frames one animation may have (`swell render --frames`): 10 000, i.e. over 5 minutes at
/// 30 fps, which already takes hours to render and gigabytes to store.
pub const MAX_FRAMES: u32 = 10_000;

/// Largest simulation time, seconds, in either direction: 10⁷ s (116 days). Every model reduces
/// its phases in f64 (`water/trochoidal_sum.rs`, `fft_ocean/cascade.rs`), where a time of 10⁷ s
/// still resolves 2 ns, far below a frame; beyond some 10¹⁵ s the phase of a 1 Hz wave would be
/// noise. Times past this limit are a mistake (a frame number given as seconds), not a wish.
pub const MAX_TIME_S: f64 = 1.0e7;

/// Checks a simulation time (s) against ±[`MAX_TIME_S`], naming `key` (e.g. `--time`).
pub fn check_time(key: &str, t: f64) -> crate::Result<()> {
    if t.is_finite() && t.abs() <= MAX_TIME_S {
        Ok(())
    } else {
        Err(crate::Error::out_of_range(
            key,
            crate::error::Human(t),
            format!("[-{MAX_TIME_S:e}, {MAX_TIME_S:e}] seconds"),
        ))
    }
}

/// Most bytes of scene-file text read: 16 MiB. A hand-written scene is a few kilobytes; the largest
/// legitimate one (64 waves per list, 16 lights) is under 100 KiB.
pub const MAX_SCENE_BYTES: u64 = 16 << 20;

/// Deepest nesting of arrays and inline tables accepted in a scene file: 64.
///
/// The deepest legitimate key (`[[water.waves]]` with a `direction` array) nests 3 levels. The TOML
/// parser recurses once per level; checking the depth before parsing means a hostile file of
/// 100 000 `[` cannot overflow the stack, whatever the parser's own guards.
pub const MAX_NESTING_DEPTH: usize = 64;

/// Most list items in a scene file: 16 384, counted before parsing as the elements of every array
/// and every `[[table]]` entry.
///
/// The largest legitimate scene (64 waves in each of a few lists, 16 lights, a vector per key)
/// holds under 2 000. Counting first means a file of 150 000 waves is refused in milliseconds,
/// not after seconds and hundreds of megabytes of parsing (issue 37); the wave models' own limits
/// (e.g. 64 Gerstner waves) then name the key that is too long.
pub const MAX_LIST_ITEMS: usize = 16_384;

/// Largest wave amplitude or wavelength, metres: 100 km, far past any real wave (the longest ocean
/// swells are about 1 km; tsunamis about 200 km but not modelled here), small enough that sums of
/// many waves stay finite in f32.
pub const MAX_WAVE_LENGTH_M: f32 = 1.0e5;

/// Largest wave speed, m/s: 1000 (a 100 km deep-water wave travels about 400 m/s).
pub const MAX_WAVE_SPEED: f32 = 1.0e3;

/// Bytes per water vertex: the [`crate::mesh::SurfaceMesh`] buffers (position 12, normal 12, uv 8,
/// foam 4) plus the renderer's transformed copy (clip position 16, colour 12) = 64, rounded up.
pub const WATER_BYTES_PER_VERTEX: u64 = 64;

/// Bytes per grid cell for triangle indices: 2 triangles of 3 `u32`.
pub const BYTES_PER_CELL: u64 = 24;

/// Bytes per terrain vertex: the height field (4), its mesh and the renderer's copy as for water
/// (64), and the water depth measured under it (4), rounded up to 80.
pub const TERRAIN_BYTES_PER_VERTEX: u64 = 80;

/// Bytes per image pixel: linear colour (12) and depth (4) in the framebuffer, and the encoded RGBA8
/// copy (4).
pub const BYTES_PER_PIXEL: u64 = 20;

/// Bytes per FFT-ocean sample, per cascade: the initial spectrum and its mirror (8 + 8), the phase
/// cycles (8), the spectrum at t and FFT work space (8 + 8), four complex field pairs (32), the
/// wavenumber (4) and foam (4), rounded up to 96.
pub const FFT_BYTES_PER_SAMPLE: u64 = 96;

/// Bytes of the FFT ocean's `cascades` grids of `grid` x `grid` samples.
pub fn estimate_fft_bytes(grid: u32, cascades: u32) -> u64 {
    (grid as u64 * grid as u64).saturating_mul(FFT_BYTES_PER_SAMPLE).saturating_mul(cascades as u64)
}

/// Bytes of the framebuffer and encoded image for a `width` x `height` frame.
pub fn estimate_frame_bytes(width: u32, height: u32) -> u64 {
    (width as u64 * height as u64).saturating_mul(BYTES_PER_PIXEL)
}

/// Bytes of a water or terrain grid of `cells_x` x `cells_z` cells with `per_vertex` bytes per
/// vertex.
pub fn estimate_grid_bytes(cells_x: u32, cells_z: u32, per_vertex: u64) -> u64 {
    // Saturating: the estimate may be asked about unvalidated sizes, and must not wrap to small.
    let verts = (cells_x as u64 + 1).saturating_mul(cells_z as u64 + 1);
    verts.saturating_mul(per_vertex).saturating_add((cells_x as u64 * cells_z as u64).saturating_mul(BYTES_PER_CELL))
}

/// Refuses a job whose estimate `bytes` passes [`MEMORY_BUDGET_BYTES`]; `what` says what was
/// estimated (e.g. `scene (water grid + terrain + framebuffer)`).
pub fn check_memory(what: &str, bytes: u64) -> Result<()> {
    if bytes <= MEMORY_BUDGET_BYTES {
        Ok(())
    } else {
        Err(Error::invalid(
            what,
            format!(
                "needs about {} MiB, over the memory budget of {} MiB (MEMORY_BUDGET_BYTES); \
                 reduce water.cells, terrain.size or the image size",
                bytes >> 20,
                MEMORY_BUDGET_BYTES >> 20
            ),
        ))
    }
}

/// Refuses scene text longer than [`MAX_SCENE_BYTES`] or nesting arrays / inline tables deeper than
/// [`MAX_NESTING_DEPTH`], before the TOML parser sees it. Brackets inside strings and comments are
/// skipped, so legitimate text is never refused for the characters it contains.
pub fn check_scene_text(text: &str, source: &str) -> Result<()> {
    if text.len() as u64 > MAX_SCENE_BYTES {
        return Err(Error::Parse {
            path: source.into(),
            message: format!(
                "{} bytes is over the scene-file limit of {MAX_SCENE_BYTES} bytes (MAX_SCENE_BYTES)",
                text.len()
            ),
        });
    }
    let shape = text_shape(text);
    if shape.depth > MAX_NESTING_DEPTH {
        return Err(Error::Parse {
            path: source.into(),
            message: format!(
                "arrays or inline tables nested {}+ deep, over the limit of {MAX_NESTING_DEPTH} \
                 (MAX_NESTING_DEPTH)",
                shape.depth
            ),
        });
    }
    if shape.items > MAX_LIST_ITEMS {
        return Err(Error::Parse {
            path: source.into(),
            message: format!(
                "{}+ list items (array elements and [[table]] entries), over the limit of {MAX_LIST_ITEMS} \
                 (MAX_LIST_ITEMS)",
                shape.items
            ),
        });
    }
    Ok(())
}

/// Reads the UTF-8 text file `path`, refusing one over `max_bytes` (named `limit_name` in the
/// error) after reading at most one byte past it, so `/dev/zero` or a huge download given as a
/// small text file cannot exhaust memory. Opened by [`crate::io::read_input`], so a FIFO with no
/// writer is refused at once rather than waited on, and a directory is refused as one.
pub fn read_text_limited(path: &std::path::Path, max_bytes: u64, limit_name: &str) -> Result<String> {
    let bytes = crate::io::read_input(path, max_bytes)?;
    let parse_err = |message: String| Error::Parse { path: path.display().to_string(), message };
    if bytes.len() as u64 > max_bytes {
        return Err(parse_err(format!("over the file-size limit of {max_bytes} bytes ({limit_name})")));
    }
    String::from_utf8(bytes).map_err(|_| parse_err("not UTF-8 text".into()))
}

/// What [`text_shape`] finds in scene text before it is parsed.
struct TextShape {
    /// Deepest `[` / `{` nesting.
    depth: usize,
    /// Array elements (commas inside brackets, plus one per array) and `[[table]]` entries.
    items: usize,
}

/// Deepest `[` / `{` nesting in TOML `text`, outside strings and comments, stopping early once past
/// [`MAX_NESTING_DEPTH`]. Table headers (`[a]`, `[[a]]`) count 1 or 2, never more, so they are
/// harmless.
#[cfg(test)]
fn nesting_depth(text: &str) -> usize {
    text_shape(text).depth
}

/// The nesting depth and list items of TOML `text`, outside strings and comments, stopping early
/// once past [`MAX_NESTING_DEPTH`] or [`MAX_LIST_ITEMS`]. Items are over-counted (a trailing comma,
/// a table header's brackets), never under-counted, which is the safe side of a limit.
fn text_shape(text: &str) -> TextShape {
    #[derive(PartialEq)]
    enum State {
        Code,
        Comment,
        Basic,
        Literal,
        MultiBasic,
        MultiLiteral,
    }
    let b = text.as_bytes();
    let (mut state, mut depth, mut max, mut i, mut items) = (State::Code, 0usize, 0usize, 0usize, 0usize);
    while i < b.len() {
        let c = b[i];
        match state {
            State::Code => match c {
                b'#' => state = State::Comment,
                b'"' if b[i..].starts_with(b"\"\"\"") => {
                    state = State::MultiBasic;
                    i += 2;
                }
                b'\'' if b[i..].starts_with(b"'''") => {
                    state = State::MultiLiteral;
                    i += 2;
                }
                b'"' => state = State::Basic,
                b'\'' => state = State::Literal,
                b'[' | b'{' => {
                    depth += 1;
                    items += usize::from(c == b'[');
                    max = max.max(depth);
                    if max > MAX_NESTING_DEPTH || items > MAX_LIST_ITEMS {
                        return TextShape { depth: max, items };
                    }
                }
                b',' if depth > 0 => {
                    items += 1;
                    if items > MAX_LIST_ITEMS {
                        return TextShape { depth: max, items };
                    }
                }
                b']' | b'}' => depth = depth.saturating_sub(1),
                _ => {}
            },
            State::Comment => {
                if c == b'\n' {
                    state = State::Code;
                }
            }
            State::Basic => match c {
                b'\\' => i += 1,
                b'"' | b'\n' => state = State::Code,
                _ => {}
            },
            State::Literal => {
                if c == b'\'' || c == b'\n' {
                    state = State::Code;
                }
            }
            State::MultiBasic => {
                if c == b'\\' {
                    i += 1;
                } else if b[i..].starts_with(b"\"\"\"") {
                    state = State::Code;
                    i += 2;
                }
            }
            State::MultiLiteral => {
                if b[i..].starts_with(b"'''") {
                    state = State::Code;
                    i += 2;
                }
            }
        }
        i += 1;
    }
    TextShape { depth: max, items }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[cfg(feature = "render")]
    use crate::math::MAX_GRID_CELLS;
    #[cfg(feature = "render")]
    use crate::scene::MAX_IMAGE_SIDE;

    #[test]
    fn nesting_counts_brackets_outside_strings_and_comments() {
        assert_eq!(nesting_depth("a = [[1], [2, [3]]]\n"), 3);
        assert_eq!(nesting_depth("[[water.waves]]\nd = [1.0, 0.0]\n"), 2);
        assert_eq!(nesting_depth("s = \"[[[[[[\" # [[[[[[[\nt = '[[[['\nu = \"\"\"[[[\n[[[\"\"\"\n"), 0);
        assert_eq!(nesting_depth("s = \"\\\"[[\"\n"), 0);
        let deep = format!("a = {}1{}\n", "[".repeat(100_000), "]".repeat(100_000));
        assert_eq!(nesting_depth(&deep), MAX_NESTING_DEPTH + 1);
        let e = check_scene_text(&deep, "deep.toml").unwrap_err().to_string();
        assert!(e.starts_with("deep.toml: arrays or inline tables nested") && e.contains("64"), "{e}");
    }

    /// 150 000 waves are refused before the parser builds them, and inline arrays count as
    /// `[[table]]` entries do; legitimate scenes stay far below the limit.
    #[test]
    fn long_lists_are_refused_before_parsing() {
        let wave = "[[water.waves]]\namplitude = 0.1\nwavelength = 9.0\nspeed = 3.7\ndirection = [1.0, 0.0]\n";
        let many = format!("[water]\nmodel = 'gerstner'\n{}", wave.repeat(150_000));
        let e = check_scene_text(&many, "many.toml").unwrap_err().to_string();
        assert!(e.starts_with("many.toml: 16385+ list items") && e.contains("(MAX_LIST_ITEMS)"), "{e}");
        let inline = format!("a = [{}]\n", "1, ".repeat(20_000));
        assert!(check_scene_text(&inline, "a").unwrap_err().to_string().contains("MAX_LIST_ITEMS"));
        assert_eq!(
            text_shape("a = [1, 2, 3]\ns = '[,,]' # ,,[\n[[b]]\n").items,
            3 + 2,
            "an array of 3, a header's two brackets"
        );
        let legit = format!("[water]\nmodel = 'gerstner'\n{}", wave.repeat(64));
        assert!(text_shape(&legit).items < MAX_LIST_ITEMS / 8);
        // The largest, `flotsam` with its 100 bodies, holds about a ninth of the limit.
        #[cfg(feature = "render")]
        for p in crate::scene::PRESETS {
            let text = crate::scene::preset(p.name).unwrap().to_toml();
            assert!(text_shape(&text).items < MAX_LIST_ITEMS / 4, "{}", p.name);
        }
        // A scene of the most bodies, every key given, still loads.
        #[cfg(feature = "render")]
        {
            let body = "[[body]]\nshape = 'box'\nsize = [1.0, 1.0, 1.0]\nposition = [0.0, 0.0, 0.0]\n\
                        rotation_deg = [0.0, 0.0, 0.0]\nvelocity = [0.0, 0.0, 0.0]\nangular_velocity = [0.0, 0.0, 0.0]\n\
                        center_of_mass = [0.0, 0.0, 0.0]\ninertia = [1.0, 1.0, 1.0]\ncolor = [0.5, 0.5, 0.5]\n";
            let text = body.repeat(crate::body::MAX_BODIES);
            assert!(text_shape(&text).items < MAX_LIST_ITEMS, "{}", text_shape(&text).items);
        }
    }

    #[cfg(feature = "render")]
    #[test]
    fn estimates_grow_with_every_size_and_the_budget_refuses_the_largest() {
        let small = estimate_grid_bytes(256, 256, WATER_BYTES_PER_VERTEX);
        assert!(small > 257 * 257 * 36 && small < 10 << 20);
        let big = estimate_grid_bytes(MAX_GRID_CELLS, MAX_GRID_CELLS, WATER_BYTES_PER_VERTEX);
        assert!(big > 1 << 30);
        // The largest image alone passes the budget: each key is in range, the sum is not.
        let frame = estimate_frame_bytes(MAX_IMAGE_SIDE, MAX_IMAGE_SIDE);
        assert!(check_memory("x", frame).is_err());
        assert!(check_memory("x", estimate_frame_bytes(3840, 2160) + small).is_ok());
        let e = check_memory("scene", big + frame).unwrap_err().to_string();
        assert!(e.contains("memory budget of 4096 MiB"), "{e}");
    }
}
