//! `Model`: one physical model's law (its info, block and SI answers; the optional hooks in
//! `hooks.rs`), and `ModelRef`, a model of the registry as a value.

use super::block::Integrator;
use super::block::{BlockOptions, PhysicsBlock};
use super::hooks::{Implausible, MotionHooks, NoHooks, TrainingHooks};
use super::info::{ModelInfo, ParamSpec};
use crate::calibration::{Calibration, DerivedValue, Readings};
use crate::encoder::EncoderKind;
use crate::peaks::PeakDecay;
use tch::{nn, Tensor};

/// What the report shows of a trained block: values (SI or latent units) and warnings about
/// answers left in latent units.
pub type Derived = (Vec<DerivedValue>, Vec<String>);

/// A physical model `estimate` can fit: its law. One file of `physics/` per model, listed once
/// in `physics::MODELS`: its [`ModelInfo`] (name, parameters and units, latent size, what its
/// footage, calibration and training need), how to build its block, and how its SI answers
/// follow from the block's parameters. What else a law may say (starts read off the frames, a
/// curriculum, the motion's rate for the verdict, …) are the optional traits of `hooks.rs`.
pub trait Model: Sync {
    fn info(&self) -> &ModelInfo;
    /// Builds the block under `path`, starting from `init` (the model's parameter order).
    fn build(&self, path: &nn::Path, init: &[f64], opts: BlockOptions) -> Box<dyn PhysicsBlock>;
    /// The reported values from the block's parameters, the calibration and the latent read at
    /// its reference frames.
    fn derive(&self, params: &[f64], cal: &Calibration, readings: &Readings) -> Derived;
    /// Its training hooks, where it has any.
    fn training_hooks(&self) -> Option<&dyn TrainingHooks> {
        None
    }
    /// What it says of the motion its parameters describe, where it says anything.
    fn motion_hooks(&self) -> Option<&dyn MotionHooks> {
        None
    }
}

/// What every model's [`ModelInfo`] answers, read through it.
impl<'a> dyn Model + 'a {
    pub fn name(&self) -> &'static str {
        self.info().law.name
    }
    pub fn help(&self) -> &'static str {
        self.info().law.help
    }
    pub fn parameters(&self) -> &'static [ParamSpec] {
        self.info().law.parameters
    }
    pub fn encoder(&self) -> EncoderKind {
        self.info().training.encoder
    }
    pub fn patience(&self) -> usize {
        self.info().training.patience
    }
    pub fn table5_clip(&self) -> (usize, f64) {
        self.info().footage.table5_clip
    }
    pub fn released_from_rest(&self) -> bool {
        self.info().footage.released_from_rest
    }
    pub fn calibrates_in_training(&self) -> bool {
        self.info().calibration.in_training
    }
    pub fn reads_past_end(&self) -> bool {
        self.info().calibration.reads_past_end
    }
    pub fn supports_residual(&self) -> bool {
        self.info().training.supports_residual
    }
    pub fn latent_dims(&self) -> usize {
        self.info().law.latent_dims
    }
    /// The parameters' names, in order.
    pub fn parameter_names(&self) -> Vec<&'static str> {
        self.parameters().iter().map(|p| p.name).collect()
    }
    /// The default starts, in order.
    pub fn default_init(&self) -> Vec<f64> {
        self.parameters().iter().map(|p| p.start).collect()
    }
}

/// The hooks' answers, the defaults where a model has none.
impl<'a> dyn Model + 'a {
    fn training(&self) -> &dyn TrainingHooks {
        self.training_hooks().unwrap_or(&NoHooks)
    }
    fn motion(&self) -> &dyn MotionHooks {
        self.motion_hooks().unwrap_or(&NoHooks)
    }
    /// [`TrainingHooks::extra_starts`].
    pub fn extra_starts(
        &self,
        train: &Tensor,
        dt: f64,
        integrator: Integrator,
        init: &[f64],
    ) -> Vec<Vec<f64>> {
        self.training().extra_starts(train, dt, integrator, init)
    }
    /// [`TrainingHooks::first_horizon`].
    pub fn first_horizon(&self, init: &[f64], dt: f64) -> Option<usize> {
        self.training().first_horizon(init, dt)
    }
    /// [`TrainingHooks::kl_coordinates`].
    pub fn kl_coordinates(&self, z: &Tensor) -> Tensor {
        self.training().kl_coordinates(z)
    }
    /// [`TrainingHooks::subharmonic`].
    pub fn subharmonic(&self, params: &[f64]) -> Option<Vec<f64>> {
        self.training().subharmonic(params)
    }
    /// [`MotionHooks::rate`].
    pub fn rate(&self, params: &[f64]) -> Option<f64> {
        self.motion().rate(params)
    }
    /// [`MotionHooks::oscillates`].
    pub fn oscillates(&self, params: &[f64]) -> bool {
        self.motion().oscillates(params)
    }
    /// [`MotionHooks::cross_check`].
    pub fn cross_check(&self, params: &[f64], latents: &[f64], dt: f64) -> Option<PeakDecay> {
        self.motion().cross_check(params, latents, dt)
    }
    /// [`MotionHooks::implausible`].
    pub fn implausible(&self, values: &[(&str, f64, f64)]) -> Vec<Implausible> {
        self.motion().implausible(values)
    }
    /// [`MotionHooks::data_warnings`].
    pub fn data_warnings(&self, timed: bool) -> Vec<String> {
        self.motion().data_warnings(timed)
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
