//! One experiment's results, and their Markdown and JSON forms.

use std::fmt::Write as _;
use std::path::Path;

use serde::Serialize;
use swell::export::write_atomically;
use swell::{Error, Result};

use super::machine::Machine;
use super::timing::{Repetitions, Stats};

/// The unit of a paper's figures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum PaperUnit {
    /// Seconds: compared with swell directly.
    Seconds,
    /// Paper 000's "ticks" (the paper never says of what clock): only growth relative to the first
    /// row can be compared.
    Ticks,
    /// The paper has no figures for this experiment.
    None,
}

/// How the plot shows the results.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PlotKind {
    /// Each series divided by its first row, swell's and the paper's, so that curves measured in
    /// different units and on different machines share one axis.
    Relative,
    /// Frames per second as bars, one per row.
    Fps,
}

/// One row: a parameter value, swell's timing and the paper's figure for it.
#[derive(Clone, Debug, Serialize)]
pub struct Point {
    /// The parameter (grid extent, polygons, waves, threads, heightmap side...).
    pub x: f64,
    /// How the parameter is written in the table (e.g. `100x100`, `sea`).
    pub label: String,
    /// swell's time per run.
    pub swell: Stats,
    /// The paper's figure, in [`Report::paper_unit`].
    pub paper: Option<f64>,
}

/// A curve: rows measured under one condition (e.g. one thread).
#[derive(Clone, Debug, Serialize)]
pub struct Series {
    /// What distinguishes it, e.g. `1 thread`; empty when the experiment has one series.
    pub name: String,
    /// Rows in table order.
    pub points: Vec<Point>,
}

impl Series {
    /// swell's median of row `i` divided by that of the first row.
    pub fn swell_relative(&self, i: usize) -> f64 {
        self.points[i].swell.median_ms / self.points[0].swell.median_ms
    }

    /// The paper's figure of row `i` divided by that of the first row, if both exist.
    pub fn paper_relative(&self, i: usize) -> Option<f64> {
        Some(self.points[i].paper? / self.points[0].paper?)
    }
}

/// Everything one experiment measured, with what is needed to read it.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// Experiment name as typed on the command line (`grid-size`).
    pub experiment: &'static str,
    /// One-line title.
    pub title: String,
    /// Where the experiment and its figures come from (`paper 000, table 4.1`).
    pub source: String,
    /// How swell sets the experiment up, one sentence each (image size, parameters, what is timed).
    pub setup: Vec<String>,
    /// Table header of the parameter column.
    pub x_label: String,
    /// Unit of the paper's figures.
    pub paper_unit: PaperUnit,
    /// How to plot it.
    pub plot: PlotKind,
    /// The curves.
    pub series: Vec<Series>,
    /// Where it ran.
    pub machine: Machine,
    /// How often each row ran.
    pub repetitions: Repetitions,
}

