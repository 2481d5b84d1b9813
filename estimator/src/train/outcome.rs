//! What training produces: one `EpochRecord` per epoch, why it stopped (`StopReason`), and the
//! `TrainOutcome` of the kept checkpoint.

use crate::calibration::Readings;
use crate::evidence::Evidence;
use crate::timeline::Timeline;
use serde::{Deserialize, Serialize};

/// One epoch's figures.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct EpochRecord {
    pub epoch: usize,
    pub train_loss: f64,
    pub val_loss: f64,
    pub val_mse: f64,
    /// Validation rollout MSE divided by the latent's variance: the fraction of the latent's
    /// variance the physics does not explain. Scale-free, so the KL term's pull on the latent's
    /// spread does not move it; the checkpoint and the early stop watch it.
    pub val_rel_mse: f64,
    /// Standard deviation of the encoded validation latents (→ 0 when the latent collapses).
    pub latent_std: f64,
    /// Parameter values after the epoch, in the model's order.
    pub parameters: Vec<f64>,
    pub lr: f64,
    pub lr_phys: f64,
    /// Seconds since training started (the first start's probe included).
    pub elapsed_s: f64,
    /// Frames per clip the epoch trained on (fewer than the clip's while a horizon curriculum
    /// runs).
    pub frames: i64,
}

/// Why training ended.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum StopReason {
    /// The validation metric stopped improving for `patience` epochs.
    EarlyStop {
        patience: usize,
    },
    /// Every parameter stayed within a relative band of `spread` for `window` epochs.
    Converged {
        window: usize,
        spread: f64,
    },
    MaxEpochs,
    /// The loss became NaN or infinite; the parameters are those of the best epoch before it.
    NonFiniteLoss {
        epoch: usize,
    },
    /// The law itself gave no finite value (a model file's expression): where, in its words.
    LawNotFinite {
        epoch: usize,
        detail: String,
    },
}

/// The answer of an earlier checkpoint of a run stopped by `--epochs` while still improving:
/// the best as of three quarters of the epochs, refined and read as the kept one is. Where the
/// two agree, the answer had settled although the validation error still fell (a slow
/// encoder polishing its last digits); where they differ, more epochs would move it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EarlierAnswer {
    /// The earlier checkpoint's epoch.
    pub epoch: usize,
    /// Its block parameters, in the model's order (as `parameters`).
    pub parameters: Vec<f64>,
}

/// The result of a training run (parameters from the best-validation epoch).
#[derive(Debug, Clone, Serialize)]
pub struct TrainOutcome {
    pub parameters: Vec<f64>,
    pub best_epoch: usize,
    pub best_val_rel_mse: f64,
    pub epochs_run: usize,
    pub stop: StopReason,
    /// Stopped by `--epochs`: the answer of the best checkpoint as of three quarters of them.
    pub earlier: Option<EarlierAnswer>,
    pub latent_std: f64,
    /// The standard deviation of the fresh noise added to every training batch (in the
    /// standardised frames' units), twice the frames' own where the encoder is dense
    /// (`train::jitter`); `None` where none was added.
    pub training_noise: Option<f64>,
    pub history: Vec<EpochRecord>,
    /// Encoded latents and their physics rollout for up to four validation clips, \[clip\]\[frame\].
    #[serde(skip)]
    pub example_latents: Vec<Vec<f32>>,
    #[serde(skip)]
    pub example_rollouts: Vec<Vec<f32>>,
    /// Encoded latents of every validation clip, \[clip\]\[frame\].
    #[serde(skip)]
    pub val_latents: Vec<Vec<f32>>,
    /// The latent at the calibration's reference frames, read through the physics.
    pub readings: Readings,
    /// For a recording: the latent of every frame, and the rollouts of clips that tile it.
    #[serde(skip)]
    pub timeline: Option<Timeline>,
    /// What the verdict weighs (see `evidence`).
    #[serde(skip)]
    pub evidence: Evidence,
}
