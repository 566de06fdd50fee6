//! Raw command-line arguments, exactly as typed. Resolution and checking happen in `cmd`.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

/// swell: water surfaces over procedural terrain, simulated and rendered on the CPU.
#[derive(Parser, Debug)]
#[command(name = "swell", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render one frame to PNG, or an animation to GIF.
    Render(RenderArgs),
    /// List the built-in scenes, one per line.
    Presets,
    /// Generate a terrain and write it as a 16-bit grayscale PNG heightmap plus a sidecar
    /// (`FILE.toml`) with its height scale, offset and extent.
    Terrain(TerrainArgs),
}

/// Where the scene comes from: exactly one of a preset or a file.
#[derive(Args, Debug)]
#[group(required = true, multiple = false)]
pub struct SceneSource {
    /// A built-in scene (see `swell presets`).
    #[arg(long, value_name = "NAME")]
    pub preset: Option<String>,
    /// A scene file (TOML, see docs/scene-format.md).
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
}

/// `swell render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub source: SceneSource,
    /// Output file: `.png` for one frame, `.gif` for an animation (with --frames).
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Simulation time of the (first) frame, in seconds.
    #[arg(long, value_name = "SECONDS", default_value_t = 0.0, allow_negative_numbers = true)]
    pub time: f64,
    /// Image size as WIDTHxHEIGHT (default: the scene's [render] size, 1280x720 unless set).
    #[arg(long, value_name = "WxH")]
    pub size: Option<String>,
    /// Number of frames of a GIF animation, 1 to 10000.
    #[arg(long, value_name = "N")]
    pub frames: Option<u32>,
    /// Frames per second of the animation, in (0, 100]; frame k shows time + k / fps.
    #[arg(long, value_name = "F", default_value_t = 24.0)]
    pub fps: f64,
    /// Worker threads, 0 = one per core (default: the scene's render.threads). The image does not
    /// depend on it.
    #[arg(long, value_name = "N")]
    pub threads: Option<u32>,
}

/// `swell terrain`.
#[derive(Args, Debug)]
pub struct TerrainArgs {
    /// The generator: diamond-square, random-average, noise, hills, flat, slope or channel.
    #[arg(long, value_name = "NAME")]
    pub generator: String,
    /// Vertices per side (diamond-square: 2^n + 1, e.g. 257, 513, 1025).
    #[arg(long, value_name = "N", default_value_t = 257)]
    pub size: u32,
    /// Seed of the random generators.
    #[arg(long, value_name = "S")]
    pub seed: Option<u64>,
    /// Horizontal extent in metres: `X` (square) or `XxZ` (default 200).
    #[arg(long, value_name = "METRES")]
    pub extent: Option<String>,
    /// A generator key as in a scene's [terrain] section, `KEY=VALUE` with a TOML value
    /// (e.g. `--set roughness=0.6 --set corners=[0,0,10,10]`); repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Output PNG; the sidecar is written beside it as `FILE.toml`.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Worker threads, 0 = one per core. The heightmap does not depend on it.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub threads: u32,
}
