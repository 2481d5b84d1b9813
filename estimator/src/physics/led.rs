//! The LED I' = −γ·I (Delfys75): the model and its exact first-order block.

use super::block::{frame_index, BlockOptions, Clips, Integrator, PhysicsBlock};
use super::info::{Footage, ModelInfo, ParamSpec, Picture, Training, TruthKey};
use super::model::{Derived, Model};
use crate::calibration::{Calibration, DerivedValue, Readings};
use crate::encoder::EncoderKind;
use crate::physics::hooks::MotionHooks;
use physvid_shared::systems;
use tch::nn;
use tch::{Kind, Tensor};

/// The dimming LED of Delfys75.
pub struct Led;

/// Brightness is affine in the pixels, and the law is invariant under I → I^p (which decays at
/// p·γ), which an MLP could learn: a linear encoder pins the latent.
const INFO: ModelInfo = {
    let info = ModelInfo::of(
        &systems::LED,
        "I' = −γ·I (gamma, offset)",
        &[
            ParamSpec::new("gamma", 1.0, true),
            ParamSpec::offset("offset", -2.0),
        ],
        &[TruthKey::positive("gamma")],
    );
    ModelInfo {
        training: Training {
            encoder: EncoderKind::Linear,
            ..Training::DEFAULT
        },
        footage: Footage {
            picture: Some(Picture::Affine(
                "an LED's brightness scales the light of every pixel",
            )),
            ..info.footage
        },
        ..info
    }
};

impl Model for Led {
    fn info(&self) -> &ModelInfo {
        &INFO
    }
    fn build(&self, path: &nn::Path, init: &[f64], opts: BlockOptions) -> Box<dyn PhysicsBlock> {
        Box::new(ExponentialDecayBlock::new(
            path,
            init,
            opts.integrator,
            opts.dt,
        ))
    }
    fn derive(&self, params: &[f64], _cal: &Calibration, _readings: &Readings) -> Derived {
        let values = vec![
            DerivedValue::si("gamma", "1/s", params[0], Some("gamma")),
            DerivedValue::latent("offset", params[1]),
        ];
        (values, Vec::new())
    }
    fn motion_hooks(&self) -> Option<&dyn MotionHooks> {
        Some(self)
    }
}

impl MotionHooks for Led {
    /// The dimming rate γ.
    fn rate(&self, params: &[f64]) -> Option<f64> {
        Some(params[0].abs())
    }
}

/// z' = −γ·(z − c), with the latent's resting value c (the latent of a dark LED) as well.
/// Over a short clip a decay is nearly a straight line, so only γ·(z0 − c) is sharply fixed and
/// gradient descent on (γ, c) crawls along that valley. So c is not a gradient parameter: for
/// the current γ, it is the least-squares best value over the batch, in closed form (variable
/// projection), and the gradient flows through that solution. The reported offset is solved
/// the same way over the validation clips. Parameters: gamma (1/s, scale-free: SI), offset
/// (latent units).
pub struct ExponentialDecayBlock {
    log_gamma: Tensor,
    integrator: Integrator,
    dt: f64,
}

impl ExponentialDecayBlock {
    pub fn new(path: &nn::Path, init: &[f64], integrator: Integrator, dt: f64) -> Self {
        ExponentialDecayBlock {
            log_gamma: path.var("log_gamma", &[], nn::Init::Const(init[0].ln())),
            integrator,
            dt,
        }
    }

    /// e^(−γ·k·dt) (exact) or the paper's Euler step (1 − γ·dt)^k, [1, steps].
    fn decay(&self, z: &Tensor, steps: i64) -> Tensor {
        let k = frame_index(steps, z);
        let gamma = self.log_gamma.exp();
        match self.integrator {
            Integrator::Exact => (k * (-&gamma * self.dt)).exp(),
            Integrator::Euler => (-(&gamma * self.dt) + 1.0).pow(&k),
        }
    }

    /// The resting latent c that fits `z` [B, steps] best: z[k] − z0·d[k] = c·(1 − d[k]).
    fn offset(z: &Tensor, decay: &Tensor, steps: i64) -> Tensor {
        let z0 = z.narrow(1, 0, 1);
        let rest = -decay + 1.0;
        let num = ((z.narrow(1, 0, steps) - &z0 * decay) * &rest).sum(Kind::Float);
        let den = (rest.square().sum(Kind::Float) * z.size()[0] as f64).clamp_min(1e-12);
        num / den
    }
}

impl PhysicsBlock for ExponentialDecayBlock {
    fn order(&self) -> i64 {
        1
    }
    fn rollout(&self, z: &Tensor, _clips: Clips, steps: i64) -> Tensor {
        let decay = self.decay(z, steps);
        let offset = Self::offset(z, &decay, steps);
        let z0 = z.narrow(1, 0, 1);
        &offset + (z0 - &offset) * decay
    }
    fn values(&self, latents: &Tensor) -> Vec<f64> {
        let steps = latents.size()[1];
        let offset = tch::no_grad(|| Self::offset(latents, &self.decay(latents, steps), steps));
        vec![
            self.log_gamma.double_value(&[]).exp(),
            offset.double_value(&[]),
        ]
    }
}
