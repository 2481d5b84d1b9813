//! `Model`: everything `estimate` knows about one physical model (its parameters, defaults,
//! block, extra starts and SI answers), and `ModelRef`, a model of the registry as a value.

use super::block::{BlockOptions, Integrator, PhysicsBlock};
use super::bounds::Bounds;
use crate::calibration::{Calibration, CalibrationInput, DerivedValue, Readings};
use crate::encoder::EncoderKind;
use crate::peaks::PeakDecay;
use physvid_shared::systems::System;
use tch::{nn, Tensor};

/// One learnable parameter of a block.
#[derive(Debug, Clone, Copy)]
pub struct ParamSpec {
    pub name: &'static str,
    /// The default start (`--init` overrides it).
    pub start: f64,
    /// The interval it is learned in (positive: (0, ∞), as a logarithm); the start must lie
    /// inside.
    pub bounds: Bounds,
    /// How the early stop judges that it has converged.
    pub settles: Settles,
}

/// How a parameter's convergence is judged (see `train::Trainer`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Settles {
    /// Relative to its own value.
    Relative,
    /// An offset in latent units, often near 0: against the latent's spread (1, which the KL
    /// term holds).
    LatentOffset,
    /// Not judged: a map from latent to physical units refitted from reference frames at every
    /// step, which moves with the encoder while the physical parameters hold the answer.
    Map,
}

impl ParamSpec {
    /// A parameter `name` starting at `start`, learned as a logarithm when `positive`.
    pub const fn new(name: &'static str, start: f64, positive: bool) -> ParamSpec {
        ParamSpec {
            name,
            start,
            bounds: if positive {
                Bounds::POSITIVE
            } else {
                Bounds::FREE
            },
            settles: Settles::Relative,
        }
    }

    /// An offset in latent units (see [`Settles::LatentOffset`]).
    pub const fn offset(name: &'static str, start: f64) -> ParamSpec {
        ParamSpec {
            settles: Settles::LatentOffset,
            ..ParamSpec::new(name, start, false)
        }
    }

    /// A parameter of the latent-to-physical map (see [`Settles::Map`]).
    pub const fn map(name: &'static str, start: f64, positive: bool) -> ParamSpec {
        ParamSpec {
            settles: Settles::Map,
            ..ParamSpec::new(name, start, positive)
        }
    }
}

/// A ground-truth value a model's report is compared with (meta.json's `model.parameters`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TruthKey {
    pub name: &'static str,
    /// No such system has it at zero or below (a rate γ0, a length).
    pub positive: bool,
}

impl TruthKey {
    /// A value that is > 0 for every such system.
    pub const fn positive(name: &'static str) -> TruthKey {
        TruthKey {
            name,
            positive: true,
        }
    }

    /// A value of either sign.
    pub const fn signed(name: &'static str) -> TruthKey {
        TruthKey {
            name,
            positive: false,
        }
    }
}

/// A value the model forbids (`forbidden`: no such system has it) or finds implausible, with
/// the fix in words (the verdict's physics check).
#[derive(Debug, Clone, PartialEq)]
pub struct Implausible {
    pub forbidden: bool,
    pub detail: String,
}

/// What the report shows of a trained block: values (SI or latent units) and warnings about
/// answers left in latent units.
pub type Derived = (Vec<DerivedValue>, Vec<String>);

