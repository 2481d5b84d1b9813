//! `EstimateArgs`: `estimate`'s command line, in argument groups flattened into one command
//! (the model, training, recording and output flags; ripgrep's low-level arguments). Nothing
//! here knows the data: `EstimateArgs::request` turns the flags into a typed
//! `config::Request`, which `config::RunConfig::resolve` completes with a probe of the input
//! (the model, dt, the load's plan). Help for `--model`, `--init` and the per-model defaults is
//! generated from `physics::MODELS`. `reproduce` builds its runs' requests field by field and
//! shows each as the command a user can type, checked against these flags in its tests.

mod batch;
mod candidate;
mod model;
mod recording;
mod reference;
mod training;

pub use crate::data::Framing;
pub use crate::device::DeviceChoice;
pub use batch::{parse_shard, BatchArgs, Shard};
pub use model::{parse_init, ModelArgs, ModelSpec};
pub use recording::{parse_crop, parse_size, RecordingArgs};
pub use reference::{parse_reference, ReferencePoints};
pub use training::TrainingArgs;

use crate::config::request::DEFAULT_OUT;
use crate::config::{CalibrationRequest, Request, TrainingRequest};
use crate::error::{input_error, EstimateError};
use clap::Parser;
use std::path::PathBuf;

/// Estimate the physical parameters of a known ODE from video, without labels.
///
/// An MLP (or linear) encoder maps each frame to a latent z (for the two-body spring, a keypoint
/// net to both bodies' positions), a physics block with learnable parameters rolls z forward
/// from the start of each clip (its first frame for first-order models and for falls from rest
/// with known start times, the initial state that best fits the whole clip for the oscillator,
/// the pendulum and the spring), and the loss is MSE(encoded,
/// rolled out) + KL(N(μ, σ²) ‖ N(0, 1)) (CVPR 2025, arXiv 2410.01376). Reads gen datasets, bare
/// .npy arrays, videos and image folders. Values are labelled SI or latent units; latent-unit
/// ones need --reference. Ends with a table of estimates (and ground truth with relative errors
/// when meta.json gives them) and writes report.html (a page to open: estimates, warnings,
/// plots, the command), report.json, metrics.csv, parameters.png and latents.png (and
/// timeline.png, timeline.csv and change.png for a recording) into --out. With --batch, many inputs in one
/// command, each row into its own directory, with summary.csv, summary.md and index.html.
#[derive(Debug, Clone, Parser)]
// A flag given twice is refused (clap's default); a batch row's flags replace the command
// line's before its process starts (`batch::file::merged_flags`).
#[command(name = "estimate", version, allow_negative_numbers = true)]
pub struct EstimateArgs {
    /// A dataset directory written by `gen` (frames.npy + meta.json); a bare float32 .npy of
    /// shape [N, T, C, H, W] (then --dt is required); a video file (anything ffmpeg reads) or a
    /// folder of PNG/JPEG images (with --fps). Without --model, a recording or a bare .npy has
    /// its model chosen (--model auto).
    #[arg(required_unless_present_any = ["batch", "merge"])]
    pub input: Option<PathBuf>,
    #[command(flatten)]
    pub model: ModelArgs,
    #[command(flatten)]
    pub training: TrainingArgs,
    #[command(flatten)]
    pub recording: RecordingArgs,
    #[command(flatten)]
    pub output: OutputArgs,
    #[command(flatten)]
    pub batch: BatchArgs,
}

/// Where the results go.
#[derive(Debug, Clone, clap::Args)]
#[command(next_help_heading = "Output")]
pub struct OutputArgs {
    /// Directory for report.json, report.html, metrics.csv and the plots; for --batch and
    /// --merge, the summaries and one directory per row. Created if missing and marked as this
    /// tool's (.physvid-outputs.json); an existing folder it did not make is refused unless it
    /// is empty or --force is given, and only files this tool wrote there are ever removed or
    /// replaced
    #[arg(long, default_value = DEFAULT_OUT, value_name = "DIR")]
    pub out: PathBuf,
    /// Write into an existing --out that this tool did not make, replacing files under its
    /// output names (report.json, …); nothing of another name is removed or changed
    #[arg(long)]
    pub force: bool,
    /// Print only the final table.
    #[arg(long)]
    pub quiet: bool,
}

