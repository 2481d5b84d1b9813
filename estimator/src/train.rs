//! The training loop: encoder + physics block, rollout loss, Adam with separate learning rates,
//! validation every epoch, the best-validation checkpoint, learning-rate halving on plateaus and
//! an early stop; a non-finite loss stops the run with the last good parameters.

use crate::config::EstimateConfig;
use crate::data::ClipData;
use crate::encoder::Encoder;
use crate::error::EstimateError;
use crate::loss::loss;
use crate::physics::DampedOscillatorBlock;
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
    /// Seconds since training started.
    pub elapsed_s: f64,
}

/// Why training ended.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum StopReason {
    /// The validation metric stopped improving for `patience` epochs.
    EarlyStop { patience: usize },
    MaxEpochs,
    /// The loss became NaN or infinite; the parameters are those of the best epoch before it.
    NonFiniteLoss { epoch: usize },
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
}

/// Encoder and physics block with their variable stores.
struct Model {
    enc_vs: nn::VarStore,
    phys_vs: nn::VarStore,
    encoder: Encoder,
    block: DampedOscillatorBlock,
}

impl Model {
    fn forward(&self, x: &Tensor, steps: i64) -> (Tensor, Tensor) {
        let z = self.encoder.encode(x);
        let z_hat = self.block.rollout(&z, steps);
        (z, z_hat)
    }

    fn snapshot(&self) -> Vec<Tensor> {
        let mut out = Vec::new();
        for vs in [&self.enc_vs, &self.phys_vs] {
            let mut vars: Vec<_> = vs.variables().into_iter().collect();
            vars.sort_by(|a, b| a.0.cmp(&b.0));
            out.extend(vars.into_iter().map(|(_, t)| t.detach().copy()));
        }
        out
    }

    fn restore(&self, saved: &[Tensor]) {
        let mut i = 0;
        tch::no_grad(|| {
            for vs in [&self.enc_vs, &self.phys_vs] {
                let mut vars: Vec<_> = vs.variables().into_iter().collect();
                vars.sort_by(|a, b| a.0.cmp(&b.0));
                for (_, mut t) in vars {
                    t.copy_(&saved[i]);
                    i += 1;
                }
            }
        });
    }
}

fn to_rows(t: &Tensor) -> Vec<Vec<f32>> {
    let t = t.to_device(Device::Cpu).to_kind(Kind::Float).contiguous();
    let (rows, cols) = t.size2().expect("a matrix");
    let flat = Vec::<f32>::try_from(&t.view([-1])).expect("float tensor");
    (0..rows as usize)
        .map(|r| flat[r * cols as usize..(r + 1) * cols as usize].to_vec())
        .collect()
}

/// Relative improvement the validation metric must make to count as better.
const MIN_IMPROVEMENT: f64 = 1e-3;

/// Trains from `init` and returns the best-validation parameters and the history.
/// `on_epoch` sees each epoch's record (for progress display).
pub fn train(
    cfg: &EstimateConfig,
    data: &ClipData,
    device: Device,
    init: &[f64],
    on_epoch: &mut dyn FnMut(&EpochRecord),
) -> Result<TrainOutcome, EstimateError> {
    tch::manual_seed(cfg.seed as i64);
    let enc_vs = nn::VarStore::new(device);
    let phys_vs = nn::VarStore::new(device);
    let encoder = Encoder::new(&(enc_vs.root() / "encoder"), data.inputs, cfg.encoder);
    let block = DampedOscillatorBlock::new(
        &(phys_vs.root() / "physics"),
        (init[0], init[1]),
        cfg.integrator,
        data.dt,
    );
    let model = Model {
        enc_vs,
        phys_vs,
        encoder,
        block,
    };
    let mut opt_enc = nn::Adam::default().build(&model.enc_vs, cfg.lr)?;
    let mut opt_phys = nn::Adam::default().build(&model.phys_vs, cfg.lr_phys)?;
    let (mut lr, mut lr_phys) = (cfg.lr, cfg.lr_phys);
    let plateau = (cfg.patience / 3).max(2);
    let steps = data.frames_per_clip;
    let n_train = data.n_train();
    let batch = (cfg.batch_size as i64).min(n_train);
    let start = Instant::now();

    let mut history: Vec<EpochRecord> = Vec::new();
    let mut best = (f64::INFINITY, 0usize, model.snapshot());
    let mut since_best = 0usize;
    let mut stop = StopReason::MaxEpochs;
    for epoch in 1..=cfg.epochs {
        let perm = Tensor::randperm(n_train, (Kind::Int64, Device::Cpu)).to_device(device);
        let mut total = 0.0;
        let mut batches = 0usize;
        let mut finite = true;
        for s in (0..n_train).step_by(batch as usize) {
            let idx = perm.narrow(0, s, batch.min(n_train - s));
            let x = data.train.index_select(0, &idx);
            let (z, z_hat) = model.forward(&x, steps);
            let (l, _) = loss(cfg.loss, &z, &z_hat);
            opt_enc.zero_grad();
            opt_phys.zero_grad();
            l.backward();
            let lv = l.double_value(&[]);
            if !lv.is_finite() {
                finite = false;
                break;
            }
            opt_enc.step();
            opt_phys.step();
            total += lv;
            batches += 1;
        }
        let (val_loss, val_mse, latent_std) = tch::no_grad(|| {
            let (z, z_hat) = model.forward(&data.val, steps);
            let (l, mse) = loss(cfg.loss, &z, &z_hat);
            (
                l.double_value(&[]),
                mse.double_value(&[]),
                z.std(false).double_value(&[]),
            )
        });
        let parameters = model.block.values().to_vec();
        if !finite || !val_loss.is_finite() || parameters.iter().any(|p| !p.is_finite()) {
            stop = StopReason::NonFiniteLoss { epoch };
            break;
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
            lr,
            lr_phys,
            elapsed_s: start.elapsed().as_secs_f64(),
        };
        on_epoch(&rec);
        history.push(rec);
        if best.1 == 0 || val_rel_mse < best.0 * (1.0 - MIN_IMPROVEMENT) {
            best = (val_rel_mse, epoch, model.snapshot());
            since_best = 0;
        } else {
            since_best += 1;
            if since_best >= cfg.patience {
                stop = StopReason::EarlyStop {
                    patience: cfg.patience,
                };
                break;
            }
            if since_best % plateau == 0 {
                lr *= 0.5;
                lr_phys *= 0.5;
                opt_enc.set_lr(lr);
                opt_phys.set_lr(lr_phys);
            }
        }
    }
    let epochs_run = history.len();
    // The best epoch's state, or the starting state if not one epoch was finite: never NaN.
    model.restore(&best.2);
    let (examples, rollouts, latent_std) = tch::no_grad(|| {
        let k = data.n_val().min(4);
        let (z, z_hat) = model.forward(&data.val.narrow(0, 0, k), steps);
        let (zall, _) = model.forward(&data.val, steps);
        (to_rows(&z), to_rows(&z_hat), zall.std(false).double_value(&[]))
    });
    Ok(TrainOutcome {
        parameters: model.block.values().to_vec(),
        best_epoch: best.1,
        best_val_rel_mse: best.0,
        epochs_run,
        stop,
        latent_std,
        history,
        example_latents: examples,
        example_rollouts: rollouts,
    })
}
