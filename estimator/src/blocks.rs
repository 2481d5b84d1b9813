//! `PhysicsBlock`: the interface every physics block implements, the block for each model, and
//! the first-order and constant-acceleration blocks of the Delfys75 systems (LED, Torricelli,
//! sliding block, free fall). The damped oscillator lives in `physics.rs`, the pendulum in
//! `pendulum.rs`.

use crate::config::ModelKind;
use crate::pendulum::PendulumBlock;
use crate::physics::{DampedOscillatorBlock, Integrator, RolloutStart};
use tch::nn;
use tch::{Kind, Tensor};

/// A differentiable model of the latent's dynamics with learnable parameters.
pub trait PhysicsBlock {
    /// Frames the rollout starts from (1 for first-order models, 2 for second-order ones).
    fn order(&self) -> i64;
    /// Rolls the latent out over `steps` frames from the first `order()` columns of `z` [B, T];
    /// `start` [B] is each clip's start time since the release (s) where the data gives it.
    fn rollout(&self, z: &Tensor, start: Option<&Tensor>, steps: i64) -> Tensor;
    /// Current parameter values, in the order of [`ModelKind::parameter_names`].
    fn values(&self) -> Vec<f64>;
    /// Blocks that read a physical quantity off the latent during training (the pendulum's
    /// angle) take the map from reference frames of known value: `latents` and `values` [R].
    /// Called before every forward pass when the block was built with `calibrated`.
    fn calibrate(&self, _latents: &Tensor, _values: &Tensor) {}
    /// The ODE residual at the inner frames of `z` [B, T], [B, T − 2], by central differences,
    /// for `--loss residual+floor`; `None` for blocks that do not offer it.
    fn residual(&self, _z: &Tensor) -> Option<Tensor> {
        None
    }
}

/// What a block needs to know besides its parameters.
#[derive(Debug, Clone, Copy)]
pub struct BlockOptions {
    pub integrator: Integrator,
    pub dt: f64,
    /// The clips' start times since the release are known (see [`ConstantAccelerationBlock`]).
    pub timed: bool,
    /// Reference frames of known value will be passed to [`PhysicsBlock::calibrate`].
    pub calibrated: bool,
    /// Where the oscillator's rollout starts.
    pub start: RolloutStart,
}

impl PhysicsBlock for DampedOscillatorBlock {
    fn order(&self) -> i64 {
        2
    }
    fn rollout(&self, z: &Tensor, _start: Option<&Tensor>, steps: i64) -> Tensor {
        DampedOscillatorBlock::rollout(self, z, steps)
    }
    fn values(&self) -> Vec<f64> {
        DampedOscillatorBlock::values(self).to_vec()
    }
    fn residual(&self, z: &Tensor) -> Option<Tensor> {
        Some(DampedOscillatorBlock::residual(self, z))
    }
}

/// Builds the block of `model` under `path`, starting from `init` (the model's parameter order).
pub fn build_block(
    model: ModelKind,
    path: &nn::Path,
    init: &[f64],
    opts: BlockOptions,
) -> Box<dyn PhysicsBlock> {
    let BlockOptions {
        integrator,
        dt,
        timed,
        calibrated,
        start,
    } = opts;
    match model {
        ModelKind::DampedOscillator => Box::new(DampedOscillatorBlock::new(
            path,
            (init[0], init[1]),
            integrator,
            dt,
            start,
        )),
        ModelKind::Led => Box::new(ExponentialDecayBlock::new(path, init, integrator, dt)),
        ModelKind::Torricelli => Box::new(TorricelliBlock::new(path, init, integrator, dt)),
        ModelKind::SlidingBlock | ModelKind::FreeFall => {
            Box::new(ConstantAccelerationBlock::new(path, init, dt, timed))
        }
        ModelKind::Pendulum => Box::new(PendulumBlock::new(path, init, integrator, dt, calibrated)),
    }
}

/// Frame index k = 0..steps as a float row vector [1, steps].
fn frame_index(steps: i64, z: &Tensor) -> Tensor {
    Tensor::arange(steps, (Kind::Float, z.device())).unsqueeze(0)
}

