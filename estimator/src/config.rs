//! `EstimateConfig`: the validated settings of one `estimate` run.

use crate::encoder::EncoderKind;
use crate::error::{input_error, EstimateError};
use crate::loss::LossKind;
use crate::physics::{Integrator, RolloutStart, OSCILLATOR_PARAMETERS};
use crate::recording::RecordingFlags;
use serde::Serialize;
use std::path::PathBuf;

/// Dynamics models `estimate` knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ModelKind {
    /// z'' + γ1·z' + γ0·z = 0 (parameters gamma0, gamma1).
    DampedOscillator,
    /// θ'' = −(g/L)·sin θ − ζ·θ', θ = (z − c)/s (g_over_l, damping, angle_scale, angle_offset).
    Pendulum,
    /// h' = −k·√h (k_latent, base).
    Torricelli,
    /// s'' = g·(sin α − μ·cos α), constant (acceleration_latent).
    SlidingBlock,
    /// I' = −γ·I (gamma, offset).
    Led,
    /// h'' = g (acceleration_latent).
    FreeFall,
}

impl ModelKind {
    pub const ALL: [ModelKind; 6] = [
        ModelKind::DampedOscillator,
        ModelKind::Pendulum,
        ModelKind::Torricelli,
        ModelKind::SlidingBlock,
        ModelKind::Led,
        ModelKind::FreeFall,
    ];

    pub fn name(self) -> &'static str {
        match self {
            ModelKind::DampedOscillator => "damped-oscillator",
            ModelKind::Pendulum => "pendulum",
            ModelKind::Torricelli => "torricelli",
            ModelKind::SlidingBlock => "sliding-block",
            ModelKind::Led => "led",
            ModelKind::FreeFall => "free-fall",
        }
    }

    pub fn from_name(name: &str) -> Option<ModelKind> {
        ModelKind::ALL.into_iter().find(|m| m.name() == name)
    }

    /// Names of the physics block's learnable parameters, in its order.
    pub fn parameter_names(self) -> &'static [&'static str] {
        match self {
            ModelKind::DampedOscillator => &OSCILLATOR_PARAMETERS,
            ModelKind::Pendulum => &["g_over_l", "damping", "angle_scale", "angle_offset"],
            ModelKind::Torricelli => &["k_latent", "base"],
            ModelKind::SlidingBlock | ModelKind::FreeFall => &["acceleration_latent"],
            ModelKind::Led => &["gamma", "offset"],
        }
    }

    /// Appendix Table 5's frames per clip and dt (s) for a recording of this system (the
    /// oscillator: 20 frames of 0.2 s, as the synthetic sets).
    pub fn table5_clip(self) -> (usize, f64) {
        match self {
            ModelKind::DampedOscillator => (20, 0.2),
            ModelKind::Pendulum => (20, 0.1),
            ModelKind::Torricelli => (20, 1.0),
            ModelKind::SlidingBlock => (10, 1.0 / 30.0),
            ModelKind::Led => (20, 1.0 / 60.0),
            ModelKind::FreeFall => (4, 1.0 / 30.0),
        }
    }

    /// Default starting values.
    pub fn default_init(self) -> Vec<f64> {
        match self {
            ModelKind::DampedOscillator => vec![1.0, 0.1],
            ModelKind::Pendulum => vec![10.0, 0.1, 10.0, 0.0],
            ModelKind::Torricelli => vec![0.1, -3.0],
            ModelKind::SlidingBlock | ModelKind::FreeFall => vec![0.0],
            ModelKind::Led => vec![1.0, -2.0],
        }
    }

    /// The encoder that makes the latent identifiable. LED brightness and a tank's water (its
    /// area) are affine in the pixels, and their laws are invariant under maps an MLP could
    /// learn (I^p decays at p·γ; any √u = p + q·√h drains by Torricelli's law), so a linear
    /// encoder, whose latent is then affine in the quantity, pins them; the others need the MLP.
    pub fn default_encoder(self) -> EncoderKind {
        match self {
            ModelKind::Led | ModelKind::Torricelli => EncoderKind::Linear,
            _ => EncoderKind::Small,
        }
    }

    /// Early-stop patience: the calibrated Delfys75 answers need the latent affine to a few
    /// parts in 10⁴, which takes longer than the oscillator's scale-free rates.
    pub fn default_patience(self) -> usize {
        match self {
            ModelKind::DampedOscillator => 20,
            _ => 30,
        }
    }

    /// Parameters learned as logarithms (must start > 0).
    pub fn positive_parameters(self) -> &'static [&'static str] {
        match self {
            ModelKind::DampedOscillator => &["gamma0"],
            ModelKind::Pendulum => &["g_over_l", "angle_scale"],
            ModelKind::Torricelli => &["k_latent"],
            ModelKind::Led => &["gamma"],
            ModelKind::SlidingBlock | ModelKind::FreeFall => &[],
        }
    }
}