impl EstimateArgs {
    /// The input of a single run (`validate` has checked that one is given unless the command
    /// is a batch or a merge, which never reach a single run's code).
    pub fn input(&self) -> &std::path::Path {
        self.input.as_deref().unwrap_or(std::path::Path::new(""))
    }

    /// The run these (validated) flags ask for, typed: what every layer below reads instead
    /// of the flags. Fails where `--candidate` is given without a model choice.
    pub fn request(&self) -> Result<Request, EstimateError> {
        let (m, t) = (&self.model, &self.training);
        let reference = m.reference.clone().unwrap_or_default();
        Ok(Request {
            load: self.load_request(),
            choose: self.chooses_model()?,
            candidates: m.candidate.clone(),
            init: m.init_pairs().to_vec(),
            calibration: CalibrationRequest {
                values: reference.values,
                times: reference.times,
                positions: reference.positions,
                stick: m.stick,
                plane: m.plane,
                incline_deg: m.incline_deg,
                g: m.g,
            },
            integrator: m.integrator,
            rollout_start: m.rollout_start,
            training: TrainingRequest {
                epochs: t.epochs,
                patience: t.patience,
                batch_size: t.batch_size,
                lr: t.lr,
                lr_phys: t.lr_phys,
                single_start: t.single_start,
                loss: t.loss,
                encoder: t.encoder,
                seed: t.seed,
                ensemble: t.ensemble,
                device: t.device,
                threads: t.thread_count(),
            },
            out: self.output.out.clone(),
            force: self.output.force,
            quiet: self.output.quiet,
        })
    }

    /// What to load, as the data layer reads it.
    fn load_request(&self) -> crate::data::LoadRequest {
        let mut recording = self.recording.request();
        recording.measured_at = self.model.reference_times().iter().map(|t| t.0).collect();
        crate::data::LoadRequest {
            input: self.input().to_path_buf(),
            model: self.model.given(),
            trying: false,
            dt: self.model.dt,
            recording,
            frames: None,
        }
    }

    /// Checks the flags that do not depend on the data.
    pub fn validate(self) -> Result<EstimateArgs, EstimateError> {
        self.model.validate()?;
        self.training.validate()?;
        self.recording.validate()?;
        self.batch.validate()?;
        physvid_shared::atomic::check_writable_dir("--out", &self.output.out)
            .map_err(input_error)?;
        Ok(self)
    }
}

/// The flag whose clap id is `id` (its field's name), as written on the command line: the name
/// comes from its one definition (`--incline-deg` for `incline_deg`).
pub fn flag_name(id: &str) -> String {
    use clap::CommandFactory;
    EstimateArgs::command()
        .get_arguments()
        .find(|a| a.get_id() == id)
        .and_then(|a| a.get_long())
        .map_or_else(|| id.to_string(), |l| format!("--{l}"))
}

/// `v` must be finite and > 0.
pub(crate) fn positive(flag: &str, v: f64) -> Result<(), EstimateError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(input_error(format!(
            "{flag} {}: must be a finite number > 0",
            physvid_shared::cli::num(v)
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(line: &[&str]) -> Request {
        EstimateArgs::try_parse_from(line)
            .unwrap()
            .validate()
            .unwrap()
            .request()
            .unwrap()
    }

    #[test]
    fn a_bare_command_line_asks_what_a_default_request_does() {
        // A data set's folder: its meta.json names the model.
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("meta.json"), "{}").unwrap();
        let input = dir.path().to_str().unwrap();
        assert_eq!(request(&["estimate", input]), Request::new(input));
    }

    #[test]
    fn flags_land_in_their_typed_fields() {
        let r = request(&[
            "estimate",
            "clip.mp4",
            "--model",
            "pendulum",
            "--reference",
            "1s=0.5,2s=0.2",
            "--g",
            "9.8",
            "--epochs",
            "7",
            "--threads",
            "1",
            "--stride",
            "2",
        ]);
        assert_eq!(r.load.model.map(|m| m.name()), Some("pendulum"));
        assert!(!r.choose);
        assert_eq!(r.calibration.times, vec![(1.0, 0.5), (2.0, 0.2)]);
        assert_eq!(r.load.recording.measured_at, vec![1.0, 2.0]);
        assert_eq!(r.calibration.g, Some(9.8));
        assert_eq!((r.training.epochs, r.training.threads), (7, 1));
        assert_eq!(r.load.recording.stride, Some(2));
        assert!(
            request(&["estimate", "clip.mp4"]).choose,
            "a recording without --model"
        );
    }
}
