//! The pipeline's result as data: `Run`, made from the configuration, the clips and the
//! training outcome: the derived values with ground truth and errors, the warnings, the
//! latent's check against the truth, the evidence. The verdict (`verdict`) and model choice
//! (`choice`) read it; `report` wraps it with the verdict into report.json.

pub mod ensemble;
pub mod parameters;
pub mod truth;
pub mod uncertainty;

use crate::calibration::Calibration;
use crate::config::RunConfig;
use crate::data::summary::RecordingSummary;
use crate::data::ClipData;
use crate::evidence::Evidence;
use crate::peaks::PeakDecay;
use crate::train::{EarlierAnswer, EpochRecord, StartProbe, StopReason, TrainOutcome};
use ensemble::Ensemble;
use parameters::ParameterResult;
use serde::Serialize;
use std::time::Duration;
use tch::Device;
use truth::LatentVsTruth;

/// A latent whose spread falls below this fraction of its largest spread during training has
/// collapsed towards a constant (the latent's scale is arbitrary, so the test is relative).
pub const COLLAPSE_FRACTION: f64 = 0.1;

/// Where and how long the run went.
#[derive(Debug, Clone, Copy)]
pub struct RunInfo {
    pub device: Device,
    pub threads: usize,
    pub wall: Duration,
}

/// One fit's result: what the pipeline returns, before any judgement (report.json holds it
/// beside the verdict).
#[derive(Debug, Clone, Serialize)]
pub struct Run {
    pub input: String,
    pub model: String,
    pub dt: f64,
    pub shape: [usize; 5],
    pub train_clips: i64,
    pub validation_clips: i64,
    pub config: RunConfig,
    pub device: String,
    pub threads: usize,
    pub parameters: Vec<ParameterResult>,
    /// The block's own parameters at the start and at the end, in its order.
    pub block_parameters: Vec<String>,
    pub initial_values: Vec<f64>,
    pub final_values: Vec<f64>,
    pub calibration: Calibration,
    /// The light's drift divided out of the frames before training, where it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub photometric: Option<crate::data::photometric::Photometric>,
    /// For a video or image folder: what was decoded and how it was cut into clips.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub recording: Option<RecordingSummary>,
    /// The starts tried (the given or default values, and the spectral estimate) and which
    /// one was kept.
    pub starts: Vec<StartProbe>,
    pub epochs_run: usize,
    pub best_epoch: usize,
    pub best_val_rel_mse: f64,
    pub stop: StopReason,
    /// Stopped by `--epochs`: the answer of an earlier checkpoint, to see whether it had
    /// settled (`train::EarlierAnswer`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub earlier: Option<EarlierAnswer>,
    pub latent_std: f64,
    pub latent_collapsed: bool,
    /// The fresh noise added to the training frames (`train::jitter`), where some was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub training_noise: Option<f64>,
    /// With ground truth: how well an affine map of the true latent explains the encoded one
    /// over the validation clips (the method's premise; its sign and scale are arbitrary).
    pub latent_vs_truth: Option<LatentVsTruth>,
    /// For a recording: a classical measurement of an answer on the encoded latent (the
    /// pendulum's damping from its swing peaks, appendix A.6), beside the learned value.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cross_check: Option<PeakDecay>,
    /// For a video: the object's own track and the laws fitted on it (`track`), the second
    /// route's answer; set after the estimation, before the verdict.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub track: Option<crate::track::TrackRoute>,
    pub wall_time_s: f64,
    /// `--ensemble K`: the spread of each value over K seeds (the fields above are seed
    /// --seed's).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ensemble: Option<Ensemble>,
    pub warnings: Vec<String>,
    /// What the verdict weighs (the covariance itself is in the parameters' errors).
    pub evidence: Evidence,
    pub history: Vec<EpochRecord>,
    #[serde(skip)]
    pub outcome: TrainOutcome,
}

impl Run {
    pub fn new(
        cfg: &RunConfig,
        data: &ClipData,
        run: RunInfo,
        init: &[f64],
        outcome: TrainOutcome,
    ) -> Run {
        let RunInfo {
            device,
            threads,
            wall,
        } = run;
        let model = cfg.model;
        let calibration = cfg.calibration.clone();
        let (rows, calibration_warnings) =
            model.derive(&outcome.parameters, &calibration, &outcome.readings);
        let mut parameters: Vec<ParameterResult> = rows
            .into_iter()
            .map(|r| ParameterResult::new(r, &data.truth))
            .collect();
        let evidence = &outcome.evidence;
        let errors = uncertainty::standard_errors(
            model,
            &outcome.parameters,
            evidence.covariance.as_deref(),
            &calibration,
            &outcome.readings,
        );
        let names: Vec<String> = parameters.iter().map(|p| p.name.clone()).collect();
        let splits = uncertainty::splits(
            model,
            &evidence.splits,
            &names,
            &calibration,
            &outcome.readings,
        );
        for ((p, se), s) in parameters.iter_mut().zip(errors).zip(splits) {
            p.standard_error = se;
            p.splits = s;
        }
        let mut warnings = data.warnings.clone();
        warnings.extend(calibration_warnings);
        warnings.extend(model.data_warnings(data.train_start.is_some()));
        let peak_std = outcome
            .history
            .iter()
            .map(|h| h.latent_std)
            .fold(0.0, f64::max);
        // Training collapsed the latent if its spread fell that far by the last epoch, even when
        // the checkpoint kept is from before (the kept parameters are then an early epoch's).
        let last_std = outcome
            .history
            .last()
            .map_or(outcome.latent_std, |h| h.latent_std);
        let collapsed = outcome.latent_std.min(last_std) < COLLAPSE_FRACTION * peak_std;
        Run {
            input: cfg.input.display().to_string(),
            model: model.name().into(),
            dt: cfg.dt,
            shape: data.shape,
            train_clips: data.n_train(),
            validation_clips: data.n_val(),
            config: cfg.clone(),
            device: format!("{device:?}"),
            threads,
            parameters,
            block_parameters: model
                .parameter_names()
                .iter()
                .map(|s| s.to_string())
                .collect(),
            initial_values: init.to_vec(),
            final_values: outcome.parameters.clone(),
            calibration,
            photometric: data.photometric.clone(),
            recording: data.recording.as_ref().map(|r| r.0.clone()),
            starts: Vec::new(),
            epochs_run: outcome.epochs_run,
            best_epoch: outcome.best_epoch,
            best_val_rel_mse: outcome.best_val_rel_mse,
            stop: outcome.stop.clone(),
            earlier: outcome.earlier.clone(),
            latent_std: outcome.latent_std,
            latent_collapsed: collapsed,
            training_noise: outcome.training_noise,
            latent_vs_truth: LatentVsTruth::of(data, cfg.model.latent_dims(), &outcome.val_latents),
            cross_check: outcome.timeline.as_ref().and_then(|t| {
                let latents: Vec<f64> = t.latents.iter().map(|&v| v as f64).collect();
                model.cross_check(&outcome.parameters, &latents, t.frame_dt)
            }),
            track: None,
            wall_time_s: wall.as_secs_f64(),
            ensemble: None,
            warnings,
            evidence: outcome.evidence.clone(),
            history: outcome.history.clone(),
            outcome,
        }
    }

    /// Records the starts of a multi-start fit.
    pub fn with_starts(mut self, starts: Vec<StartProbe>) -> Run {
        self.starts = starts;
        self
    }
}
