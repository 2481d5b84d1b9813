//! `Request`: what a caller asks of one run before its input is probed, typed (the command
//! line's flags once parsed and validated, `cli::EstimateArgs::request`; a program builds one
//! itself). `RunConfig::resolve` completes it against the probe; a model choice derives each
//! candidate's request from the user's (`choice::candidate_request`), never from a command
//! line. It serialises whole (models by name or model file path), so a worker process is
//! handed one, not a command line.

use crate::calibration::{CalibrationInput, Plane, Stick};
use crate::data::LoadRequest;
use crate::device::DeviceChoice;
use crate::encoder::EncoderKind;
use crate::loss::LossKind;
use crate::physics::model::by_source;
use crate::physics::{Integrator, ModelRef, RolloutStart};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// One run as asked: what to load, the model's settings, the training's, where results go.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Request {
    /// What to load: the input, the model when one is named, dt, the recording's settings.
    pub load: LoadRequest,
    /// The model is chosen among candidates (`--model auto`); it is also where no model is
    /// named and the input names none (a recording or a bare `.npy`: `run::chooses`).
    pub choose: bool,
    /// Model files tried beside the built-in models when the model is chosen.
    #[serde(serialize_with = "by_source::list")]
    pub candidates: Vec<ModelRef>,
    /// Starting values by parameter name (the model's defaults for the others).
    pub init: Vec<(String, f64)>,
    pub calibration: CalibrationRequest,
    pub integrator: Integrator,
    pub rollout_start: RolloutStart,
    pub training: TrainingRequest,
    /// Where report.json and the rest go (`output` checks it is this tool's to write).
    pub out: PathBuf,
    /// Write into a folder this tool did not make.
    pub force: bool,
    /// No progress lines.
    pub quiet: bool,
}

/// What the answers in SI units read: values or bodies' positions at reference frames or
/// times, an incline's angle, gravity.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct CalibrationRequest {
    /// The physical quantity at (clip, frame).
    pub values: Vec<(usize, usize, f64)>,
    /// The physical quantity at a time on a recording's timeline (seconds).
    pub times: Vec<(f64, f64)>,
    /// The bodies' pixel positions at (clip, frame).
    pub positions: Vec<(usize, usize, Vec<f64>)>,
    /// A length in the picture (`--stick`): the track in metres.
    #[serde(default)]
    pub stick: Option<Stick>,
    /// A rectangle in the plane of the motion (`--plane`): the track on that plane, in metres.
    #[serde(default)]
    pub plane: Option<Plane>,
    pub incline_deg: Option<f64>,
    pub g: Option<f64>,
}

/// How the network is trained.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrainingRequest {
    pub epochs: usize,
    /// `None`: the model's own patience.
    pub patience: Option<usize>,
    pub batch_size: usize,
    pub lr: f64,
    pub lr_phys: f64,
    pub single_start: bool,
    pub loss: LossKind,
    /// `None`: the model's encoder (or the one its frames call for).
    pub encoder: Option<EncoderKind>,
    pub seed: u64,
    pub ensemble: usize,
    pub device: DeviceChoice,
    /// CPU threads for libtorch.
    pub threads: usize,
}

/// Where results go when no folder is named (`--out`'s default).
pub const DEFAULT_OUT: &str = "runs/estimate";

impl Default for TrainingRequest {
    /// The command line's defaults (its help is generated from these).
    fn default() -> TrainingRequest {
        TrainingRequest {
            epochs: 300,
            patience: None,
            batch_size: 32,
            lr: 1e-3,
            lr_phys: 1e-2,
            single_start: false,
            loss: LossKind::default(),
            encoder: None,
            seed: 0,
            ensemble: 1,
            device: DeviceChoice::default(),
            threads: all_cores(),
        }
    }
}

/// Every core this process may use.
pub fn all_cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

impl CalibrationRequest {
    /// The calibrations given.
    pub fn given(&self) -> Vec<CalibrationInput> {
        CalibrationInput::ALL
            .into_iter()
            .filter(|&c| match c {
                CalibrationInput::Reference => {
                    !(self.values.is_empty() && self.times.is_empty() && self.positions.is_empty())
                }
                CalibrationInput::InclineDeg => self.incline_deg.is_some(),
                CalibrationInput::G => self.g.is_some(),
            })
            .collect()
    }

    /// Without calibration `c`.
    pub fn drop(&mut self, c: CalibrationInput) {
        match c {
            CalibrationInput::Reference => {
                self.values.clear();
                self.times.clear();
                self.positions.clear();
            }
            CalibrationInput::InclineDeg => self.incline_deg = None,
            CalibrationInput::G => self.g = None,
        }
    }
}

impl Request {
    /// A run on `input` with every default: the model named by a data set's meta.json, or
    /// chosen among the candidates for a recording or a bare `.npy` (set `load.model` to name
    /// one), results into [`DEFAULT_OUT`].
    pub fn new(input: impl Into<PathBuf>) -> Request {
        Request {
            load: LoadRequest {
                input: input.into(),
                ..LoadRequest::default()
            },
            choose: false,
            candidates: Vec::new(),
            init: Vec::new(),
            calibration: CalibrationRequest::default(),
            integrator: Integrator::default(),
            rollout_start: RolloutStart::default(),
            training: TrainingRequest::default(),
            out: DEFAULT_OUT.into(),
            force: false,
            quiet: false,
        }
    }

    /// The input.
    pub fn input(&self) -> &std::path::Path {
        &self.load.input
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_request_survives_json_with_its_model_files() {
        let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/cooling.toml");
        let mut req = Request::new("clip.mp4");
        req.load.model = Some(ModelRef::by_name("pendulum").unwrap());
        req.candidates = vec![ModelRef::parse(file).unwrap()];
        req.calibration.times = vec![(1.5, 0.25)];
        req.load.recording.crop = Some(crate::data::Framing::Full);
        req.training.encoder = Some(EncoderKind::Centroid);
        let text = serde_json::to_string(&req).unwrap();
        assert!(
            text.contains("cooling.toml"),
            "a file model by its path: {text}"
        );
        let back: Request = serde_json::from_str(&text).unwrap();
        assert_eq!(back, req);
        assert_eq!(back.candidates[0].source(), req.candidates[0].source());
    }
}
