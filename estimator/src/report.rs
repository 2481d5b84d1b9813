//! The run's report: `report.json`, `metrics.csv`, the plots, and the table printed at the end.

use crate::calibration::{derive, Calibration};
use crate::config::{EstimateConfig, ModelKind};
use crate::data::ClipData;
use crate::error::EstimateError;
use crate::plots::{plot_latents, plot_parameters, plot_timeline};
use crate::train::{StopReason, TrainOutcome};
use serde::Serialize;
use std::path::Path;
use std::time::Duration;
use tch::Device;

/// libtorch's version, read from the linked installation at build time.
pub const LIBTORCH_VERSION: &str = env!("PHYSVID_LIBTORCH_VERSION");

/// A latent whose spread falls below this fraction of its largest spread during training has
/// collapsed towards a constant (the latent's scale is arbitrary, so the test is relative).
pub const COLLAPSE_FRACTION: f64 = 0.1;

/// One estimated parameter.
#[derive(Debug, Clone, Serialize)]
pub struct ParameterResult {
    pub name: String,
    pub estimate: f64,
    /// "SI" or "latent" (latent units: not determined by the video without a calibration).
    pub units: String,
    pub truth: Option<f64>,
    /// (estimate − truth) / truth.
    pub relative_error: Option<f64>,
}

/// Least-squares fit y = slope·x + intercept, with R².
#[derive(Debug, Clone, Copy, Serialize)]
pub struct AffineFit {
    pub slope: f64,
    pub intercept: f64,
    pub r2: f64,
}

impl AffineFit {
    /// The fit of `y` against `x` (pairs in order); `None` unless both vary.
    pub fn of(x: &[f64], y: &[f64]) -> Option<AffineFit> {
        if x.len() < 2 || y.len() != x.len() {
            return None;
        }
        let n = x.len() as f64;
        let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
        let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
        for (a, b) in x.iter().zip(y) {
            sxx += (a - mx).powi(2);
            sxy += (a - mx) * (b - my);
            syy += (b - my).powi(2);
        }
        (sxx > 0.0 && syy > 0.0).then(|| AffineFit {
            slope: sxy / sxx,
            intercept: my - sxy / sxx * mx,
            r2: sxy * sxy / (sxx * syy),
        })
    }
}

/// Fits the encoded validation latents against the ground truth of the same clips.
fn latent_fit(data: &ClipData, encoded: &[Vec<f32>]) -> Option<AffineFit> {
    let meta = data.meta.as_ref()?;
    let n_train = data.n_train() as usize;
    let (truth, latent): (Vec<f64>, Vec<f64>) = encoded
        .iter()
        .enumerate()
        .flat_map(|(i, row)| {
            let truth = &meta.latents[n_train + i];
            row.iter().zip(truth).map(|(&z, &q)| (q, z as f64))
        })
        .unzip();
    AffineFit::of(&truth, &latent)
}

/// Where and how long the run went.
#[derive(Debug, Clone, Copy)]
pub struct RunInfo {
    pub device: Device,
    pub threads: usize,
    pub wall: Duration,
}

/// Everything `report.json` holds.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    pub tool: String,
    pub version: String,
    pub input: String,
    pub model: String,
    pub dt: f64,
    pub shape: [usize; 5],
    pub train_clips: i64,
    pub validation_clips: i64,
    pub config: EstimateConfig,
    pub device: String,
    pub threads: usize,
    pub libtorch_version: String,
    pub parameters: Vec<ParameterResult>,
    /// The block's own parameters at the start and at the end, in its order.
    pub block_parameters: Vec<String>,
    pub initial_values: Vec<f64>,
    pub final_values: Vec<f64>,
    pub calibration: Calibration,
    /// For a video or image folder: what was decoded and how it was cut into clips.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub recording: Option<crate::recording::RecordingSummary>,
    /// The starts tried (the given or default values, and the spectral estimate) and which
    /// one was kept.
    pub starts: Vec<crate::train::StartProbe>,
    pub epochs_run: usize,
    pub best_epoch: usize,
    pub best_val_rel_mse: f64,
    pub stop: StopReason,
    pub latent_std: f64,
    pub latent_collapsed: bool,
    /// With ground truth: how well an affine map of the true latent explains the encoded one
    /// over the validation clips (the method's premise; its sign and scale are arbitrary).
    pub latent_vs_truth: Option<AffineFit>,
    pub wall_time_s: f64,
    /// `--ensemble K`: the spread of each value over K seeds (the fields above are seed
    /// --seed's).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ensemble: Option<crate::ensemble::Ensemble>,
    pub warnings: Vec<String>,
    pub history: Vec<crate::train::EpochRecord>,
    #[serde(skip)]
    pub outcome: TrainOutcome,
}

