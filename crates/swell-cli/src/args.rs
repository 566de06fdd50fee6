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
    /// Write the displaced surface (and camera) as OBJ, glTF or GLB meshes.
    Export(ExportArgs),
    /// Bake displacement, normal and foam maps per frame (EXR, optionally PNG) into a directory.
    Bake(BakeArgs),
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

/// `swell export`.
#[derive(Args, Debug)]
pub struct ExportArgs {
    #[command(flatten)]
    pub source: SceneSource,
    /// Output file; with --frames, frame k goes to STEM_kkkk.EXT beside it.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Mesh format: obj, gltf (JSON + .bin) or glb (default: from the --out extension).
    #[arg(long, value_name = "FORMAT")]
    pub format: Option<String>,
    /// Simulation time in seconds (one file).
    #[arg(
        long,
        value_name = "SECONDS",
        default_value_t = 0.0,
        allow_negative_numbers = true,
        conflicts_with = "frames"
    )]
    pub time: f64,
    /// Frames A..B (inclusive) to export, one file each, frame k at time k / fps.
    #[arg(long, value_name = "A..B", allow_hyphen_values = true)]
    pub frames: Option<String>,
    /// Frames per second for --frames, in (0, 1000].
    #[arg(long, value_name = "F", default_value_t = 24.0, allow_negative_numbers = true)]
    pub fps: f64,
    /// Worker threads, 0 = one per core. The files do not depend on it.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub threads: u32,
}

/// `swell bake`.
#[derive(Args, Debug)]
pub struct BakeArgs {
    #[command(flatten)]
    pub source: SceneSource,
    /// Frames A..B to bake, both included (0..0 is one frame), frame k at time k / fps.
    #[arg(long, value_name = "A..B", allow_hyphen_values = true)]
    pub frames: String,
    /// Frames per second, in (0, 1000].
    #[arg(long, value_name = "F", default_value_t = 24.0, allow_negative_numbers = true)]
    pub fps: f64,
    /// Output directory (created if missing); holds bake.json and the frames' maps.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Skip frames whose files all exist (a killed or partial bake continues where it stopped).
    #[arg(long)]
    pub resume: bool,
    /// Bake only shard I of N: frames A+I, A+I+N, ... (I from 0).
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Also write PNG maps with 8 or 16 bits per sample (16 if no value is given).
    #[arg(long, value_name = "BITS", num_args = 0..=1, default_missing_value = "16")]
    pub png: Option<u8>,
    /// PNG displacement range in metres: components map from [-R, R] (default: from the first frame).
    #[arg(long, value_name = "R")]
    pub png_range: Option<f32>,
    /// Maps of CELLS x CELLS pixels (leave out the last column and row, which repeat the first for
    /// models periodic over the patch, such as the FFT ocean), for wrap-around sampling.
    #[arg(long)]
    pub tile: bool,
    /// EXR compression: none, rle, zip or piz (all lossless).
    #[arg(long, value_name = "C", default_value = "none")]
    pub exr_compression: String,
    /// Worker threads, 0 = one per core. The files do not depend on it.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub threads: u32,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}