/// LED: z' = −γ·(z − c), with the latent's resting value c (the latent of a dark LED) as well.
/// Over a short clip a decay is nearly a straight line, so only γ·(z0 − c) is sharply fixed and
/// gradient descent on (γ, c) crawls along that valley. So c is not a gradient parameter: for
/// the current γ, it is the least-squares best value over the batch, in closed form (variable
/// projection), and the gradient flows through that solution; the last value is kept as a
/// buffer for the report. Parameters: gamma (1/s, scale-free: SI), offset (latent units).
pub struct ExponentialDecayBlock {
    log_gamma: Tensor,
    offset: Tensor,
    integrator: Integrator,
    dt: f64,
}

impl ExponentialDecayBlock {
    pub fn new(path: &nn::Path, init: &[f64], integrator: Integrator, dt: f64) -> Self {
        let mut offset = path.zeros_no_train("offset", &[]);
        let _ = tch::no_grad(|| offset.fill_(init[1]));
        ExponentialDecayBlock {
            log_gamma: path.var("log_gamma", &[], nn::Init::Const(init[0].ln())),
            offset,
            integrator,
            dt,
        }
    }
}

impl PhysicsBlock for ExponentialDecayBlock {
    fn order(&self) -> i64 {
        1
    }
    fn rollout(&self, z: &Tensor, _start: Option<&Tensor>, steps: i64) -> Tensor {
        let k = frame_index(steps, z);
        let gamma = self.log_gamma.exp();
        // Exact: e^(−γ·k·dt); the paper's Euler step: (1 − γ·dt)^k.
        let decay = match self.integrator {
            Integrator::Exact => (k * (-&gamma * self.dt)).exp(),
            Integrator::Euler => (-(&gamma * self.dt) + 1.0).pow(&k),
        };
        let z0 = z.narrow(1, 0, 1);
        // z[k] − z0·d[k] = c·(1 − d[k]): c by least squares over the batch's frames.
        let rest = -&decay + 1.0;
        let num = ((z.narrow(1, 0, steps) - &z0 * &decay) * &rest).sum(Kind::Float);
        let den = (rest.square().sum(Kind::Float) * z.size()[0] as f64).clamp_min(1e-12);
        let offset = num / den;
        let mut buffer = self.offset.shallow_clone();
        tch::no_grad(|| buffer.copy_(&offset));
        &offset + (z0 - &offset) * decay
    }
    fn values(&self) -> Vec<f64> {
        vec![
            self.log_gamma.double_value(&[]).exp(),
            self.offset.double_value(&[]),
        ]
    }
}

/// Torricelli: h' = −k·√h. With u = σ·(z − base) (σ = ±1 read off the data: the level falls)
/// the block is u' = −k_lat·√u, solved exactly as √u(t) = √u(0) − k_lat·t/2 (Euler: the paper's
/// step). Any latent with √u = p + q·√h obeys it, with k_lat = q·k; the SI k takes q from the
/// reference frames (see `calibration.rs`). Parameters: k_latent (√latent/s), base (the latent
/// of an empty tank).
pub struct TorricelliBlock {
    log_k: Tensor,
    base: Tensor,
    integrator: Integrator,
    dt: f64,
}

impl TorricelliBlock {
    pub fn new(path: &nn::Path, init: &[f64], integrator: Integrator, dt: f64) -> Self {
        TorricelliBlock {
            log_k: path.var("log_k", &[], nn::Init::Const(init[0].ln())),
            base: path.var("base", &[], nn::Init::Const(init[1])),
            integrator,
            dt,
        }
    }
}

impl PhysicsBlock for TorricelliBlock {
    fn order(&self) -> i64 {
        1
    }
    fn rollout(&self, z: &Tensor, _start: Option<&Tensor>, steps: i64) -> Tensor {
        // σ: the level falls, so u = σ(z − base) must fall over each clip.
        let trend = (z.select(1, steps - 1) - z.select(1, 0)).mean(Kind::Float);
        let sigma = if trend.double_value(&[]) <= 0.0 {
            1.0
        } else {
            -1.0
        };
        let k = self.log_k.exp();
        let u0 = ((z.narrow(1, 0, 1) - &self.base) * sigma).clamp_min(0.0);
        let u = match self.integrator {
            Integrator::Exact => {
                let t = frame_index(steps, z) * self.dt;
                ((u0 + 1e-12).sqrt() - t * &k * 0.5).clamp_min(0.0).square()
            }
            Integrator::Euler => {
                let mut cols = vec![u0];
                for _ in 1..steps {
                    let last = cols.last().expect("one column");
                    let next = (last - (last + 1e-12).sqrt() * &k * self.dt).clamp_min(0.0);
                    cols.push(next);
                }
                Tensor::cat(&cols, 1)
            }
        };
        &self.base + u * sigma
    }
    fn values(&self) -> Vec<f64> {
        vec![
            self.log_k.double_value(&[]).exp(),
            self.base.double_value(&[]),
        ]
    }
}

