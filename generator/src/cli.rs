//! `GenArgs`: `gen`'s command line (clap), and its resolution into a `GenConfig`: the scene's
//! defaults, `--setting`, `--set`, `--omega`, `--zeta` and `--model` (a model file's system on a
//! disc scene, its map onto z fitted after validation). Scene names and help come from
//! `scenes::SCENES`. `reproduce` and the tests build datasets from the same arguments.

use crate::config::GenConfig;
use crate::error::{invalid, ConfigError};
use crate::perturb::{self, MAX_LEVEL, PERTURBATIONS};
use crate::scenes::file::FileScene;
use crate::scenes::{SceneRef, SCENES};
use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::Parser;
use physvid_shared::cli::parse_name_values;
use std::path::PathBuf;

/// Render a seeded synthetic video dataset of a known dynamical system.
///
/// intensity, position, scale: a damped oscillator z(t) = A·exp(−ζt)·cos(ωt + φ), γ0 = ω² + ζ²,
/// γ1 = 2ζ; A ~ Uniform[0.5, 1), φ ~ Uniform[0, 2π). pendulum, torricelli, sliding-block, led,
/// free-fall: the Delfys75 systems with the parameters of appendix Table 4 (--setting 1|2|3,
/// any value changed with --set), clips starting at random points of the motion. spring: two
/// digits joined by a spring (appendix A.5), over a cluttered backdrop, in grey or --color.
///
/// Writes DIR/frames.npy (float32 [N, T, C, H, W], C = 1, or 3 with --color; values in
/// [0, 1]), DIR/meta.json (ground truth: the model and its parameters in SI units, dt,
/// per-sample draws, the latent of every frame (both bodies' pixel positions for the spring),
/// the calibration a user would measure, and for the sliding block and free fall each clip's
/// start time since the release) and DIR/preview.png. Draws come from seeded
/// per-sample ChaCha8 streams, so the same flags give byte-identical files on any number of
/// threads.
#[derive(Debug, Parser)]
#[command(name = "gen", version, allow_negative_numbers = true)]
pub struct GenArgs {
    /// The scene: one of the damped-oscillator scenes (what z controls) or a Delfys75 system.
    #[arg(long, value_parser = scene_parser())]
    pub scenario: SceneRef,
    /// A model file (see README, "Your own model") drawn on the intensity, position or scale
    /// scene instead of the damped oscillator: its parameters' starts (changed with --set), each
    /// clip's initial state from its \[initial\] ranges, its first observed variable mapped onto the
    /// scene's z in [-1, 1] (the map and reference frames of known value go to meta.json).
    #[arg(long, value_name = "FILE.toml")]
    pub model: Option<PathBuf>,
    /// Output directory (created and marked as this tool's, .physvid-outputs.json; must be empty
    /// unless --force; a refused or stopped run leaves no folder it made).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Number of clips N (≥ 1).
    #[arg(long, default_value_t = 500)]
    pub samples: usize,
    #[arg(long, help = clip_help("Frames per clip T (≥ 3)", |(f, _)| f.to_string()))]
    pub frames: Option<usize>,
    #[arg(long, help = size_help())]
    pub size: Option<usize>,
    #[arg(long, help = clip_help("Time between frames in seconds (> 0)", |(_, dt)| seconds(dt)))]
    pub dt: Option<f64>,
    /// Angular frequency ω in rad/s (> 0; ω·dt < π) of the oscillator scenes [default: 2].
    #[arg(long)]
    pub omega: Option<f64>,
    /// Decay rate ζ in 1/s of the oscillator scenes (≥ 0, or slightly negative if the object
    /// stays in frame) [default: 0.04].
    #[arg(long)]
    pub zeta: Option<f64>,
    #[arg(long, value_parser = clap::value_parser!(u8).range(1..=3), help = setting_help())]
    pub setting: Option<u8>,
    #[arg(long, value_name = "NAME=VALUE,...", help = set_help())]
    pub set: Option<String>,
    /// Seed of the random draws (amplitude, phase, noise).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Standard deviation σ of Gaussian pixel noise in [0, 1]; noisy values are clipped to [0, 1].
    #[arg(long, default_value_t = 0.0)]
    pub noise: f64,
    #[arg(long, value_name = "NAME:LEVEL,...", help = perturb_help())]
    pub perturb: Option<String>,
    /// Write into a non-empty DIR, replacing frames.npy, meta.json and preview.png (nothing of
    /// another name is touched).
    #[arg(long)]
    pub force: bool,
    /// The scene in colour (spring: PAIG's digit one in the red channel, digit two in green,
    /// over a colour background; frames get C = 3).
    #[arg(long)]
    pub color: bool,
    /// Worker threads, 1 to 256 (default: all cores). Output does not depend on it.
    #[arg(long, value_parser = physvid_shared::cli::thread_count)]
    pub threads: Option<usize>,
}

