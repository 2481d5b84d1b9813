//! `EstimateArgs`: `estimate`'s command line (clap), and its conversion to an `EstimateConfig`;
//! `reproduce` builds its runs from the same arguments, so each table row is a command a user
//! can type.

use crate::config::{
    parse_init, parse_reference, DeviceChoice, EstimateConfig, InitValues, ModelKind,
    ReferencePoints,
};
use crate::encoder::EncoderKind;
use crate::loss::LossKind;
use crate::physics::{Integrator, RolloutStart};
use crate::recording::{parse_crop, parse_size, RecordingFlags};
use clap::Parser;
use physvid_shared::video::Crop;
use std::path::PathBuf;

/// Estimate the physical parameters of a known ODE from video, without labels.
///
/// An MLP (or linear) encoder maps each frame to a latent z, a physics block with learnable
/// parameters rolls z forward from the start of each clip (its first frame for first-order
/// models and for falls from rest with known start times, the initial state that best fits the
/// whole clip for the oscillator and the pendulum), and the loss is MSE(encoded,
/// rolled out) + KL(N(μ, σ²) ‖ N(0, 1)) (CVPR 2025, arXiv 2410.01376). Reads gen datasets, bare
/// .npy arrays, videos and image folders. Values are labelled SI or latent units; latent-unit
/// ones need --reference. Ends with a table of estimates (and ground truth with relative errors
/// when meta.json gives them) and writes report.json, metrics.csv, parameters.png and
/// latents.png (and timeline.png for a recording) into --out.
#[derive(Debug, Clone, Parser)]
#[command(name = "estimate", version, allow_negative_numbers = true)]
pub struct EstimateArgs {
    /// A dataset directory written by `gen` (frames.npy + meta.json); a bare float32 .npy of
    /// shape [N, T, C, H, W] (then --dt and --model are required); a video file (anything
    /// ffmpeg reads) or a folder of PNG/JPEG images (with --fps), with --model.
    pub input: PathBuf,
    /// Recording: frames per second of real time; overrides the container's (slow-motion files
    /// store 30 fps for a 120 fps capture); required for an image folder.
    #[arg(long, help_heading = "Recordings")]
    pub fps: Option<f64>,
    /// Recording: crop X,Y,W,H in pixels of the displayed (rotated) frame.
    #[arg(long, value_parser = parse_crop, value_name = "X,Y,W,H", help_heading = "Recordings")]
    pub crop: Option<Crop>,
    /// Recording: first second to use (of the file's own timeline). For sliding-block and
    /// free-fall the first frame kept is taken as the release from rest.
    #[arg(long, help_heading = "Recordings")]
    pub start: Option<f64>,
    /// Recording: last second to use.
    #[arg(long, help_heading = "Recordings")]
    pub end: Option<f64>,
    /// Recording: frame size fed to the encoder (grey, area-averaged).
    #[arg(long, value_parser = parse_size, value_name = "WxH", default_value = "100x56", help_heading = "Recordings")]
    pub size: (usize, usize),
    /// Recording: frames per clip [default: appendix Table 5's for the model: pendulum 20,
    /// torricelli 20, sliding-block 10, led 20, free-fall 4, damped-oscillator 20].
    #[arg(long, help_heading = "Recordings")]
    pub frames_per_clip: Option<usize>,
    /// Recording: recording frames between clip frames, so dt = stride / fps [default: Table
    /// 5's dt × fps, e.g. 6 for the pendulum at 60 fps].
    #[arg(long, help_heading = "Recordings")]
    pub stride: Option<usize>,
    /// Recording: recording frames between the starts of consecutive clips [default: 1, or more
    /// to stay within 1000 clips].
    #[arg(long, help_heading = "Recordings")]
    pub hop: Option<usize>,
    /// Recording: also write clips.png, the first clips as the model sees them (check crop and
    /// stride).
    #[arg(long, help_heading = "Recordings")]
    pub preview: bool,
    /// Seconds between frames (taken from meta.json when present).
    #[arg(long)]
    pub dt: Option<f64>,
    /// The governing equation (taken from meta.json when present; required for recordings).
    #[arg(long, value_enum)]
    pub model: Option<ModelKind>,
    /// Maximum number of epochs; the early stop usually ends training sooner.
    #[arg(long, default_value_t = 300)]
    pub epochs: usize,
    /// Stop after this many epochs without a 0.1 % lower validation rollout error (MSE over the
    /// latent's variance); learning rates halve every patience/3 such epochs [default: 20 for
    /// damped-oscillator, 30 for the Delfys75 systems].
    #[arg(long)]
    pub patience: Option<usize>,
    /// Clips per optimisation step.
    #[arg(long, default_value_t = 32)]
    pub batch_size: usize,
    /// Adam learning rate of the encoder.
    #[arg(long, default_value_t = 1e-3)]
    pub lr: f64,
    /// Adam learning rate of the physics parameters, which are learned as logarithms (so this
    /// is a relative step).
    #[arg(long, default_value_t = 1e-2)]
    pub lr_phys: f64,
    /// Initial values of the block's parameters, NAME=VALUE[,NAME=VALUE] (damped-oscillator:
    /// gamma0=1,gamma1=0.1; pendulum: g_over_l=10,damping=0.1,angle_scale=10,angle_offset=0;
    /// torricelli: k_latent=0.1,base=-3; led: gamma=1,offset=-2; sliding-block, free-fall:
    /// acceleration_latent=0).
    #[arg(long, value_parser = parse_init, value_name = "NAME=VALUE,...")]
    pub init: Option<InitValues>,
    /// Calibration for answers in SI units: the physical quantity (level, distance, …; the
    /// pendulum's angle in rad, which then fixes its angle scale) at two or more frames,
    /// CLIP:FRAME=VALUE[,...] (taken from meta.json for gen data).
    #[arg(long, value_parser = parse_reference, value_name = "CLIP:FRAME=VALUE,...")]
    pub reference: Option<ReferencePoints>,
    /// Sliding block: the incline's angle in degrees, for μ (taken from meta.json for gen data).
    #[arg(long)]
    pub incline_deg: Option<f64>,
    /// Gravitational acceleration in m/s² for the pendulum's L and the block's μ [default: 9.81].
    #[arg(long)]
    pub g: Option<f64>,
    /// Physics integrator: exact (closed form, or RK4 with sub-steps for the pendulum), or the
    /// paper's Euler step (biased at large dt).
    #[arg(long, value_enum, default_value_t = Integrator::Exact)]
    pub integrator: Integrator,
    /// damped-oscillator: where each clip's rollout starts: fit (the initial state that fits
    /// the whole clip in least squares, robust to pixel noise) or frames (the first two encoded
    /// frames, the paper's). The pendulum always fits its start; first-order and
    /// constant-acceleration blocks start from the first frame.
    #[arg(long, value_enum, default_value_t = RolloutStart::Fit)]
    pub rollout_start: RolloutStart,
    /// Train only from --init (the paper's behaviour). By default a second start, estimated
    /// from the frames' principal components, is probed beside it and the better one kept.
    #[arg(long)]
    pub single_start: bool,
    /// Training loss; `mse` is the appendix's ablation, whose latent collapses.
    #[arg(long, value_enum, default_value_t = LossKind::MseKl)]
    pub loss: LossKind,
    /// Encoder: small (D → 16 → 1), the paper's (D → 1000 → 100 → 1), or linear (D → 1)
    /// [default: linear for led and torricelli, whose brightness / water area is affine in the
    /// pixels and whose laws an MLP could bend; small for the others].
    #[arg(long, value_enum)]
    pub encoder: Option<EncoderKind>,
    /// Seed of the weight initialisation and batch order.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Train K models with seeds --seed … --seed+K−1 (one after another, each on every core)
    /// and report each value's mean, standard deviation and range (report.json `ensemble`).
    #[arg(long, default_value_t = 1, value_name = "K")]
    pub ensemble: usize,
    /// Where to train.
    #[arg(long, value_enum, default_value_t = DeviceChoice::Auto)]
    pub device: DeviceChoice,
    /// CPU threads for libtorch (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Directory for report.json, metrics.csv and the plots (created; files are replaced).
    #[arg(long, default_value = "runs/estimate", value_name = "DIR")]
    pub out: PathBuf,
    /// Print only the final table.
    #[arg(long)]
    pub quiet: bool,
}

impl EstimateArgs {
    /// The configuration these arguments describe (not yet validated).
    pub fn into_config(self) -> EstimateConfig {
        EstimateConfig {
            input: self.input,
            dt: self.dt,
            model: self.model,
            epochs: self.epochs,
            patience: self.patience,
            batch_size: self.batch_size,
            lr: self.lr,
            lr_phys: self.lr_phys,
            init: self.init.map(|i| i.0).unwrap_or_default(),
            reference: self.reference.map(|r| r.0).unwrap_or_default(),
            incline_deg: self.incline_deg,
            g: self.g,
            integrator: self.integrator,
            rollout_start: self.rollout_start,
            single_start: self.single_start,
            loss: self.loss,
            encoder: self.encoder,
            seed: self.seed,
            ensemble: self.ensemble,
            recording: RecordingFlags {
                fps: self.fps,
                crop: self.crop,
                start: self.start,
                end: self.end,
                size: self.size,
                frames_per_clip: self.frames_per_clip,
                stride: self.stride,
                hop: self.hop,
                preview: self.preview,
            },
            device: self.device,
            threads: self.threads,
            out: self.out,
            quiet: self.quiet,
        }
    }
}
