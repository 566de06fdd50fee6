use glam::{Vec2, Vec3};
use swell::math::GridSpec;
use swell::water::{Gerstner, GerstnerWave, WaveModel};
fn cpu() -> f64 {
    let s = std::fs::read_to_string("/proc/self/stat").unwrap();
    let f: Vec<&str> = s.rsplit(')').next().unwrap().split_whitespace().collect();
    (f[11].parse::<f64>().unwrap() + f[12].parse::<f64>().unwrap()) / 100.0
}
fn main() {
    let waves: Vec<GerstnerWave> = (0..12)
        .map(|i| {
            let l = 48.0 * 0.8f32.powi(i);
            let a = (i as f32 * 0.7).sin() * 0.7;
            GerstnerWave {
                amplitude: 0.012 * l,
                wavelength: l,
                speed: 5.0,
                direction: Vec2::new(a.cos(), a.sin()),
                steepness: 0.7,
            }
        })
        .collect();
    let g = Gerstner::new(waves).unwrap();
    for cells in [255u32, 511] {
        let grid = GridSpec::centered(Vec2::splat(200.0), cells, cells).unwrap();
        let mut p = vec![Vec3::ZERO; grid.vertex_count()];
        let mut n = p.clone();
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let iters = if cells == 255 { 400 } else { 100 };
        let c0 = cpu();
        pool.install(|| {
            for k in 0..iters {
                g.evaluate(&grid, k as f64 * 0.04, &mut p, &mut n);
            }
        });
        println!("{} cells+1: {:.3} ms CPU per frame (1 thread)", cells, (cpu() - c0) * 1000.0 / iters as f64);
    }
}