/// `--scenario`'s values with their help, from the registry.
fn scene_parser() -> impl TypedValueParser<Value = SceneRef> {
    let values: Vec<PossibleValue> = SCENES
        .iter()
        .map(|s| PossibleValue::new(s.name()).help(s.help()))
        .collect();
    PossibleValuesParser::new(values)
        .map(|name| SceneRef::by_name(&name).expect("a possible value names a scene"))
}

fn clip_help(what: &str, show: impl Fn((usize, f64)) -> String) -> String {
    let each: Vec<String> = SCENES
        .iter()
        .map(|s| format!("{} {}", s.name(), show(s.default_clip())))
        .collect();
    format!(
        "{what} [default: the scene's (appendix Table 5's for Delfys75): {}]",
        each.join(", ")
    )
}

/// `dt` as a person writes it: 0.2, or 1/30 for a frame rate.
fn seconds(dt: f64) -> String {
    let rate = 1.0 / dt;
    if dt < 1.0 && (rate - rate.round()).abs() < 1e-9 {
        format!("1/{}", rate.round())
    } else {
        format!("{dt}")
    }
}

fn size_help() -> String {
    let each: Vec<String> = SCENES
        .iter()
        .map(|s| format!("{} {}", s.name(), s.default_size()))
        .collect();
    format!(
        "Frame width and height in pixels (≥ 8) [default: the scene's: {}]",
        each.join(", ")
    )
}

fn setting_help() -> String {
    let each: Vec<String> = SCENES
        .iter()
        .filter(|s| s.has_settings())
        .filter_map(|s| {
            let (a, b, c) = (s.params(1), s.params(2), s.params(3));
            let key = a.keys().find(|k| a[*k] != b[*k] || b[*k] != c[*k])?;
            Some(format!(
                "{} {key} = {}/{}/{}",
                s.name(),
                a[key],
                b[key],
                c[key]
            ))
        })
        .collect();
    format!(
        "Delfys75 scenes: the column of appendix Table 4 ({}) [default: 1]",
        each.join("; ")
    )
}

fn perturb_help() -> String {
    let each: Vec<String> = PERTURBATIONS
        .iter()
        .map(|p| format!("{}: {}", p.name(), p.help()))
        .collect();
    format!(
        "Perturb every clip after rendering, levels 1 to {MAX_LEVEL} (the footage of others: \
         applied in this order, seeded apart from the scene's draws). {}",
        each.join("; ")
    )
}

fn set_help() -> String {
    let each: Vec<String> = SCENES
        .iter()
        .filter(|s| s.accepts_set())
        .map(|s| {
            let keys: Vec<String> = s.params(1).into_keys().collect();
            format!("{}: {}", s.name(), keys.join(", "))
        })
        .collect();
    format!(
        "Delfys75 scenes: override parameters, NAME=VALUE[,NAME=VALUE] (SI units). {}",
        each.join("; ")
    )
}