/// Sliding block and free fall: z'' = a (constant). Both start from rest, and then the law alone
/// is degenerate: any latent z = β·s + γ·√s + c is a parabola in time, so the encoder may bend
/// the latent (γ ≠ 0, z'' = 0 at the extreme) and the calibrated acceleration comes out wrong.
/// Known start times since the release pin it: the velocity at a clip's first frame is then
/// a·t0, so the block rolls out from one frame, z[k] = z0 + a·t0·k·dt + a·(k·dt)²/2, which only
/// the latent affine in s fits. Without start times it rolls out from two frames,
/// z[k] = z0 + k·(z1 − z0) + a·dt²·k(k−1)/2 (the paper's Euler step gives the same sequence).
/// Parameter: acceleration a in latent units/s² (a/α in SI for z = α·s + c).
pub struct ConstantAccelerationBlock {
    /// a·dt², the change of velocity per frame (so one learning rate suits any dt).
    per_frame: Tensor,
    dt: f64,
    timed: bool,
}

impl ConstantAccelerationBlock {
    pub fn new(path: &nn::Path, init: &[f64], dt: f64, timed: bool) -> Self {
        ConstantAccelerationBlock {
            per_frame: path.var("accel_per_frame", &[], nn::Init::Const(init[0] * dt * dt)),
            dt,
            timed,
        }
    }
}

impl PhysicsBlock for ConstantAccelerationBlock {
    fn order(&self) -> i64 {
        if self.timed {
            1
        } else {
            2
        }
    }
    fn rollout(&self, z: &Tensor, start: Option<&Tensor>, steps: i64) -> Tensor {
        let k = frame_index(steps, z);
        let z0 = z.narrow(1, 0, 1);
        match start.filter(|_| self.timed) {
            Some(t0) => {
                let frames_since_release = (t0 / self.dt).unsqueeze(1);
                &z0 + &self.per_frame * (frames_since_release * &k + &k * &k * 0.5)
            }
            None => {
                let z1 = z.narrow(1, 1, 1);
                &z0 + (&z1 - &z0) * &k + &self.per_frame * (&k * (&k - 1.0) * 0.5)
            }
        }
    }
    fn values(&self) -> Vec<f64> {
        vec![self.per_frame.double_value(&[]) / (self.dt * self.dt)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timed_constant_acceleration_rolls_out_from_one_frame() {
        let vs = nn::VarStore::new(tch::Device::Cpu);
        let (a, dt) = (1.42, 1.0 / 30.0);
        let b = ConstantAccelerationBlock::new(&vs.root(), &[a], dt, true);
        assert_eq!(b.order(), 1);
        // s = a·t²/2 from the release; clips start 0.1 s and 0.5 s after it.
        let starts = [0.1, 0.5];
        let z: Vec<f32> = starts
            .iter()
            .flat_map(|t0| (0..6).map(move |k| (a * (t0 + k as f64 * dt).powi(2) / 2.0) as f32))
            .collect();
        let z = Tensor::from_slice(&z).view([2, 6]);
        let t0 = Tensor::from_slice(&[0.1f32, 0.5]);
        let err = (b.rollout(&z, Some(&t0), 6) - &z)
            .abs()
            .max()
            .double_value(&[]);
        assert!(err < 1e-6, "{err}");
        // The bent latent √s is linear in time: the untimed block fits it with a = 0, the
        // timed one cannot.
        let bent = z.sqrt();
        let flat = ConstantAccelerationBlock::new(&vs.root(), &[0.0], dt, false);
        let err = (flat.rollout(&bent, None, 6) - &bent)
            .abs()
            .max()
            .double_value(&[]);
        assert!(err < 1e-6, "{err}");
        let timed_zero = ConstantAccelerationBlock::new(&vs.root(), &[0.0], dt, true);
        let err = (timed_zero.rollout(&bent, Some(&t0), 6) - &bent)
            .abs()
            .max()
            .double_value(&[]);
        assert!(err > 1e-2, "{err}");
    }
}
