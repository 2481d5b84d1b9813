//! `meta.json`: the ground truth and provenance written beside `frames.npy`.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Identifies the file format; bumped on any incompatible change.
pub const FORMAT_NAME: &str = "physvid-dataset";
pub const FORMAT_VERSION: u32 = 1;

/// The largest ground-truth value a data set may hold (a value beyond it is no physical one):
/// `gen` refuses to write one, `estimate` to read one.
pub const MAX_TRUTH: f64 = 1e15;

/// The dynamics model behind a dataset and its true parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelSpec {
    /// Model name as `estimate --model` spells it, e.g. `damped-oscillator`.
    pub name: String,
    /// True parameters by name (for the oscillator: omega, zeta, gamma0, gamma1).
    pub parameters: BTreeMap<String, f64>,
    /// The model file's text, for data made with `gen --model FILE.toml`: `estimate DIR` reads
    /// the model from it without the file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
}

/// Per-sample draws of the initial condition, by name (the oscillator's `amplitude` and
/// `phase`; a Delfys system's start time, initial angle, ...), written as a flat JSON object.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct SampleTruth(pub BTreeMap<String, f64>);

impl SampleTruth {
    /// A truth from name/value pairs.
    pub fn from_pairs<'a>(pairs: impl IntoIterator<Item = (&'a str, f64)>) -> SampleTruth {
        SampleTruth(pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect())
    }
}

/// Which program and version wrote the dataset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GeneratorInfo {
    pub name: String,
    pub version: String,
}

/// Everything `meta.json` holds. Field order is the order written.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DatasetMeta {
    pub format: String,
    pub format_version: u32,
    pub generator: GeneratorInfo,
    pub scenario: String,
    pub model: ModelSpec,
    /// Time between consecutive frames, seconds.
    pub dt: f64,
    /// [N, T, C, H, W] of `frames.npy`.
    pub shape: [usize; 5],
    pub seed: u64,
    /// Standard deviation of the Gaussian pixel noise added before clipping to [0, 1].
    pub noise: f64,
    /// How the latent z maps to the picture, in words.
    pub latent_mapping: String,
    /// What a user would measure to turn latent-unit answers into SI units (pixels per metre,
    /// focal length, incline angle, reference values of the physical quantity at given frames);
    /// empty for the oscillator scenes.
    #[serde(default, skip_serializing_if = "Calibration::is_empty")]
    pub calibration: Calibration,
    /// Frames per second of the (virtual) camera: 1/dt.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fps: Option<f64>,
    /// Time of each clip's first frame since the recording started (s), for systems released
    /// from rest at the start of the recording (sliding block, free fall): what a user reads off
    /// the frame counter, not a label. It pins the release, without which motion from rest is
    /// not identified (the latent √s is exactly linear in time and fits z'' = 0 too).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clip_start_times: Option<Vec<f64>>,
    /// Distributions the per-sample amplitude and phase are drawn from, in words.
    pub sampling: String,
    pub samples: Vec<SampleTruth>,
    /// Numbers per frame in `latents`: 1 (one physical quantity), or more (the spring: both
    /// bodies' x, y in pixels). Written only when not 1.
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub latent_dims: usize,
    /// Ground-truth latent of every sample (outer) and frame (inner; `latent_dims` numbers per
    /// frame, frame-major).
    pub latents: Vec<Vec<f64>>,
    /// Perturbations applied after rendering (`gen --perturb`), in the order applied.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub perturbations: Vec<PerturbationSpec>,
}

/// One perturbation of a data set: its name, level (1–5) and what it did, in words.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PerturbationSpec {
    pub name: String,
    pub level: u8,
    pub description: String,
}

fn one() -> usize {
    1
}

fn is_one(v: &usize) -> bool {
    *v == 1
}

/// One reference frame of the calibration: the physical quantity (angle, level, distance,
/// brightness; SI units) at frame `frame` of clip `clip`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ReferencePoint {
    pub clip: usize,
    pub frame: usize,
    pub value: f64,
}

