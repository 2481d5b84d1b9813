//! The one place that writes a run's outputs into `--out`: report.json, report.html,
//! metrics.csv, the plots and, for a recording, timeline.png, timeline.csv and clips.png. Each file is written under a temporary
//! name and renamed.

use crate::data::ClipData;
use crate::error::EstimateError;
use crate::html::{report_page, Figure};
use crate::plots::{latents_png, parameters_png, timeline_png};
use crate::report::Report;
use physvid_shared::write_atomic;
use std::path::Path;

/// Writes `dir/name` under a temporary name, then renames it.
pub fn write_file(dir: &Path, name: &str, bytes: &[u8]) -> Result<(), EstimateError> {
    write_atomic(&dir.join(name), bytes).map_err(|e| match e {
        physvid_shared::DatasetError::Write { path, source } => {
            EstimateError::Write { path, source }
        }
        other => EstimateError::Dataset(other),
    })
}

fn plot(dir: &Path, name: &str, png: Result<Vec<u8>, String>) -> Result<Vec<u8>, EstimateError> {
    let png = png.map_err(|reason| EstimateError::Plot {
        path: dir.join(name),
        reason,
    })?;
    write_file(dir, name, &png)?;
    Ok(png)
}

/// Every file a run may write, report.json first: removed before a run writes its own.
const OUTPUTS: [&str; 8] = [
    "report.json",
    "report.html",
    "metrics.csv",
    "parameters.png",
    "latents.png",
    "timeline.png",
    "timeline.csv",
    "clips.png",
];

/// Removes every file a run writes from `out`, report.json first (a directory with a
/// report.json is complete).
pub fn clear_outputs(out: &Path) -> Result<(), EstimateError> {
    for name in OUTPUTS {
        let path = out.join(name);
        if path.is_file() {
            std::fs::remove_file(&path).map_err(|source| EstimateError::Write { path, source })?;
        }
    }
    Ok(())
}

/// An exclusive lock on `out` (its `.lock` file) for as long as it is held: two runs writing
/// one directory take turns, each clearing and writing its whole set, so the directory never
/// mixes the two.
pub fn lock_dir(out: &Path) -> Result<std::fs::File, EstimateError> {
    let err = |source| EstimateError::Write {
        path: out.join(".lock"),
        source,
    };
    std::fs::create_dir_all(out).map_err(|source| EstimateError::Write {
        path: out.to_path_buf(),
        source,
    })?;
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(out.join(".lock"))
        .map_err(err)?;
    file.lock().map_err(err)?;
    Ok(file)
}

/// Removes an earlier run's files from `out` (if it exists) under its lock: a run that gives
/// no estimate must not leave another run's complete report.json behind.
pub fn clear_earlier(out: &Path) -> Result<(), EstimateError> {
    if !out.is_dir() {
        return Ok(());
    }
    let _lock = lock_dir(out)?;
    clear_outputs(out)
}

/// Writes report.html, metrics.csv, parameters.png and latents.png (and timeline.png,
/// timeline.csv and clips.png for a recording) into `out`, report.json last.
pub fn write_outputs(out: &Path, data: &ClipData, report: &Report) -> Result<(), EstimateError> {
    let _lock = lock_dir(out)?;
    // The directory becomes wholly this run's.
    clear_outputs(out)?;
    write_file(out, "metrics.csv", report.metrics_csv().as_bytes())?;
    let plot_figure = |caption, png| Figure {
        caption,
        png,
        pixels: false,
    };
    let mut figures = vec![plot_figure(
        "Parameters over epochs",
        plot(out, "parameters.png", parameters_png(report))?,
    )];
    let dims = report.config.model.latent_dims();
    let latents = latents_png(report, report.config.dt, data.frames_per_clip, dims);
    figures.push(plot_figure(
        "Latents of validation clips",
        plot(out, "latents.png", latents)?,
    ));
    if let Some(t) = &report.outcome.timeline {
        figures.push(plot_figure(
            "The recording's timeline",
            plot(out, "timeline.png", timeline_png(t))?,
        ));
        write_file(out, "timeline.csv", t.csv(dims).as_bytes())?;
    }
    if let Some(png) = &data.preview_png {
        if report.recording.as_ref().is_some_and(|r| r.preview) {
            write_file(out, "clips.png", png)?;
        }
        figures.push(Figure {
            caption: "The first clips as the model saw them (above them, for --crop auto, where \
                      the picture moves: the motion map, the part kept in red)",
            png: png.clone(),
            pixels: true,
        });
    }
    write_file(out, "report.html", report_page(report, &figures).as_bytes())?;
    let json = serde_json::to_vec_pretty(report).expect("report serialises");
    write_file(out, "report.json", &json)
}
