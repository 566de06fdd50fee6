//! Where `--scene` reads from (issue 37): a file through [`Scene::load`], which refuses a FIFO
//! that no process writes to instead of blocking on it, or standard input for `--scene -`.

use std::io::Read;
use std::path::Path;

use swell::limits::MAX_SCENE_BYTES;
use swell::scene::Scene;
use swell::{Error, Result};

/// What errors call a scene read from standard input.
const STDIN: &str = "<stdin>";

/// The scene of `--scene PATH`: standard input for `-`, else the file (a pipe with a writer,
/// `<(...)` or `/dev/stdin`, reads like one). A file really named `-` is `./-`.
pub fn load(path: &Path) -> Result<Scene> {
    if path == Path::new("-") {
        from_stdin()
    } else {
        Scene::load(path)
    }
}

/// The scene on standard input, at most [`MAX_SCENE_BYTES`] as from a file (one byte past it is
/// read, and refused); relative paths in it (heightmaps, textures) resolve against the current
/// directory, as there is no file whose directory they could be relative to.
fn from_stdin() -> Result<Scene> {
    let mut bytes = Vec::new();
    std::io::stdin().lock().take(MAX_SCENE_BYTES + 1).read_to_end(&mut bytes).map_err(|e| Error::io(STDIN, e))?;
    Scene::from_bytes(bytes, STDIN, Path::new(""))
}
