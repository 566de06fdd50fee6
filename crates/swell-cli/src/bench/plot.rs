//! PNG plots of a [`Report`], drawn in memory with plotters and a font shipped in the binary.
//!
//! The font (a DejaVu Sans subset, `assets/DejaVuSans-subset.ttf`, licence beside it) is compiled
//! in and registered with plotters as `sans-serif`, so plotting needs no font installed on the
//! machine.

use std::path::Path;
use std::sync::OnceLock;

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder};
use plotters::coord::Shift;
use plotters::prelude::*;
use swell::export::write_atomically;
use swell::{Error, Result};

use super::report::{PlotKind, Report};

/// The bundled font.
const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans-subset.ttf");
/// Plot size in pixels.
const SIZE: (u32, u32) = (960, 600);
/// One colour per series; swell solid, the paper dashed in the same colour.
const PALETTE: [RGBColor; 5] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
];

/// Registers the bundled font once; false if it does not parse (a build defect, reported as an
/// error rather than a panic).
fn register_font() -> bool {
    static OK: OnceLock<bool> = OnceLock::new();
    *OK.get_or_init(|| plotters::style::register_font("sans-serif", FontStyle::Normal, FONT).is_ok())
}

/// Writes `EXPERIMENT.png` into `dir`, atomically.
pub fn write_plot(report: &Report, dir: &Path) -> Result<()> {
    let path = dir.join(format!("{}.png", report.experiment));
    if !register_font() {
        return Err(Error::Image { path, message: "the bundled font does not parse".into() });
    }
    let (w, h) = SIZE;
    let mut rgb = vec![255u8; 3 * (w * h) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area();
        let drawn = match report.plot {
            PlotKind::Relative => relative(report, &root),
            PlotKind::Fps => fps(report, &root),
        };
        drawn.and_then(|()| root.present().map_err(|e| e.to_string())).map_err(|message| Error::Image {
            path: path.clone(),
            message: format!("cannot draw the plot: {message}"),
        })?;
    }
    // Best compression: plots are flat colours and compress ~3x better than renders do.
    write_atomically(&path, |out| {
        let encoder = PngEncoder::new_with_quality(out, CompressionType::Best, FilterType::Adaptive);
        encoder
            .write_image(&rgb, w, h, ExtendedColorType::Rgb8)
            .map_err(|e| Error::Image { path: path.clone(), message: e.to_string() })
    })
}

type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;

/// Whether the parameter doubles from row to row (threads 1..32, heightmap sides 33..513): then
/// rows are drawn evenly spaced and labelled, as on a log axis.
fn doubling(report: &Report) -> bool {
    report.series.iter().all(|s| {
        s.points.len() >= 3 && s.points.windows(2).all(|p| p[0].x > 0.0 && (1.8..=2.2).contains(&(p[1].x / p[0].x)))
    })
}

