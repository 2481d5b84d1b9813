//! The resolved configuration's checks against its model: calibration flags it does not read,
//! a dt outside the range taken or beyond the model's longest, references of the wrong kind
//! for its latent.

use super::CalibrationRequest;
use crate::calibration::Calibration;
use crate::data::Plan;
use crate::error::{input_error, EstimateError};
use crate::physics::info::DT_RANGE;
use crate::physics::{ModelRef, MODELS};
use physvid_shared::cli::num;

/// Refuses a calibration flag the model's answers do not read, naming the models that do.
pub(super) fn check_calibration_flags(
    model: ModelRef,
    asked: &CalibrationRequest,
) -> Result<(), EstimateError> {
    let Some(c) = asked
        .given()
        .into_iter()
        .find(|c| !model.info().calibration.inputs.contains(c))
    else {
        return Ok(());
    };
    let readers: Vec<&str> = MODELS
        .iter()
        .filter(|r| r.info().calibration.inputs.contains(&c))
        .map(|r| r.name())
        .collect();
    Err(input_error(format!(
        "{}: {} does not use it (its answers need no calibration of that kind); it applies \
         to {}; drop it",
        c.flag(),
        model.name(),
        readers.join(", ")
    )))
}

/// The data's `dt` against [`DT_RANGE`] and the model's longest, naming where it came from.
pub(super) fn check_dt(model: ModelRef, dt: f64, plan: &Plan) -> Result<(), EstimateError> {
    let source = match plan {
        Plan::Recording(_) => "dt = --stride / fps",
        Plan::Dataset(h) if h.meta.is_some() => "meta.json's dt",
        Plan::Dataset(_) => "--dt",
    };
    let (lo, hi) = DT_RANGE;
    if !(lo..=hi).contains(&dt) {
        return Err(input_error(format!(
            "{source} {} s: outside {lo:e}–{hi} s (a million frames per second to one a day); give dt in seconds",
            num(dt)
        )));
    }
    let (max, why) = model.info().footage.max_dt;
    if dt > max {
        return Err(input_error(format!(
            "{source} {} s: {} takes dt ≤ {max} s ({why})",
            num(dt),
            model.name()
        )));
    }
    Ok(())
}

/// The reference frames and positions against the model's latent: positions of its size, one
/// kind of reference for its latent, and (with `values`) the values themselves.
pub(super) fn check_references(
    calibration: &Calibration,
    model: ModelRef,
    values: bool,
) -> Result<(), EstimateError> {
    calibration
        .check_positions(model.latent_dims())
        .map_err(input_error)?;
    if model.latent_dims() > 1 && !calibration.reference.is_empty() {
        return Err(input_error(format!(
            "{}: {} needs the bodies' positions at reference frames, CLIP:FRAME=X1/Y1/X2/Y2 (pixels), not one value",
            calibration.origin(),
            model.name()
        )));
    }
    if model.latent_dims() == 1 && !calibration.positions.is_empty() {
        return Err(input_error(format!(
            "{}: {} takes one value per reference frame, CLIP:FRAME=VALUE, not body positions",
            calibration.origin(),
            model.name()
        )));
    }
    if values {
        calibration
            .check_values(model.info().calibration.nonnegative_reference)
            .map_err(input_error)?;
    }
    Ok(())
}
