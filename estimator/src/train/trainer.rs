//! `Trainer`: one start of a fit: the network with its optimisers (Adam per parameter group),
//! the epoch loop (rollout loss, validation, checkpoint on the validation rollout error relative
//! to the latent's variance, learning-rate halving, early stop, NaN stop) and the outcome of
//! the kept checkpoint.

use super::jitter::Jitter;
use super::outcome::{EpochRecord, StopReason, TrainOutcome};
use super::{readings, refine, settled};
use crate::config::RunConfig;
use crate::data::ClipData;
use crate::error::EstimateError;
use crate::evidence;
use crate::loss::{loss, LossKind};
use crate::network::{to_rows, Network};
use crate::physics::Clips;
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
    /// What the encoder's learned part reads of the training and validation clips, made once.
    inputs: (Tensor, Tensor),
    opt_enc: nn::Optimizer,
    opt_phys: nn::Optimizer,
    lr: f64,
    lr_phys: f64,
    pub history: Vec<EpochRecord>,
    /// (best validation metric, its epoch, the variables then).
    best: (f64, usize, Vec<Tensor>),
    /// The best checkpoint as of three quarters of `--epochs` (its epoch and variables): what
    /// a run stopped by the epoch limit is compared with (`EarlierAnswer`).
    earlier: Option<(usize, Vec<Tensor>)>,
    since_best: usize,
    pub stop: Option<StopReason>,
    start: Instant,
    /// Frames per clip trained on (the horizon curriculum: see [`Trainer::advance`]).
    horizon: i64,
    /// The first epoch at the current horizon.
    stage_start: usize,
    /// The fresh noise added to every training batch (`jitter`).
    jitter: Option<Jitter>,
}

/// A curriculum stage whose validation error falls below this has fitted its horizon.
const STAGE_FITTED: f64 = 1e-2;

