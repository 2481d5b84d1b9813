//! The training loop: encoder + physics block, rollout loss, Adam with separate learning rates,
//! validation every epoch, the best-validation checkpoint, learning-rate halving on plateaus and
//! an early stop; a non-finite loss stops the run with the last good parameters.

use crate::blocks::{build_block, BlockOptions, PhysicsBlock};
use crate::config::{EstimateConfig, ModelKind};
use crate::data::ClipData;
use crate::encoder::Encoder;
use crate::error::EstimateError;
use crate::loss::{loss, LossKind};
use crate::timeline::{timeline, Timeline};
use serde::Serialize;
use std::time::Instant;
use tch::nn::{self, OptimizerConfig};
use tch::{Device, Kind, Tensor};

/// One epoch's figures.
#[derive(Debug, Clone, Serialize)]
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
}

/// Why training ended.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum StopReason {
    /// The validation metric stopped improving for `patience` epochs.
    EarlyStop {
        patience: usize,
    },
    MaxEpochs,
    /// The loss became NaN or infinite; the parameters are those of the best epoch before it.
    NonFiniteLoss {
        epoch: usize,
    },
}

/// The result of a training run (parameters from the best-validation epoch).
#[derive(Debug, Clone, Serialize)]
pub struct TrainOutcome {
    pub parameters: Vec<f64>,
    pub best_epoch: usize,
    pub best_val_rel_mse: f64,
    pub epochs_run: usize,
    pub stop: StopReason,
    pub latent_std: f64,
    pub history: Vec<EpochRecord>,
    /// Encoded latents and their physics rollout for up to four validation clips, [clip][frame].
    #[serde(skip)]
    pub example_latents: Vec<Vec<f32>>,
    #[serde(skip)]
    pub example_rollouts: Vec<Vec<f32>>,
    /// Encoded latents of every validation clip, [clip][frame].
    #[serde(skip)]
    pub val_latents: Vec<Vec<f32>>,
    /// Encoded latents of the calibration's reference frames (clip, frame), in order.
    pub reference_latents: Vec<f64>,
    /// For a recording: the latent of every frame, and the rollouts of clips that tile it.
    #[serde(skip)]
    pub timeline: Option<Timeline>,
}

/// Frames of known physical value that a calibrated block reads its map from during training.
struct ReferenceFrames {
    /// [1, R, D], standardised like the clips.
    frames: Tensor,
    /// [R].
    values: Tensor,
}

impl ReferenceFrames {
    /// The reference frames of `reference` (clip, frame, value) for a block that calibrates
    /// during training (the pendulum), when two or more distinct values are given.
    fn for_training(data: &ClipData, reference: &[(usize, usize, f64)]) -> Option<Self> {
        let distinct = reference.iter().any(|r| r.2 != reference[0].2);
        if data.model != ModelKind::Pendulum || reference.len() < 2 || !distinct {
            return None;
        }
        let n_train = data.n_train() as usize;
        let frames: Vec<Tensor> = reference
            .iter()
            .map(|&(clip, frame, _)| {
                let (x, i) = if clip < n_train {
                    (&data.train, clip)
                } else {
                    (&data.val, clip - n_train)
                };
                x.get(i as i64).get(frame as i64)
            })
            .collect();
        let values: Vec<f32> = reference.iter().map(|r| r.2 as f32).collect();
        Some(ReferenceFrames {
            frames: Tensor::stack(&frames, 0).unsqueeze(0),
            values: Tensor::from_slice(&values).to_device(data.train.device()),
        })
    }
}

/// Encoder and physics block with their variable stores.
pub(crate) struct Model {
    enc_vs: nn::VarStore,
    phys_vs: nn::VarStore,
    pub(crate) encoder: Encoder,
    block: Box<dyn PhysicsBlock>,
    reference: Option<ReferenceFrames>,
}

impl Model {
    /// Encodes clips [B, T, D] and rolls the latent out: (encoded, rolled out) [B, T] each.
    pub(crate) fn forward(
        &self,
        x: &Tensor,
        start: Option<&Tensor>,
        steps: i64,
    ) -> (Tensor, Tensor) {
        if let Some(r) = &self.reference {
            let z_ref = tch::no_grad(|| self.encoder.encode(&r.frames));
            self.block.calibrate(&z_ref, &r.values);
        }
        let z = self.encoder.encode(x);
        let z_hat = self.block.rollout(&z, start, steps);
        (z, z_hat)
    }

