//! The pages a person opens: `report.html` for a run (estimates, warnings, the run's facts, the
//! plots inlined as PNG, the command), and the rendering and style that `batch`'s index.html
//! shares. One self-contained file each, plain HTML and CSS from minijinja templates; nothing
//! is fetched from the network.

use crate::digits::{sig, significant};
use crate::report::Report;
use base64::Engine;
use minijinja::{context, Environment};
use serde::Serialize;

/// The pages' style sheet, inlined into each.
pub fn style() -> minijinja::Value {
    minijinja::Value::from_safe_string(include_str!("style.css").to_string())
}

/// Renders a template (HTML-escaping every value not marked safe).
pub fn render(name: &str, source: &'static str, ctx: minijinja::Value) -> String {
    let mut env = Environment::new();
    env.add_template(name, source).expect("the template parses");
    env.get_template(name)
        .and_then(|t| t.render(ctx))
        .expect("the template renders")
}

#[derive(Serialize)]
struct Row {
    name: String,
    estimate: String,
    error_bar: String,
    /// Each route's value where the track measured it too (`ParameterResult::routes_phrase`).
    routes: String,
    unit: String,
    truth: String,
    error: String,
}

#[derive(Serialize)]
struct Image {
    caption: &'static str,
    data: String,
    pixels: bool,
}

/// A picture for the page: its caption, its PNG bytes, and whether it is drawn pixel for pixel
/// (frames as the model sees them) rather than smoothed (plots).
pub struct Figure {
    pub caption: &'static str,
    pub png: Vec<u8>,
    pub pixels: bool,
}

/// A frame of the recording for the page: its JPEG bytes, the frame's size as a player shows
/// it (what `--stick` counts in; the JPEG may be smaller), and its time in the file (s).
pub struct Frame {
    pub jpeg: Vec<u8>,
    pub size: (usize, usize),
    pub at: f64,
}

/// The frame's context: the picture, its size, the stick or the plane given drawn on it.
fn frame_context(frame: &Frame, route: Option<&crate::track::TrackRoute>) -> minijinja::Value {
    let b64 = base64::engine::general_purpose::STANDARD;
    let (w, h) = frame.size;
    let stick = route.and_then(|r| r.stick).map(|s| {
        context! {
            flag => s.flag(), x1 => s.from.0, y1 => s.from.1, x2 => s.to.0, y2 => s.to.1,
        }
    });
    let plane = route.and_then(|r| r.plane).map(|p| {
        let points: Vec<String> = p
            .corners
            .iter()
            .map(|c| format!("{},{}", c.0, c.1))
            .collect();
        context! {
            flag => p.flag(), points => points.join(" "),
            x1 => p.corners[0].0, y1 => p.corners[0].1,
        }
    });
    // The object's track where it was seen, and its chosen law's span.
    let points = |range: std::ops::Range<usize>| {
        route.map_or(String::new(), |r| {
            let t = &r.track;
            let xy = t.x[range.clone()].iter().zip(&t.y[range]);
            let xy: Vec<String> = xy.map(|(x, y)| format!("{x:.1},{y:.1}")).collect();
            xy.join(" ")
        })
    };
    let n = route.map_or(0, |r| r.track.t.len());
    let span = route
        .and_then(|r| r.chosen_span())
        .map_or(0..0, |l| l.first..l.first + l.samples);
    context! {
        data => b64.encode(&frame.jpeg), width => w, height => h, at => sig(frame.at),
        r => format!("{:.1}", w.max(h) as f64 / 120.0), stick, plane,
        track => points(0..n), span => points(span),
    }
}