impl<'a> Trainer<'a> {
    /// Builds the network with weights seeded by `cfg.seed` and physics parameters at `init`;
    /// training starts on the clips' first `horizon` frames (all when `None`).
    pub fn new(
        cfg: &'a RunConfig,
        data: &'a ClipData,
        device: Device,
        init: &[f64],
        horizon: Option<usize>,
        start: Instant,
    ) -> Result<Trainer<'a>, EstimateError> {
        let full = data.frames_per_clip;
        let network = Network::new(cfg, data, device, init);
        let inputs = (
            network.encoder.input(&data.train),
            network.encoder.input(&data.val),
        );
        // A batch's inputs: its clips' share of the training inputs (all their frames).
        let n_train = data.n_train().max(1);
        let per_clip = inputs.0.numel() as i64 / n_train;
        let batch = (cfg.batch_size as i64).min(n_train);
        let jitter = Jitter::of(cfg, data, &inputs.0, batch * per_clip);
        let (enc_vs, phys_vs) = network.stores();
        let opt_enc = nn::Adam::default().build(enc_vs, cfg.lr)?;
        let opt_phys = nn::Adam::default().build(phys_vs, cfg.lr_phys)?;
        let snapshot = network.snapshot();
        Ok(Trainer {
            cfg,
            data,
            device,
            network,
            inputs,
            opt_enc,
            opt_phys,
            lr: cfg.lr,
            lr_phys: cfg.lr_phys,
            history: Vec::new(),
            best: (f64::INFINITY, 0, snapshot),
            earlier: None,
            since_best: 0,
            stop: None,
            start,
            horizon: horizon.map_or(full, |h| (h as i64).clamp(3, full)),
            stage_start: 1,
            jitter,
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
        network.prepare();
        let epoch = self.history.len() + 1;
        let steps = self.horizon;
        let first = |x: Tensor| {
            if steps < x.size()[1] {
                x.narrow(1, 0, steps)
            } else {
                x
            }
        };
        let n_train = data.n_train();
        let batch = (cfg.batch_size as i64).min(n_train);
        let perm = Tensor::randperm(n_train, (Kind::Int64, Device::Cpu));
        let order: Vec<usize> = Vec::<i64>::try_from(&perm)
            .expect("an index tensor")
            .into_iter()
            .map(|i| i as usize)
            .collect();
        let perm = perm.to_device(self.device);
        // The losses stay on the device; one read per epoch (a NaN step spoils the parameters,
        // and the epoch's check then restores the last good checkpoint).
        let mut total = Tensor::zeros([], (Kind::Double, self.device));
        let mut batches = 0usize;
        // The training noise and where each batch takes its slice of it.
        let noise = self.jitter.as_ref().map(|j| {
            let at = j.offsets((n_train as usize).div_ceil(batch as usize));
            (j, at)
        });
        for s in (0..n_train).step_by(batch as usize) {
            let len = batch.min(n_train - s);
            let idx = perm.narrow(0, s, len);
            let x = first(self.inputs.0.index_select(0, &idx));
            let x = match &noise {
                Some((j, at)) => j.add(&x, at[batches]),
                None => x,
            };
            let start = data.train_start.as_ref().map(|t| t.index_select(0, &idx));
            let ids = &order[s as usize..(s + len) as usize];
            let clips = Clips {
                start: start.as_ref(),
                ids: Some(ids),
            };
            let (z, z_hat) = network.forward_input(&x, clips, steps);
            let residual = network.residual(cfg.loss, &z);
            let kl_z = cfg.model.kl_coordinates(&z);
            let (mut l, _) = loss(cfg.loss, &z, &kl_z, &z_hat, residual.as_ref());
            if cfg.loss == LossKind::MseKl {
                if let Some(extra) = network.auxiliary_loss(&z) {
                    l += extra;
                }
            }
            self.opt_enc.zero_grad();
            self.opt_phys.zero_grad();
            l.backward();
            self.opt_enc.step();
            self.opt_phys.step();
            total += l.detach().to_kind(Kind::Double);
            batches += 1;
        }
        if let Some(detail) = network.law_failure() {
            self.stop = Some(StopReason::LawNotFinite { epoch, detail });
            return;
        }
        let total = total.double_value(&[]);
        let finite = total.is_finite();
        let val_ids: Vec<usize> = (n_train as usize..data.shape[0]).collect();
        let (val_loss, val_mse, latent_std, parameters) = tch::no_grad(|| {
            let val = first(self.inputs.1.shallow_clone());
            let clips = Clips {
                start: data.val_start.as_ref(),
                ids: Some(&val_ids),
            };
            let (z, z_hat) = network.forward_input(&val, clips, steps);
            let residual = network.residual(cfg.loss, &z);
            let kl_z = cfg.model.kl_coordinates(&z);
            let (l, mse) = loss(cfg.loss, &z, &kl_z, &z_hat, residual.as_ref());
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
            frames: steps,
        };
        on_epoch(&rec);
        self.history.push(rec);
        if self.best.1 == 0 || val_rel_mse < self.best.0 * (1.0 - MIN_IMPROVEMENT) {
            self.best = (val_rel_mse, epoch, network.snapshot());
            self.since_best = 0;
        } else {
            self.since_best += 1;
        }
        if epoch == (3 * cfg.epochs).div_ceil(4) && self.best.1 > 0 {
            self.earlier = Some((self.best.1, self.best.2.iter().map(Tensor::copy).collect()));
        }
        if self.horizon < data.frames_per_clip {
            self.advance(epoch);
        } else {
            self.schedule(epoch);
        }
    }

    /// A curriculum stage ends when its horizon is fitted (validation error below
    /// [`STAGE_FITTED`], no better for two epochs) or stalled (a third of the patience without
    /// a better epoch); the next trains on twice the frames, its checkpoints judged afresh.
    fn advance(&mut self, epoch: usize) {
        let stalled = self.since_best >= (self.cfg.patience / 3).max(2);
        let fitted = self.best.0 < STAGE_FITTED && self.since_best >= 2;
        if stalled || fitted {
            self.horizon = (2 * self.horizon).min(self.data.frames_per_clip);
            self.best = (f64::INFINITY, 0, self.network.snapshot());
            self.since_best = 0;
            self.stage_start = epoch + 1;
        }
        if epoch >= self.cfg.epochs {
            self.stop = Some(StopReason::MaxEpochs);
        }
    }

    /// At the full horizon: learning-rate halving, the early stop and the convergence stop.
    fn schedule(&mut self, epoch: usize) {
        let cfg = self.cfg;
        if self.since_best > 0 {
            let patience = cfg.patience;
            if self.since_best >= patience {
                self.stop = Some(StopReason::EarlyStop { patience });
                return;
            }
            if self.since_best.is_multiple_of((patience / 3).max(2)) {
                self.lr *= 0.5;
                self.lr_phys *= 0.5;
                self.opt_enc.set_lr(self.lr);
                self.opt_phys.set_lr(self.lr_phys);
            }
        }
        if let Some(window) = settled::converged(cfg, &self.history, self.stage_start) {
            self.stop = Some(StopReason::Converged {
                window,
                spread: self.cfg.model.info().training.converged_spread,
            });
        } else if epoch >= cfg.epochs {
            self.stop = Some(StopReason::MaxEpochs);
        }
    }

    /// Restores the best epoch's state (the starting state if no epoch was finite: never NaN)
    /// and reads off what the report needs.
    pub fn finish(self) -> TrainOutcome {
        let network = &self.network;
        let stopped_by_limit = matches!(self.stop, None | Some(StopReason::MaxEpochs));
        let earlier = match &self.earlier {
            Some((epoch, vars)) if stopped_by_limit && *epoch != self.best.1 => Some(
                settled::answer_of(network, self.cfg, self.data, *epoch, vars),
            ),
            _ => None,
        };
        network.restore(&self.best.2);
        // The encoder is held from here on: the recording's latent serves the refinement and
        // the timeline.
        let refine::Held {
            recording_latents,
            z,
            z_hat,
        } = refine::held(network, self.cfg, self.data);
        let data = self.data;
        let (examples, rollouts, latent_std, val_latents, parameters) = tch::no_grad(|| {
            let k = data.n_val().min(4);
            (
                to_rows(&z.narrow(0, 0, k)),
                to_rows(&z_hat.narrow(0, 0, k)),
                z.std(false).double_value(&[]),
                to_rows(&z),
                network.values(&z),
            )
        });
        let evidence = evidence::gather(network, data, (&z, &z_hat), recording_latents.as_deref());
        let readings = readings::read(network, data, &self.cfg.calibration);
        let timeline = data
            .recording
            .as_ref()
            .zip(recording_latents)
            .map(|((summary, frames), latents)| timeline(network, data, summary, frames, latents));
        TrainOutcome {
            timeline,
            parameters,
            best_epoch: self.best.1,
            best_val_rel_mse: self.best.0,
            epochs_run: self.history.len(),
            stop: self.stop.unwrap_or(StopReason::MaxEpochs),
            earlier,
            latent_std,
            training_noise: self.jitter.as_ref().map(|j| j.sigma),
            history: self.history,
            example_latents: examples,
            example_rollouts: rollouts,
            val_latents,
            readings,
            evidence,
        }
    }
}
