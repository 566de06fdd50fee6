//! One file per subcommand, plus what they share: loading a scene and building a thread pool.

mod bench;
mod presets;
mod render;
mod scene_input;
mod terrain;
// issue 8: meshes and map bakes.
mod bake;
mod export;
mod stats;
mod view;

use indicatif::{ProgressBar, ProgressStyle};
use swell::error::Human;
use swell::scene::{preset, Scene};
use swell::world::World;

pub use crate::thread_pool::thread_pool;
use swell::water::MAX_STEPS_PER_ADVANCE;
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
        eprintln!("warning: {}", swell::error::printable(&warning.to_string()));
    }
    Ok(scene)
}

/// Reads and validates the scene named by `--preset` or `--scene`.
fn read_scene(source: &SceneSource) -> Result<Scene> {
    match (&source.preset, &source.scene) {
        (Some(name), _) => preset(name),
        (None, Some(path)) => scene_input::load(path),
        (None, None) => unreachable!("clap requires one of --preset and --scene"),
    }
}

/// Steps of a time-stepped model above which reaching a time shows a progress bar and can be
/// interrupted (about a second of work on the `springs` preset's lattice).
const PROGRESS_STEPS: f64 = 20_000.0;

/// Refuses, before any work, a time `t` (s) that the scene's time-stepped model (the spring mesh,
/// which integrates from t = 0) would need more than [`MAX_STEPS_PER_ADVANCE`] steps to reach.
pub fn check_steps(scene: &Scene, key: &str, t: f64) -> Result<()> {
    let Some(water) = &scene.water else { return Ok(()) };
    let Some(steps) = water.model.steps_to(t) else { return Ok(()) };
    if steps <= MAX_STEPS_PER_ADVANCE as f64 {
        return Ok(());
    }
    let reachable = water.model.time_after_steps(MAX_STEPS_PER_ADVANCE as f64).unwrap_or(0.0);
    Err(Error::out_of_range(
        key,
        Human(t),
        format!(
            "the times the spring mesh reaches in at most {} steps from t = 0 (up to about {} s at its \
             time_step, warm-up included): it would need {} steps",
            group_digits(MAX_STEPS_PER_ADVANCE as f64),
            group_digits(reachable.floor()),
            group_digits(steps)
        ),
    ))
}

/// How a command moves its world to a time: [`World::update`] or [`World::advance`].
pub type Step = fn(&mut World, f64) -> Result<()>;

/// Moves `world` to time `t` (s); when its time-stepped model has many steps to take, in a
/// hundred slices with a progress bar and an estimate on stderr, stoppable by SIGINT/SIGTERM
/// between slices. Slicing does not change the result: the model steps at its fixed time step
/// whatever the slices. `step` is [`World::update`] for commands that draw the water and
/// [`World::advance`] for those that only sample its patch (export, bake): displacing a drawn
/// surface nobody draws would be wasted work.
pub fn advance_with_progress(world: &mut World, t: f64, step: Step) -> Result<()> {
    let steps = |t: f64| world.scene.water.as_ref().and_then(|w| w.model.steps_to(t));
    let from = if world.time().is_finite() { world.time() } else { 0.0 };
    let todo = match (steps(t), steps(from)) {
        (Some(to), Some(done)) if to > done => to - done,
        (Some(to), Some(_)) => to, // backwards: the model starts again from t = 0
        _ => 0.0,
    };
    if todo < PROGRESS_STEPS {
        return step(world, t);
    }
    let from = if t >= from { from } else { 0.0 };
    eprintln!(
        "stepping the spring mesh {} steps to t = {} s (it integrates from t = 0); Ctrl-C stops",
        group_digits(todo),
        Human(t)
    );
    let bar = ProgressBar::new(100).with_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {percent}%, {elapsed} elapsed, ETA {eta}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_message("simulating");
    let interrupt = crate::interrupt::Interrupt::install()?;
    let start = std::time::Instant::now();
    for i in 1..=100 {
        interrupt.check(format_args!("stopped at {i}% of the steps to t = {} s; nothing was written", Human(t)))?;
        let ti = if i == 100 { t } else { from + (t - from) * f64::from(i) / 100.0 };
        step(world, ti)?;
        bar.inc(1);
    }
    bar.finish_and_clear();
    eprintln!("stepped {} steps in {:.1} s", group_digits(todo), start.elapsed().as_secs_f64());
    Ok(())
}

/// A whole number with thousands separators (`250,000`); numbers past 10^15 in scientific form.
pub fn group_digits(x: f64) -> String {
    if x.is_nan() || x.abs() >= 1e15 {
        return format!("{x:e}");
    }
    let digits = format!("{}", x.abs().round() as u64);
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    if x < 0.0 {
        out.insert(0, '-');
    }
    out
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
        Err(Error::invalid("--out", missing_dir(dir)))
    }
}

/// Why `dir` cannot hold an output, naming the real cause (issue 37): the first of its ancestors
/// that exists but is not a directory (`out/x.png` under a file `out`), or that it does not exist.
fn missing_dir(dir: &std::path::Path) -> String {
    for a in dir.ancestors().filter(|a| !a.as_os_str().is_empty()) {
        if a.is_dir() {
            break;
        }
        if a.exists() {
            return format!("{} is a file, not a directory, so {} cannot be under it", a.display(), dir.display());
        }
    }
    format!("directory {} does not exist", dir.display())
}

#[cfg(test)]
mod tests {
    #[test]
    fn big_numbers_are_grouped_for_people() {
        assert_eq!(super::group_digits(250_000.0), "250,000");
        assert_eq!(super::group_digits(999.0), "999");
        assert_eq!(super::group_digits(1_000.0), "1,000");
        assert_eq!(super::group_digits(-1_234_567.0), "-1,234,567");
        assert_eq!(super::group_digits(2.5e300), "2.5e300");
    }
}
