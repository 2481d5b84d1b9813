//! The one place that writes a run's outputs into `--out`: report.json, report.html,
//! metrics.csv, the plots and, for a recording, timeline.png, timeline.csv, change.png,
//! clips.png, track.png, track.csv and frame.jpg (a frame with the track and the stick or
//! plane drawn), in a folder this tool owns (`physvid_shared::outdir`): each file written whole
//! under a temporary name and renamed, only the tool's own files ever removed or replaced.

use crate::data::summary::RecordingSummary;
use crate::data::ClipData;
use crate::error::{input_error, EstimateError};
use crate::html::{report_page, Figure, Frame};
use crate::plots::{change_png, frame_jpeg, latents_png, parameters_png, timeline_png, track_png};
use crate::report::Report;
use crate::track::TrackRoute;
use physvid_shared::outdir::{self, OutputDir, Wait, MANIFEST};
use std::path::Path;

/// Every file a run may write, report.json first: an earlier run's (this tool's) are removed
/// before a run writes its own.
pub const OUTPUTS: [&str; 12] = [
    "report.json",
    "report.html",
    "metrics.csv",
    "parameters.png",
    "latents.png",
    "timeline.png",
    "timeline.csv",
    "change.png",
    "clips.png",
    "track.png",
    "track.csv",
    "frame.jpg",
];

/// Checks before any work that a run may write into `out` (`outdir::check`), and that it
/// would not write among its own input: an image folder as --out would have the next run read
/// the plots as frames, and a folder of this tool's outputs is not a recording.
pub fn check_out(out: &Path, input: Option<&Path>, force: bool) -> Result<(), EstimateError> {
    if let Some(input) = input.filter(|i| i.is_dir()) {
        let same = match (std::fs::canonicalize(input), std::fs::canonicalize(out)) {
            (Ok(i), Ok(o)) => i == o,
            _ => false,
        };
        if same {
            return Err(input_error(format!(
                "--out {}: the input folder itself; write the results elsewhere (the next run \
                 would read them as input)",
                out.display()
            )));
        }
        if input.join(MANIFEST).is_file() && !input.join("frames.npy").exists() {
            return Err(input_error(format!(
                "{}: a folder of this tool's outputs ({MANIFEST}), not a recording: its images \
                 are plots, not frames",
                input.display()
            )));
        }
    }
    // A run folder of a version before the mark is this tool's: its report says so.
    let report_of_estimate = |dir: &Path| {
        std::fs::read(dir.join("report.json"))
            .ok()
            .and_then(|b| serde_json::from_slice::<serde_json::Value>(&b).ok())
            .is_some_and(|r| r["tool"] == "estimate")
    };
    outdir::adopt(out, "estimate", &OUTPUTS, report_of_estimate)?;
    Ok(outdir::check("--out", out, &OUTPUTS, force)?)
}

/// `out` opened for this run's files (waiting for another run writing there: two runs into
/// one folder take turns, each writing its whole set).
fn open(out: &Path, force: bool) -> Result<OutputDir, EstimateError> {
    Ok(OutputDir::open(
        "--out",
        out,
        "estimate",
        &OUTPUTS,
        force,
        Wait::Turns,
    )?)
}

fn plot(
    dir: &mut OutputDir,
    name: &str,
    png: Result<Vec<u8>, String>,
) -> Result<Vec<u8>, EstimateError> {
    let png = png.map_err(|reason| EstimateError::Plot {
        path: dir.path().join(name),
        reason,
    })?;
    dir.write(name, &png)?;
    Ok(png)
}

/// Removes an earlier run's files (this tool's) from `out`, if it exists, under its lock: a run
/// that gives no estimate must not leave another run's complete report.json behind.
pub fn clear_earlier(out: &Path, force: bool) -> Result<(), EstimateError> {
    if !out.is_dir() {
        return Ok(());
    }
    let mut dir = open(out, force)?;
    dir.remove_own(&OUTPUTS)?;
    dir.finish();
    Ok(())
}