impl Report {
    /// The Markdown section: title, setup, machine, then one table per series.
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "## `{}`: {} ({})\n", self.experiment, self.title, self.source);
        for line in &self.setup {
            let _ = writeln!(s, "- {line}");
        }
        let r = &self.repetitions;
        let _ = writeln!(s, "- Machine: {}.", self.machine.summary());
        let _ = writeln!(
            s,
            "- Each row: {} warm-up run(s), then {} to {} timed runs within {} s; median and spread \
             (min–max) of wall-clock time in milliseconds; CPU = the process's CPU time per run, all threads \
             (below the median: the run waited for a CPU; above: it ran in parallel).",
            r.warmup, r.min_runs, r.max_runs, r.budget_s
        );
        if self.machine.build == "debug" {
            let _ = writeln!(s, "- **Debug build: unoptimised, these figures mean nothing.** Use `--release`.");
        }
        for series in &self.series {
            s.push('\n');
            if !series.name.is_empty() {
                let _ = writeln!(s, "### {}\n", series.name);
            }
            self.table(&mut s, series);
        }
        s
    }

    fn table(&self, s: &mut String, series: &Series) {
        let x = &self.x_label;
        // Columns every table starts with: the parameter and swell's timing.
        let head = format!("| {x} | swell median (ms) | min–max (ms) | CPU (ms) |");
        let cells = |p: &Point| {
            format!("| {} | {} | {} | {} |", p.label, ms(p.swell.median_ms), spread(&p.swell), opt(p.swell.cpu_ms, ms))
        };
        match (self.plot, self.paper_unit) {
            (PlotKind::Fps, _) => {
                let _ = writeln!(s, "{head} frames per second |\n|---|---:|---:|---:|---:|");
                for p in &series.points {
                    let _ = writeln!(s, "{} {:.1} |", cells(p), 1e3 / p.swell.median_ms);
                }
            }
            (_, PaperUnit::Seconds) => {
                let _ = writeln!(
                    s,
                    "{head} paper (ms) | swell / paper | swell / row 1 | paper / row 1 |\n\
                     |---|---:|---:|---:|---:|---:|---:|---:|"
                );
                for (i, p) in series.points.iter().enumerate() {
                    let paper_ms = p.paper.map(|v| v * 1e3);
                    let _ = writeln!(
                        s,
                        "{} {} | {} | {:.2} | {} |",
                        cells(p),
                        opt(paper_ms, ms),
                        opt(paper_ms, |v| format!("{:.3}", p.swell.median_ms / v)),
                        series.swell_relative(i),
                        opt(series.paper_relative(i), |v| format!("{v:.2}")),
                    );
                }
            }
            (_, unit) => {
                let paper_col = if unit == PaperUnit::Ticks { "paper (ticks)" } else { "paper" };
                let _ = writeln!(
                    s,
                    "{head} {paper_col} | swell / row 1 | paper / row 1 | growth ratio |\n\
                     |---|---:|---:|---:|---:|---:|---:|---:|"
                );
                for (i, p) in series.points.iter().enumerate() {
                    let (sr, pr) = (series.swell_relative(i), series.paper_relative(i));
                    let _ = writeln!(
                        s,
                        "{} {} | {sr:.2} | {} | {} |",
                        cells(p),
                        opt(p.paper, |v| format!("{v:.0}")),
                        opt(pr, |v| format!("{v:.2}")),
                        opt(pr, |v| format!("{:.2}", sr / v)),
                    );
                }
            }
        }
    }

    /// Writes `EXPERIMENT.md` and `EXPERIMENT.json` into `dir`, atomically.
    pub fn write_text(&self, dir: &Path) -> Result<()> {
        let md = dir.join(format!("{}.md", self.experiment));
        let text = format!("# swell bench {}\n\n{}", self.experiment, self.markdown());
        write_atomically(&md, |w| w.write_all(text.as_bytes()).map_err(|e| Error::io(&md, e)))?;
        let json = dir.join(format!("{}.json", self.experiment));
        write_atomically(&json, |w| {
            serde_json::to_writer_pretty(&mut *w, self).map_err(|e| Error::io(&json, e.into()))?;
            w.write_all(b"\n").map_err(|e| Error::io(&json, e))
        })
    }
}

/// Milliseconds with three significant figures or more.
fn ms(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else if v >= 1.0 {
        format!("{v:.2}")
    } else {
        format!("{v:.3}")
    }
}

fn spread(s: &Stats) -> String {
    format!("{}–{}", ms(s.min_ms), ms(s.max_ms))
}

fn opt<T>(v: Option<T>, f: impl FnOnce(T) -> String) -> String {
    v.map_or_else(|| "–".to_string(), f)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::timing::summarize;

    fn report(unit: PaperUnit) -> Report {
        let point = |x: f64, t: f64, paper| Point { x, label: format!("{x}"), swell: summarize(&mut [t]), paper };
        Report {
            experiment: "test",
            title: "t".into(),
            source: "paper 000".into(),
            setup: vec![],
            x_label: "n".into(),
            paper_unit: unit,
            plot: PlotKind::Relative,
            series: vec![Series {
                name: String::new(),
                points: vec![point(1.0, 2.0, Some(100.0)), point(2.0, 6.0, Some(150.0))],
            }],
            machine: Machine::detect(),
            repetitions: Repetitions::exactly(1),
        }
    }

    #[test]
    fn ticks_compare_growth_and_seconds_compare_time() {
        let md = report(PaperUnit::Ticks).markdown();
        // Row 2: swell grew 3x, the paper 1.5x, so swell's growth is twice the paper's.
        assert!(md.contains("| 2 | 6.00 | 6.00–6.00 | – | 150 | 3.00 | 1.50 | 2.00 |"), "{md}");
        let md = report(PaperUnit::Seconds).markdown();
        // 6 ms against the paper's 150 s.
        assert!(md.contains("| 2 | 6.00 | 6.00–6.00 | – | 150000 | 0.000 | 3.00 | 1.50 |"), "{md}");
    }
}
