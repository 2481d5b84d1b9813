//! PNG plots drawn with plotters: the parameters over epochs (ground truth as a dashed line) and
//! the encoded latent against the physics rollout for a few validation clips.

use crate::data::ClipData;
use crate::error::EstimateError;
use crate::report::{write_atomic, Report};
use crate::timeline::Timeline;
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

const WIDTH: u32 = 900;
const PANEL_HEIGHT: u32 = 300;

/// Registers the embedded DejaVu Sans as plotters' sans-serif font (once per process), so
/// plots need no system fonts.
fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

fn plot_error(path: &Path, e: impl std::fmt::Display) -> EstimateError {
    EstimateError::Plot {
        path: path.to_path_buf(),
        reason: e.to_string(),
    }
}

/// Draws into an RGB buffer with `draw`, then writes it as PNG atomically.
fn render_png(
    path: &Path,
    height: u32,
    draw: impl FnOnce(DrawingArea<BitMapBackend, plotters::coord::Shift>) -> Result<(), String>,
) -> Result<(), EstimateError> {
    register_font();
    let mut buf = vec![0u8; (WIDTH * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
        draw(root.clone()).map_err(|e| plot_error(path, e))?;
        root.present().map_err(|e| plot_error(path, e))?;
    }
    let img = image::RgbImage::from_raw(WIDTH, height, buf).expect("buffer matches size");
    let mut png = std::io::Cursor::new(Vec::new());
    img.write_to(&mut png, image::ImageFormat::Png)
        .map_err(|e| plot_error(path, e))?;
    write_atomic(path, &png.into_inner())
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = ((hi - lo) * 0.08)
        .max(hi.abs().max(lo.abs()) * 0.01)
        .max(1e-9);
    (lo - pad, hi + pad)
}

/// `parameters.png`: each of the block's parameters against the epoch, its ground truth dashed.
pub fn plot_parameters(path: &Path, report: &Report) -> Result<(), EstimateError> {
    let n = report.block_parameters.len().max(1);
    render_png(path, PANEL_HEIGHT * n as u32, |root| {
        let panels = root.split_evenly((n, 1));
        let epochs = report.history.len().max(2) as f64;
        for (i, (panel, name)) in panels.iter().zip(&report.block_parameters).enumerate() {
            // Ground truth where the block's parameter is itself an SI answer.
            let truth = report
                .parameters
                .iter()
                .find(|r| &r.name == name && r.units == "SI")
                .and_then(|r| r.truth);
            let series: Vec<(f64, f64)> = report
                .history
                .iter()
                .map(|r| (r.epoch as f64, r.parameters[i]))
                .collect();
            let (lo, hi) = range(series.iter().map(|s| s.1).chain(truth));
            let mut chart = ChartBuilder::on(panel)
                .caption(format!("{name} over training"), ("sans-serif", 18))
                .margin(10)
                .x_label_area_size(30)
                .y_label_area_size(70)
                .build_cartesian_2d(0.0..epochs, lo..hi)
                .map_err(|e| e.to_string())?;
            chart
                .configure_mesh()
                .x_desc("epoch")
                .y_desc(name.as_str())
                .draw()
                .map_err(|e| e.to_string())?;
            chart
                .draw_series(LineSeries::new(series, BLUE.stroke_width(2)))
                .map_err(|e| e.to_string())?
                .label("estimate")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE));
            if let Some(t) = truth {
                chart
                    .draw_series(DashedLineSeries::new(
                        vec![(0.0, t), (epochs, t)],
                        8,
                        5,
                        RED.stroke_width(2),
                    ))
                    .map_err(|e| e.to_string())?
                    .label(format!("ground truth {t:.5}"))
                    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .draw()
                .map_err(|e| e.to_string())?;
        }
        Ok(())
    })
}

/// `latents.png`: encoded latent (dots) and physics rollout (line) over time for up to four
/// validation clips.
pub fn plot_latents(path: &Path, report: &Report, data: &ClipData) -> Result<(), EstimateError> {
    let z = &report.outcome.example_latents;
    let r = &report.outcome.example_rollouts;
    let dt = data.dt;
    render_png(path, PANEL_HEIGHT + 100, |root| {
        let t_end = (data.frames_per_clip - 1) as f64 * dt;
        let (lo, hi) = range(z.iter().chain(r).flatten().map(|&v| v as f64));
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "encoded latent (dots) vs physics rollout (lines), validation clips",
                ("sans-serif", 18),
            )
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..t_end.max(dt), lo..hi)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("time (s)")
            .y_desc("latent z")
            .draw()
            .map_err(|e| e.to_string())?;
        for (k, (zs, rs)) in z.iter().zip(r).enumerate() {
            let color = Palette99::pick(k).to_rgba();
            chart
                .draw_series(LineSeries::new(
                    rs.iter()
                        .enumerate()
                        .map(|(i, &v)| (i as f64 * dt, v as f64)),
                    color.stroke_width(2),
                ))
                .map_err(|e| e.to_string())?
                .label(format!("clip {k}"))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
            chart
                .draw_series(
                    zs.iter()
                        .enumerate()
                        .map(|(i, &v)| Circle::new((i as f64 * dt, v as f64), 4, color.filled())),
                )
                .map_err(|e| e.to_string())?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| e.to_string())?;
        Ok(())
    })
}

/// `timeline.png`: the encoded latent of every recording frame (grey) with the physics rollouts
/// of back-to-back clips over it (coloured, dots at the clip frames).
pub fn plot_timeline(path: &Path, t: &Timeline) -> Result<(), EstimateError> {
    render_png(path, PANEL_HEIGHT + 100, |root| {
        let end = t.latents.len().max(2) as f64 * t.frame_dt;
        let values = t
            .latents
            .iter()
            .chain(t.rollouts.iter().flat_map(|r| &r.1))
            .map(|&v| v as f64);
        let (lo, hi) = range(values);
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "encoded latent over the recording (grey) and physics rollouts of clips (colour)",
                ("sans-serif", 18),
            )
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..end, lo..hi)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("time in the recording (s, real time)")
            .y_desc("latent z")
            .draw()
            .map_err(|e| e.to_string())?;
        chart
            .draw_series(LineSeries::new(
                t.latents
                    .iter()
                    .enumerate()
                    .map(|(i, &v)| (i as f64 * t.frame_dt, v as f64)),
                RGBColor(150, 150, 150).stroke_width(1),
            ))
            .map_err(|e| e.to_string())?;
        for (k, (start, roll)) in t.rollouts.iter().enumerate() {
            let color = Palette99::pick(k).to_rgba();
            let at = |i: usize| (start + i * t.stride) as f64 * t.frame_dt;
            chart
                .draw_series(LineSeries::new(
                    roll.iter().enumerate().map(|(i, &v)| (at(i), v as f64)),
                    color.stroke_width(2),
                ))
                .map_err(|e| e.to_string())?;
            chart
                .draw_series(
                    roll.iter()
                        .enumerate()
                        .map(|(i, &v)| Circle::new((at(i), v as f64), 2, color.filled())),
                )
                .map_err(|e| e.to_string())?;
        }
        Ok(())
    })
}