/// Every series and its paper curve divided by their first rows.
fn relative(report: &Report, root: &Area) -> std::result::Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let by_row = doubling(report);
    // Row labels for an evenly spaced axis, from the longest series.
    let rows: Vec<String> = report
        .series
        .iter()
        .max_by_key(|s| s.points.len())
        .map(|s| s.points.iter().map(|p| p.label.clone()).collect())
        .unwrap_or_default();
    let tx = |i: usize, x: f64| if by_row { i as f64 } else { x };
    let xs = report.series.iter().flat_map(|s| s.points.iter().enumerate().map(|(i, p)| tx(i, p.x)));
    let (x0, x1) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    let pad = if by_row { 0.3 } else { 0.03 * (x1 - x0).max(1.0) };
    let mut y1: f64 = 1.0;
    for s in &report.series {
        for i in 0..s.points.len() {
            y1 = y1.max(s.swell_relative(i)).max(s.paper_relative(i).unwrap_or(0.0));
        }
    }
    let caption = format!("{}: {}", report.experiment, report.title);
    let mut chart = ChartBuilder::on(root)
        .caption(caption, ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(64)
        // Headroom above the highest point for the legend.
        .build_cartesian_2d((x0 - pad)..(x1 + pad), 0.0..(1.35 * y1))
        .map_err(e)?;
    let row_label = |v: &f64| {
        let i = v.round();
        if (v - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < rows.len() {
            rows[i as usize].clone()
        } else {
            String::new()
        }
    };
    let plain = |v: &f64| format!("{v}");
    let mut mesh = chart.configure_mesh();
    if by_row {
        mesh.x_labels(4 * rows.len() + 1).x_label_formatter(&row_label).disable_x_mesh();
    } else {
        mesh.x_label_formatter(&plain);
    }
    mesh.x_desc(report.x_label.as_str())
        .y_desc("time / time of the first row")
        .max_light_lines(1)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .draw()
        .map_err(e)?;
    for (k, s) in report.series.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let name = if s.name.is_empty() { String::new() } else { format!(", {}", s.name) };
        let ours: Vec<(f64, f64)> = (0..s.points.len()).map(|i| (tx(i, s.points[i].x), s.swell_relative(i))).collect();
        chart
            .draw_series(LineSeries::new(ours.clone(), color.stroke_width(3)))
            .map_err(e)?
            .label(format!("swell{name}"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(3)));
        chart.draw_series(ours.iter().map(|&p| Circle::new(p, 4, color.filled()))).map_err(e)?;
        let paper: Vec<(f64, f64)> =
            (0..s.points.len()).filter_map(|i| Some((tx(i, s.points[i].x), s.paper_relative(i)?))).collect();
        if paper.len() >= 2 {
            chart
                .draw_series(DashedLineSeries::new(paper.clone(), 8, 5, color.stroke_width(2)))
                .map_err(e)?
                .label(format!("paper{name}"))
                .legend(move |(x, y)| {
                    // A dashed sample, in pixels relative to (x, y).
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (9, 0)], color.stroke_width(2))
                        + PathElement::new(vec![(15, 0), (24, 0)], color.stroke_width(2))
                });
            chart.draw_series(paper.iter().map(|&p| TriangleMarker::new(p, 5, color))).map_err(e)?;
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .label_font(("sans-serif", 16))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;
    Ok(())
}

/// Frames per second as one bar per row, with the 30 and 60 FPS marks.
fn fps(report: &Report, root: &Area) -> std::result::Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let points: Vec<_> = report.series.iter().flat_map(|s| s.points.iter()).collect();
    let n = points.len().max(1) as f64;
    let top = points.iter().map(|p| 1e3 / p.swell.median_ms).fold(60.0, f64::max) * 1.15;
    let caption = format!("{}: {}", report.experiment, report.title);
    let mut chart = ChartBuilder::on(root)
        .caption(caption, ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(64)
        .build_cartesian_2d(-0.5..(n - 0.5), 0.0..top)
        .map_err(e)?;
    let label = |v: &f64| {
        let i = v.round();
        if (v - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < points.len() {
            points[i as usize].label.clone()
        } else {
            String::new()
        }
    };
    chart
        .configure_mesh()
        .disable_x_mesh()
        .max_light_lines(1)
        .x_labels(points.len() * 4 + 1)
        .x_label_formatter(&label)
        .x_desc(report.x_label.as_str())
        .y_desc("frames per second (median)")
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .draw()
        .map_err(e)?;
    chart
        .draw_series(points.iter().enumerate().map(|(i, p)| {
            let x = i as f64;
            Rectangle::new([(x - 0.3, 0.0), (x + 0.3, 1e3 / p.swell.median_ms)], PALETTE[0].filled())
        }))
        .map_err(e)?;
    for (fps, color) in [(30.0, PALETTE[1]), (60.0, PALETTE[2])] {
        chart
            .draw_series(DashedLineSeries::new(vec![(-0.5, fps), (n - 0.5, fps)], 8, 5, color.stroke_width(2)))
            .map_err(e)?
            .label(format!("{fps} FPS"))
            .legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(0, 0), (9, 0)], color.stroke_width(2))
                    + PathElement::new(vec![(15, 0), (24, 0)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .label_font(("sans-serif", 16))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;
    Ok(())
}
