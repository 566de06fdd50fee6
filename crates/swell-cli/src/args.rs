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
    /// Render one frame to PNG, or an animation to GIF or a PNG sequence.
    Render(RenderArgs),
    /// List the built-in scenes, one per line.
    Presets,
    /// Generate a terrain and write it as a 16-bit grayscale PNG heightmap plus a sidecar
    /// (`FILE.toml`) with its height scale, offset and extent.
    Terrain(TerrainArgs),
    /// Time the papers' experiments on this machine; write Markdown, JSON and PNG results.
    Bench(BenchArgs),
    /// Write the displaced surface (and camera) as OBJ, glTF or GLB meshes.
    Export(ExportArgs),
    /// Bake displacement, normal and foam maps per frame (EXR, optionally PNG) into a directory.
    Bake(BakeArgs),
    /// Open the interactive viewer (see docs/viewer.md).
    View(ViewArgs),
    /// Print the sea state realised by a spectral (`model = "fft"`) scene, as JSON.
    Stats(StatsArgs),
}

/// `swell stats`.
#[derive(Args, Debug)]
pub struct StatsArgs {
    #[command(flatten)]
    pub source: SceneSource,
    /// Simulation time, in seconds, in [-1e7, 1e7].
    #[arg(long, value_name = "SECONDS", default_value_t = 0.0, allow_negative_numbers = true)]
    pub time: f64,
}

/// Where the scene comes from: exactly one of a preset or a file.
#[derive(Args, Debug)]
#[group(required = true, multiple = false)]
pub struct SceneSource {
    /// A built-in scene (see `swell presets`).
    #[arg(long, value_name = "NAME")]
    pub preset: Option<String>,
    /// A scene file (TOML, see docs/scene-format.md), or `-` to read it from standard input
    /// (relative paths in it then resolve against the current directory). A pipe with a writer
    /// (`<(...)`, /dev/stdin) reads like a file; a FIFO that no process writes to is refused at
    /// once, never waited on.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
}

