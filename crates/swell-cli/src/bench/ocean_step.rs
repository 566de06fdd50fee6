//! `swell bench ocean`: wall-clock timings of the FFT ocean's full step (spectrum evolution, 8
//! fields, foam) and of the displaced mesh, median over many steps, stage by stage.
//!
//! Two forms: [`ocean_experiment`], the `ocean` experiment of `swell bench ocean` and `swell bench
//! all` (grids 64..1024, a Markdown table, JSON and a plot in `--out` like every experiment), and
//! [`run`], `swell bench ocean --grid N [--json]`, which prints one grid's figures to stdout (a
//! short table, or one JSON object with `--json`).

use std::time::Instant;

use glam::Vec2;
use swell::math::GridSpec;
use swell::mesh::SurfaceMesh;
use swell::scene::{preset, WaterModelSpec};
use swell::water::{FftOcean, WaveModel, FFT_GRID_RANGE};
use swell::{Error, Result};

use super::report::{PaperUnit, PlotKind, Point, Report, Series};
use super::timing::summarize;
use super::Context;
use crate::args::BenchArgs;
use crate::thread_pool::thread_pool;

/// Untimed steps before measuring (caches, page faults, thread start-up).
const WARM_UP_STEPS: u32 = 5;
/// Simulated time between steps, s (60 frames per second).
const STEP_S: f64 = 1.0 / 60.0;

/// Grids timed when `--grid` is not given (issue 9: 64..1024, single cascade).
const DEFAULT_GRIDS: [u32; 5] = [64, 128, 256, 512, 1024];

