//! `realtime`: frames per second of every built-in preset at 1280 x 720 (paper 000's goal: a large
//! sea in real time on the CPU only).

use swell::render::Renderer;
use swell::scene::{preset, PRESETS};
use swell::world::World;
use swell::Result;

use super::report::{PaperUnit, PlotKind, Point, Report, Series};
use super::timing::measure;
use super::Context;

/// Image size, pixels.
pub const IMAGE: (u32, u32) = (1280, 720);
/// Simulated time between frames, s: what a frame advances the scene at 60 fps in real time (the
/// floating bodies of `flotsam` take two of their 120 Hz steps a frame).
const FRAME_DT: f64 = 1.0 / 60.0;

/// Times `World::update` + `Renderer::render_size` for each preset, and the median of each
/// stage over the same frames (the world's update, then the renderer's passes).
pub fn realtime(ctx: &Context) -> Result<Report> {
    let mut points = Vec::new();
    let mut split = vec!["Median ms per stage over the same frames, one line per preset: `World::update` (the models \
         stepped and the drawn surface displaced), then the renderer's passes (`swell::render::RenderStages`; \
         the water pass rasterizes and shades in one deferred walk)."
        .to_string()];
    for (i, p) in PRESETS.iter().enumerate() {
        ctx.progress(p.name);
        let mut world = World::new(preset(p.name)?)?;
        let mut renderer = Renderer::new();
        let mut t = 0.0;
        let mut stages: Vec<[f64; 7]> = Vec::new();
        let swell = measure(ctx.reps, || {
            t += FRAME_DT;
            let start = std::time::Instant::now();
            world.update(t)?;
            let update = start.elapsed();
            renderer.render_size(&world, IMAGE.0, IMAGE.1);
            let r = renderer.last_stages();
            stages.push(
                [update, r.terrain, r.sea_filter, r.water, r.far_field, r.sky, r.finish].map(|d| d.as_secs_f64() * 1e3),
            );
            Ok(())
        })?;
        let names = ["update", "terrain", "sea filter", "water", "far field", "sky", "finish"];
        let medians: Vec<String> = (0..7)
            .map(|k| {
                let mut v: Vec<f64> = stages.iter().map(|s| s[k]).collect();
                v.sort_by(f64::total_cmp);
                format!("{} {:.2}", names[k], v[v.len() / 2])
            })
            .collect();
        split.push(format!("`{}` stages (ms): {}", p.name, medians.join(", ")));
        points.push(Point { x: i as f64, label: p.name.to_string(), swell, paper: None });
    }
    Ok(Report {
        experiment: "realtime",
        title: "frames per second of each preset".into(),
        source: "paper 000's real-time goal; no table".into(),
        setup: vec![
            format!(
                "Frame = `World::update` + `Renderer::render_size` at {}x{} pixels, all threads; each preset as \
                 shipped (its own grid, waves and shading).",
                IMAGE.0, IMAGE.1
            ),
            "Frames per second = 1000 / median frame time in ms.".into(),
        ]
        .into_iter()
        .chain(split)
        .collect(),
        x_label: "preset".into(),
        paper_unit: PaperUnit::None,
        plot: PlotKind::Fps,
        series: vec![Series { name: String::new(), points }],
        machine: ctx.machine.clone(),
        repetitions: ctx.reps,
    })
}
