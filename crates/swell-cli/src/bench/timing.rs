//! Wall-clock timing: warm-up, repeated runs, median and spread.
//!
//! The median rather than the mean because a loaded machine adds rare long outliers (another
//! process taking the core) that would drag a mean; the spread (min, quartiles, max) shows how
//! noisy the run was.

use std::time::{Duration, Instant};

use serde::Serialize;
use swell::Result;

/// How many times each measurement runs.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Repetitions {
    /// Untimed runs first, to fill caches, fault in buffers and let the CPU clock settle.
    pub warmup: u32,
    /// Least number of timed runs, >= 1.
    pub min_runs: u32,
    /// Most timed runs.
    pub max_runs: u32,
    /// Timed runs stop once they have taken this long (and `min_runs` are done), so that slow points
    /// do not dominate the whole experiment.
    pub budget_s: f64,
}

impl Repetitions {
    /// Full measurement: 3 warm-up runs, then 10 to 100 runs within 3 s per point (paper 001 averaged
    /// 100 runs).
    pub const FULL: Self = Self { warmup: 3, min_runs: 10, max_runs: 100, budget_s: 3.0 };
    /// `--quick`: 1 warm-up, 3 to 10 runs within 0.3 s per point; enough for shapes, not for figures.
    pub const QUICK: Self = Self { warmup: 1, min_runs: 3, max_runs: 10, budget_s: 0.3 };

    /// Exactly `runs` timed runs and no warm-up (the hidden `--runs` flag, for tests).
    pub fn exactly(runs: u32) -> Self {
        let runs = runs.max(1);
        Self { warmup: 0, min_runs: runs, max_runs: runs, budget_s: 0.0 }
    }
}

/// Summary of the timed runs of one measurement, in milliseconds.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Stats {
    /// Number of timed runs.
    pub runs: u32,
    /// Median.
    pub median_ms: f64,
    /// Fastest run.
    pub min_ms: f64,
    /// First quartile.
    pub q1_ms: f64,
    /// Third quartile.
    pub q3_ms: f64,
    /// Slowest run.
    pub max_ms: f64,
    /// Mean CPU time of the whole process (all threads, user + system) per timed run, where the OS
    /// reports it (Linux, 10 ms resolution over all runs together; `None` below 50 ms in all). On a loaded machine it shows
    /// the work done when wall-clock time is inflated by waiting; above the wall time it shows
    /// parallel work.
    pub cpu_ms: Option<f64>,
}

/// Runs `f` `reps.warmup` times untimed, then times it between `min_runs` and `max_runs` times.
/// The first error stops the measurement.
pub fn measure(reps: Repetitions, mut f: impl FnMut() -> Result<()>) -> Result<Stats> {
    for _ in 0..reps.warmup {
        f()?;
    }
    let budget = Duration::from_secs_f64(reps.budget_s);
    let cpu_before = process_cpu_ms();
    let started = Instant::now();
    let mut samples = Vec::with_capacity(reps.max_runs as usize);
    while samples.len() < reps.min_runs.max(1) as usize
        || (samples.len() < reps.max_runs as usize && started.elapsed() < budget)
    {
        let t = Instant::now();
        f()?;
        samples.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let cpu_ms = match (cpu_before, process_cpu_ms()) {
        // Below 5 ticks in all the error of the 10 ms clock exceeds 20%: report nothing.
        (Some(a), Some(b)) if b - a >= MIN_CPU_MS => Some((b - a) / samples.len() as f64),
        _ => None,
    };
    Ok(Stats { cpu_ms, ..summarize(&mut samples) })
}

/// Least total CPU time over a measurement's runs for [`Stats::cpu_ms`] to be reported, ms.
const MIN_CPU_MS: f64 = 50.0;

/// CPU time used so far by this process, all threads, user + system, in ms: fields 14 and 15 of
/// /proc/self/stat (proc(5)), in clock ticks of 1/100 s (Linux's USER_HZ on every architecture).
fn process_cpu_ms() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The command name (field 2) is in parentheses and may contain spaces: count from the last ')'.
    let rest = &stat[stat.rfind(')')? + 1..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // `rest` starts at field 3, so fields 14 and 15 are at 11 and 12.
    let ticks: u64 = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
    Some(ticks as f64 * 10.0)
}

/// Median, quartiles and range of `samples` (at least one), which get sorted.
pub fn summarize(samples: &mut [f64]) -> Stats {
    samples.sort_by(f64::total_cmp);
    Stats {
        runs: samples.len() as u32,
        median_ms: quantile(samples, 0.5),
        min_ms: samples[0],
        q1_ms: quantile(samples, 0.25),
        q3_ms: quantile(samples, 0.75),
        max_ms: samples[samples.len() - 1],
        cpu_ms: None,
    }
}

/// Linear interpolation between the closest ranks (R's type 7, NumPy's default) of sorted `s`.
fn quantile(s: &[f64], p: f64) -> f64 {
    let h = (s.len() - 1) as f64 * p;
    let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
    s[lo] + (h - lo as f64) * (s[hi] - s[lo])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_and_quartiles_of_odd_and_even_samples() {
        let s = summarize(&mut [5.0, 1.0, 3.0, 2.0, 4.0]);
        assert_eq!((s.runs, s.min_ms, s.q1_ms, s.median_ms, s.q3_ms, s.max_ms), (5, 1.0, 2.0, 3.0, 4.0, 5.0));
        let s = summarize(&mut [4.0, 1.0, 2.0, 3.0]);
        assert_eq!(s.median_ms, 2.5);
        assert_eq!((s.q1_ms, s.q3_ms), (1.75, 3.25));
        let s = summarize(&mut [7.0]);
        assert_eq!((s.min_ms, s.median_ms, s.max_ms), (7.0, 7.0, 7.0));
    }

    #[test]
    fn runs_stay_within_their_bounds_and_errors_stop_the_measurement() {
        let mut calls = 0;
        let s = measure(Repetitions { warmup: 2, min_runs: 3, max_runs: 4, budget_s: 10.0 }, || {
            calls += 1;
            Ok(())
        })
        .unwrap();
        assert_eq!((s.runs, calls), (4, 6));
        let s = measure(Repetitions::exactly(2), || Ok(())).unwrap();
        assert_eq!(s.runs, 2);
        let e = measure(Repetitions::QUICK, || Err(swell::Error::invalid("x", "boom")));
        assert!(e.is_err());
    }

    #[test]
    fn cpu_time_counts_the_work_done() {
        if process_cpu_ms().is_none() {
            return; // not Linux
        }
        // A fixed amount of work (at least ~25 ms of CPU even at 4 GHz, 75 ms over the 3 runs), however long a loaded
        // machine makes it take in wall time.
        let work = || {
            let mut x = 0u64;
            for _ in 0..100_000_000u64 {
                x = std::hint::black_box(x.wrapping_add(1));
            }
        };
        let busy = measure(Repetitions::exactly(3), || {
            let _: () = work();
            Ok(())
        })
        .unwrap();
        // Other tests run in threads of this process and only add to its CPU time, so bound from
        // below only.
        assert!(busy.cpu_ms.unwrap() >= 5.0, "{busy:?}");
    }
}
