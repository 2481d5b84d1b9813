//! The optional parts of a model, beside its law (`model::Model`): how training may start and
//! what it holds near N(0, 1) (`TrainingHooks`), and what the verdict and the report read of
//! the motion the parameters describe (`MotionHooks`). A model implements either where its law
//! has something to say and hands it out from `Model::training_hooks` / `motion_hooks`; callers
//! go through `dyn Model`'s methods (`model.rs`), which fall back on the defaults here.

use super::block::Integrator;
use crate::peaks::PeakDecay;
use tch::Tensor;

/// A value the model forbids (`forbidden`: no such system has it) or finds implausible, with
/// the fix in words (the verdict's physics check).
#[derive(Debug, Clone, PartialEq)]
pub struct Implausible {
    pub forbidden: bool,
    pub detail: String,
}

/// How a model's training starts and what its KL term reads.
pub trait TrainingHooks: Sync {
    /// Starts read off the training clips [N, T, D] before training, beside `init`.
    fn extra_starts(
        &self,
        _train: &Tensor,
        _dt: f64,
        _integrator: Integrator,
        _init: &[f64],
    ) -> Vec<Vec<f64>> {
        Vec::new()
    }
    /// Frames of the first stage of a horizon curriculum when starting from `init` at `dt`, if
    /// the model wants one: over many swings the loss has a minimum per basin of phase, so
    /// training starts on the clips' first frames and doubles the horizon (`train::Trainer`).
    fn first_horizon(&self, _init: &[f64], _dt: f64) -> Option<usize> {
        None
    }
    /// The coordinates of latents `z` [B, T, D] the KL term holds near N(0, 1), one by one:
    /// the latent itself unless the law has a degenerate solution that a transform of it
    /// exposes (the spring's rigid pair).
    fn kl_coordinates(&self, z: &Tensor) -> Tensor {
        z.shallow_clone()
    }
    /// The parameters of the same law swinging at half the frequency of `params`' motion, for
    /// a start there when the latent folds the picture (an even function of the motion swings
    /// at twice its frequency); `None` where the law has no such rescaling.
    fn subharmonic(&self, _params: &[f64]) -> Option<Vec<f64>> {
        None
    }
}

/// What the verdict and the report read of the motion a model's parameters describe.
pub trait MotionHooks: Sync {
    /// The fastest rate of the motion the parameters describe (rad/s for an oscillation, 1/s
    /// for a decay), to judge the answer against the frames' dt; `None` for motions without one
    /// (a constant acceleration, a draining tank).
    fn rate(&self, _params: &[f64]) -> Option<f64> {
        None
    }
    /// Whether the motion the parameters describe oscillates (swings and springs; a decay, a
    /// drain or a fall does not): the verdict compares small and large motions for those,
    /// low and high levels for the others.
    fn oscillates(&self, _params: &[f64]) -> bool {
        false
    }
    /// A classical measurement of one of the answers on a recording's encoded latent
    /// (`latents`, one per recording frame, `dt` apart), to check the learned value against.
    fn cross_check(&self, _params: &[f64], _latents: &[f64], _dt: f64) -> Option<PeakDecay> {
        None
    }
    /// Values of the report (name, estimate, standard error; 0 where unknown) that the model
    /// forbids or finds implausible.
    fn implausible(&self, _values: &[(&str, f64, f64)]) -> Vec<Implausible> {
        Vec::new()
    }
    /// Warnings about the data: `timed` says whether the clips' start times are known.
    fn data_warnings(&self, _timed: bool) -> Vec<String> {
        Vec::new()
    }
}

/// The defaults where a model has no hooks of a kind.
pub(super) struct NoHooks;
impl TrainingHooks for NoHooks {}
impl MotionHooks for NoHooks {}