    /// The block's ODE residual of `z` when the loss needs it.
    fn residual(&self, kind: LossKind, z: &Tensor) -> Option<Tensor> {
        (kind == LossKind::ResidualFloor)
            .then(|| self.block.residual(z))
            .flatten()
    }

    /// Every variable of the encoder and the block, in a fixed order (sorted by name).
    fn variables(&self) -> Vec<Tensor> {
        let mut out = Vec::new();
        for vs in [&self.enc_vs, &self.phys_vs] {
            let mut vars: Vec<_> = vs.variables().into_iter().collect();
            vars.sort_by(|a, b| a.0.cmp(&b.0));
            out.extend(vars.into_iter().map(|(_, t)| t));
        }
        out
    }

    fn snapshot(&self) -> Vec<Tensor> {
        self.variables().iter().map(|t| t.detach().copy()).collect()
    }

    fn restore(&self, saved: &[Tensor]) {
        tch::no_grad(|| {
            for (mut t, s) in self.variables().into_iter().zip(saved) {
                t.copy_(s);
            }
        });
    }
}

pub(crate) fn to_rows(t: &Tensor) -> Vec<Vec<f32>> {
    let t = t.to_device(Device::Cpu).to_kind(Kind::Float).contiguous();
    let (rows, cols) = t.size2().expect("a matrix");
    let flat = Vec::<f32>::try_from(&t.view([-1])).expect("float tensor");
    (0..rows as usize)
        .map(|r| flat[r * cols as usize..(r + 1) * cols as usize].to_vec())
        .collect()
}

/// Relative improvement the validation metric must make to count as better.
const MIN_IMPROVEMENT: f64 = 1e-3;

/// A model in training with its optimisers, schedule and history: one start of [`fit`].
struct Trainer<'a> {
    cfg: &'a EstimateConfig,
    data: &'a ClipData,
    device: Device,
    model: Model,
    opt_enc: nn::Optimizer,
    opt_phys: nn::Optimizer,
    lr: f64,
    lr_phys: f64,
    history: Vec<EpochRecord>,
    /// (best validation metric, its epoch, the variables then).
    best: (f64, usize, Vec<Tensor>),
    since_best: usize,
    stop: Option<StopReason>,
    start: Instant,
}

