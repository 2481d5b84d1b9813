//! `gen`: command-line entry point; parses flags into a validated `GenConfig` and calls `run`.

use clap::Parser;
use generator::{ConfigError, GenConfig, Scenario};
use physvid_shared::cli::parse_name_values;
use physvid_shared::DatasetError;
use std::path::PathBuf;
use std::process::ExitCode;

/// Render a seeded synthetic video dataset of a known dynamical system.
///
/// intensity, position, scale: a damped oscillator z(t) = A·exp(−ζt)·cos(ωt + φ), γ0 = ω² + ζ²,
/// γ1 = 2ζ; A ~ Uniform[0.5, 1), φ ~ Uniform[0, 2π). pendulum, torricelli, sliding-block, led,
/// free-fall: the Delfys75 systems with the parameters of appendix Table 4 (--setting 1|2|3,
/// any value changed with --set), clips starting at random points of the motion.
///
/// Writes DIR/frames.npy (float32 [N, T, 1, H, W], values in [0, 1]), DIR/meta.json (ground
/// truth: the model and its parameters in SI units, dt, per-sample draws, the latent of every
/// frame, the calibration a user would measure, and for the sliding block and free fall each clip's
/// start time since the release) and DIR/preview.png. Draws come from seeded
/// per-sample ChaCha8 streams, so the same flags give byte-identical files on any number of
/// threads.
#[derive(Debug, Parser)]
#[command(name = "gen", version, allow_negative_numbers = true)]
struct Cli {
    /// The scene: one of the three damped-oscillator scenes (what z controls) or a Delfys75 system.
    #[arg(long, value_enum)]
    scenario: Scenario,
    /// Output directory (created; must be empty unless --force).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Number of clips N (≥ 1).
    #[arg(long, default_value_t = 500)]
    samples: usize,
    /// Frames per clip T (≥ 3) [default: 20; Delfys75 scenes: Table 5's, e.g. pendulum 20,
    /// sliding-block 10, free-fall 4].
    #[arg(long)]
    frames: Option<usize>,
    /// Frame width and height in pixels (≥ 8).
    #[arg(long, default_value_t = 50)]
    size: usize,
    /// Time between frames in seconds (> 0) [default: 0.2; Delfys75 scenes: Table 5's, e.g.
    /// pendulum 0.1, torricelli 1, sliding-block 1/30, led 1/60, free-fall 1/30].
    #[arg(long)]
    dt: Option<f64>,
    /// Angular frequency ω in rad/s (> 0; ω·dt < π) of the oscillator scenes [default: 2].
    #[arg(long)]
    omega: Option<f64>,
    /// Decay rate ζ in 1/s of the oscillator scenes (≥ 0, or slightly negative if the object
    /// stays in frame) [default: 0.04].
    #[arg(long)]
    zeta: Option<f64>,
    /// Delfys75 scenes: the column of appendix Table 4 (pendulum L = 0.45/0.90/1.50 m,
    /// torricelli k = 0.0095/0.0128/0.0162, sliding-block incline 20/25/30°, led γ = 2.3/0.92/0.46,
    /// free-fall radius 3.35/6/10 cm).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(1..=3))]
    setting: u8,
    /// Delfys75 scenes: override parameters, NAME=VALUE[,NAME=VALUE]. pendulum: length, damping,
    /// g, amplitude_min_deg, amplitude_max_deg; torricelli: k, h_start, h_end; sliding-block:
    /// incline_deg, mu, g, travel; led: gamma; free-fall: radius, h0, g (SI units).
    #[arg(long, value_name = "NAME=VALUE,...")]
    set: Option<String>,
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

/// Resolves scenario-dependent defaults, `--setting` and `--set` into a `GenConfig`.
fn config_from(cli: Cli) -> Result<GenConfig, ConfigError> {
    let system = cli.scenario.system();
    let (frames, dt) = system.map_or((20, 0.2), |s| s.default_frames_and_dt());
    let mut params = system.map(|s| s.setting(cli.setting)).unwrap_or_default();
    if let Some(system) = system {
        for (flag, given) in [
            ("--omega", cli.omega.is_some()),
            ("--zeta", cli.zeta.is_some()),
        ] {
            if given {
                return Err(ConfigError {
                    flag,
                    value: cli.scenario.to_string(),
                    expected: format!(
                        "applies to the intensity, position and scale scenes only; set the {} parameters with --set",
                        system.model_name()
                    ),
                });
            }
        }
        let text = cli.set.clone().unwrap_or_default();
        let pairs = parse_name_values(&text).map_err(|expected| ConfigError {
            flag: "--set",
            value: text.clone(),
            expected,
        })?;
        for (k, v) in pairs {
            if !params.contains_key(&k) {
                let names: Vec<&str> = params.keys().map(String::as_str).collect();
                return Err(ConfigError {
                    flag: "--set",
                    value: format!("{k}={v}"),
                    expected: format!(
                        "{} has no parameter '{k}'; its parameters are {}",
                        system.model_name(),
                        names.join(", ")
                    ),
                });
            }
            params.insert(k, v);
        }
    } else if cli.set.is_some() {
        return Err(ConfigError {
            flag: "--set",
            value: cli.set.unwrap_or_default(),
            expected: "applies to the Delfys75 scenes only; use --omega and --zeta".into(),
        });
    }
    Ok(GenConfig {
        scenario: cli.scenario,
        out: cli.out,
        samples: cli.samples,
        frames: cli.frames.unwrap_or(frames),
        size: cli.size,
        dt: cli.dt.unwrap_or(dt),
        omega: cli.omega.unwrap_or(2.0),
        zeta: cli.zeta.unwrap_or(0.04),
        seed: cli.seed,
        noise: cli.noise,
        force: cli.force,
        params,
    })
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
    let cfg = match config_from(cli).and_then(GenConfig::validate) {
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
