//! The Delfys75 systems (appendix A.6, Table 4) as synthetic scenes: `DelfysSystem`, one file
//! per system, and `Delfys`, which adds what they share: `--setting`, the finiteness check, the
//! blank frame, and the calibration a user would measure (the scene's scale and the physical
//! quantity at five reference frames).

use super::{Params, Scene};
use crate::error::{invalid, ConfigError};
use crate::render::Canvas;
use physvid_shared::systems::System;
use physvid_shared::{Calibration, ReferencePoint, SampleTruth};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Standard gravity used by the scenes (m/s²).
pub const G: f64 = 9.81;

/// Fractions of the physical quantity's range at which `reference_points` are taken.
pub const REFERENCE_FRACTIONS: [f64; 5] = [0.1, 0.3, 0.5, 0.7, 0.9];

/// Text for `meta.json` describing the draws of the Delfys75 scenes.
pub const DELFYS_SAMPLING_TEXT: &str = "per clip, from ChaCha8 stream i (seeded with --seed) for \
     sample i: a start time uniform over the part of the motion a whole clip fits in (the pendulum: \
     an amplitude uniform in [amplitude_min_deg, amplitude_max_deg], an initial angle uniform in \
     [-amplitude, amplitude] and the direction of swing), then the pixel noise";

/// The facts about a Delfys75 system, one record per system (its file's `INFO`).
#[derive(Debug, Clone, Copy)]
pub struct SystemInfo {
    /// The physical system (shared with `estimate`): its model name, which is also the
    /// scenario's, Table 5's clip, and whether it starts from rest.
    pub system: &'static System,
    pub help: &'static str,
    /// What z is, in words (meta.json's latent_mapping).
    pub mapping_text: &'static str,
    /// What the reference values measure, in words.
    pub quantity: &'static str,
}

/// One Delfys75 system: its [`SystemInfo`], parameters, dynamics and drawing.
pub trait DelfysSystem: Sync {
    fn info(&self) -> &SystemInfo;
    /// Table 4's values for setting index 0, 1 or 2, plus the fixed quantities of the scene.
    fn setting(&self, index: usize) -> Params;
    /// The true values `estimate` recovers, as written in meta.json's model.
    fn model_parameters(&self, p: &Params) -> Params;
    /// Checks the (finite) parameters against physics and the clip's span (s).
    fn validate(&self, p: &Params, span: f64, dt: f64) -> Result<(), ConfigError>;
    /// Draws one clip: its ground truth and the physical quantity at each frame (the angle in
    /// rad, the level or distance in m, the brightness relative to its start).
    fn sample(
        &self,
        p: &Params,
        rng: &mut ChaCha8Rng,
        frames: usize,
        dt: f64,
    ) -> (SampleTruth, Vec<f64>);
    /// Pixels per metre in a `size`-pixel frame (the focal length in pixels for free fall).
    fn pixels_per_metre(&self, p: &Params, size: usize) -> f64;
    /// Draws the scene for quantity `z` over a black `out`.
    fn render(&self, p: &Params, z: f64, size: usize, canvas: &mut Canvas, out: &mut [f32]);
    /// Adds the scene's measurable constants (scale, incline, g, …) to the calibration.
    fn calibrate(&self, p: &Params, pixels_per_metre: f64, c: &mut Calibration);
}

/// A Delfys75 system as a [`Scene`].
pub struct Delfys<S>(pub S);

/// `k` of `p` must be > 0.
pub fn positive(p: &Params, k: &str) -> Result<(), ConfigError> {
    if p[k] > 0.0 {
        Ok(())
    } else {
        Err(set_error(format!("{k}={}", p[k]), "must be > 0"))
    }
}

/// A [`ConfigError`] naming `--set`.
pub fn set_error(value: impl ToString, expected: impl Into<String>) -> ConfigError {
    invalid("--set", value, expected)
}

/// A start time uniform over the part of a motion lasting `duration` s that a whole clip of
/// `frames` frames at `dt` fits in.
pub fn start_within(rng: &mut ChaCha8Rng, duration: f64, frames: usize, dt: f64) -> f64 {
    let span = (frames - 1) as f64 * dt;
    rng.random_range(0.0..=(duration - span).max(0.0))
}

