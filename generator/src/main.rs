//! `gen`: command-line entry point; parses flags into a validated `GenConfig` and calls `run`.

use clap::Parser;
use generator::{GenConfig, Scenario};
use physvid_shared::DatasetError;
use std::path::PathBuf;
use std::process::ExitCode;

/// Render a seeded synthetic video dataset of a damped oscillator,
/// z(t) = A·exp(−ζt)·cos(ωt + φ), with γ0 = ω² + ζ² and γ1 = 2ζ.
///
/// Writes DIR/frames.npy (float32 [N, T, 1, H, W], values in [0, 1]), DIR/meta.json (ground
/// truth: parameters, dt, per-sample A and φ, the latent z of every frame) and DIR/preview.png.
/// A ~ Uniform[0.5, 1), φ ~ Uniform[0, 2π), drawn per sample from seeded ChaCha8 streams, so
/// the same flags give byte-identical files on any number of threads.
#[derive(Debug, Parser)]
#[command(name = "gen", version, allow_negative_numbers = true)]
struct Cli {
    /// What z controls: the brightness of a fixed disc, the horizontal position of a disc, or its size.
    #[arg(long, value_enum)]
    scenario: Scenario,
    /// Output directory (created; must be empty unless --force).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Number of clips N (≥ 1).
    #[arg(long, default_value_t = 500)]
    samples: usize,
    /// Frames per clip T (≥ 3).
    #[arg(long, default_value_t = 20)]
    frames: usize,
    /// Frame width and height in pixels (≥ 8).
    #[arg(long, default_value_t = 50)]
    size: usize,
    /// Time between frames in seconds (> 0); ω·dt must stay below π.
    #[arg(long, default_value_t = 0.2)]
    dt: f64,
    /// Angular frequency ω in rad/s (> 0).
    #[arg(long, default_value_t = 2.0)]
    omega: f64,
    /// Decay rate ζ in 1/s (≥ 0, or slightly negative if the object stays in frame).
    #[arg(long, default_value_t = 0.04)]
    zeta: f64,
    /// Seed of the random draws (amplitude, phase, noise).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Standard deviation σ of Gaussian pixel noise in [0, 1]; noisy values are clipped to [0, 1].
    #[arg(long, default_value_t = 0.0)]
    noise: f64,
    /// Overwrite the dataset files in a non-empty DIR.
    #[arg(long)]
    force: bool,
    /// Worker threads (default: all cores). Output does not depend on it.
    #[arg(long)]
    threads: Option<usize>,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return physvid_shared::cli::exit_on_clap_error(e),
    };
    if let Some(n) = cli.threads {
        if n == 0 {
            eprintln!("gen: error: --threads 0: must be at least 1");
            return ExitCode::from(2);
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
            .expect("the global thread pool is configured once");
    }
    let cfg = GenConfig {
        scenario: cli.scenario,
        out: cli.out,
        samples: cli.samples,
        frames: cli.frames,
        size: cli.size,
        dt: cli.dt,
        omega: cli.omega,
        zeta: cli.zeta,
        seed: cli.seed,
        noise: cli.noise,
        force: cli.force,
    };
    let cfg = match cfg.validate() {
        Ok(cfg) => cfg,
        Err(e) => {
            eprintln!("gen: error: {e}");
            return ExitCode::from(2);
        }
    };
    match generator::run(&cfg) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("gen: error: {e:#}");
            let bad_input = matches!(
                e.downcast_ref::<DatasetError>(),
                Some(DatasetError::NotEmpty { .. })
            );
            ExitCode::from(if bad_input { 2 } else { 1 })
        }
    }
}