/// `swell render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub source: SceneSource,
    /// Output file: `.png` for one frame, or `.exr` for one frame's linear scene radiance (float
    /// RGB in units of 20,000 cd/m², the pixels before exposure and the tone curve, for compositing
    /// and measuring); with --frames, `.gif` for an animation or a PNG sequence pattern such as
    /// `frames/sea_%04d.png` (one file per frame, `%04d` replaced by the frame number zero-padded to 4 digits; `%d`
    /// unpadded, `%0Nd` for N in [1, 9], `%%` a literal %; the directory must exist).
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Simulation time of the frame (of frame 0 of an animation), in seconds, in [-1e7, 1e7].
    /// Default 0. Not with --obj (a mesh does not move).
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    pub time: Option<f64>,
    /// Image size as WIDTHxHEIGHT (default: the scene's [render] size, 1280x720 unless set).
    #[arg(long, value_name = "WxH")]
    pub size: Option<String>,
    /// The frames of a GIF animation or PNG sequence: a count N (frames 0 to N-1) or a range A..B
    /// (both included), as in `export` and `bake`; frame k shows time --time + k / fps, and a PNG
    /// sequence names it k (48..95 writes files 48 to 95). At most 10000.
    #[arg(long, value_name = "N|A..B", allow_hyphen_values = true)]
    pub frames: Option<String>,
    /// Frames per second, in (0, 1000] as in `export` and `bake`; a GIF plays at most 50 (its
    /// delays are hundredths of a second, alternated so that the rate is exact on average).
    #[arg(long, value_name = "F", default_value_t = 24.0, allow_negative_numbers = true)]
    pub fps: f64,
    /// Worker threads, 0 = one per core (default: the scene's render.threads). The image does not
    /// depend on it.
    #[arg(long, value_name = "N")]
    pub threads: Option<u32>,
    /// Shading model of the water (scene mode) or of the mesh (--obj mode): flat, gouraud, phong
    /// or blinn-phong (default: the scene's water.material.shading; flat with --obj).
    #[arg(long, value_name = "MODEL")]
    pub shading: Option<String>,
    /// Draw the water's triangle edges over the image (scene's render.wireframe).
    #[arg(long)]
    pub wireframe: bool,
    /// Draw the water's vertex normals as short lines (scene's render.normals).
    #[arg(long)]
    pub normals: bool,
    /// Supersampling anti-aliasing: N x N samples per pixel, N in [1, 4], box-filtered in linear
    /// colour (default: the scene's render.supersample).
    #[arg(long, value_name = "N")]
    pub supersample: Option<u32>,
    /// The camera's exposure value at ISO 100, in [-6, 24] (scene's render.ev100; 15 is the
    /// sunny-16 rule's sunlit scene): the luminance 1.2 x 2^EV cd/m² is exposed to white. Turns
    /// the scene's auto_exposure off
    #[arg(long, value_name = "EV", allow_hyphen_values = true)]
    pub ev100: Option<f32>,
    /// Meter each frame and expose for its log-average luminance (scene's render.auto_exposure).
    /// Turns the scene's ev100 off
    #[arg(long, conflicts_with = "ev100")]
    pub auto_exposure: bool,
    /// The curve from exposed radiance to the display: aces or clip (scene's render.tone_curve)
    #[arg(long, value_name = "CURVE")]
    pub tone_curve: Option<String>,
    /// PNG sequence only: skip frames whose file is already a complete PNG of the image's size
    /// (a killed run continues where it stopped; a truncated or foreign file is rendered again).
    #[arg(long)]
    pub resume: bool,
    /// Print on stderr how long rendering the frames took and how long the whole command took
    /// (encoding and writing included).
    #[arg(long)]
    pub verbose: bool,
    /// Comparison mode: render this Wavefront OBJ mesh (v, vn, f) instead of a scene; needs
    /// --camera. Writes the framebuffer without gamma encoding, as OpenGL's RGBA8 would hold it.
    #[arg(long, value_name = "MESH.obj", group = "SceneSource")]
    pub obj: Option<PathBuf>,
    /// With --obj: camera JSON {"eye","target","up","fov_y_deg","near","far","width","height"}.
    #[arg(long, value_name = "CAMERA.json")]
    pub camera: Option<PathBuf>,
    /// With --obj: directional light JSON {"dir","color","ambient","base_color","background"}
    /// (linear colours; dir is where the light travels); default a white light from above.
    #[arg(long, value_name = "LIGHT.json")]
    pub light: Option<PathBuf>,
    /// With --obj: render N times and print the median render time as {"median_ms": ...}
    /// (file loading and writing excluded). N in [1, 10000].
    #[arg(long, value_name = "N")]
    pub repeat: Option<u32>,
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
    /// (e.g. `--set roughness=0.6 --set corners=[0,0,10,10]`); repeatable, one key each. The keys
    /// with flags of their own (generator, size, extent, seed) are refused here.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Output file, `.png` (16-bit heightmap) or `.exr` (float32 heights in metres); the sidecar
    /// is written beside it as `FILE.toml`.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Output format, png or exr; default: from the --out extension.
    #[arg(long, value_name = "FORMAT")]
    pub format: Option<String>,
    /// Worker threads, 0 = one per core. The heightmap does not depend on it.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub threads: u32,
}