impl Report {
    pub fn new(
        cfg: &EstimateConfig,
        data: &ClipData,
        run: RunInfo,
        init: &[f64],
        outcome: TrainOutcome,
        calibration: Calibration,
    ) -> Report {
        let RunInfo {
            device,
            threads,
            wall,
        } = run;
        let (rows, calibration_warnings) = derive(
            data.model,
            &outcome.parameters,
            &calibration,
            &outcome.reference_latents,
        );
        let parameters: Vec<ParameterResult> = rows
            .into_iter()
            .map(|r| {
                let truth = r.truth_key.and_then(|k| data.truth.get(k).copied());
                ParameterResult {
                    relative_error: truth.filter(|t| *t != 0.0).map(|t| (r.estimate - t) / t),
                    name: r.name,
                    estimate: r.estimate,
                    units: r.units.into(),
                    truth,
                }
            })
            .collect();
        let mut warnings = data.warnings.clone();
        warnings.extend(calibration_warnings);
        if matches!(data.model, ModelKind::SlidingBlock | ModelKind::FreeFall)
            && data.train_start.is_none()
        {
            warnings.push(
                "no clip start times (meta.json's clip_start_times): the block rolls out from two \
                 frames, and for motion from rest that law is degenerate (a latent like √s is \
                 linear in time and fits z'' = 0), so the acceleration may come out far too small"
                    .into(),
            );
        }
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
        let low_std = outcome.latent_std.min(last_std);
        let collapsed = low_std < COLLAPSE_FRACTION * peak_std;
        if collapsed {
            warnings.push(format!(
                "the latent collapsed towards a constant (std {low_std:.2e} over the validation \
                 clips, down from {peak_std:.2e}): a constant latent makes the rollout error \
                 vanish whatever the parameters, so these estimates are not determined by the \
                 video; train with --loss mse+kl"
            ));
        }
        match outcome.stop {
            StopReason::NonFiniteLoss { epoch } => warnings.push(format!(
                "the loss became NaN or infinite in epoch {epoch}; training stopped and the \
                 parameters are {} (lower --lr or --lr-phys)",
                if outcome.best_epoch == 0 {
                    "the starting values: no epoch finished with a finite loss".to_string()
                } else {
                    format!("those of epoch {}, the best before it", outcome.best_epoch)
                }
            )),
            StopReason::MaxEpochs => warnings.push(format!(
                "the validation rollout error was still improving after --epochs {}; the estimate \
                 may not have converged (raise --epochs)",
                cfg.epochs
            )),
            StopReason::EarlyStop { .. } => {}
        }
        Report {
            tool: "estimate".into(),
            version: env!("CARGO_PKG_VERSION").into(),
            input: cfg.input.display().to_string(),
            model: data.model.name().into(),
            dt: data.dt,
            shape: data.shape,
            train_clips: data.n_train(),
            validation_clips: data.n_val(),
            config: cfg.clone(),
            device: format!("{device:?}"),
            threads,
            libtorch_version: LIBTORCH_VERSION.into(),
            parameters,
            block_parameters: data
                .model
                .parameter_names()
                .iter()
                .map(|s| s.to_string())
                .collect(),
            initial_values: init.to_vec(),
            final_values: outcome.parameters.clone(),
            calibration,
            recording: data.recording.as_ref().map(|r| r.0.clone()),
            starts: Vec::new(),
            epochs_run: outcome.epochs_run,
            best_epoch: outcome.best_epoch,
            best_val_rel_mse: outcome.best_val_rel_mse,
            stop: outcome.stop.clone(),
            latent_std: outcome.latent_std,
            latent_collapsed: collapsed,
            latent_vs_truth: latent_fit(data, &outcome.val_latents),
            wall_time_s: wall.as_secs_f64(),
            ensemble: None,
            warnings,
            history: outcome.history.clone(),
            outcome,
        }
    }

