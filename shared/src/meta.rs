//! `meta.json`: the ground truth and provenance written beside `frames.npy`.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Identifies the file format; bumped on any incompatible change.
pub const FORMAT_NAME: &str = "physvid-dataset";
pub const FORMAT_VERSION: u32 = 1;

/// The dynamics model behind a dataset and its true parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelSpec {
    /// Model name as `estimate --model` spells it, e.g. `damped-oscillator`.
    pub name: String,
    /// True parameters by name (for the oscillator: omega, zeta, gamma0, gamma1).
    pub parameters: BTreeMap<String, f64>,
}

/// Per-sample draws of the initial condition, by name (the oscillator's `amplitude` and
/// `phase`; a Delfys system's start time, initial angle, ...), written as a flat JSON object.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct SampleTruth(pub BTreeMap<String, f64>);

impl SampleTruth {
    /// A truth from name/value pairs.
    pub fn from_pairs<'a>(pairs: impl IntoIterator<Item = (&'a str, f64)>) -> SampleTruth {
        SampleTruth(pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect())
    }
}

/// Which program and version wrote the dataset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GeneratorInfo {
    pub name: String,
    pub version: String,
}

/// Everything `meta.json` holds. Field order is the order written.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DatasetMeta {
    pub format: String,
    pub format_version: u32,
    pub generator: GeneratorInfo,
    pub scenario: String,
    pub model: ModelSpec,
    /// Time between consecutive frames, seconds.
    pub dt: f64,
    /// [N, T, C, H, W] of `frames.npy`.
    pub shape: [usize; 5],
    pub seed: u64,
    /// Standard deviation of the Gaussian pixel noise added before clipping to [0, 1].
    pub noise: f64,
    /// How the latent z maps to the picture, in words.
    pub latent_mapping: String,
    /// What a user would measure to turn latent-unit answers into SI units (pixels per metre,
    /// focal length, incline angle, reference values of the physical quantity at given frames),
    /// by name; empty for the oscillator scenes.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub calibration: BTreeMap<String, serde_json::Value>,
    /// Frames per second of the (virtual) camera: 1/dt.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fps: Option<f64>,
    /// Time of each clip's first frame since the recording started (s), for systems released
    /// from rest at the start of the recording (sliding block, free fall): what a user reads off
    /// the frame counter, not a label. It pins the release, without which motion from rest is
    /// not identified (the latent √s is exactly linear in time and fits z'' = 0 too).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clip_start_times: Option<Vec<f64>>,
    /// Distributions the per-sample amplitude and phase are drawn from, in words.
    pub sampling: String,
    pub samples: Vec<SampleTruth>,
    /// Ground-truth z of every sample (outer) and frame (inner).
    pub latents: Vec<Vec<f64>>,
}
