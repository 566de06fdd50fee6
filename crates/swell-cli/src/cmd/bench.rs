//! `swell bench EXPERIMENT`: runs the experiments in [`crate::bench`] and writes their Markdown,
//! JSON and PNG results into `--out`.

use swell::export::write_atomically;
use swell::{Error, Result};

use crate::args::BenchArgs;
use crate::bench::{run_one, select, Context, Machine, Repetitions};

/// Most timed runs the hidden `--runs` flag accepts.
const MAX_RUNS: u32 = 10_000;

pub fn run(a: BenchArgs) -> Result<()> {
    // `--grid N` / `--json`: one grid (or each) printed to stdout, as issue 4 specifies; plain
    // `ocean` is an experiment like the others.
    if a.experiment == "ocean" && (a.grid.is_some() || a.json || a.steps.is_some()) {
        return crate::bench::ocean_step::run(&a);
    }
    let experiments = select(&a.experiment)?;
    let reps = match a.runs {
        Some(n) if !(1..=MAX_RUNS).contains(&n) => {
            return Err(Error::out_of_range("--runs", n, format!("[1, {MAX_RUNS}]")))
        }
        Some(n) => Repetitions::exactly(n),
        None if a.quick => Repetitions::QUICK,
        None => Repetitions::FULL,
    };
    std::fs::create_dir_all(&a.out).map_err(|e| Error::io(&a.out, e))?;
    let ctx = Context { reps, machine: Machine::detect(), verbose: true };
    if ctx.machine.build == "debug" {
        eprintln!("warning: this is an unoptimised debug build; its timings mean nothing (build with --release)");
    }
    eprintln!("machine: {}", ctx.machine.summary());
    let mut sections = Vec::new();
    for e in &experiments {
        eprintln!("{}: {}", e.name, e.description);
        let (report, files) = run_one(e, &ctx, &a.out)?;
        for f in files {
            eprintln!("wrote {}", f.display());
        }
        let md = report.markdown();
        println!("{md}");
        sections.push(md);
    }
    if experiments.len() > 1 {
        let path = a.out.join("all.md");
        let text = format!("# swell bench all\n\n{}", sections.join("\n"));
        write_atomically(&path, |w| w.write_all(text.as_bytes()).map_err(|e| Error::io(&path, e)))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