impl<'a> Trainer<'a> {
    /// Builds the model with weights seeded by `--seed` and physics parameters at `init`.
    fn new(
        cfg: &'a EstimateConfig,
        data: &'a ClipData,
        device: Device,
        init: &[f64],
        reference: &[(usize, usize, f64)],
        start: Instant,
    ) -> Result<Trainer<'a>, EstimateError> {
        let reference = ReferenceFrames::for_training(data, reference);
        tch::manual_seed(cfg.seed as i64);
        let enc_vs = nn::VarStore::new(device);
        let phys_vs = nn::VarStore::new(device);
        let encoder = Encoder::new(
            &(enc_vs.root() / "encoder"),
            data.inputs,
            cfg.encoder_for(data.model),
        );
        let block = build_block(
            data.model,
            &(phys_vs.root() / "physics"),
            init,
            BlockOptions {
                integrator: cfg.integrator,
                dt: data.dt,
                timed: data.train_start.is_some(),
                calibrated: reference.is_some(),
                start: cfg.rollout_start,
            },
        );
        let model = Model {
            enc_vs,
            phys_vs,
            encoder,
            block,
            reference,
        };
        let opt_enc = nn::Adam::default().build(&model.enc_vs, cfg.lr)?;
        let opt_phys = nn::Adam::default().build(&model.phys_vs, cfg.lr_phys)?;
        let snapshot = model.snapshot();
        Ok(Trainer {
            cfg,
            data,
            device,
            model,
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

    /// Runs one epoch (training, validation, checkpoint, schedule); sets `stop` when done.
    fn epoch(&mut self, on_epoch: &mut dyn FnMut(&EpochRecord)) {
        let (cfg, data, model) = (self.cfg, self.data, &self.model);
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
            let (z, z_hat) = model.forward(&x, start.as_ref(), steps);
            let residual = model.residual(cfg.loss, &z);
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
        let (val_loss, val_mse, latent_std) = tch::no_grad(|| {
            let (z, z_hat) = model.forward(&data.val, data.val_start.as_ref(), steps);
            let residual = model.residual(cfg.loss, &z);
            let (l, mse) = loss(cfg.loss, &z, &z_hat, residual.as_ref());
            (
                l.double_value(&[]),
                mse.double_value(&[]),
                z.std(false).double_value(&[]),
            )
        });
        let parameters = model.block.values();
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
            self.best = (val_rel_mse, epoch, model.snapshot());
            self.since_best = 0;
        } else {
            self.since_best += 1;
            let patience = cfg.patience_for(data.model);
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

    /// Restores the best epoch's state (the starting state if no epoch was finite: never NaN).
    fn finish(self, reference: &[(usize, usize, f64)]) -> TrainOutcome {
        let model = &self.model;
        model.restore(&self.best.2);
        let data = self.data;
        let steps = data.frames_per_clip;
        let (examples, rollouts, latent_std, val_latents) = tch::no_grad(|| {
            let k = data.n_val().min(4);
            let (z, z_hat) = model.forward(&data.val, data.val_start.as_ref(), steps);
            (
                to_rows(&z.narrow(0, 0, k)),
                to_rows(&z_hat.narrow(0, 0, k)),
                z.std(false).double_value(&[]),
                to_rows(&z),
            )
        });
        let n_train = data.n_train() as usize;
        let reference_latents = tch::no_grad(|| {
            reference
                .iter()
                .map(|&(clip, frame, _)| {
                    let (x, start) = if clip < n_train {
                        (&data.train, &data.train_start)
                    } else {
                        (&data.val, &data.val_start)
                    };
                    let i = if clip < n_train { clip } else { clip - n_train } as i64;
                    let start = start.as_ref().map(|t| t.narrow(0, i, 1));
                    let (z, z_hat) = model.forward(&x.narrow(0, i, 1), start.as_ref(), steps);
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
            .map(|(summary, frames)| timeline(model, data, summary, frames));
        TrainOutcome {
            timeline,
            parameters: model.block.values(),
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

/// How one start fared in the probe phase of [`fit`].
#[derive(Debug, Clone, Serialize)]
pub struct StartProbe {
    pub initial: Vec<f64>,
    /// Best validation metric within the probe epochs.
    pub probe_val_rel_mse: f64,
    pub chosen: bool,
}

/// Epochs each start trains before the best one (by validation metric) is kept.
pub const PROBE_EPOCHS: usize = 8;

/// Trains from each of `starts` for [`PROBE_EPOCHS`] epochs, keeps the start with the lowest
/// validation metric (a start that locked onto a harmonic of the motion fits far worse) and
/// trains it to the end. With one start this is plain training. `on_epoch` sees the kept
/// start's epochs.
pub fn fit(
    cfg: &EstimateConfig,
    data: &ClipData,
    device: Device,
    starts: &[Vec<f64>],
    reference: &[(usize, usize, f64)],
    on_epoch: &mut dyn FnMut(&EpochRecord),
) -> Result<(TrainOutcome, Vec<StartProbe>), EstimateError> {
    assert!(!starts.is_empty(), "at least one start");
    let mut probes = Vec::new();
    let mut chosen: Option<(usize, Trainer)> = None;
    let start = Instant::now();
    for (i, init) in starts.iter().enumerate() {
        let mut t = Trainer::new(cfg, data, device, init, reference, start)?;
        if starts.len() > 1 {
            while t.stop.is_none() && t.history.len() < PROBE_EPOCHS {
                t.epoch(&mut |_| {});
            }
        }
        let score = if t.best.1 == 0 {
            f64::INFINITY
        } else {
            t.best.0
        };
        probes.push(StartProbe {
            initial: init.clone(),
            probe_val_rel_mse: score,
            chosen: false,
        });
        if chosen
            .as_ref()
            .is_none_or(|(k, _)| score < probes[*k].probe_val_rel_mse)
        {
            chosen = Some((i, t));
        }
    }
    let (k, mut t) = chosen.expect("one start");
    probes[k].chosen = true;
    for rec in &t.history {
        on_epoch(rec);
    }
    while t.stop.is_none() {
        t.epoch(on_epoch);
    }
    Ok((t.finish(reference), probes))
}

/// Trains from one start (see [`fit`]).
pub fn train(
    cfg: &EstimateConfig,
    data: &ClipData,
    device: Device,
    init: &[f64],
    on_epoch: &mut dyn FnMut(&EpochRecord),
) -> Result<TrainOutcome, EstimateError> {
    fit(cfg, data, device, &[init.to_vec()], &[], on_epoch).map(|(o, _)| o)
}
