//! Models from a file (`--model FILE.toml`): the user's system of ODEs (read and checked by
//! `physvid_shared::model_file`) as a `Model`, rolled out by the shooting machinery
//! (`block.rs`) with exact Jacobians of the file's expressions (`system.rs`). Which parameters
//! are SI as learned and which are in latent units is found numerically: those a change of the
//! observed variables' scale or offset moves (`model_file::symmetry`) are in latent units until
//! reference frames calibrate the map; a part of the map the law leaves free is held, a part
//! it pins is learned. Where the motion oscillates, a start scaled in time to the frames'
//! frequency (spectral) is probed beside the file's start.

mod block;
mod derive;
mod kl;
mod system;

use super::block::{BlockOptions, Integrator, PhysicsBlock};
use super::info::{Calibrates, Law, ModelInfo, ParamSpec, Settles, Training, TruthKey};
use super::model::{Derived, Model};
use super::{Bounds, ModelRef};
use crate::calibration::{Calibration, CalibrationInput, Readings};
use crate::encoder::EncoderKind;
use crate::physics::hooks::{MotionHooks, TrainingHooks};
use crate::physics::spectral::spectral_start;
use block::FileBlock;
use physvid_shared::model_file::symmetry::{symmetries, transformed, Transform};
use physvid_shared::model_file::{self, ModelFile, Symmetries};
use std::path::Path;
use system::FileSystem;
use tch::nn;
use tch::Tensor;

/// A model read from a file.
pub struct FileModel {
    file: ModelFile,
    system: FileSystem,
    info: ModelInfo,
    symmetries: Symmetries,
    /// The parameters' units, then the derived values' ("-" where the file gives none).
    units: Vec<&'static str>,
}

fn leak(s: String) -> &'static str {
    Box::leak(s.into_boxed_str())
}

impl FileModel {
    /// Reads `path` into a registry-like model that lives as long as the process.
    pub fn load(path: &Path) -> Result<ModelRef, model_file::ModelFileError> {
        FileModel::from_file(model_file::load(path)?)
    }

    /// The model of a data set made from a model file (meta.json's `model.file`, the file's
    /// text), `origin` naming it in errors.
    pub fn from_text(origin: &Path, text: &str) -> Result<ModelRef, model_file::ModelFileError> {
        FileModel::from_file(model_file::parse(origin, text)?)
    }

    fn from_file(file: ModelFile) -> Result<ModelRef, model_file::ModelFileError> {
        if let Some(builtin) = ModelRef::by_name(&file.name) {
            return Err(file.error(
                "name",
                format!(
                    "'{}' is a built-in model's name: choose another",
                    builtin.name()
                ),
            ));
        }
        let system = FileSystem::new(&file);
        let symmetries = symmetries(&file, &system.compiled);
        let mut specs: Vec<ParamSpec> = file
            .parameters
            .iter()
            .enumerate()
            .map(|(j, p)| {
                let shifted = symmetries.shift.as_ref().is_some_and(|s| s[j]);
                ParamSpec {
                    bounds: Bounds::new(p.min, p.max),
                    settles: if shifted {
                        Settles::LatentOffset
                    } else {
                        Settles::Relative
                    },
                    ..ParamSpec::new(leak(p.name.clone()), p.start, false)
                }
            })
            .collect();
        let observed: Vec<&str> = file
            .observed
            .iter()
            .map(|&i| file.states[i].as_str())
            .collect();
        let amplitude = |i: usize| {
            file.initial[i].map_or(1.0, |(lo, hi): (f64, f64)| lo.abs().max(hi.abs()).max(1e-6))
        };
        for &o in &file.observed {
            let name = &file.states[o];
            specs.push(ParamSpec::map(
                leak(format!("{name}_scale")),
                1.0 / amplitude(o),
                true,
            ));
        }
        for o in &observed {
            specs.push(ParamSpec::map(leak(format!("{o}_offset")), 0.0, false));
        }
        let truth: Vec<TruthKey> = file
            .parameters
            .iter()
            .map(|p| p.name.clone())
            .chain(file.derived.iter().map(|d| d.name.clone()))
            .map(|n| TruthKey::signed(leak(n)))
            .collect();
        let curved = file.encoder.is_none()
            && model_file::curved::kept_by_curved_maps(&file, &system.compiled);
        let encoder = match file.encoder.as_deref() {
            Some("paper") => EncoderKind::Paper,
            Some("linear") => EncoderKind::Linear,
            Some("keypoints") => EncoderKind::Keypoints,
            _ if curved => EncoderKind::Linear,
            _ => EncoderKind::Small,
        };
        let encoder_note = curved.then(|| {
            leak(format!(
                "{}'s law is affine in {} and first order, so curved maps of it keep the law \
                 with another rate: the linear encoder (which cannot bend the latent) is used; \
                 an `encoder` line in the file, or --encoder, chooses another",
                file.name, file.states[0]
            ))
        });
        let d = file.observed.len();
        let help = if file.description.is_empty() {
            format!("from {}", file.path.display())
        } else {
            file.description.clone()
        };
        let info = ModelInfo::new(
            leak(file.name.clone()),
            leak(help),
            Box::leak(specs.into_boxed_slice()),
            (20, 0.1),
        );
        let info = ModelInfo {
            law: Law {
                latent_dims: d,
                truth: Box::leak(truth.into_boxed_slice()),
                file: Some(leak(file.path.display().to_string())),
                ..info.law
            },
            calibration: Calibrates {
                in_training: d == 1,
                ..Calibrates::by(&[CalibrationInput::Reference])
            },
            training: Training {
                encoder,
                encoder_note,
                has_euler: false,
                ..Training::DEFAULT
            },
            ..info
        };
        let units = file
            .parameters
            .iter()
            .map(|p| &p.unit)
            .chain(file.derived.iter().map(|d| &d.unit))
            .map(|u| leak(u.clone().unwrap_or_else(|| "-".into())))
            .collect();
        let model: &'static FileModel = Box::leak(Box::new(FileModel {
            units,
            file,
            system,
            info,
            symmetries,
        }));
        Ok(ModelRef(model))
    }

    fn calibrated(&self, cal: &Calibration) -> bool {
        self.info.calibration.in_training && cal.reference.len() >= 2
    }
}