/// The facts about a model, one record per model (its file's `INFO`).
#[derive(Debug, Clone, Copy)]
pub struct ModelInfo {
    /// The `--model` value (and meta.json's `model.name`).
    pub name: &'static str,
    /// The equation and its parameters, one line for `--help`.
    pub help: &'static str,
    /// The block's learnable parameters, in its order.
    pub parameters: &'static [ParamSpec],
    /// The encoder that makes the latent identifiable for this law, and why, when the model
    /// chose it itself (a model file without an `encoder` line; reported with the answer).
    pub encoder: EncoderKind,
    pub encoder_note: Option<&'static str>,
    /// Early-stop patience (epochs without improvement).
    pub patience: usize,
    /// The convergence stop's band: training ends when every parameter stayed within this
    /// fraction of its value (offsets: of the latent's spread; maps refitted from references
    /// are not judged) over a window of half the patience.
    pub converged_spread: f64,
    /// Appendix Table 5's frames per clip and dt (s) for a recording of this system.
    pub table5_clip: (usize, f64),
    /// Motion from rest at the start of the recording: clip start times since the release pin
    /// the latent (from meta.json, or a recording's release found in its frames).
    pub released_from_rest: bool,
    /// The block reads the latent's map from reference frames during training.
    pub calibrates_in_training: bool,
    /// The block offers an ODE residual for `--loss residual+floor`.
    pub supports_residual: bool,
    /// Numbers per frame of the latent (1: one quantity; the spring: x, y of two bodies).
    pub latent_dims: usize,
    /// The paper's Euler step exists for the block (`--integrator euler`).
    pub has_euler: bool,
    /// The smallest frame side (pixels) that can show the system (0: any), with what needs it.
    pub min_frame: (usize, &'static str),
    /// The calibrations its answers read; the others are refused for it.
    pub calibration: &'static [CalibrationInput],
    /// The ground-truth values its report compares with (meta.json checks against them).
    pub truth: &'static [TruthKey],
    /// What its reference values are when they cannot be below zero (`None`: any sign).
    pub nonnegative_reference: Option<&'static str>,
    /// The longest dt (s) the block can integrate (∞: any within [`DT_RANGE`]), with why.
    pub max_dt: (f64, &'static str),
    /// The model file it was read from (`None`: built in).
    pub file: Option<&'static str>,
    /// What makes every pixel an affine function of the modelled quantity, when the model
    /// assumes it (an LED's brightness scales its light): the verdict checks the frames.
    pub affine_picture: Option<&'static str>,
}

pub use physvid_shared::dynamics::DT_RANGE;

impl ModelInfo {
    /// A built-in model of `system` (its name, Table 5's clip and whether it starts from rest
    /// come from the record `gen` shares), with the defaults most share.
    pub const fn of(
        system: &System,
        help: &'static str,
        parameters: &'static [ParamSpec],
    ) -> ModelInfo {
        ModelInfo {
            released_from_rest: system.released_from_rest,
            ..ModelInfo::new(system.model, help, parameters, system.clip)
        }
    }

    /// A model with the defaults most share: the small encoder, patience 30, no special needs.
    pub const fn new(
        name: &'static str,
        help: &'static str,
        parameters: &'static [ParamSpec],
        table5_clip: (usize, f64),
    ) -> ModelInfo {
        ModelInfo {
            name,
            help,
            parameters,
            encoder: EncoderKind::Small,
            encoder_note: None,
            patience: 30,
            converged_spread: 4e-3,
            table5_clip,
            released_from_rest: false,
            calibrates_in_training: false,
            supports_residual: false,
            latent_dims: 1,
            has_euler: true,
            min_frame: (0, ""),
            max_dt: (f64::INFINITY, ""),
            calibration: &[],
            nonnegative_reference: None,
            truth: &[],
            file: None,
            affine_picture: None,
        }
    }
}

/// A physical model `estimate` can fit. One file of `physics/` per model, listed once in
/// `physics::MODELS`: its [`ModelInfo`], how to build its block, the starts it reads off the
/// data, and how its SI answers follow from the block's parameters.
pub trait Model: Sync {
    fn info(&self) -> &ModelInfo;
    /// Builds the block under `path`, starting from `init` (the model's parameter order).
    fn build(&self, path: &nn::Path, init: &[f64], opts: BlockOptions) -> Box<dyn PhysicsBlock>;
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
    /// The reported values from the block's parameters, the calibration and the latent read at
    /// its reference frames.
    fn derive(&self, params: &[f64], cal: &Calibration, readings: &Readings) -> Derived;
    /// Frames of the first stage of a horizon curriculum when starting from `init` at `dt`, if
    /// the model wants one: over many swings the loss has a minimum per basin of phase, so
    /// training starts on the clips' first frames and doubles the horizon (`train::Trainer`).
    fn first_horizon(&self, _init: &[f64], _dt: f64) -> Option<usize> {
        None
    }
    /// A classical measurement of one of the answers on a recording's encoded latent
    /// (`latents`, one per recording frame, `dt` apart), to check the learned value against.
    fn cross_check(&self, _params: &[f64], _latents: &[f64], _dt: f64) -> Option<PeakDecay> {
        None
    }
    /// The coordinates of latents `z` [B, T, D] the KL term holds near N(0, 1), one by one:
    /// the latent itself unless the law has a degenerate solution that a transform of it
    /// exposes (the spring's rigid pair).
    fn kl_coordinates(&self, z: &Tensor) -> Tensor {
        z.shallow_clone()
    }
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
    /// The parameters of the same law swinging at half the frequency of `params`' motion, for
    /// a start there when the latent folds the picture (an even function of the motion swings
    /// at twice its frequency); `None` where the law has no such rescaling.
    fn subharmonic(&self, _params: &[f64]) -> Option<Vec<f64>> {
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

    fn name(&self) -> &'static str {
        self.info().name
    }
    fn help(&self) -> &'static str {
        self.info().help
    }
    fn parameters(&self) -> &'static [ParamSpec] {
        self.info().parameters
    }
    fn encoder(&self) -> EncoderKind {
        self.info().encoder
    }
    fn patience(&self) -> usize {
        self.info().patience
    }
    fn table5_clip(&self) -> (usize, f64) {
        self.info().table5_clip
    }
    fn released_from_rest(&self) -> bool {
        self.info().released_from_rest
    }
    fn calibrates_in_training(&self) -> bool {
        self.info().calibrates_in_training
    }
    fn supports_residual(&self) -> bool {
        self.info().supports_residual
    }
    fn latent_dims(&self) -> usize {
        self.info().latent_dims
    }
    /// The parameters' names, in order.
    fn parameter_names(&self) -> Vec<&'static str> {
        self.parameters().iter().map(|p| p.name).collect()
    }
    /// The default starts, in order.
    fn default_init(&self) -> Vec<f64> {
        self.parameters().iter().map(|p| p.start).collect()
    }
}

/// A model of the registry, compared, printed and serialised by name.
#[derive(Clone, Copy)]
pub struct ModelRef(pub &'static dyn Model);

impl std::ops::Deref for ModelRef {
    type Target = dyn Model;
    fn deref(&self) -> &(dyn Model + 'static) {
        self.0
    }
}

impl PartialEq for ModelRef {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name()
    }
}

impl std::fmt::Debug for ModelRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::fmt::Display for ModelRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl serde::Serialize for ModelRef {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}