    /// Records the starts of a multi-start fit.
    pub fn with_starts(mut self, starts: Vec<crate::train::StartProbe>) -> Report {
        self.starts = starts;
        self
    }

    /// The closing table: parameter, estimate, ground truth, relative error.
    pub fn table(&self) -> String {
        let mut s = format!(
            "{} on {} ({}, {} integrator, {} epochs, best {}, {:.1} s on {})\n",
            self.model,
            self.input,
            self.config.loss.name(),
            match self.config.integrator {
                crate::physics::Integrator::Exact => "exact",
                crate::physics::Integrator::Euler => "euler",
            },
            self.epochs_run,
            self.best_epoch,
            self.wall_time_s,
            self.device
        );
        s += &format!(
            "{:<20} {:>12} {:>7} {:>12} {:>12}\n",
            "parameter", "estimate", "units", "truth", "rel. error"
        );
        for p in &self.parameters {
            let truth = p.truth.map_or("-".into(), |t| format!("{t:.6}"));
            let err = p
                .relative_error
                .map_or("-".into(), |e| format!("{:+.3} %", e * 100.0));
            s += &format!(
                "{:<20} {:>12.6} {:>7} {:>12} {:>12}\n",
                p.name, p.estimate, p.units, truth, err
            );
        }
        s.trim_end().to_string()
    }

    /// `metrics.csv`: one row per epoch.
    pub fn metrics_csv(&self) -> String {
        let names: Vec<&str> = self.block_parameters.iter().map(String::as_str).collect();
        let mut s = format!(
            "epoch,train_loss,val_loss,val_mse,val_rel_mse,latent_std,{},lr,lr_phys,elapsed_s\n",
            names.join(",")
        );
        for r in &self.history {
            let params: Vec<String> = r.parameters.iter().map(|v| format!("{v}")).collect();
            s += &format!(
                "{},{},{},{},{},{},{},{},{},{:.4}\n",
                r.epoch,
                r.train_loss,
                r.val_loss,
                r.val_mse,
                r.val_rel_mse,
                r.latent_std,
                params.join(","),
                r.lr,
                r.lr_phys,
                r.elapsed_s
            );
        }
        s
    }
}

/// Writes `bytes` to `path` through a temporary file and a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), EstimateError> {
    let tmp = path.with_extension("partial");
    let err = |source| EstimateError::Write {
        path: path.to_path_buf(),
        source,
    };
    std::fs::write(&tmp, bytes).map_err(err)?;
    std::fs::rename(&tmp, path).map_err(err)
}

/// Writes report.json, metrics.csv, parameters.png and latents.png into `cfg.out`.
pub fn write_outputs(
    cfg: &EstimateConfig,
    data: &ClipData,
    report: &Report,
) -> Result<(), EstimateError> {
    std::fs::create_dir_all(&cfg.out).map_err(|source| EstimateError::Write {
        path: cfg.out.clone(),
        source,
    })?;
    write_atomic(
        &cfg.out.join("metrics.csv"),
        report.metrics_csv().as_bytes(),
    )?;
    plot_parameters(&cfg.out.join("parameters.png"), report)?;
    plot_latents(&cfg.out.join("latents.png"), report, data)?;
    if let Some(t) = &report.outcome.timeline {
        plot_timeline(&cfg.out.join("timeline.png"), t)?;
    }
    if let Some(png) = &data.preview_png {
        write_atomic(&cfg.out.join("clips.png"), png)?;
    }
    let json = serde_json::to_vec_pretty(report).expect("report serialises");
    write_atomic(&cfg.out.join("report.json"), &json)
}
