//! `GenConfig`: the validated settings of one `gen` run.

use crate::error::{invalid, ConfigError};
use crate::perturb::Perturbed;
use crate::scenes::{Params, SceneRef};
use physvid_shared::cli::num;
use physvid_shared::dynamics::DT_RANGE;
use std::path::PathBuf;

/// Largest dataset `gen` will hold in memory.
pub const MAX_BYTES: u64 = 8 << 30;

/// Largest frame side (pixels).
pub const MAX_SIZE: usize = 4096;

/// Settings of one generation run; build with [`GenConfig::new`], change fields, then
/// [`GenConfig::validate`].
#[derive(Debug, Clone, PartialEq)]
pub struct GenConfig {
    pub scene: SceneRef,
    pub out: PathBuf,
    pub samples: usize,
    pub frames: usize,
    pub size: usize,
    pub dt: f64,
    pub seed: u64,
    pub noise: f64,
    pub force: bool,
    /// The scene's colour version (the spring: digit one in red, digit two in green).
    pub color: bool,
    /// The scene's parameters (SI): the oscillator's omega and zeta, or a Delfys75 system's.
    pub params: Params,
    /// Perturbations applied to every clip after rendering (`--perturb`).
    pub perturbations: Vec<Perturbed>,
}

impl GenConfig {
    /// `gen`'s defaults for `scene` into `out`: 500 clips of 50×50, the scene's clip length
    /// and dt, its first setting, seed 0, no noise.
    pub fn new(scene: SceneRef, out: impl Into<PathBuf>) -> GenConfig {
        let (frames, dt) = scene.default_clip();
        GenConfig {
            scene,
            out: out.into(),
            samples: 500,
            frames,
            size: scene.default_size(),
            dt,
            seed: 0,
            noise: 0.0,
            force: false,
            color: false,
            params: scene.params(1),
            perturbations: Vec::new(),
        }
    }

    /// Checks every field; the first problem found is returned.
    pub fn validate(self) -> Result<GenConfig, ConfigError> {
        if let Err(e) = physvid_shared::atomic::check_writable_dir("--out", &self.out) {
            let reason = e
                .strip_prefix(&format!("--out {}: ", self.out.display()))
                .unwrap_or(&e)
                .to_string();
            return Err(invalid("--out", self.out.display(), reason));
        }
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
        if !(8..=MAX_SIZE).contains(&self.size) {
            return Err(invalid(
                "--size",
                self.size,
                format!("must be from 8 to {MAX_SIZE} pixels"),
            ));
        }
        let (lo, hi) = DT_RANGE;
        if !(lo..=hi).contains(&self.dt) {
            return Err(invalid(
                "--dt",
                num(self.dt),
                format!("must be from {lo:e} to {hi} s (a million frames a second to one a day)"),
            ));
        }
        self.scene
            .validate(&self.params, self.frames, self.dt, self.size)?;
        // The truth meta.json would hold: what `estimate` reads, refused alike here.
        let max = physvid_shared::meta::MAX_TRUTH;
        let truth = self.scene.model_parameters(&self.params);
        if let Some((name, v)) = truth.iter().find(|(_, v)| v.is_nan() || v.abs() > max) {
            return Err(invalid(
                "--set",
                format!("{name}={}", num(*v)),
                format!("not a physical value (within ±{max:e}): estimate could not read it"),
            ));
        }
        if !(self.noise.is_finite() && (0.0..=1.0).contains(&self.noise)) {
            return Err(invalid(
                "--noise",
                self.noise,
                "must be in [0, 1] (grey levels)",
            ));
        }
        let bytes = (self.samples as u64)
            .saturating_mul(self.frames as u64)
            .saturating_mul(self.scene.channels(self.color) as u64)
            .saturating_mul((self.size as u64).saturating_mul(self.size as u64))
            .saturating_mul(4);
        if bytes > MAX_BYTES {
            return Err(invalid(
                "--samples × --frames × --size²",
                format!("{} × {} × {}²", self.samples, self.frames, self.size),
                format!(
                    "{} clips × {} frames × {}² pixels needs {:.1} GiB, more than the 8 GiB limit; lower --samples, --frames or --size",
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
        let c = self.scene.channels(self.color);
        [self.samples, self.frames, c, self.size, self.size]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn defaults() -> GenConfig {
        GenConfig::new(SceneRef::by_name("intensity").unwrap(), "data")
    }

    fn with(name: &str, v: f64) -> GenConfig {
        let mut c = defaults();
        c.params.insert(name.into(), v);
        c
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
            (with("omega", 20.0), "--omega"),
            (with("zeta", -0.5), "--zeta"),
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
                "--samples × --frames × --size²",
            ),
            // Used to blame --samples.
            (
                GenConfig {
                    size: 100_000,
                    ..defaults()
                },
                "--size",
            ),
            // All frames identical.
            (
                GenConfig {
                    dt: 1e-300,
                    ..defaults()
                },
                "--dt",
            ),
            // Still after the first frame.
            (with("zeta", 1e9), "--zeta"),
        ];
        for (cfg, flag) in cases {
            let e = cfg.validate().unwrap_err();
            assert_eq!(e.flag, flag, "{e}");
        }
    }
}