/// `report.html` for `report`, with its figures inlined and, for a recording, a frame of it
/// with the stick given drawn and the tool that makes one.
pub fn report_page(report: &Report, figures: &[Figure], frame: Option<&Frame>) -> String {
    let b64 = base64::engine::general_purpose::STANDARD;
    let parameters: Vec<Row> = report
        .run
        .parameters
        .iter()
        .map(|p| Row {
            name: p.name.clone(),
            estimate: sig(p.estimate),
            error_bar: p
                .standard_error
                .map_or("–".into(), |e| format!("± {}", significant(e))),
            unit: p.unit.clone(),
            routes: p.routes_phrase().unwrap_or_default(),
            truth: p.truth.map_or("–".into(), sig),
            error: p
                .relative_error
                .map_or("–".into(), |e| format!("{:+.3} %", e * 100.0)),
        })
        .collect();
    let ensemble: Vec<_> = report
        .run
        .ensemble
        .iter()
        .flat_map(|e| &e.values)
        .map(|v| {
            context! {
                name => v.name, mean => sig(v.mean), std => sig(v.std),
                range => format!("{} – {}", sig(v.min), sig(v.max)), unit => v.unit,
                truth => v.truth.map_or("–".into(), sig),
            }
        })
        .collect();
    let cross_check = report.run.cross_check.as_ref().map(|c| {
        format!(
            "Cross-check: {} from the amplitude decay of {} swings (appendix A.6) is {} ± {} \
             (learned {}): {}.",
            c.name,
            c.peaks.len(),
            sig(c.estimate),
            sig(c.std_error),
            sig(c.learned),
            if c.agrees {
                "within 2 standard errors"
            } else {
                "outside 2 standard errors"
            }
        )
    });
    let cfg = &report.run.config;
    let [n, t, ch, h, w] = report.run.shape;
    let mut facts = vec![
        ("model", report.run.model.clone()),
        ("frame interval dt", format!("{} s", sig(report.run.dt))),
        ("clips", format!("{n} × {t} frames of {w}×{h}×{ch}")),
        (
            "train / validation clips",
            format!(
                "{} / {}",
                report.run.train_clips, report.run.validation_clips
            ),
        ),
        ("loss", cfg.loss.name().to_string()),
        ("integrator", cfg.integrator.name().to_string()),
        (
            "epochs run (best)",
            format!("{} ({})", report.run.epochs_run, report.run.best_epoch),
        ),
        ("stopped", stop_text(&report.run.stop)),
        (
            "validation rel. MSE",
            format!("{:.3e}", report.run.best_val_rel_mse),
        ),
        (
            "latent std",
            format!(
                "{:.3e}{}",
                report.run.latent_std,
                if report.run.latent_collapsed {
                    " (collapsed)"
                } else {
                    ""
                }
            ),
        ),
        ("seed", cfg.seed.to_string()),
        (
            "device, threads",
            format!("{}, {}", report.run.device, report.run.threads),
        ),
        ("wall time", format!("{:.1} s", report.run.wall_time_s)),
    ];
    if let Some(p) = &report.run.photometric {
        facts.push((
            "light normalised",
            format!(
                "gain varied by {:.1} %, across the frame by {:.1} % (a tenth of the frames more)",
                100.0 * p.gain_spread,
                100.0 * p.gradient
            ),
        ));
    }
    if let Some(l) = &report.run.latent_vs_truth {
        facts.push(("latent vs truth R²", format!("{:.4}", l.r2())));
    }
    let recording = report.run.recording.as_ref().map(|r| {
        vec![
            (
                "frame rate",
                format!("{} fps ({})", sig(r.fps), r.fps_source),
            ),
            ("frames decoded", r.frames_decoded.to_string()),
            (
                "kept",
                format!(
                    "{} to {}",
                    r.start
                        .map_or("its start".into(), |s| format!("{} s", sig(s))),
                    r.end.map_or("its end".into(), |e| format!("{} s", sig(e)))
                ),
            ),
            (
                "framing",
                match r.crop {
                    Some(c) => format!("{}: {},{},{},{}", r.framing, c.x, c.y, c.w, c.h),
                    None => r.framing.to_string(),
                },
            ),
            ("encoder frame size", format!("{}×{}", r.size.0, r.size.1)),
            (
                "clip frames, stride, hop",
                format!("{}, {}, {}", r.frames_per_clip, r.stride, r.hop),
            ),
            ("decoding", format!("{:.1} s", r.decode_s)),
        ]
    });
    let images: Vec<Image> = figures
        .iter()
        .map(|f| Image {
            caption: f.caption,
            data: b64.encode(&f.png),
            pixels: f.pixels,
        })
        .collect();
    let choice = report.model_choice.as_ref().map(|c| {
        let rows: Vec<_> = c
            .candidates
            .iter()
            .map(|x| {
                context! {
                    model => x.model, answer => x.answer, freedom => x.freedom(),
                    grade => x.grade.map_or("no estimate", |g| g.name()),
                    unexplained => x.unexplained_text(), picture => x.picture_text(),
                }
            })
            .collect();
        context! {
            chosen => c.chosen, why => c.why, close => c.close, cut => c.cut, rows,
            seconds => format!("{:.1}", c.wall_time_s),
        }
    });
    // The second route: each law fitted on the object's track, where it holds.
    let track = report.run.track.as_ref().map(|r| {
        let rows: Vec<_> = r
            .laws
            .iter()
            .map(|l| {
                let values: Vec<String> = l
                    .values
                    .iter()
                    .chain(&l.si)
                    .map(|v| {
                        format!(
                            "{} {} ± {} {}",
                            v.name,
                            sig(v.value),
                            significant(v.error),
                            v.unit
                        )
                    })
                    .collect();
                context! {
                    law => l.law.name(), chosen => Some(l.law) == r.chosen, holds => l.holds,
                    span => format!("{:.2}–{:.2} s ({} samples)", l.first_s, l.last_s, l.samples),
                    rms => format!("{:.2} {}", l.rms_px, r.unit()), answer => values.join(", "),
                }
            })
            .collect();
        let stick = match (r.plane, r.stick) {
            (Some(p), _) => Some(format!(
                "--plane {}: a {} m × {} m rectangle, {} px a metre over it (the track read on \
                 that plane, in metres)",
                p.flag(),
                sig(p.width),
                sig(p.height),
                sig(p.per_metre())
            )),
            (None, Some(s)) => Some(format!(
                "--stick {}: {} px for {} m, {} px a metre (the track's lengths in metres from it)",
                s.flag(),
                sig(s.pixels()),
                sig(s.metres),
                sig(s.per_metre())
            )),
            (None, None) => None,
        };
        context! { line => r.line(), rows, stick }
    });
    let headline = format!(
        "{} clips, dt {} s; {} epochs in {:.1} s on {}",
        report.run.train_clips + report.run.validation_clips,
        sig(report.run.dt),
        report.run.epochs_run,
        report.run.wall_time_s,
        report.run.device
    );
    render(
        "report.html",
        include_str!("report.html"),
        context! {
            style => style(),
            model => report.run.model, input => report.run.input, headline,
            parameters, ensemble, cross_check, track, warnings => report.run.warnings, facts, recording,
            choice,
            frame => frame.map(|f| frame_context(f, report.run.track.as_ref())),
            stick_js => minijinja::Value::from_safe_string(include_str!("stick.js").to_string()),
            grade => report.verdict.grade.name(), reasons => &report.verdict.reasons,
            images, command => report.command.clone().unwrap_or_else(|| "(not recorded)".into()),
            version => report.version, libtorch => report.libtorch_version,
        },
    )
}

fn stop_text(stop: &crate::train::StopReason) -> String {
    use crate::train::StopReason::*;
    match stop {
        EarlyStop { patience } => format!("no improvement for {patience} epochs"),
        Converged { window, spread } => format!(
            "parameters within {:.2} % for {window} epochs",
            spread * 100.0
        ),
        MaxEpochs => "at --epochs".into(),
        NonFiniteLoss { epoch } => format!("non-finite loss at epoch {epoch}"),
        LawNotFinite { epoch, .. } => format!("the law not finite at epoch {epoch}"),
    }
}
