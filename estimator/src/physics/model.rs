//! `Model`: everything `estimate` knows about one physical model (its parameters, defaults,
//! block, extra starts and SI answers), and `ModelRef`, a model of the registry as a value.

use super::block::{BlockOptions, Integrator, PhysicsBlock};
use super::info::{ModelInfo, ParamSpec};
use crate::calibration::{Calibration, DerivedValue, Readings};
use crate::encoder::EncoderKind;
use crate::peaks::PeakDecay;
use tch::{nn, Tensor};

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
        self.info().law.name
    }
    fn help(&self) -> &'static str {
        self.info().law.help
    }
    fn parameters(&self) -> &'static [ParamSpec] {
        self.info().law.parameters
    }
    fn encoder(&self) -> EncoderKind {
        self.info().training.encoder
    }
    fn patience(&self) -> usize {
        self.info().training.patience
    }
    fn table5_clip(&self) -> (usize, f64) {
        self.info().footage.table5_clip
    }
    fn released_from_rest(&self) -> bool {
        self.info().footage.released_from_rest
    }
    fn calibrates_in_training(&self) -> bool {
        self.info().calibration.in_training
    }
    fn supports_residual(&self) -> bool {
        self.info().training.supports_residual
    }
    fn latent_dims(&self) -> usize {
        self.info().law.latent_dims
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

/// Read back from a built-in's name or a model file's path (`ModelRef::parse`).
impl<'de> serde::Deserialize<'de> for ModelRef {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<ModelRef, D::Error> {
        let text = <String as serde::Deserialize>::deserialize(d)?;
        ModelRef::parse(&text).map_err(serde::de::Error::custom)
    }
}

impl ModelRef {
    /// What names it so that `ModelRef::parse` finds it again: a built-in's name, a model
    /// file's path.
    pub fn source(&self) -> &'static str {
        self.info().law.file.unwrap_or(self.0.name())
    }
}

/// Serde helpers writing models by [`ModelRef::source`] (a typed request handed to another
/// process; report.json names them by name).
pub mod by_source {
    use super::ModelRef;
    use serde::Serializer;

    pub fn option<S: Serializer>(m: &Option<ModelRef>, s: S) -> Result<S::Ok, S::Error> {
        match m {
            Some(m) => s.serialize_some(m.source()),
            None => s.serialize_none(),
        }
    }

    pub fn list<S: Serializer>(ms: &[ModelRef], s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(ms.iter().map(|m| m.source()))
    }
}
