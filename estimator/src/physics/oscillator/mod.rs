//! The damped oscillator z'' + γ1·z' + γ0·z = 0 (the paper's synthetic sets): the model here;
//! its block (`block.rs`) rolls the latent forward with the exact two-step propagator
//! (`two_step.rs`; or the paper's Euler step) from each clip's least-squares initial state (or
//! its first two frames), and solves (γ0, γ1) at the end on the held encoder's latents
//! (`two_step_solve.rs`, then through a smooth map of the latent, `physics::smooth_map`).

mod block;
pub(crate) mod two_step;
pub(crate) mod two_step_solve;

pub use block::{DampedOscillatorBlock, FORECAST_FIT_FRAMES};

use super::block::{BlockOptions, Integrator, PhysicsBlock};
use super::hooks::Implausible;
use super::info::{Footage, ModelInfo, ParamSpec, Training, TruthKey};
use super::model::{Derived, Model};
use crate::calibration::{Calibration, DerivedValue, Readings};
use crate::encoder::EncoderKind;
use crate::peaks::{self, PeakDecay};
use crate::physics::hooks::{MotionHooks, TrainingHooks};
use crate::physics::spectral::spectral_start;
use physvid_shared::cli::approx;
use physvid_shared::systems;
use tch::nn;
use tch::Tensor;

/// The model of the intensity, position and scale sets.
pub struct DampedOscillator;

const INFO: ModelInfo = {
    let info = ModelInfo::of(
        &systems::DAMPED_OSCILLATOR,
        "z'' + γ1·z' + γ0·z = 0 (gamma0, gamma1)",
        &[
            ParamSpec::new("gamma0", 1.0, true),
            ParamSpec::new("gamma1", 0.1, false),
        ],
        &[TruthKey::positive("gamma0"), TruthKey::signed("gamma1")],
    );
    ModelInfo {
        footage: Footage {
            swings: Some("its frequency gives gamma0, the decay of its swings gamma1"),
            ..info.footage
        },
        training: Training {
            encoder: EncoderKind::Small,
            patience: 20,
            // The final solve gives (γ0, γ1) exactly on the kept encoder: the band only shows that
            // the encoder settled, not Adam's ±1 % jitter of γ1 (clean position: 47 epochs instead
            // of 83).
            converged_spread: 1e-2,
            supports_residual: true,
            ..Training::DEFAULT
        },
        ..info
    }
};

impl Model for DampedOscillator {
    fn info(&self) -> &ModelInfo {
        &INFO
    }
    fn build(&self, path: &nn::Path, init: &[f64], opts: BlockOptions) -> Box<dyn PhysicsBlock> {
        Box::new(DampedOscillatorBlock::new(
            path,
            (init[0], init[1]),
            opts.integrator,
            opts.dt,
            opts.start,
        ))
    }
    fn derive(&self, params: &[f64], _cal: &Calibration, _readings: &Readings) -> Derived {
        (
            vec![
                DerivedValue::si("gamma0", "1/s^2", params[0], Some("gamma0")),
                DerivedValue::si("gamma1", "1/s", params[1], Some("gamma1")),
            ],
            Vec::new(),
        )
    }
    fn training_hooks(&self) -> Option<&dyn TrainingHooks> {
        Some(self)
    }
    fn motion_hooks(&self) -> Option<&dyn MotionHooks> {
        Some(self)
    }
}

impl TrainingHooks for DampedOscillator {
    /// γ0 and γ1 read off the frames' principal components (see `spectral.rs`).
    fn extra_starts(
        &self,
        train: &Tensor,
        dt: f64,
        integrator: Integrator,
        _init: &[f64],
    ) -> Vec<Vec<f64>> {
        spectral_start(train, dt, integrator).into_iter().collect()
    }
    /// Half the frequency: γ0/4 (ω² + ζ² with both halved), γ1/2.
    fn subharmonic(&self, params: &[f64]) -> Option<Vec<f64>> {
        Some(vec![params[0] / 4.0, params[1] / 2.0])
    }
}

impl MotionHooks for DampedOscillator {
    fn oscillates(&self, _params: &[f64]) -> bool {
        true
    }
    fn rate(&self, params: &[f64]) -> Option<f64> {
        Some(params[0].max(0.0).sqrt())
    }
    /// γ1 from the decay of the swing peaks (the envelope is e^(−γ1·t/2)).
    fn cross_check(&self, params: &[f64], latents: &[f64], dt: f64) -> Option<PeakDecay> {
        peaks::cross_check("gamma1", params[1], latents, dt, 0.0)
    }
    /// A damping below zero by more than two standard errors: an amplitude that grows.
    fn implausible(&self, values: &[(&str, f64, f64)]) -> Vec<Implausible> {
        values
            .iter()
            .filter(|(name, v, se)| *name == "gamma1" && *v + 2.0 * se < 0.0)
            .map(|(_, v, se)| Implausible {
                forbidden: true,
                detail: format!(
                    "gamma1 = {} ± {} is negative: an amplitude that grows, which a damped \
                     oscillator cannot do; the latent follows something else (a drift of the \
                     light, the camera or a distractor): crop to the object (--crop)",
                    approx(*v),
                    approx(*se)
                ),
            })
            .collect()
    }
}