/// Runs `swell bench ocean --grid N` or `--json`: the `--grid` given, or each of [`DEFAULT_GRIDS`],
/// printed to stdout.
pub fn run(a: &BenchArgs) -> Result<()> {
    let grids: Vec<u32> = match a.grid {
        Some(g) => vec![g],
        None => DEFAULT_GRIDS.to_vec(),
    };
    for grid in grids {
        ocean(grid, a)?;
    }
    Ok(())
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// The `ocean` preset's FFT parameters at grid side `grid`.
fn preset_params(grid: u32) -> Result<swell::water::FftOceanParams> {
    match preset("ocean")?.water.map(|w| w.model) {
        Some(WaterModelSpec::Fft(p)) => Ok(swell::water::FftOceanParams { grid, ..p }),
        _ => Err(Error::invalid("preset ocean", "is not an FFT sea")),
    }
}

/// One step's times in milliseconds: the whole simulation, its stages as the ocean clocks them,
/// and the displaced mesh built from it.
struct StepTimes {
    sim: f64,
    evolve: f64,
    fft: f64,
    foam: f64,
    mesh: f64,
}

/// Steps `ocean` to the time of step `k` (1/60 s apart) and rebuilds `mesh` from it, timing both.
fn timed_step(ocean: &mut FftOcean, mesh: &mut SurfaceMesh, k: u32) -> Result<StepTimes> {
    let t = f64::from(k + 1) * STEP_S;
    let t0 = Instant::now();
    ocean.advance(t)?;
    let t1 = Instant::now();
    mesh.displace(ocean, t);
    let t2 = Instant::now();
    let st = ocean.stage_times();
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    Ok(StepTimes { sim: ms(t1 - t0), evolve: st.evolve_ms, fft: st.fft_ms, foam: st.foam_ms, mesh: ms(t2 - t1) })
}

/// Stage names of the `ocean` experiment, in series order.
const STAGES: [&str; 5] = [
    "simulation (evolve + FFTs + foam)",
    "evolve h(k, t), bases, FFTs over kz (column pass)",
    "FFTs over kx, gathering the bases into pairs, foam (row pass)",
    "foam lattice (the first cascade at the 20 Hz foam times; 0 in most steps)",
    "displaced mesh (positions, normals, foam)",
];

/// The `ocean` experiment: for each grid of [`DEFAULT_GRIDS`] the `ocean` preset's sea (one
/// cascade) is stepped at 60 steps per second of simulated time, on all threads; each stage's
/// wall-clock time per step is a row of its own series.
pub fn ocean_experiment(ctx: &Context) -> Result<Report> {
    let mut series: Vec<Series> =
        STAGES.iter().map(|name| Series { name: (*name).to_string(), points: Vec::new() }).collect();
    for grid in DEFAULT_GRIDS {
        ctx.progress(&format!("{grid}x{grid}"));
        let params = preset_params(grid)?;
        let mut ocean = FftOcean::new(&params)?;
        let mut mesh = SurfaceMesh::new(GridSpec::new(Vec2::ZERO, Vec2::splat(params.patch_size), grid, grid)?);
        let mut samples: [Vec<f64>; 5] = Default::default();
        let reps = ctx.reps;
        let budget = std::time::Duration::from_secs_f64(reps.budget_s);
        let mut k = 0u32;
        let mut started = None;
        loop {
            let timed = k >= reps.warmup;
            let n = samples[0].len();
            if timed && n >= reps.min_runs.max(1) as usize {
                let out_of_time = started.is_some_and(|s: Instant| s.elapsed() >= budget);
                if n >= reps.max_runs as usize || out_of_time {
                    break;
                }
            }
            if timed && started.is_none() {
                started = Some(Instant::now());
            }
            let step = timed_step(&mut ocean, &mut mesh, k)?;
            if timed {
                for (v, x) in samples.iter_mut().zip([step.sim, step.evolve, step.fft, step.foam, step.mesh]) {
                    v.push(x);
                }
            }
            k += 1;
        }
        for (s, v) in series.iter_mut().zip(samples.iter_mut()) {
            s.points.push(Point {
                x: f64::from(grid),
                label: format!("{grid}x{grid}"),
                swell: summarize(v),
                paper: None,
            });
        }
    }
    Ok(Report {
        experiment: "ocean",
        title: "FFT ocean step, stage by stage, against the grid".into(),
        source: "issue 4's performance goals; no paper table".into(),
        setup: vec![
            "The `ocean` preset's sea (JONSWAP, 14 m/s, one cascade, foam on) at each FFT grid N x N, stepped at \
             1/60 s of simulated time per step, all threads."
                .into(),
            "Simulation = evolving h(k, t) + eight fields (height, 2 choppy displacements, 2 slopes, 3 Jacobian \
             terms) by four packed complex inverse FFTs + foam; the mesh is N x N cells over the patch \
             (positions, normals, foam), as `swell bench ocean --grid N` reports."
                .into(),
            "Goals (issue 4, 2 cores): simulation about 0.4 ms at 256x256 and under 10 ms at 1024x1024, 5x faster \
             than Blender's Ocean modifier (1.8-2.6 ms and 47 ms); the mesh 20x faster than Blender's (41 ms \
             and 890 ms)."
                .into(),
            "Each stage's time is measured inside the same steps (its own clock), so the stages of one row \
             come from the same runs; the spread is over steps. Since session 3 the step is two fused passes: \
             `evolve_ms` times the column pass (evolution, the five bases, transforms over kz), `fft_ms` the row \
             pass (gathering the bases into the packed pairs, transforms over kx, Jacobian and foam), and \
             `foam_ms` the foam lattice's steps (since session 6 the foam is defined by time alone: the first \
             cascade is also synthesised every 0.05 s of simulated time, so one step in three at 60 steps/s \
             carries one more first-cascade step; the medians are of the steps without it)."
                .into(),
        ],
        x_label: "grid".into(),
        paper_unit: PaperUnit::None,
        plot: PlotKind::Relative,
        series,
        machine: ctx.machine.clone(),
        repetitions: ctx.reps,
    })
}

/// Times the FFT ocean of preset `ocean` at grid N: per step the simulation (evolve, FFTs, foam)
/// and the displaced mesh (N x N cells over the patch, positions, normals and foam).
fn ocean(grid: u32, a: &BenchArgs) -> Result<()> {
    let (lo, hi) = FFT_GRID_RANGE;
    if !(grid.is_power_of_two() && (lo..=hi).contains(&grid)) {
        return Err(Error::out_of_range("--grid", grid, format!("powers of two in [{lo}, {hi}]")));
    }
    let params = preset_params(grid)?;
    let pool = thread_pool(a.threads)?;
    let mesh_grid = GridSpec::new(Vec2::ZERO, Vec2::splat(params.patch_size), grid, grid)?;
    let steps = match a.steps {
        Some(s) if (1..=100_000).contains(&s) => s,
        Some(s) => return Err(Error::out_of_range("--steps", s, "[1, 100000]")),
        // About a second of work at the goal speeds, at least 10 steps.
        None if a.quick => 10,
        None => (400_000 / (grid * grid / 256).max(1)).clamp(10, 2000),
    };
    let (mut total, mut sim, mut evolve, mut fft, mut foam, mut mesh_ms) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    pool.install(|| -> Result<()> {
        let mut ocean = FftOcean::new(&params)?;
        let mut mesh = SurfaceMesh::new(mesh_grid);
        for k in 0..WARM_UP_STEPS + steps {
            let step = timed_step(&mut ocean, &mut mesh, k)?;
            if k >= WARM_UP_STEPS {
                sim.push(step.sim);
                mesh_ms.push(step.mesh);
                total.push(step.sim + step.mesh);
                evolve.push(step.evolve);
                fft.push(step.fft);
                foam.push(step.foam);
            }
        }
        Ok(())
    })?;
    let (sim_ms, mesh_med) = (median(&mut sim), median(&mut mesh_ms));
    let stages = serde_json::json!({
        "evolve_ms": median(&mut evolve),
        "fft_ms": median(&mut fft),
        "foam_ms": median(&mut foam),
        "simulation_ms": sim_ms,
        "mesh_ms": mesh_med,
    });
    if a.json {
        let json = serde_json::json!({
            "experiment": "ocean",
            "grid": grid,
            "steps": steps,
            "threads": pool.current_num_threads(),
            "median_ms": sim_ms,
            "median_with_mesh_ms": median(&mut total),
            "stages": stages,
        });
        println!("{json}");
    } else {
        println!(
            "ocean {n}x{n}, {threads} threads, {steps} steps after {WARM_UP_STEPS} warm-up (medians):",
            n = grid,
            threads = pool.current_num_threads()
        );
        println!("  simulation (8 fields + foam) {sim_ms:9.3} ms");
        for (name, v) in stages.as_object().expect("object") {
            println!("    {name:<24} {:9.3}", v.as_f64().unwrap_or(f64::NAN));
        }
        println!("  step with displaced mesh     {:9.3} ms", median(&mut total));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn all_includes_the_ocean_experiment() {
        let all = super::super::select("all").unwrap();
        assert!(all.iter().any(|e| e.name == "ocean"));
        assert_eq!(super::super::select("ocean").unwrap()[0].name, "ocean");
    }
}
