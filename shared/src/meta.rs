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

/// Per-sample draws of the initial condition.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SampleTruth {
    pub amplitude: f64,
    pub phase: f64,
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
    /// Distributions the per-sample amplitude and phase are drawn from, in words.
    pub sampling: String,
    pub samples: Vec<SampleTruth>,
    /// Ground-truth z of every sample (outer) and frame (inner).
    pub latents: Vec<Vec<f64>>,
}