/// Refuses a clip spanning `span` s of a motion that lasts only `duration` s (`what` says what
/// the motion does in that time; `value` is the parameter to blame).
pub fn fits_in_motion(
    value: String,
    what: &str,
    duration: f64,
    span: f64,
) -> Result<(), ConfigError> {
    if !duration.is_finite() {
        return Err(set_error(
            value,
            format!("{what} in a time that overflows; choose values nearer the physical range"),
        ));
    }
    if span > duration {
        return Err(set_error(
            value,
            format!(
                "{what} in {duration:.2} s, shorter than one clip ({span:.2} s); lower --frames or --dt"
            ),
        ));
    }
    Ok(())
}

/// The times of a clip's frames from `t0`.
pub fn times(t0: f64, frames: usize, dt: f64) -> impl Iterator<Item = f64> {
    (0..frames).map(move |k| t0 + k as f64 * dt)
}

impl<S: DelfysSystem> Scene for Delfys<S> {
    fn name(&self) -> &'static str {
        self.0.info().system.model
    }
    fn help(&self) -> &'static str {
        self.0.info().help
    }
    fn model_name(&self) -> &'static str {
        self.0.info().system.model
    }
    fn default_clip(&self) -> (usize, f64) {
        self.0.info().system.clip
    }
    fn params(&self, setting: u8) -> Params {
        self.0.setting((setting.clamp(1, 3) - 1) as usize)
    }
    fn accepts_set(&self) -> bool {
        true
    }
    fn validate(
        &self,
        p: &Params,
        frames: usize,
        dt: f64,
        _size: usize,
    ) -> Result<(), ConfigError> {
        for (k, v) in p {
            if !v.is_finite() {
                return Err(set_error(format!("{k}={v}"), "must be a finite number"));
            }
        }
        self.0.validate(p, (frames - 1) as f64 * dt, dt)
    }
    fn sample(
        &self,
        p: &Params,
        rng: &mut ChaCha8Rng,
        frames: usize,
        dt: f64,
        _size: usize,
    ) -> (SampleTruth, Vec<f64>) {
        self.0.sample(p, rng, frames, dt)
    }
    fn render(&self, p: &Params, z: &[f64], size: usize, canvas: &mut Canvas, out: &mut [f32]) {
        out.fill(0.0);
        self.0.render(p, z[0], size, canvas, out);
    }
    fn mapping_text(&self) -> &'static str {
        self.0.info().mapping_text
    }
    fn sampling_text(&self) -> &'static str {
        DELFYS_SAMPLING_TEXT
    }
    fn model_parameters(&self, p: &Params) -> Params {
        self.0.model_parameters(p)
    }

    /// The scene's scale, and the physical quantity at five reference frames spread over its
    /// range (those nearest to 10, 30, 50, 70 and 90 % of it), which is what turns latent units
    /// into SI units (appendix A.6 measures h0 = 7 cm and ht = 1 cm likewise; marks inside the
    /// range, rather than at its ends, where a clip's first or last frame sits, make the scale
    /// less sensitive to any one frame).
    fn calibration(&self, p: &Params, size: usize, latents: &[Vec<f64>]) -> Calibration {
        let reference_points = reference_points(latents, |z| z);
        let mut c = Calibration {
            quantity: Some(self.0.info().quantity.into()),
            reference_points,
            ..Default::default()
        };
        self.0
            .calibrate(p, self.0.pixels_per_metre(p, size), &mut c);
        c
    }

    fn fps(&self, dt: f64) -> Option<f64> {
        Some(1.0 / dt)
    }
    fn released_from_rest(&self) -> bool {
        self.0.info().system.released_from_rest
    }
}

/// Reference frames spread over the range of the quantity `value(z)` of every clip's latents:
/// those nearest to [`REFERENCE_FRACTIONS`] of it (the first such frame on ties).
pub fn reference_points(latents: &[Vec<f64>], value: impl Fn(f64) -> f64) -> Vec<ReferencePoint> {
    let value = &value;
    let all = || {
        latents
            .iter()
            .enumerate()
            .flat_map(move |(i, clip)| clip.iter().enumerate().map(move |(k, &z)| (i, k, value(z))))
    };
    let lo = all().map(|p| p.2).fold(f64::INFINITY, f64::min);
    let hi = all().map(|p| p.2).fold(f64::NEG_INFINITY, f64::max);
    REFERENCE_FRACTIONS
        .iter()
        .map(|f| {
            let target = lo + f * (hi - lo);
            // The first frame nearest the target (a strict `<` keeps ties deterministic).
            let mut best = (0, 0, f64::NAN);
            for (i, k, z) in all() {
                if best.2.is_nan() || (z - target).abs() < (best.2 - target).abs() {
                    best = (i, k, z);
                }
            }
            ReferencePoint {
                clip: best.0,
                frame: best.1,
                value: best.2,
            }
        })
        .collect()
}
