//! `ParameterResult`: one reported value with its units and, when the data's metadata knows
//! it, the ground truth and the relative error.

use super::uncertainty::SplitValue;
use crate::calibration::DerivedValue;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One estimated parameter.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ParameterResult {
    pub name: String,
    pub estimate: f64,
    /// "SI" or "latent" (latent units: not determined by the video without a calibration).
    pub units: String,
    /// The unit's symbol ("m/s^2", "1/s", "1" for a pure number; "latent").
    pub unit: String,
    pub truth: Option<f64>,
    /// (estimate − truth) / truth.
    pub relative_error: Option<f64>,
    /// Its standard error from the final fit's curvature with the encoder held (clusters of
    /// clips as independent draws); `None` where it could not be computed.
    pub standard_error: Option<f64>,
    /// The value refitted on halves of the training clips (see `evidence::SplitBy`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub splits: Vec<SplitValue>,
}

impl ParameterResult {
    /// The result for a derived value, with the truth looked up in `truth` by its key.
    pub fn new(value: DerivedValue, truth: &BTreeMap<String, f64>) -> ParameterResult {
        let t = value.truth_key.and_then(|k| truth.get(k).copied());
        ParameterResult {
            relative_error: t.filter(|t| *t != 0.0).map(|t| (value.estimate - t) / t),
            name: value.name,
            estimate: value.estimate,
            units: value.units.into(),
            unit: value.unit.into(),
            truth: t,
            standard_error: None,
            splits: Vec::new(),
        }
    }
}
