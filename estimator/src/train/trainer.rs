//! `Trainer`: one start of a fit: the network with its optimisers (Adam per parameter group),
//! the epoch loop (rollout loss, validation, checkpoint on the validation rollout error relative
//! to the latent's variance, learning-rate halving, early stop, NaN stop) and the outcome of
//! the kept checkpoint.

use super::outcome::{EpochRecord, StopReason, TrainOutcome};
use crate::config::RunConfig;
use crate::data::ClipData;
use crate::error::EstimateError;
use crate::loss::loss;
use crate::network::{to_rows, Network};
use crate::timeline::timeline;
use std::time::Instant;
use tch::nn::{self, OptimizerConfig};
use tch::{Device, Kind, Tensor};

/// Relative improvement the validation metric must make to count as better.
const MIN_IMPROVEMENT: f64 = 1e-3;

/// A network in training with its optimisers, schedule and history: one start of
/// [`super::fit`].
pub struct Trainer<'a> {
    cfg: &'a RunConfig,
    data: &'a ClipData,
    device: Device,
    network: Network,
    opt_enc: nn::Optimizer,
    opt_phys: nn::Optimizer,
    lr: f64,
    lr_phys: f64,
    pub history: Vec<EpochRecord>,
    /// (best validation metric, its epoch, the variables then).
    best: (f64, usize, Vec<Tensor>),
    since_best: usize,
    pub stop: Option<StopReason>,
    start: Instant,
}

