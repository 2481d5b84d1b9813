//! `estimate`: command-line entry point; parses flags into a validated `EstimateConfig` and calls `run`.

use clap::Parser;
use estimator::config::{
    parse_init, parse_reference, DeviceChoice, EstimateConfig, InitValues, ModelKind,
    ReferencePoints,
};
use estimator::encoder::EncoderKind;
use estimator::loss::LossKind;
use estimator::physics::Integrator;
use estimator::recording::{parse_crop, parse_size, RecordingFlags};
use estimator::EstimateError;
use physvid_shared::video::Crop;
use std::path::PathBuf;
use std::process::ExitCode;

/// Estimate the physical parameters of a known ODE from video, without labels.
///
/// An MLP (or linear) encoder maps each frame to a latent z, a physics block with learnable
/// parameters rolls z forward from the start of each clip (its first frame for first-order
/// models and for falls from rest with known start times, its first two frames for the
/// oscillator, the best-fitting initial state for the pendulum), and the loss is MSE(encoded,
/// rolled out) + KL(N(μ, σ²) ‖ N(0, 1)) (CVPR 2025, arXiv 2410.01376). Reads gen datasets, bare
/// .npy arrays, videos and image folders. Values are labelled SI or latent units; latent-unit
/// ones need --reference. Ends with a table of estimates (and ground truth with relative errors
/// when meta.json gives them) and writes report.json, metrics.csv, parameters.png and
/// latents.png (and timeline.png for a recording) into --out.
#[derive(Debug, Parser)]
#[command(name = "estimate", version, allow_negative_numbers = true)]
struct Cli {
    /// A dataset directory written by `gen` (frames.npy + meta.json); a bare float32 .npy of
    /// shape [N, T, C, H, W] (then --dt and --model are required); a video file (anything
    /// ffmpeg reads) or a folder of PNG/JPEG images (with --fps), with --model.
    input: PathBuf,
    /// Recording: frames per second of real time; overrides the container's (slow-motion files
    /// store 30 fps for a 120 fps capture); required for an image folder.
    #[arg(long, help_heading = "Recordings")]
    fps: Option<f64>,
    /// Recording: crop X,Y,W,H in pixels of the displayed (rotated) frame.
    #[arg(long, value_parser = parse_crop, value_name = "X,Y,W,H", help_heading = "Recordings")]
    crop: Option<Crop>,
    /// Recording: first second to use (of the file's own timeline). For sliding-block and
    /// free-fall the first frame kept is taken as the release from rest.
    #[arg(long, help_heading = "Recordings")]
    start: Option<f64>,
    /// Recording: last second to use.
    #[arg(long, help_heading = "Recordings")]
    end: Option<f64>,
    /// Recording: frame size fed to the encoder (grey, area-averaged).
    #[arg(long, value_parser = parse_size, value_name = "WxH", default_value = "100x56", help_heading = "Recordings")]
    size: (usize, usize),
    /// Recording: frames per clip [default: appendix Table 5's for the model: pendulum 20,
    /// torricelli 20, sliding-block 10, led 20, free-fall 4, damped-oscillator 20].
    #[arg(long, help_heading = "Recordings")]
    frames_per_clip: Option<usize>,
    /// Recording: recording frames between clip frames, so dt = stride / fps [default: Table
    /// 5's dt × fps, e.g. 6 for the pendulum at 60 fps].
    #[arg(long, help_heading = "Recordings")]
    stride: Option<usize>,
    /// Recording: recording frames between the starts of consecutive clips [default: 1, or more
    /// to stay within 1000 clips].
    #[arg(long, help_heading = "Recordings")]
    hop: Option<usize>,
    /// Recording: also write clips.png, the first clips as the model sees them (check crop and
    /// stride).
    #[arg(long, help_heading = "Recordings")]
    preview: bool,
    /// Seconds between frames (taken from meta.json when present).
    #[arg(long)]
    dt: Option<f64>,
    /// The governing equation (taken from meta.json when present; required for recordings).
    #[arg(long, value_enum)]
    model: Option<ModelKind>,
    /// Maximum number of epochs; the early stop usually ends training sooner.
    #[arg(long, default_value_t = 300)]
    epochs: usize,
    /// Stop after this many epochs without a 0.1 % lower validation rollout error (MSE over the
    /// latent's variance); learning rates halve every patience/3 such epochs [default: 10 for
    /// damped-oscillator, 30 for the Delfys75 systems].
    #[arg(long)]
    patience: Option<usize>,
    /// Clips per optimisation step.
    #[arg(long, default_value_t = 32)]
    batch_size: usize,
    /// Adam learning rate of the encoder.
    #[arg(long, default_value_t = 1e-3)]
    lr: f64,
    /// Adam learning rate of the physics parameters, which are learned as logarithms (so this
    /// is a relative step).
    #[arg(long, default_value_t = 1e-2)]
    lr_phys: f64,
    /// Initial values of the block's parameters, NAME=VALUE[,NAME=VALUE] (damped-oscillator:
    /// gamma0=1,gamma1=0.1; pendulum: g_over_l=10,damping=0.1,angle_scale=10,angle_offset=0;
    /// torricelli: k_latent=0.1,base=-3; led: gamma=1,offset=-2; sliding-block, free-fall:
    /// acceleration_latent=0).
    #[arg(long, value_parser = parse_init, value_name = "NAME=VALUE,...")]
    init: Option<InitValues>,
    /// Calibration for answers in SI units: the physical quantity (level, distance, …; the
    /// pendulum's angle in rad, which then fixes its angle scale) at two or more frames,
    /// CLIP:FRAME=VALUE[,...] (taken from meta.json for gen data).
    #[arg(long, value_parser = parse_reference, value_name = "CLIP:FRAME=VALUE,...")]
    reference: Option<ReferencePoints>,
    /// Sliding block: the incline's angle in degrees, for μ (taken from meta.json for gen data).
    #[arg(long)]
    incline_deg: Option<f64>,
    /// Gravitational acceleration in m/s² for the pendulum's L and the block's μ [default: 9.81].
    #[arg(long)]
    g: Option<f64>,
    /// Physics integrator: exact (closed form, or RK4 with sub-steps for the pendulum), or the
    /// paper's Euler step (biased at large dt).
    #[arg(long, value_enum, default_value_t = Integrator::Exact)]
    integrator: Integrator,
    /// Train only from --init (the paper's behaviour). By default a second start, estimated
    /// from the frames' principal components, is probed beside it and the better one kept.
    #[arg(long)]
    single_start: bool,
    /// Training loss; `mse` is the appendix's ablation, whose latent collapses.
    #[arg(long, value_enum, default_value_t = LossKind::MseKl)]
    loss: LossKind,
    /// Encoder: small (D → 16 → 1), the paper's (D → 1000 → 100 → 1), or linear (D → 1)
    /// [default: linear for led and torricelli, whose brightness / water area is affine in the
    /// pixels and whose laws an MLP could bend; small for the others].
    #[arg(long, value_enum)]
    encoder: Option<EncoderKind>,
    /// Seed of the weight initialisation and batch order.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Train K models with seeds --seed … --seed+K−1 (one after another, each on every core)
    /// and report each value's mean, standard deviation and range (report.json `ensemble`).
    #[arg(long, default_value_t = 1, value_name = "K")]
    ensemble: usize,
    /// Where to train.
    #[arg(long, value_enum, default_value_t = DeviceChoice::Auto)]
    device: DeviceChoice,
    /// CPU threads for libtorch (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Directory for report.json, metrics.csv and the plots (created; files are replaced).
    #[arg(long, default_value = "runs/estimate", value_name = "DIR")]
    out: PathBuf,
    /// Print only the final table.
    #[arg(long)]
    quiet: bool,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return physvid_shared::cli::exit_on_clap_error(e),
    };
    let cfg = EstimateConfig {
        input: cli.input,
        dt: cli.dt,
        model: cli.model,
        epochs: cli.epochs,
        patience: cli.patience,
        batch_size: cli.batch_size,
        lr: cli.lr,
        lr_phys: cli.lr_phys,
        init: cli.init.map(|i| i.0).unwrap_or_default(),
        reference: cli.reference.map(|r| r.0).unwrap_or_default(),
        incline_deg: cli.incline_deg,
        g: cli.g,
        integrator: cli.integrator,
        single_start: cli.single_start,
        loss: cli.loss,
        encoder: cli.encoder,
        seed: cli.seed,
        ensemble: cli.ensemble,
        recording: RecordingFlags {
            fps: cli.fps,
            crop: cli.crop,
            start: cli.start,
            end: cli.end,
            size: cli.size,
            frames_per_clip: cli.frames_per_clip,
            stride: cli.stride,
            hop: cli.hop,
            preview: cli.preview,
        },
        device: cli.device,
        threads: cli.threads,
        out: cli.out,
        quiet: cli.quiet,
    };
    let result = cfg
        .validate()
        .map_err(anyhow::Error::from)
        .and_then(|cfg| estimator::run(&cfg));
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("estimate: error: {e:#}");
            let bad_input = e
                .downcast_ref::<EstimateError>()
                .is_some_and(EstimateError::is_bad_input);
            ExitCode::from(if bad_input { 2 } else { 1 })
        }
    }
}