/// Where to train.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DeviceChoice {
    /// CUDA when libtorch sees a GPU, else CPU.
    Auto,
    Cpu,
    Cuda,
}

/// Settings of one run; build with [`EstimateConfig::validate`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EstimateConfig {
    pub input: PathBuf,
    /// Overrides / supplies dt (required for a bare .npy).
    pub dt: Option<f64>,
    /// Overrides / supplies the model (required for a bare .npy).
    pub model: Option<ModelKind>,
    /// Upper bound on epochs; the early stop usually ends the run sooner.
    pub epochs: usize,
    /// Epochs without a better validation loss before stopping (the model's default when
    /// `None`; see [`ModelKind::default_patience`]).
    pub patience: Option<usize>,
    pub batch_size: usize,
    /// Adam learning rate of the encoder.
    pub lr: f64,
    /// Adam learning rate of the physics parameters (their logarithms: a relative step).
    pub lr_phys: f64,
    /// Starting values as NAME=VALUE pairs (model defaults where absent).
    pub init: Vec<(String, f64)>,
    /// Calibration for SI answers: the physical quantity at reference frames, as
    /// (clip, frame, value); read from meta.json when empty.
    pub reference: Vec<(usize, usize, f64)>,
    /// Incline of the sliding block in degrees (meta.json when absent).
    pub incline_deg: Option<f64>,
    /// Gravitational acceleration for the pendulum's L and the block's μ (default 9.81).
    pub g: Option<f64>,
    pub integrator: Integrator,
    /// Where the oscillator's rollout starts (least-squares fit, or the paper's first frames).
    pub rollout_start: RolloutStart,
    /// Train only from the given (or default) start, without the spectral start (the paper's
    /// behaviour).
    pub single_start: bool,
    pub loss: LossKind,
    /// Encoder architecture (the model's default when `None`; see
    /// [`ModelKind::default_encoder`]).
    pub encoder: Option<EncoderKind>,
    pub seed: u64,
    /// Independently seeded trainings whose spread is reported (1: a single run).
    pub ensemble: usize,
    /// How a video or image folder becomes clips (ignored for datasets).
    pub recording: RecordingFlags,
    pub device: DeviceChoice,
    pub threads: Option<usize>,
    pub out: PathBuf,
    pub quiet: bool,
}

fn positive(flag: &str, v: f64) -> Result<(), EstimateError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(input_error(format!(
            "{flag} {v}: must be a finite number > 0"
        )))
    }
}

/// `--reference` values: CLIP:FRAME=VALUE triples.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferencePoints(pub Vec<(usize, usize, f64)>);

/// Parses `--reference 0:0=0.07,12:19=0.01` (clip:frame=physical value).
pub fn parse_reference(text: &str) -> Result<ReferencePoints, String> {
    text.split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|item| {
            let bad = || format!("'{item}' is not CLIP:FRAME=VALUE (e.g. 0:0=0.07,3:19=0.01)");
            let (at, v) = item.split_once('=').ok_or_else(bad)?;
            let (c, f) = at.split_once(':').ok_or_else(bad)?;
            Ok((
                c.trim().parse().map_err(|_| bad())?,
                f.trim().parse().map_err(|_| bad())?,
                v.trim().parse().map_err(|_| bad())?,
            ))
        })
        .collect::<Result<Vec<_>, String>>()
        .map(ReferencePoints)
}

