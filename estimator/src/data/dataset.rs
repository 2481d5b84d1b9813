//! A `gen` dataset directory or a bare `.npy` as training input: probed (its header and
//! meta.json settle dt and the model; flags must agree with meta.json), then read.

use super::probe::{Plan, Probe};
use super::request::Frames;
use super::{LoadRequest, Source};
use crate::error::{input_error, EstimateError};
use crate::physics::ModelRef;
use physvid_shared::cli::num;
use physvid_shared::{read_dataset_header, DatasetHeader};
use std::collections::BTreeMap;

/// A dataset directory or a bare `.npy`, probed by its header and meta.json: the model and dt
/// (flags must agree with meta.json), the clips' shape checked.
pub(crate) fn probe(req: &LoadRequest) -> Result<Probe, EstimateError> {
    if let Some(flag) = req.recording.given.first() {
        return Err(input_error(format!(
            "{flag}: applies to recordings (videos, image folders); {} is a dataset of clips \
             already cut; drop it",
            req.input.display()
        )));
    }
    let header = match &req.frames {
        Some(f) => DatasetHeader {
            shape: f.shape,
            meta: f.meta.clone(),
            frames_path: req.input.clone(),
        },
        None => read_dataset_header(&req.input)?,
    };
    let DatasetHeader {
        shape,
        ref meta,
        ref frames_path,
    } = header;
    let source = frames_path.display().to_string();
    let [n, t, c, h, w] = shape;
    if t < 3 {
        return Err(input_error(format!(
            "{source}: clips have {t} frames; the second-order model needs at least 3 (two to start the rollout, one to predict)"
        )));
    }
    if n < 2 {
        return Err(input_error(format!(
            "{source}: {n} clip; at least 2 are needed for the 80/20 train/validation split"
        )));
    }
    if c * h * w == 0 {
        return Err(input_error(format!(
            "{source}: frames have no pixels (shape {shape:?})"
        )));
    }
    let model_file = req
        .model
        .filter(|m| m.info().law.file.is_some() || req.trying);
    let (dt, model) = match (meta, model_file) {
        (Some(meta), Some(model)) => {
            // A model file, or a candidate of a choice, may be tried on any data: meta.json's
            // model is not checked against it (its ground truth is compared by name where the
            // names agree).
            dt_flag_agrees(req, meta.dt)?;
            (meta.dt, model)
        }
        (Some(meta), None) if meta.model.file.is_some() && req.model.is_none() => {
            // Data made from a model file carry its text: the model is read from it.
            let text = meta.model.file.as_deref().unwrap_or_default();
            let origin = frames_path.with_file_name("meta.json (model.file)");
            let model = crate::physics::file::FileModel::from_text(&origin, text)
                .map_err(|e| input_error(e.to_string()))?;
            dt_flag_agrees(req, meta.dt)?;
            (meta.dt, model)
        }
        (Some(meta), None) => {
            let meta_model = ModelRef::by_name(&meta.model.name).ok_or_else(|| {
                input_error(format!(
                    "meta.json names model '{}', which estimate does not know (known: {}); for \
                     data made from a model file, pass it: --model FILE.toml",
                    meta.model.name,
                    ModelRef::names()
                ))
            })?;
            dt_flag_agrees(req, meta.dt)?;
            if let Some(m) = req.model {
                if m != meta_model {
                    return Err(input_error(format!(
                        "--model {} contradicts meta.json's model {}; drop --model to use the metadata",
                        m.name(),
                        meta_model.name()
                    )));
                }
            }
            check_truth(&meta.model.parameters, meta_model)?;
            (meta.dt, meta_model)
        }
        (None, _) => {
            let dt = req.dt.ok_or_else(|| {
                input_error(format!(
                    "{source} has no meta.json beside it: pass --dt (seconds between frames)"
                ))
            })?;
            let model = req.model.ok_or_else(|| {
                input_error(format!(
                    "{source} has no meta.json beside it: pass --model (e.g. --model damped-oscillator)"
                ))
            })?;
            (dt, model)
        }
    };
    Ok(Probe {
        model,
        dt,
        plan: Plan::Dataset(Box::new(header)),
    })
}

/// The frames of a probed dataset directory or bare `.npy` (its `header`), read in full, or
/// those held in memory (`frames`).
pub(crate) fn dataset_source(
    header: &DatasetHeader,
    frames: Option<&Frames>,
) -> Result<Source, EstimateError> {
    if let Some(f) = frames {
        return Ok(Source {
            frames: f.data.clone(),
            shape: f.shape,
            meta: f.meta.clone(),
            start_times: f.meta.as_ref().and_then(|m| m.clip_start_times.clone()),
            clip_index: None,
            recording: None,
            warnings: Vec::new(),
            preview_png: None,
        });
    }
    let ds = header.read_frames()?;
    let start_times = ds.meta.as_ref().and_then(|m| m.clip_start_times.clone());
    Ok(Source {
        frames: ds.frames,
        shape: ds.shape,
        meta: ds.meta,
        start_times,
        clip_index: None,
        recording: None,
        warnings: Vec::new(),
        preview_png: None,
    })
}

/// `--dt`, when given, must be meta.json's.
fn dt_flag_agrees(req: &LoadRequest, meta_dt: f64) -> Result<(), EstimateError> {
    match req.dt {
        Some(dt) if (dt - meta_dt).abs() > 1e-12 * meta_dt.max(1.0) => Err(input_error(format!(
            "--dt {dt} contradicts meta.json's dt {meta_dt}; drop --dt to use the metadata"
        ))),
        _ => Ok(()),
    }
}

pub use physvid_shared::meta::MAX_TRUTH;

/// meta.json's ground truth against its model: when it has any, it names at least one value
/// the model reports, each finite and within ±[`MAX_TRUTH`], and > 0 where no such system has
/// it otherwise.
fn check_truth(truth: &BTreeMap<String, f64>, model: ModelRef) -> Result<(), EstimateError> {
    let keys = model.info().law.truth;
    let bad = |what: String| input_error(format!("meta.json's ground truth {what}"));
    if !truth.is_empty() && !keys.iter().any(|k| truth.contains_key(k.name)) {
        let names: Vec<&str> = keys.iter().map(|k| k.name).collect();
        let found: Vec<&str> = truth.keys().map(String::as_str).collect();
        return Err(bad(format!(
            "({}) names none of {}'s values ({}): written for another model?",
            found.join(", "),
            model.name(),
            names.join(", ")
        )));
    }
    for key in keys {
        let Some(&v) = truth.get(key.name) else {
            continue;
        };
        if v.is_nan() || v.abs() > MAX_TRUTH {
            return Err(bad(format!(
                "{} = {}: not a physical value (within ±{MAX_TRUTH:e})",
                key.name,
                num(v)
            )));
        }
        if key.positive && v <= 0.0 {
            return Err(bad(format!(
                "{} = {}: must be > 0 for {}",
                key.name,
                num(v),
                model.name()
            )));
        }
    }
    Ok(())
}
