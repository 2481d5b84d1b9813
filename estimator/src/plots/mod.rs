//! PNG plots drawn with plotters, returned as bytes (`output.rs` writes them): the parameters
//! over epochs (ground truth dashed), the encoded latent against the physics rollout for a few
//! validation clips (the bodies' paths in the latent plane for a vector latent), and a
//! recording's timeline, its picture's change with the span fitted (`change.rs`) and the
//! object's own track with the laws fitted on it (`track.rs`), and a frame of it with the track
//! and the stick or plane drawn (`frame.rs`). One
//! chart set-up serves them all.

mod change;
mod frame;
mod track;

pub use change::change_png;
pub use frame::frame_jpeg;
pub use track::track_png;

use crate::analysis::Run;
use crate::timeline::Timeline;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;
use std::sync::Once;

const WIDTH: u32 = 900;
const PANEL_HEIGHT: u32 = 300;

type Area<'b> = DrawingArea<BitMapBackend<'b>, Shift>;
type Chart<'a, 'b> =
    ChartContext<'a, BitMapBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

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

/// Draws into an RGB buffer of `height` pixels with `draw` and encodes it as PNG.
fn render_png(
    height: u32,
    draw: impl FnOnce(Area) -> Result<(), String>,
) -> Result<Vec<u8>, String> {
    register_font();
    let mut buf = vec![0u8; (WIDTH * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        draw(root.clone())?;
        root.present().map_err(|e| e.to_string())?;
    }
    let img = image::RgbImage::from_raw(WIDTH, height, buf).expect("buffer matches size");
    let mut png = std::io::Cursor::new(Vec::new());
    img.write_to(&mut png, image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    Ok(png.into_inner())
}

/// A chart with a caption, axes over `x` and `y`, and their labels.
fn chart<'a, 'b>(
    area: &'a Area<'b>,
    caption: &str,
    (x, x_desc): (Range<f64>, &str),
    (y, y_desc): (Range<f64>, &str),
) -> Result<Chart<'a, 'b>, String> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(30)
        .y_label_area_size(70)
        .build_cartesian_2d(x, y)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(chart)
}

/// Draws the legend of the series that have labels.
fn legend<'a, 'b: 'a>(chart: &mut Chart<'a, 'b>) -> Result<(), String> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| e.to_string())
}

/// The finite values' range with a margin ((0, 1) when there are none).
fn range(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return 0.0..1.0;
    }
    let pad = ((hi - lo) * 0.08)
        .max(hi.abs().max(lo.abs()) * 0.01)
        .max(1e-9);
    lo - pad..hi + pad
}

/// `parameters.png`: each of the block's parameters against the epoch, its ground truth dashed.
pub fn parameters_png(report: &Run) -> Result<Vec<u8>, String> {
    let n = report.block_parameters.len().max(1);
    render_png(PANEL_HEIGHT * n as u32, |root| {
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
            let y = range(series.iter().map(|s| s.1).chain(truth));
            let caption = format!("{name} over training");
            let mut c = chart(panel, &caption, (0.0..epochs, "epoch"), (y, name.as_str()))?;
            c.draw_series(LineSeries::new(series, BLUE.stroke_width(2)))
                .map_err(|e| e.to_string())?
                .label("estimate")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE));
            if let Some(t) = truth {
                c.draw_series(DashedLineSeries::new(
                    vec![(0.0, t), (epochs, t)],
                    8,
                    5,
                    RED.stroke_width(2),
                ))
                .map_err(|e| e.to_string())?
                .label(format!("ground truth {t:.5}"))
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
            }
            legend(&mut c)?;
        }
        Ok(())
    })
}

