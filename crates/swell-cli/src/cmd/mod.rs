//! One file per subcommand, plus what they share: loading a scene and building a thread pool.

mod bench;
mod presets;
mod render;
mod terrain;
// issue 8: meshes and map bakes.
mod bake;
mod export;
mod stats;
mod view;

use swell::scene::{preset, Scene, MAX_THREADS};
use swell::{Error, Result};

use crate::args::{Cli, Command, SceneSource};

/// Runs the parsed command line.
pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Render(a) => render::run(a),
        Command::Presets => presets::run(),
        Command::Terrain(a) => terrain::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Export(a) => export::run(a),
        Command::Bake(a) => bake::run(a),
        Command::View(a) => view::run(a),
        Command::Stats(a) => stats::run(a),
    }
}

/// Loads the scene named by `--preset` or `--scene`, printing on stderr what the scene asks for
/// but will not get exactly (a loop period too short for the sea).
pub fn load_scene(source: &SceneSource) -> Result<Scene> {
    let scene = read_scene(source)?;
    if let Some(warning) = scene.water.as_ref().and_then(|w| w.model.loop_warning()) {
        eprintln!("warning: {warning}");
    }
    Ok(scene)
}

/// Reads and validates the scene named by `--preset` or `--scene`.
fn read_scene(source: &SceneSource) -> Result<Scene> {
    match (&source.preset, &source.scene) {
        (Some(name), _) => preset(name),
        (None, Some(path)) => {
            // Read at most one byte past the limit, so a huge file (or /dev/zero) is refused
            // without being read whole; Scene::from_toml then names the limit.
            let mut bytes = Vec::new();
            let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
            std::io::Read::read_to_end(&mut std::io::Read::take(file, swell::limits::MAX_SCENE_BYTES + 1), &mut bytes)
                .map_err(|e| Error::io(path, e))?;
            if bytes.len() as u64 > swell::limits::MAX_SCENE_BYTES {
                return Err(Error::Parse {
                    path: path.display().to_string(),
                    message: format!(
                        "over the scene-file limit of {} bytes (MAX_SCENE_BYTES)",
                        swell::limits::MAX_SCENE_BYTES
                    ),
                });
            }
            let text = String::from_utf8(bytes).map_err(|_| Error::Parse {
                path: path.display().to_string(),
                message: "not UTF-8 text (a scene file is TOML)".into(),
            })?;
            let mut scene = Scene::from_toml(&text, &path.display().to_string())?;
            // Files a scene names (heightmaps) are relative to the scene file.
            scene.resolve_paths(path.parent().unwrap_or(std::path::Path::new("")));
            Ok(scene)
        }
        (None, None) => unreachable!("clap requires one of --preset and --scene"),
    }
}

/// A rayon pool with `threads` workers (0 = one per core).
pub fn thread_pool(threads: u32) -> Result<rayon::ThreadPool> {
    if threads > MAX_THREADS {
        return Err(Error::out_of_range("--threads", threads, format!("[0, {MAX_THREADS}]")));
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads as usize)
        .build()
        .map_err(|e| Error::invalid("--threads", format!("cannot start {threads} threads: {e}")))
}

/// Fails early, before any work, if the directory `--out` would be written into does not exist.
fn check_output_dir(out: &std::path::Path) -> Result<()> {
    let dir = match out.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => std::path::Path::new("."),
    };
    if dir.is_dir() {
        Ok(())
    } else {
        Err(Error::invalid("--out", format!("directory {} does not exist", dir.display())))
    }
}