/// The `calibration` object of meta.json: what a user would measure in the scene. Written by
/// `gen`, read by `estimate`; a malformed entry is an error, never dropped. Fields are in
/// alphabetical order, the order they are written.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Calibration {
    /// Free fall: the camera's focal length in pixels per metre of object size at 1 m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub focal_px_per_m: Option<f64>,
    /// Gravitational acceleration of the scene (m/s²).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub g: Option<f64>,
    /// Free fall: the ball's distance from the camera at the release (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub h0: Option<f64>,
    /// Sliding block: the incline's angle (degrees).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub incline_deg: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pixels_per_metre: Option<f64>,
    /// What the reference values measure, in words (e.g. "water level h (m)").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub quantity: Option<String>,
    /// Free fall: the ball's radius (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reference_points: Vec<ReferencePoint>,
    /// Positions of the bodies (x, y per body, in pixels) at reference frames, for latents of
    /// several numbers per frame (the spring).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reference_positions: Vec<PositionPoint>,
}

/// Body positions at one reference frame: (x, y) of each body in pixels, x1, y1, x2, y2, ….
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PositionPoint {
    pub clip: usize,
    pub frame: usize,
    pub positions: Vec<f64>,
}

/// The largest gravitational acceleration taken (m/s²): the Sun's surface has 274.
pub const MAX_G: f64 = 1000.0;

/// The largest length, distance or pixel scale taken (SI units or pixels per metre).
pub const MAX_SCALE: f64 = 1e9;

impl Calibration {
    /// Whether nothing was measured (the oscillator scenes).
    pub fn is_empty(&self) -> bool {
        *self == Calibration::default()
    }

    /// Refuses what no measurement gives: g outside (0, [`MAX_G`]], an incline outside
    /// (0°, 90°) (flat, it does not slide; vertical, it falls), a scale, distance or radius that
    /// is not positive or beyond [`MAX_SCALE`], reference values or positions that are not
    /// finite. The message names the key.
    pub fn check(&self) -> Result<(), String> {
        if let Some(g) = self.g {
            if !(g.is_finite() && g > 0.0 && g <= MAX_G) {
                return Err(format!(
                    "calibration.g is {g}: gravity must be in (0, {MAX_G}] m/s² (Earth: 9.81)"
                ));
            }
        }
        if let Some(a) = self.incline_deg {
            if !(a.is_finite() && a > 0.0 && a < 90.0) {
                return Err(format!(
                    "calibration.incline_deg is {a}: an incline must be between 0° and 90° \
                     (flat, nothing slides; vertical, it falls)"
                ));
            }
        }
        for (key, v) in [
            ("focal_px_per_m", self.focal_px_per_m),
            ("h0", self.h0),
            ("pixels_per_metre", self.pixels_per_metre),
            ("radius", self.radius),
        ] {
            if let Some(v) = v {
                if !(v.is_finite() && v > 0.0 && v <= MAX_SCALE) {
                    return Err(format!(
                        "calibration.{key} is {v}: must be a positive number up to {MAX_SCALE:e}"
                    ));
                }
            }
        }
        if let Some(p) = self.reference_points.iter().find(|p| !p.value.is_finite()) {
            return Err(format!(
                "calibration.reference_points: clip {} frame {} has the value {}, not a finite \
                 number",
                p.clip, p.frame, p.value
            ));
        }
        if let Some(p) = self
            .reference_positions
            .iter()
            .find(|p| p.positions.iter().any(|v| !v.is_finite()))
        {
            return Err(format!(
                "calibration.reference_positions: clip {} frame {} has a position that is not a \
                 finite number",
                p.clip, p.frame
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calibration_reads_what_it_writes_and_refuses_malformed_points() {
        let c = Calibration {
            g: Some(9.81),
            quantity: Some("angle theta (rad)".into()),
            reference_points: vec![ReferencePoint {
                clip: 3,
                frame: 7,
                value: 0.25,
            }],
            ..Default::default()
        };
        let text = serde_json::to_string(&c).unwrap();
        assert_eq!(
            text,
            r#"{"g":9.81,"quantity":"angle theta (rad)","reference_points":[{"clip":3,"frame":7,"value":0.25}]}"#
        );
        assert_eq!(serde_json::from_str::<Calibration>(&text).unwrap(), c);
        for bad in [
            r#"{"reference_points":[{"clip":3,"value":0.25}]}"#,
            r#"{"reference_points":[{"clip":-1,"frame":0,"value":0.25}]}"#,
            r#"{"reference_points":[{"clip":1,"frame":0,"value":"high"}]}"#,
            r#"{"g":"9.81"}"#,
        ] {
            assert!(serde_json::from_str::<Calibration>(bad).is_err(), "{bad}");
        }
    }
}