impl GenArgs {
    /// The configuration these arguments describe (validated).
    pub fn into_config(self) -> Result<GenConfig, ConfigError> {
        let file = match &self.model {
            Some(path) => Some(self.file_scene(path)?),
            None => None,
        };
        let scene = file.map_or(self.scenario, |f| SceneRef(f));
        let mut cfg = GenConfig::new(scene, self.out.clone());
        if let Some(s) = self.setting.filter(|_| !scene.has_settings()) {
            let with: Vec<&str> = SCENES
                .iter()
                .filter(|s| s.has_settings())
                .map(|s| s.name())
                .collect();
            return Err(invalid(
                "--setting",
                s,
                format!(
                    "{} has no settings (they are appendix Table 4's columns of {})",
                    scene.name(),
                    with.join(", ")
                ),
            ));
        }
        cfg.params = scene.params(self.setting.unwrap_or(1));
        for (flag, name, value) in [
            ("--omega", "omega", self.omega),
            ("--zeta", "zeta", self.zeta),
        ] {
            let Some(v) = value else { continue };
            if self.model.is_some() {
                return Err(invalid(
                    flag,
                    v,
                    "a model file's parameters are set with --set NAME=VALUE,...",
                ));
            }
            if !cfg.params.contains_key(name) {
                return Err(invalid(
                    flag,
                    scene.name(),
                    format!(
                        "applies to the intensity, position and scale scenes only; set the {} parameters with --set",
                        scene.model_name()
                    ),
                ));
            }
            cfg.params.insert(name.into(), v);
        }
        if let Some(text) = &self.set {
            if !scene.accepts_set() {
                return Err(invalid(
                    "--set",
                    text,
                    "applies to the Delfys75 scenes and model files only; use --omega and --zeta",
                ));
            }
            let pairs = parse_name_values(text).map_err(|e| invalid("--set", text, e))?;
            for (k, v) in pairs {
                if !cfg.params.contains_key(&k) {
                    let names: Vec<&str> = cfg.params.keys().map(String::as_str).collect();
                    return Err(invalid(
                        "--set",
                        format!("{k}={}", physvid_shared::cli::num(v)),
                        format!(
                            "{} has no parameter '{k}'; its parameters are {}",
                            scene.model_name(),
                            names.join(", ")
                        ),
                    ));
                }
                cfg.params.insert(k, v);
            }
        }
        cfg.samples = self.samples;
        cfg.frames = self.frames.unwrap_or(cfg.frames);
        cfg.size = self.size.unwrap_or(cfg.size);
        if self.color && scene.channels(true) == 1 {
            return Err(invalid(
                "--color",
                scene.name(),
                "the scene has no colour version (the spring has)",
            ));
        }
        cfg.color = self.color;
        cfg.dt = self.dt.unwrap_or(cfg.dt);
        cfg.seed = self.seed;
        cfg.noise = self.noise;
        cfg.force = self.force;
        if let Some(text) = &self.perturb {
            cfg.perturbations = perturb::parse(text).map_err(|e| invalid("--perturb", text, e))?;
        }
        let mut cfg = cfg.validate()?;
        if let Some(f) = file {
            // The map from the observed variable onto z, from every clip's trajectory.
            let map = f.fit_map(&cfg.params, cfg.samples, cfg.seed, cfg.frames, cfg.dt)?;
            cfg.scene = SceneRef(Box::leak(Box::new(f.with_map(map))));
        }
        Ok(cfg)
    }

    /// The scene of `--model`'s file on `--scenario`'s picture (its map fitted once the
    /// configuration is valid).
    fn file_scene(&self, path: &std::path::Path) -> Result<&'static FileScene, ConfigError> {
        let picture = self.scenario.0.picture().ok_or_else(|| {
            invalid(
                "--scenario",
                self.scenario.name(),
                "a model file is drawn on intensity, position or scale",
            )
        })?;
        let file = physvid_shared::model_file::load(path).map_err(|e| {
            invalid(
                "--model",
                path.display(),
                format!("{}: {}", e.key, e.problem),
            )
        })?;
        Ok(Box::leak(Box::new(FileScene::new(file, picture)?)))
    }

    /// Parses `gen` arguments (without the program name) into a validated configuration: what
    /// `reproduce` and the tests use to make datasets as a user would.
    pub fn config_from(args: &[&str]) -> anyhow::Result<GenConfig> {
        let args = GenArgs::try_parse_from(std::iter::once("gen").chain(args.iter().copied()))
            .map_err(|e| {
                anyhow::anyhow!("{}", physvid_shared::cli::one_line(&e.render().to_string()))
            })?;
        Ok(args.into_config()?)
    }
}
