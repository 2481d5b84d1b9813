//! `GenConfig`: the validated settings of one `gen` run, and `ConfigError` for bad flags.

use crate::delfys::Params;
use crate::scenario::Scenario;
use std::path::PathBuf;

/// Largest dataset `gen` will hold in memory.
pub const MAX_BYTES: u64 = 8 << 30;

/// Settings of one generation run; build with [`GenConfig::validate`].
#[derive(Debug, Clone, PartialEq)]
pub struct GenConfig {
    pub scenario: Scenario,
    pub out: PathBuf,
    pub samples: usize,
    pub frames: usize,
    pub size: usize,
    pub dt: f64,
    pub omega: f64,
    pub zeta: f64,
    pub seed: u64,
    pub noise: f64,
    pub force: bool,
    /// Parameters of a Delfys75 scene (SI), empty for the oscillator scenes.
    pub params: Params,
}

/// A flag outside its valid range; the message names the flag, the value and the range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{flag} {value}: {expected}")]
pub struct ConfigError {
    pub flag: &'static str,
    pub value: String,
    pub expected: String,
}

fn invalid(flag: &'static str, value: impl ToString, expected: impl Into<String>) -> ConfigError {
    ConfigError {
        flag,
        value: value.to_string(),
        expected: expected.into(),
    }
}

/// Amplitudes are drawn from U[AMPLITUDE_MIN, AMPLITUDE_MAX].
pub const AMPLITUDE_MIN: f64 = 0.5;
pub const AMPLITUDE_MAX: f64 = 1.0;

impl GenConfig {
    /// Checks every field; the first problem found is returned.
    pub fn validate(self) -> Result<GenConfig, ConfigError> {
        if self.samples == 0 {
            return Err(invalid("--samples", self.samples, "must be at least 1"));
        }
        if self.frames < 3 {
            return Err(invalid(
                "--frames",
                self.frames,
                "must be at least 3 (a second-order model needs two frames to start and one to predict)",
            ));
        }
        if self.size < 8 {
            return Err(invalid("--size", self.size, "must be at least 8 pixels"));
        }
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return Err(invalid(
                "--dt",
                self.dt,
                "must be a finite number > 0 (seconds)",
            ));
        }
        if let Some(system) = self.scenario.system() {
            system.validate(&self.params, self.frames, self.dt)?;
            return self.check_size();
        }
        if !(self.omega.is_finite() && self.omega > 0.0) {
            return Err(invalid(
                "--omega",
                self.omega,
                "must be a finite number > 0 (rad/s)",
            ));
        }
        if self.omega * self.dt >= std::f64::consts::PI {
            return Err(invalid(
                "--omega",
                self.omega,
                format!(
                    "with --dt {} the frames sample the oscillation below its Nyquist rate (omega*dt = {:.3} >= pi); need omega < {:.4}",
                    self.dt,
                    self.omega * self.dt,
                    std::f64::consts::PI / self.dt
                ),
            ));
        }
        if !self.zeta.is_finite() {
            return Err(invalid(
                "--zeta",
                self.zeta,
                "must be a finite number (1/s)",
            ));
        }
        let t_end = (self.frames - 1) as f64 * self.dt;
        let growth = (-self.zeta * t_end).exp().max(1.0);
        if AMPLITUDE_MAX * growth > 1.0 {
            return Err(invalid(
                "--zeta",
                self.zeta,
                format!(
                    "a negative decay rate makes the amplitude grow {growth:.3}x by the last frame, pushing the object out of the frame; need zeta >= 0 for {} frames at dt {}",
                    self.frames, self.dt
                ),
            ));
        }
        self.check_size()
    }

    /// Checks --noise and the memory the dataset needs.
    fn check_size(self) -> Result<GenConfig, ConfigError> {
        if !(self.noise.is_finite() && (0.0..=1.0).contains(&self.noise)) {
            return Err(invalid(
                "--noise",
                self.noise,
                "must be in [0, 1] (grey levels)",
            ));
        }
        let bytes = (self.samples as u64)
            .saturating_mul(self.frames as u64)
            .saturating_mul((self.size * self.size) as u64)
            .saturating_mul(4);
        if bytes > MAX_BYTES {
            return Err(invalid(
                "--samples",
                self.samples,
                format!(
                    "{} × {} frames × {}² pixels needs {:.1} GiB, more than the 8 GiB limit; lower --samples, --frames or --size",
                    self.samples,
                    self.frames,
                    self.size,
                    bytes as f64 / (1u64 << 30) as f64
                ),
            ));
        }
        Ok(self)
    }

    /// [N, T, C, H, W].
    pub fn shape(&self) -> [usize; 5] {
        [self.samples, self.frames, 1, self.size, self.size]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn defaults() -> GenConfig {
        GenConfig {
            scenario: Scenario::Intensity,
            out: "data".into(),
            samples: 500,
            frames: 20,
            size: 50,
            dt: 0.2,
            omega: 2.0,
            zeta: 0.04,
            seed: 0,
            noise: 0.0,
            force: false,
            params: Default::default(),
        }
    }

    #[test]
    fn defaults_are_valid_and_each_bad_flag_is_named() {
        assert!(defaults().validate().is_ok());
        let cases: Vec<(GenConfig, &str)> = vec![
            (
                GenConfig {
                    samples: 0,
                    ..defaults()
                },
                "--samples",
            ),
            (
                GenConfig {
                    frames: 2,
                    ..defaults()
                },
                "--frames",
            ),
            (
                GenConfig {
                    size: 7,
                    ..defaults()
                },
                "--size",
            ),
            (
                GenConfig {
                    dt: 0.0,
                    ..defaults()
                },
                "--dt",
            ),
            (
                GenConfig {
                    dt: f64::NAN,
                    ..defaults()
                },
                "--dt",
            ),
            (
                GenConfig {
                    omega: 20.0,
                    ..defaults()
                },
                "--omega",
            ),
            (
                GenConfig {
                    zeta: -0.5,
                    ..defaults()
                },
                "--zeta",
            ),
            (
                GenConfig {
                    noise: -0.1,
                    ..defaults()
                },
                "--noise",
            ),
            (
                GenConfig {
                    samples: 1_000_000,
                    ..defaults()
                },
                "--samples",
            ),
        ];
        for (cfg, flag) in cases {
            let e = cfg.validate().unwrap_err();
            assert_eq!(e.flag, flag, "{e}");
        }
    }
}
