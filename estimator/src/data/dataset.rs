//! A `gen` dataset directory or a bare `.npy` as training input: validated, with dt and the
//! model resolved against meta.json (flags must agree with it).

use super::Source;
use crate::cli::EstimateArgs;
use crate::error::{input_error, EstimateError};
use crate::physics::ModelRef;
use physvid_shared::read_dataset;

/// A dataset directory or a bare `.npy`.
pub(crate) fn dataset_source(args: &EstimateArgs) -> Result<Source, EstimateError> {
    let ds = read_dataset(&args.input)?;
    let source = ds.frames_path.display().to_string();
    let [n, t, c, h, w] = ds.shape;
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
            "{source}: frames have no pixels (shape {:?})",
            ds.shape
        )));
    }
    let (dt, model) = match &ds.meta {
        Some(meta) => {
            let meta_model = ModelRef::by_name(&meta.model.name).ok_or_else(|| {
                input_error(format!(
                    "meta.json names model '{}', which estimate does not know (known: {})",
                    meta.model.name,
                    ModelRef::names()
                ))
            })?;
            if let Some(dt) = args.model.dt {
                if (dt - meta.dt).abs() > 1e-12 * meta.dt.max(1.0) {
                    return Err(input_error(format!(
                        "--dt {dt} contradicts meta.json's dt {}; drop --dt to use the metadata",
                        meta.dt
                    )));
                }
            }
            if let Some(m) = args.model.model {
                if m != meta_model {
                    return Err(input_error(format!(
                        "--model {} contradicts meta.json's model {}; drop --model to use the metadata",
                        m.name(),
                        meta_model.name()
                    )));
                }
            }
            (meta.dt, meta_model)
        }
        None => {
            let dt = args.model.dt.ok_or_else(|| {
                input_error(format!(
                    "{source} has no meta.json beside it: pass --dt (seconds between frames)"
                ))
            })?;
            let model = args.model.model.ok_or_else(|| {
                input_error(format!(
                    "{source} has no meta.json beside it: pass --model (e.g. --model damped-oscillator)"
                ))
            })?;
            (dt, model)
        }
    };
    let start_times = ds.meta.as_ref().and_then(|m| m.clip_start_times.clone());
    Ok(Source {
        frames: ds.frames,
        shape: ds.shape,
        dt,
        model,
        meta: ds.meta,
        start_times,
        clip_index: None,
        recording: None,
        warnings: Vec::new(),
        preview_png: None,
    })
}
