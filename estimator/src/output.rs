//! The one place that writes a run's outputs into `--out`: report.json, metrics.csv, the plots
//! and, for a recording, timeline.png, timeline.csv and clips.png. Each file is written under a temporary
//! name and renamed.

use crate::data::ClipData;
use crate::error::EstimateError;
use crate::plots::{latents_png, parameters_png, timeline_png};
use crate::report::Report;
use physvid_shared::write_atomic;
use std::path::Path;

fn write(dir: &Path, name: &str, bytes: &[u8]) -> Result<(), EstimateError> {
    write_atomic(&dir.join(name), bytes).map_err(|e| match e {
        physvid_shared::DatasetError::Write { path, source } => {
            EstimateError::Write { path, source }
        }
        other => EstimateError::Dataset(other),
    })
}

fn plot(dir: &Path, name: &str, png: Result<Vec<u8>, String>) -> Result<(), EstimateError> {
    let png = png.map_err(|reason| EstimateError::Plot {
        path: dir.join(name),
        reason,
    })?;
    write(dir, name, &png)
}

/// Every file a run may write, report.json first: removed before a run writes its own.
const OUTPUTS: [&str; 7] = [
    "report.json",
    "metrics.csv",
    "parameters.png",
    "latents.png",
    "timeline.png",
    "timeline.csv",
    "clips.png",
];

/// Writes report.json, metrics.csv, parameters.png and latents.png (and timeline.png,
/// timeline.csv and clips.png for a recording) into `out`, report.json last.
pub fn write_outputs(out: &Path, data: &ClipData, report: &Report) -> Result<(), EstimateError> {
    std::fs::create_dir_all(out).map_err(|source| EstimateError::Write {
        path: out.to_path_buf(),
        source,
    })?;
    // The directory becomes wholly this run's: an earlier run's report.json goes first (a
    // directory with a report.json is complete), then what this run will not write again.
    for name in OUTPUTS {
        let path = out.join(name);
        if path.is_file() {
            std::fs::remove_file(&path).map_err(|source| EstimateError::Write { path, source })?;
        }
    }
    write(out, "metrics.csv", report.metrics_csv().as_bytes())?;
    plot(out, "parameters.png", parameters_png(report))?;
    plot(
        out,
        "latents.png",
        latents_png(
            report,
            data.dt,
            data.frames_per_clip,
            data.model.latent_dims(),
        ),
    )?;
    if let Some(t) = &report.outcome.timeline {
        plot(out, "timeline.png", timeline_png(t))?;
        write(
            out,
            "timeline.csv",
            t.csv(data.model.latent_dims()).as_bytes(),
        )?;
    }
    if let Some(png) = &data.preview_png {
        write(out, "clips.png", png)?;
    }
    let json = serde_json::to_vec_pretty(report).expect("report serialises");
    write(out, "report.json", &json)
}
