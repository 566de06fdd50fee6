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
    /// Print the sea state realised by a spectral (`model = "fft"`) scene, as JSON.
    Stats(StatsArgs),
    /// Time an experiment (see `swell bench --help`).
    Bench(BenchArgs),
}

/// `swell stats`.
#[derive(Args, Debug)]
pub struct StatsArgs {
    #[command(flatten)]
    pub source: SceneSource,
    /// Simulation time, in seconds.
    #[arg(long, value_name = "SECONDS", default_value_t = 0.0, allow_negative_numbers = true)]
    pub time: f64,
}

/// `swell bench EXPERIMENT`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// The experiment to run.
    #[command(subcommand)]
    pub experiment: BenchExperiment,
}

/// The experiments `swell bench` can time.
#[derive(Subcommand, Debug)]
pub enum BenchExperiment {
    /// The FFT ocean's full step (spectrum evolution, 8 fields, foam) and the displaced mesh.
    Ocean(OceanBenchArgs),
}

/// `swell bench ocean`.
#[derive(Args, Debug)]
pub struct OceanBenchArgs {
    /// FFT grid side N, a power of two in [16, 2048].
    #[arg(long, value_name = "N", default_value_t = 256)]
    pub grid: u32,
    /// Timed steps after the warm-up, 1 to 100000 (default: about one second's worth, at least 10).
    #[arg(long, value_name = "N")]
    pub steps: Option<u32>,
    /// Worker threads, 0 = one per core.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub threads: u32,
    /// Print JSON: {"grid": N, "median_ms": ..., "stages": {...}}.
    #[arg(long)]
    pub json: bool,
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