impl Model for FileModel {
    fn info(&self) -> &ModelInfo {
        &self.info
    }
    fn build(&self, path: &nn::Path, init: &[f64], opts: BlockOptions) -> Box<dyn PhysicsBlock> {
        let learn = (
            self.symmetries.scale.is_none(),
            self.symmetries.shift.is_none(),
        );
        Box::new(FileBlock::new(
            path,
            &self.file,
            &self.system,
            self.info.law.parameters,
            init,
            opts,
            learn,
        ))
    }
    /// The file's parameters, and values derived from them (see `derive.rs`).
    fn derive(&self, params: &[f64], cal: &Calibration, readings: &Readings) -> Derived {
        self.values(params, cal, readings)
    }
    fn training_hooks(&self) -> Option<&dyn TrainingHooks> {
        Some(self)
    }
    fn motion_hooks(&self) -> Option<&dyn MotionHooks> {
        Some(self)
    }
}

impl TrainingHooks for FileModel {
    /// Where the frames oscillate (their most persistent mode) and so does the file's law, the
    /// start rescaled in time to the frames' frequency, and to half of it (a latent like |x|
    /// oscillates at twice the motion's frequency). Where the law pins the map's scale (it is
    /// learned), both also with the scale ten times larger: the motion a tenth of the
    /// file's `[initial]` range, as small swings of a pendulum are (measured on a real swing:
    /// g/L 14.0 from the file's scale, 9.17 from ten times it, the built-in block's 9.17).
    fn extra_starts(
        &self,
        train: &Tensor,
        dt: f64,
        integrator: Integrator,
        init: &[f64],
    ) -> Vec<Vec<f64>> {
        let m = self.file.parameters.len();
        let Some(g) = spectral_start(train, dt, integrator) else {
            return Vec::new();
        };
        let Some(w) = self.system.frequency(&init[..m], dt) else {
            return Vec::new();
        };
        let kappa = g[0].max(0.0).sqrt() / w;
        let d = self.file.observed.len();
        let mut starts: Vec<Vec<f64>> = [kappa, kappa / 2.0]
            .into_iter()
            .filter(|k| k.is_finite() && *k > 0.0)
            .filter_map(|k| {
                transformed(
                    &self.file,
                    &self.system.compiled,
                    &init[..m],
                    Transform::Time(k),
                )
            })
            .filter(|p| {
                p.iter()
                    .zip(self.info.law.parameters)
                    .all(|(v, s)| s.bounds.contains(*v))
            })
            .map(|mut p| {
                p.extend_from_slice(&init[m..]);
                p
            })
            .collect();
        if self.symmetries.scale.is_none() {
            let small: Vec<Vec<f64>> = starts
                .iter()
                .map(|p| {
                    let mut p = p.clone();
                    for s in &mut p[m..m + d] {
                        *s *= 10.0;
                    }
                    p
                })
                .collect();
            starts.extend(small);
        }
        starts
    }
    /// The file's `[observed] kl` combinations when it names them (the spring's relative
    /// position: KL on the raw coordinates would let a rigid pair through), else each coordinate.
    fn kl_coordinates(&self, z: &Tensor) -> Tensor {
        if self.file.kl.is_empty() || z.dim() < 3 {
            return z.shallow_clone();
        }
        kl::kl_coordinates(&self.file.kl, &self.file.observed, z)
    }
    /// The same motion at half its frequency: the law rescaled in time, the map kept.
    fn subharmonic(&self, params: &[f64]) -> Option<Vec<f64>> {
        let m = self.file.parameters.len();
        let mut p = transformed(
            &self.file,
            &self.system.compiled,
            &params[..m],
            Transform::Time(0.5),
        )?;
        p.extend_from_slice(&params[m..]);
        Some(p)
    }
    /// One and a half periods of the start's motion, at least four frames.
    fn first_horizon(&self, init: &[f64], dt: f64) -> Option<usize> {
        let w = self
            .system
            .frequency(&init[..self.file.parameters.len()], dt)?;
        Some((1.5 * std::f64::consts::TAU / (w * dt)).ceil().max(4.0) as usize)
    }
}

impl MotionHooks for FileModel {
    /// When the file's motion has a frequency at these parameters.
    fn oscillates(&self, params: &[f64]) -> bool {
        self.rate(params).is_some()
    }
    fn rate(&self, params: &[f64]) -> Option<f64> {
        // The frequency needs a dt to sample at; the frames' own is unknown here: 0.01 s, then
        // finer.
        self.system
            .frequency(&params[..self.file.parameters.len()], 0.01)
    }
}