/// Draws `values` at times `at(i)` as a line, with dots of `dot` pixels (none for 0).
fn trace(
    c: &mut Chart,
    values: &[f32],
    at: impl Fn(usize) -> f64,
    color: RGBAColor,
    dot: u32,
) -> Result<(), String> {
    let points: Vec<(f64, f64)> = values
        .iter()
        .enumerate()
        .map(|(i, &v)| (at(i), v as f64))
        .collect();
    c.draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))
        .map_err(|e| e.to_string())?;
    if dot > 0 {
        c.draw_series(
            points
                .into_iter()
                .map(|p| Circle::new(p, dot, color.filled())),
        )
        .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// `latents.png`: encoded latent (dots) and physics rollout (line) over time for up to four
/// validation clips.
/// For a vector latent of (x, y) per body (`dims` numbers per frame), the bodies' paths in the
/// latent plane instead.
pub fn latents_png(
    report: &Run,
    dt: f64,
    frames_per_clip: i64,
    dims: usize,
) -> Result<Vec<u8>, String> {
    if dims > 1 {
        return planar_latents_png(report, dims);
    }
    let z = &report.outcome.example_latents;
    let r = &report.outcome.example_rollouts;
    render_png(PANEL_HEIGHT + 100, |root| {
        let t_end = (frames_per_clip - 1) as f64 * dt;
        let y = range(z.iter().chain(r).flatten().map(|&v| v as f64));
        let caption = "encoded latent (dots) vs physics rollout (lines), validation clips";
        let mut c = chart(
            &root,
            caption,
            (0.0..t_end.max(dt), "time (s)"),
            (y, "latent z"),
        )?;
        for (k, (zs, rs)) in z.iter().zip(r).enumerate() {
            let color = Palette99::pick(k).to_rgba();
            trace(&mut c, rs, |i| i as f64 * dt, color, 0)?;
            c.draw_series(
                zs.iter()
                    .enumerate()
                    .map(|(i, &v)| Circle::new((i as f64 * dt, v as f64), 4, color.filled())),
            )
            .map_err(|e| e.to_string())?
            .label(format!("clip {k}"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
        }
        legend(&mut c)
    })
}

/// `timeline.png`: the encoded latent of every recording frame (grey) with the physics rollouts
/// of back-to-back clips over it (coloured, dots at the clip frames).
pub fn timeline_png(t: &Timeline) -> Result<Vec<u8>, String> {
    render_png(PANEL_HEIGHT + 100, |root| {
        let end = t.time(t.latents.len().max(2));
        let values = t
            .latents
            .iter()
            .chain(t.rollouts.iter().flat_map(|r| &r.1))
            .map(|&v| v as f64);
        let caption =
            "encoded latent over the recording (grey) and physics rollouts of clips (colour)";
        let x = (t.start_s..end, "time in the recording (s, real time)");
        let mut c = chart(&root, caption, x, (range(values), "latent z"))?;
        let grey = RGBColor(150, 150, 150).to_rgba();
        c.draw_series(LineSeries::new(
            t.latents
                .iter()
                .enumerate()
                .map(|(i, &v)| (t.time(i), v as f64)),
            grey.stroke_width(1),
        ))
        .map_err(|e| e.to_string())?;
        for (k, (start, roll)) in t.rollouts.iter().enumerate() {
            let color = Palette99::pick(k).to_rgba();
            trace(&mut c, roll, |i| t.time(start + i * t.stride), color, 2)?;
        }
        Ok(())
    })
}

/// The planar `latents.png`: each example clip's bodies in the latent plane, encoded (dots,
/// the first body filled, the others hollow) and rolled out (lines).
fn planar_latents_png(report: &Run, dims: usize) -> Result<Vec<u8>, String> {
    let z = &report.outcome.example_latents;
    let r = &report.outcome.example_rollouts;
    let coord = |rows: &[Vec<f32>], axis: usize| -> Vec<f64> {
        rows.iter()
            .flat_map(|row| row.iter().skip(axis).step_by(2).map(|&v| v as f64))
            .collect()
    };
    let (xs, ys) = (
        [coord(z, 0), coord(r, 0)].concat(),
        [coord(z, 1), coord(r, 1)].concat(),
    );
    // One scale on both axes: a similarity of the true plane stays one.
    let (x, y) = (range(xs.into_iter()), range(ys.into_iter()));
    let half = (x.end - x.start).max(y.end - y.start) / 2.0;
    let (cx, cy) = ((x.start + x.end) / 2.0, (y.start + y.end) / 2.0);
    render_png(WIDTH, |root| {
        let caption = "bodies in the latent plane: encoded (dots) vs physics rollout (lines)";
        let mut c = chart(
            &root,
            caption,
            (cx - half..cx + half, "latent x"),
            (cy - half..cy + half, "latent y"),
        )?;
        for (k, (zs, rs)) in z.iter().zip(r).enumerate() {
            let color = Palette99::pick(k).to_rgba();
            for body in 0..dims / 2 {
                let path = |row: &[f32]| -> Vec<(f64, f64)> {
                    row.chunks_exact(dims)
                        .map(|f| (f[2 * body] as f64, f[2 * body + 1] as f64))
                        .collect()
                };
                c.draw_series(LineSeries::new(path(rs), color.stroke_width(2)))
                    .map_err(|e| e.to_string())?;
                let style = if body == 0 {
                    color.filled()
                } else {
                    color.stroke_width(2)
                };
                let dots = c
                    .draw_series(path(zs).into_iter().map(|p| Circle::new(p, 4, style)))
                    .map_err(|e| e.to_string())?;
                if body == 0 {
                    dots.label(format!("clip {k}"))
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
                }
            }
        }
        legend(&mut c)
    })
}
