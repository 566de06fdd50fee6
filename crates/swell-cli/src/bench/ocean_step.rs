//! `swell bench ocean`: wall-clock timings of the FFT ocean's full step (spectrum evolution, 8
//! fields, foam) and of the displaced mesh, median over many steps, stage by stage. Prints a short
//! table per grid, or one JSON object per grid with `--json`.

use std::time::Instant;

use glam::Vec2;
use swell::math::GridSpec;
use swell::mesh::SurfaceMesh;
use swell::scene::{preset, WaterModelSpec};
use swell::water::{FftOcean, WaveModel, FFT_GRID_RANGE};
use swell::{Error, Result};

use crate::args::BenchArgs;
use crate::cmd::thread_pool;

/// Untimed steps before measuring (caches, page faults, thread start-up).
const WARM_UP_STEPS: u32 = 5;
/// Simulated time between steps, s (60 frames per second).
const STEP_S: f64 = 1.0 / 60.0;

/// Grids timed when `--grid` is not given (issue 9: 64..1024, single cascade).
const DEFAULT_GRIDS: [u32; 5] = [64, 128, 256, 512, 1024];

/// Runs `swell bench ocean`: the `--grid` given, or each of [`DEFAULT_GRIDS`].
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

/// Times the FFT ocean of preset `ocean` at grid N: per step the simulation (evolve, FFTs, foam)
/// and the displaced mesh (N x N cells over the patch, positions, normals and foam).
fn ocean(grid: u32, a: &BenchArgs) -> Result<()> {
    let (lo, hi) = FFT_GRID_RANGE;
    if !(grid.is_power_of_two() && (lo..=hi).contains(&grid)) {
        return Err(Error::out_of_range("--grid", grid, format!("powers of two in [{lo}, {hi}]")));
    }
    let mut params = match preset("ocean")?.water.map(|w| w.model) {
        Some(WaterModelSpec::Fft(p)) => p,
        _ => unreachable!("preset ocean is an FFT sea"),
    };
    params.grid = grid;
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
            let t = f64::from(k + 1) * STEP_S;
            let t0 = Instant::now();
            ocean.advance(t)?;
            let t1 = Instant::now();
            mesh.displace(&ocean, t);
            let t2 = Instant::now();
            if k >= WARM_UP_STEPS {
                let st = ocean.stage_times();
                let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
                sim.push(ms(t1 - t0));
                mesh_ms.push(ms(t2 - t1));
                total.push(ms(t2 - t0));
                evolve.push(st.evolve_ms);
                fft.push(st.fft_ms);
                foam.push(st.foam_ms);
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