impl<'a> Trainer<'a> {
    /// Builds the network with weights seeded by `cfg.seed` and physics parameters at `init`.
    pub fn new(
        cfg: &'a RunConfig,
        data: &'a ClipData,
        device: Device,
        init: &[f64],
        start: Instant,
    ) -> Result<Trainer<'a>, EstimateError> {
        let network = Network::new(cfg, data, device, init);
        let (enc_vs, phys_vs) = network.stores();
        let opt_enc = nn::Adam::default().build(enc_vs, cfg.lr)?;
        let opt_phys = nn::Adam::default().build(phys_vs, cfg.lr_phys)?;
        let snapshot = network.snapshot();
        Ok(Trainer {
            cfg,
            data,
            device,
            network,
            opt_enc,
            opt_phys,
            lr: cfg.lr,
            lr_phys: cfg.lr_phys,
            history: Vec::new(),
            best: (f64::INFINITY, 0, snapshot),
            since_best: 0,
            stop: None,
            start,
        })
    }

    /// The best validation metric so far (infinite before any finite epoch).
    pub fn best_score(&self) -> f64 {
        if self.best.1 == 0 {
            f64::INFINITY
        } else {
            self.best.0
        }
    }

    /// Runs one epoch (training, validation, checkpoint, schedule); sets `stop` when done.
    pub fn epoch(&mut self, on_epoch: &mut dyn FnMut(&EpochRecord)) {
        let (cfg, data, network) = (self.cfg, self.data, &self.network);
        let epoch = self.history.len() + 1;
        let steps = data.frames_per_clip;
        let n_train = data.n_train();
        let batch = (cfg.batch_size as i64).min(n_train);
        let perm = Tensor::randperm(n_train, (Kind::Int64, Device::Cpu)).to_device(self.device);
        let mut total = 0.0;
        let mut batches = 0usize;
        let mut finite = true;
        for s in (0..n_train).step_by(batch as usize) {
            let idx = perm.narrow(0, s, batch.min(n_train - s));
            let x = data.train.index_select(0, &idx);
            let start = data.train_start.as_ref().map(|t| t.index_select(0, &idx));
            let (z, z_hat) = network.forward(&x, start.as_ref(), steps);
            let residual = network.residual(cfg.loss, &z);
            let (l, _) = loss(cfg.loss, &z, &z_hat, residual.as_ref());
            self.opt_enc.zero_grad();
            self.opt_phys.zero_grad();
            l.backward();
            let lv = l.double_value(&[]);
            if !lv.is_finite() {
                finite = false;
                break;
            }
            self.opt_enc.step();
            self.opt_phys.step();
            total += lv;
            batches += 1;
        }
        let (val_loss, val_mse, latent_std, parameters) = tch::no_grad(|| {
            let (z, z_hat) = network.forward(&data.val, data.val_start.as_ref(), steps);
            let residual = network.residual(cfg.loss, &z);
            let (l, mse) = loss(cfg.loss, &z, &z_hat, residual.as_ref());
            (
                l.double_value(&[]),
                mse.double_value(&[]),
                z.std(false).double_value(&[]),
                network.values(&z),
            )
        });
        if !finite || !val_loss.is_finite() || parameters.iter().any(|p| !p.is_finite()) {
            self.stop = Some(StopReason::NonFiniteLoss { epoch });
            return;
        }
        let val_rel_mse = val_mse / (latent_std * latent_std).max(1e-30);
        let rec = EpochRecord {
            epoch,
            train_loss: total / batches.max(1) as f64,
            val_loss,
            val_mse,
            val_rel_mse,
            latent_std,
            parameters,
            lr: self.lr,
            lr_phys: self.lr_phys,
            elapsed_s: self.start.elapsed().as_secs_f64(),
        };
        on_epoch(&rec);
        self.history.push(rec);
        if self.best.1 == 0 || val_rel_mse < self.best.0 * (1.0 - MIN_IMPROVEMENT) {
            self.best = (val_rel_mse, epoch, network.snapshot());
            self.since_best = 0;
        } else {
            self.since_best += 1;
            let patience = cfg.patience;
            if self.since_best >= patience {
                self.stop = Some(StopReason::EarlyStop { patience });
                return;
            }
            if self.since_best % (patience / 3).max(2) == 0 {
                self.lr *= 0.5;
                self.lr_phys *= 0.5;
                self.opt_enc.set_lr(self.lr);
                self.opt_phys.set_lr(self.lr_phys);
            }
        }
        if epoch >= cfg.epochs {
            self.stop = Some(StopReason::MaxEpochs);
        }
    }

    /// Restores the best epoch's state (the starting state if no epoch was finite: never NaN)
    /// and reads off what the report needs.
    pub fn finish(self) -> TrainOutcome {
        let network = &self.network;
        network.restore(&self.best.2);
        let data = self.data;
        let steps = data.frames_per_clip;
        let (examples, rollouts, latent_std, val_latents, parameters) = tch::no_grad(|| {
            let k = data.n_val().min(4);
            let (z, z_hat) = network.forward(&data.val, data.val_start.as_ref(), steps);
            (
                to_rows(&z.narrow(0, 0, k)),
                to_rows(&z_hat.narrow(0, 0, k)),
                z.std(false).double_value(&[]),
                to_rows(&z),
                network.values(&z),
            )
        });
        let reference_latents = tch::no_grad(|| {
            self.cfg
                .calibration
                .reference
                .iter()
                .map(|&(clip, frame, _)| {
                    let (x, i) = data.clip(clip);
                    let start = data.clip_start(clip);
                    let (z, z_hat) = network.forward(&x.narrow(0, i, 1), start.as_ref(), steps);
                    // The physics rollout at the frame, shifted by the clip's mean residual:
                    // the latent there as the whole clip sees it, not one frame's encoding.
                    let shift = (&z - &z_hat).mean(Kind::Float);
                    (z_hat.get(0).get(frame as i64) + shift).double_value(&[])
                })
                .collect()
        });
        let timeline = data
            .recording
            .as_ref()
            .map(|(summary, frames)| timeline(network, data, summary, frames));
        TrainOutcome {
            timeline,
            parameters,
            best_epoch: self.best.1,
            best_val_rel_mse: self.best.0,
            epochs_run: self.history.len(),
            stop: self.stop.unwrap_or(StopReason::MaxEpochs),
            latent_std,
            history: self.history,
            example_latents: examples,
            example_rollouts: rollouts,
            val_latents,
            reference_latents,
        }
    }
}
