//! `EstimateConfig`: the validated settings of one `estimate` run.

use crate::encoder::EncoderKind;
use crate::error::{input_error, EstimateError};
use crate::loss::LossKind;
use crate::physics::{Integrator, OSCILLATOR_PARAMETERS};
use serde::Serialize;
use std::path::PathBuf;

/// Dynamics models `estimate` knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ModelKind {
    /// z'' + γ1·z' + γ0·z = 0 (parameters gamma0, gamma1).
    DampedOscillator,
}

impl ModelKind {
    pub fn name(self) -> &'static str {
        match self {
            ModelKind::DampedOscillator => "damped-oscillator",
        }
    }

    pub fn from_name(name: &str) -> Option<ModelKind> {
        [ModelKind::DampedOscillator]
            .into_iter()
            .find(|m| m.name() == name)
    }

    pub fn parameter_names(self) -> &'static [&'static str] {
        match self {
            ModelKind::DampedOscillator => &OSCILLATOR_PARAMETERS,
        }
    }

    /// Default starting values.
    pub fn default_init(self) -> Vec<f64> {
        match self {
            ModelKind::DampedOscillator => vec![1.0, 0.1],
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
    /// Epochs without a better validation loss before stopping.
    pub patience: usize,
    pub batch_size: usize,
    /// Adam learning rate of the encoder.
    pub lr: f64,
    /// Adam learning rate of the physics parameters (their logarithms: a relative step).
    pub lr_phys: f64,
    /// Starting values as NAME=VALUE pairs (model defaults where absent).
    pub init: Vec<(String, f64)>,
    pub integrator: Integrator,
    /// Train only from the given (or default) start, without the spectral start (the paper's
    /// behaviour).
    pub single_start: bool,
    pub loss: LossKind,
    pub encoder: EncoderKind,
    pub seed: u64,
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

/// `--init` values: NAME=VALUE pairs in the order given.
#[derive(Debug, Clone, PartialEq)]
pub struct InitValues(pub Vec<(String, f64)>);

/// Parses `--init` text such as `gamma0=10,gamma1=0.5`.
pub fn parse_init(text: &str) -> Result<InitValues, String> {
    text.split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|pair| {
            let (k, v) = pair
                .split_once('=')
                .ok_or_else(|| format!("'{pair}' is not NAME=VALUE (e.g. gamma0=10,gamma1=0.5)"))?;
            let v: f64 = v
                .trim()
                .parse()
                .map_err(|_| format!("'{v}' in '{pair}' is not a number"))?;
            Ok((k.trim().to_string(), v))
        })
        .collect::<Result<Vec<_>, String>>()
        .map(InitValues)
}

impl EstimateConfig {
    /// Checks the flags that do not depend on the data.
    pub fn validate(self) -> Result<EstimateConfig, EstimateError> {
        if let Some(dt) = self.dt {
            positive("--dt", dt)?;
        }
        if self.epochs == 0 {
            return Err(input_error("--epochs 0: must be at least 1"));
        }
        if self.patience == 0 {
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
            if name == "gamma0" && *v <= 0.0 {
                return Err(input_error(format!(
                    "--init gamma0={v}: must be > 0 (γ0 = ω² + ζ² of an oscillator)"
                )));
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
