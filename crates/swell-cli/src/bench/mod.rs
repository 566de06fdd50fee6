//! `swell bench`: the papers' timing experiments reproduced on this machine, and swell's own.
//!
//! One file per source of experiments ([`paper000`], [`paper001`], [`realtime`]); each experiment
//! returns a [`Report`] that [`report`] writes as Markdown and JSON and [`plot`] as a PNG.
//! [`timing`] does the warm-up and repeated runs, [`machine`] says where they ran.
//!
//! To add an experiment (e.g. `ocean`, the FFT step per stage): write `bench/NAME.rs` with a
//! `fn(&Context) -> Result<Report>` and add one line to [`EXPERIMENTS`].

mod machine;
pub mod ocean_step;
mod paper000;
mod paper001;
mod plot;
mod realtime;
mod report;
mod timing;

use std::path::{Path, PathBuf};

use swell::{Error, Result};

pub use machine::Machine;
pub use report::Report;
pub use timing::Repetitions;

/// What every experiment runs with.
pub struct Context {
    /// How many runs per row.
    pub reps: Repetitions,
    /// Where it runs.
    pub machine: Machine,
    /// Prints what is being measured (to stderr), or nothing.
    pub verbose: bool,
}

impl Context {
    /// Says which row is being measured.
    pub fn progress(&self, what: &str) {
        if self.verbose {
            eprintln!("  {what}");
        }
    }
}

/// A named experiment.
pub struct Experiment {
    /// Name on the command line.
    pub name: &'static str,
    /// What it measures, one line.
    pub description: &'static str,
    /// Runs it.
    pub run: fn(&Context) -> Result<Report>,
}

/// Every experiment, in the order `all` runs them.
pub const EXPERIMENTS: &[Experiment] = &[
    Experiment {
        name: "grid-size",
        description: "paper 000 table 4.1: frame time against grid extent 100..800",
        run: paper000::grid_size,
    },
    Experiment {
        name: "polygons",
        description: "paper 000 table 4.2: frame time against 100..22 500 polygons",
        run: paper000::polygons,
    },
    Experiment {
        name: "waves",
        description: "paper 000 table 4.3: frame time against 0..12 added waves",
        run: paper000::waves,
    },
    Experiment {
        name: "zbuffer-threads",
        description: "paper 001 table 4.1: z-buffer time on 1..32 threads, 33x33 and 513x513 heightmaps",
        run: paper001::zbuffer_threads,
    },
    Experiment {
        name: "zbuffer-sizes",
        description: "paper 001 table 4.2: z-buffer time for heightmaps 33..513, 1 thread and all",
        run: paper001::zbuffer_sizes,
    },
    Experiment {
        name: "realtime",
        description: "frames per second of each preset at 1280x720",
        run: realtime::realtime,
    },
    Experiment {
        name: "ocean",
        description: "FFT ocean step per stage (evolve, FFTs, foam, mesh) on grids 64..1024",
        run: ocean_step::ocean_experiment,
    },
];

/// The experiments `name` stands for (`all` = every one), or an error listing the valid names.
pub fn select(name: &str) -> Result<Vec<&'static Experiment>> {
    if name == "all" {
        return Ok(EXPERIMENTS.iter().collect());
    }
    match EXPERIMENTS.iter().find(|e| e.name == name) {
        Some(e) => Ok(vec![e]),
        None => {
            let names: Vec<_> = EXPERIMENTS.iter().map(|e| e.name).chain(["all"]).collect();
            Err(Error::invalid(
                "EXPERIMENT",
                format!("unknown experiment `{name}`; choose one of: {}", names.join(", ")),
            ))
        }
    }
}

/// Runs `experiment` and writes `NAME.md`, `NAME.json` and `NAME.png` into `dir`; returns the
/// report and the files written.
pub fn run_one(experiment: &Experiment, ctx: &Context, dir: &Path) -> Result<(Report, Vec<PathBuf>)> {
    let report = (experiment.run)(ctx)?;
    report.write_text(dir)?;
    plot::write_plot(&report, dir)?;
    let files = ["md", "json", "png"].map(|ext| dir.join(format!("{}.{ext}", report.experiment)));
    Ok((report, files.to_vec()))
}
