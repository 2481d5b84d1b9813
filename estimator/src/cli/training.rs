//! The training flags: epochs and the early stop, learning rates, starts, loss, encoder, seeds,
//! ensemble and where to train. Per-model defaults (patience, encoder) are generated from
//! `physics::MODELS`.

use super::positive;
use crate::config::request::all_cores;
use crate::config::TrainingRequest;
use crate::device::DeviceChoice;
use crate::encoder::EncoderKind;
use crate::error::{input_error, EstimateError};
use crate::loss::LossKind;
use crate::physics::MODELS;

/// How the encoder and the physics parameters are trained.
#[derive(Debug, Clone, clap::Args)]
#[command(next_help_heading = "Training")]
pub struct TrainingArgs {
    /// Maximum number of epochs; the early stop usually ends training sooner.
    #[arg(long, default_value_t = TrainingRequest::default().epochs)]
    pub epochs: usize,
    #[arg(long, help = patience_help())]
    pub patience: Option<usize>,
    /// Clips per optimisation step.
    #[arg(long, default_value_t = TrainingRequest::default().batch_size)]
    pub batch_size: usize,
    /// Adam learning rate of the encoder.
    #[arg(long, default_value_t = TrainingRequest::default().lr)]
    pub lr: f64,
    /// Adam learning rate of the physics parameters. Those that must stay positive (γ0, g/L,
    /// rates) are learned as logarithms, so for them it is a relative step.
    #[arg(long, default_value_t = TrainingRequest::default().lr_phys)]
    pub lr_phys: f64,
    /// Train only from --init (the paper's behaviour). By default starts estimated from the
    /// frames (principal components) are probed beside it and the best one kept, and an
    /// oscillation whose latent folds the picture is trained again from half its frequency;
    /// where the object's track guides the run (see --model), from the track's answer alone.
    #[arg(long)]
    pub single_start: bool,
    /// Training loss; `mse` is the appendix's ablation, whose latent collapses.
    #[arg(long, value_enum, default_value_t = LossKind::default())]
    pub loss: LossKind,
    #[arg(long, value_enum, help = encoder_help())]
    pub encoder: Option<EncoderKind>,
    /// Seed of the weight initialisation and batch order.
    #[arg(long, default_value_t = TrainingRequest::default().seed)]
    pub seed: u64,
    /// Train K models with seeds --seed … --seed+K−1 (one after another, each on every core)
    /// and report each value's mean, standard deviation and range (report.json `ensemble`).
    #[arg(long, default_value_t = TrainingRequest::default().ensemble, value_name = "K")]
    pub ensemble: usize,
    /// Where to train.
    #[arg(long, value_enum, default_value_t = DeviceChoice::default())]
    pub device: DeviceChoice,
    /// CPU threads for libtorch, 1 to 256 (default: all cores).
    #[arg(long, value_parser = physvid_shared::cli::thread_count)]
    pub threads: Option<usize>,
}

/// Lists `value` for every model.
fn per_model(show: impl Fn(&dyn crate::physics::Model) -> String) -> String {
    MODELS
        .iter()
        .map(|m| format!("{} {}", m.name(), show(*m)))
        .collect::<Vec<_>>()
        .join(", ")
}

fn patience_help() -> String {
    format!(
        "Stop after this many epochs without a 0.1 % lower validation rollout error (MSE over \
         the latent's variance); learning rates halve every patience/3 such epochs \
         [default: the model's: {}]",
        per_model(|m| m.patience().to_string())
    )
}

fn encoder_help() -> String {
    format!(
        "Encoder: small (D → 16 → 1), the paper's (D → 1000 → 100 → 1), linear (D → 1), \
         for laws an MLP could bend where brightness or area is affine in the pixels, \
         keypoints (x, y per body, for vector latents), or centroid (one object's position) \
         [default: the model's: {}; centroid on a recording where an object released from rest \
         crosses the frame, or where one object moves about it and the built-in model's is small]",
        per_model(|m| m.encoder().name().to_string())
    )
}

/// The most epochs, ensemble members and clips per batch taken.
pub const MAX_EPOCHS: usize = 100_000;
pub const MAX_ENSEMBLE: usize = 100;
pub const MAX_BATCH: usize = 65_536;

impl TrainingArgs {
    /// CPU threads for libtorch: `--threads`, else every core.
    pub fn thread_count(&self) -> usize {
        self.threads.unwrap_or_else(all_cores)
    }

    /// Checks the flags that do not depend on the data.
    pub fn validate(&self) -> Result<(), EstimateError> {
        // Bounded, so that no flag asks for work that never ends.
        for (flag, v, max, why) in [
            (
                "--epochs",
                self.epochs,
                MAX_EPOCHS,
                "the early stop ends most runs within 300",
            ),
            (
                "--ensemble",
                self.ensemble,
                MAX_ENSEMBLE,
                "each member is a whole training",
            ),
            (
                "--patience",
                self.patience.unwrap_or(1),
                self.epochs,
                "it cannot exceed --epochs",
            ),
            (
                "--batch-size",
                self.batch_size,
                MAX_BATCH,
                "a batch larger than this holds more clips than any data set here",
            ),
        ] {
            if v == 0 || v > max {
                return Err(input_error(format!(
                    "{flag} {v}: must be from 1 to {max} ({why})"
                )));
            }
        }
        for (flag, lr) in [("--lr", self.lr), ("--lr-phys", self.lr_phys)] {
            positive(flag, lr)?;
            // Adam moves each weight by about lr per step: beyond 1 every step overshoots.
            if lr > 1.0 {
                return Err(input_error(format!(
                    "{flag} {}: must be at most 1 (Adam moves each weight by about this much per step)",
                    physvid_shared::cli::num(lr)
                )));
            }
        }
        Ok(())
    }
}