/// `--init` values: NAME=VALUE pairs in the order given.
#[derive(Debug, Clone, PartialEq)]
pub struct InitValues(pub Vec<(String, f64)>);

/// Parses `--init` text such as `gamma0=10,gamma1=0.5`.
pub fn parse_init(text: &str) -> Result<InitValues, String> {
    physvid_shared::cli::parse_name_values(text)
        .map(InitValues)
        .map_err(|e| format!("{e} (e.g. gamma0=10,gamma1=0.5)"))
}

impl EstimateConfig {
    /// This configuration with the model's defaults filled in (encoder, patience).
    pub fn for_model(&self, model: ModelKind) -> EstimateConfig {
        EstimateConfig {
            encoder: Some(self.encoder.unwrap_or(model.default_encoder())),
            patience: Some(self.patience.unwrap_or(model.default_patience())),
            ..self.clone()
        }
    }

    /// The encoder for `model`: the flag, else the model's default.
    pub fn encoder_for(&self, model: ModelKind) -> EncoderKind {
        self.encoder.unwrap_or(model.default_encoder())
    }

    /// The early-stop patience for `model`: the flag, else the model's default.
    pub fn patience_for(&self, model: ModelKind) -> usize {
        self.patience.unwrap_or(model.default_patience())
    }

    /// Checks the flags that do not depend on the data.
    pub fn validate(self) -> Result<EstimateConfig, EstimateError> {
        if let Some(dt) = self.dt {
            positive("--dt", dt)?;
        }
        if self.epochs == 0 {
            return Err(input_error("--epochs 0: must be at least 1"));
        }
        if let Some(g) = self.g {
            positive("--g", g)?;
        }
        self.recording.validate()?;
        if self.ensemble == 0 {
            return Err(input_error("--ensemble 0: must be at least 1"));
        }
        if let Some(deg) = self.incline_deg {
            if !(deg.is_finite() && deg > 0.0 && deg < 90.0) {
                return Err(input_error(format!(
                    "--incline-deg {deg}: must be an angle in (0, 90) degrees"
                )));
            }
        }
        if self.patience == Some(0) {
            return Err(input_error("--patience 0: must be at least 1"));
        }
        if self.batch_size == 0 {
            return Err(input_error("--batch-size 0: must be at least 1"));
        }
        positive("--lr", self.lr)?;
        positive("--lr-phys", self.lr_phys)?;
        if self.threads == Some(0) {
            return Err(input_error("--threads 0: must be at least 1"));
        }
        for (name, v) in &self.init {
            if !v.is_finite() {
                return Err(input_error(format!(
                    "--init {name}={v}: must be a finite number"
                )));
            }
        }
        Ok(self)
    }

    /// Starting values for `model`, in its parameter order; unknown names are an error.
    pub fn initial_values(&self, model: ModelKind) -> Result<Vec<f64>, EstimateError> {
        let names = model.parameter_names();
        let mut values = model.default_init();
        for (name, v) in &self.init {
            let i = names.iter().position(|n| n == name).ok_or_else(|| {
                input_error(format!(
                    "--init {name}={v}: {} has no parameter '{name}'; its parameters are {}",
                    model.name(),
                    names.join(", ")
                ))
            })?;
            if model.positive_parameters().contains(&name.as_str()) && *v <= 0.0 {
                return Err(input_error(format!("--init {name}={v}: must be > 0")));
            }
            values[i] = *v;
        }
        Ok(values)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn init_text_parses_and_rejects_garbage() {
        assert_eq!(
            parse_init("gamma0=10, gamma1=0.5").unwrap().0,
            vec![("gamma0".to_string(), 10.0), ("gamma1".to_string(), 0.5)]
        );
        assert!(parse_init("gamma0").is_err());
        assert!(parse_init("gamma0=x").is_err());
    }
}