/// Writes report.html, metrics.csv, parameters.png and latents.png (and timeline.png,
/// timeline.csv, change.png, clips.png, track.png, track.csv and frame.jpg for a recording)
/// into `out`, report.json last.
pub fn write_outputs(
    out: &Path,
    force: bool,
    data: &ClipData,
    report: &Report,
) -> Result<(), EstimateError> {
    let mut dir = open(out, force)?;
    // The tool's files in the folder become wholly this run's.
    dir.remove_own(&OUTPUTS)?;
    dir.write("metrics.csv", report.metrics_csv().as_bytes())?;
    let plot_figure = |caption, png| Figure {
        caption,
        png,
        pixels: false,
    };
    let mut figures = vec![plot_figure(
        "Parameters over epochs",
        plot(&mut dir, "parameters.png", parameters_png(&report.run))?,
    )];
    let dims = report.run.config.model.latent_dims();
    let latents = latents_png(
        &report.run,
        report.run.config.dt,
        data.frames_per_clip,
        dims,
    );
    figures.push(plot_figure(
        "Latents of validation clips",
        plot(&mut dir, "latents.png", latents)?,
    ));
    if let Some(t) = &report.run.outcome.timeline {
        figures.push(plot_figure(
            "The recording's timeline",
            plot(&mut dir, "timeline.png", timeline_png(t))?,
        ));
        dir.write("timeline.csv", t.csv(dims).as_bytes())?;
    }
    if let Some(png) = report.run.recording.as_ref().and_then(change_png) {
        figures.push(plot_figure(
            "The picture's change over the recording, and the span fitted (shaded)",
            plot(&mut dir, "change.png", png)?,
        ));
    }
    if let Some(route) = &report.run.track {
        figures.push(plot_figure(
            "The object's own track and the laws fitted on it (the second route)",
            plot(&mut dir, "track.png", track_png(route))?,
        ));
        dir.write("track.csv", route.track.csv().as_bytes())?;
    }
    if let Some(png) = &data.preview_png {
        if report.run.recording.as_ref().is_some_and(|r| r.preview) {
            dir.write("clips.png", png)?;
        }
        figures.push(Figure {
            caption: "The first clips as the model saw them (above them, for --crop auto, where \
                      the picture moves: the motion map, the part kept in red)",
            png: png.clone(),
            pixels: true,
        });
    }
    let frame = report
        .run
        .recording
        .as_ref()
        .and_then(|r| frame_of(report, r));
    if let Some(jpeg) = frame.as_ref().and_then(|f| framed(report, f)) {
        dir.write("frame.jpg", &jpeg)?;
    }
    dir.write(
        "report.html",
        report_page(report, &figures, frame.as_ref()).as_bytes(),
    )?;
    let json = serde_json::to_vec_pretty(report).expect("report serialises");
    dir.write("report.json", &json)?;
    dir.finish();
    Ok(())
}

/// frame.jpg of `report`'s recording (`plots::frame_jpeg`: a frame with the track and the stick
/// or plane drawn); `None` without a recording, a frame or a track. Best effort, as the frame
/// itself: a picture beside the answer, never a reason to fail.
pub fn frame_picture(report: &Report) -> Option<Vec<u8>> {
    let frame = frame_of(report, report.run.recording.as_ref()?)?;
    framed(report, &frame)
}

/// `frame` with `report`'s track drawn on it.
fn framed(report: &Report, frame: &Frame) -> Option<Vec<u8>> {
    frame_jpeg(&frame.jpeg, frame.size, report.run.track.as_ref()?).ok()
}

/// A frame of the recording `report` was run on, for the page: the middle of the track's
/// chosen span where it has one (the object in motion), else of the part kept; none where it
/// cannot be read again (the page goes without it).
fn frame_of(report: &Report, rec: &RecordingSummary) -> Option<Frame> {
    let at = match report.run.track.as_ref().and_then(TrackRoute::shown_at) {
        Some(at) => at,
        None => {
            let start = rec.start.unwrap_or(0.0);
            let frames = rec.frames_decoded.saturating_sub(1) as f64;
            start + frames / (2.0 * rec.timeline_fps.max(1e-9))
        }
    };
    let jpeg = physvid_shared::video::still(&report.run.config.input, at, rec.timeline_fps).ok()?;
    Some(Frame {
        jpeg,
        size: (rec.info.width, rec.info.height),
        at,
    })
}