/// `swell bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// grid-size, polygons, waves (paper 000); zbuffer-threads, zbuffer-sizes (paper 001); realtime;
    /// ocean (the FFT ocean's step, stage by stage, grids 64..1024); all (every one of these).
    /// `ocean --grid N [--json]` prints one grid's figures to stdout instead.
    #[arg(value_name = "EXPERIMENT")]
    pub experiment: String,
    /// Directory for the results (created if missing): EXPERIMENT.md, .json and .png.
    #[arg(long, value_name = "DIR", default_value = "bench-results")]
    pub out: PathBuf,
    /// Fewer runs per row (shapes, not figures): `swell bench all --quick` takes about half a minute on 2 cores.
    #[arg(long)]
    pub quick: bool,
    /// Exactly N timed runs per row and no warm-up (for tests).
    #[arg(long, value_name = "N", hide = true)]
    pub runs: Option<u32>,
    /// `ocean` only: time one FFT grid side N (a power of two in [16, 2048]) instead of 64..1024.
    #[arg(long, value_name = "N")]
    pub grid: Option<u32>,
    /// `ocean` only: timed steps after the warm-up, 1 to 100000 (default: about a second's worth).
    #[arg(long, value_name = "N")]
    pub steps: Option<u32>,
    /// `ocean` only: worker threads, 0 = one per core.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub threads: u32,
    /// `ocean` only: print one JSON object per grid, {"grid": N, "median_ms": ..., "stages": {...}}.
    #[arg(long)]
    pub json: bool,
}

/// `swell export`.
#[derive(Args, Debug)]
pub struct ExportArgs {
    #[command(flatten)]
    pub source: SceneSource,
    /// Output file; with --frames, frame k goes to STEM_kkkk.EXT beside it.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Mesh format: obj, gltf (JSON + .bin) or glb (default: from the --out extension; given with
    /// an .obj, .gltf or .glb extension, the two must agree; any other extension takes it as given).
    #[arg(long, value_name = "FORMAT")]
    pub format: Option<String>,
    /// Simulation time in seconds (one file), in [-1e7, 1e7].
    #[arg(
        long,
        value_name = "SECONDS",
        default_value_t = 0.0,
        allow_negative_numbers = true,
        conflicts_with = "frames"
    )]
    pub time: f64,
    /// The frames to export, one file each: a count N (frames 0 to N-1) or a range A..B (both
    /// included), frame k at time k / fps.
    #[arg(long, value_name = "N|A..B", allow_hyphen_values = true)]
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
    /// The frames to bake: a count N (frames 0 to N-1) or a range A..B (both included: 0..0 is one
    /// frame), frame k at time k / fps.
    #[arg(long, value_name = "N|A..B", allow_hyphen_values = true)]
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
    /// Bake only shard I of N: frames A+I, A+I+N, ... (I from 0). `auto` takes I and N from a
    /// Slurm job array (SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN, SLURM_ARRAY_TASK_COUNT), a
    /// Kubernetes indexed job (JOB_COMPLETION_INDEX; N from `auto/N` or SWELL_SHARD_COUNT) or an
    /// AWS Batch array job (AWS_BATCH_JOB_ARRAY_INDEX, AWS_BATCH_JOB_ARRAY_SIZE).
    #[arg(long, value_name = "I/N|auto[/N]")]
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
    /// Space of the normal maps: world (unit normal in swell's axes, +Y up), tangent-gl or
    /// tangent-dx (tangent space of the flat patch, T = +X, N = +Y, green towards the image's top
    /// for OpenGL / Blender / Unity / Godot, towards its bottom for DirectX / Unreal).
    #[arg(long, value_name = "SPACE", default_value = "world")]
    pub normal_space: String,
    /// Worker threads, 0 = one per core. The files do not depend on it.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub threads: u32,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// `swell view`.
#[derive(Args, Debug)]
pub struct ViewArgs {
    #[command(flatten)]
    pub source: SceneSource,
    /// Save the window's content as PNG after --exit-after-frames frames, then exit.
    #[arg(long, value_name = "FILE.png", requires = "exit_after_frames")]
    pub screenshot: Option<PathBuf>,
    /// Close the window after rendering N frames (for scripted checks), N >= 1.
    // Negative numbers reach our own check, which names the flag (clap would call `-3` an unknown argument).
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    pub exit_after_frames: Option<i64>,
}
