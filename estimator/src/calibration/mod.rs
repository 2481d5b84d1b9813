//! From latent units to SI units. Scale-free parameters (rates, g/L) are SI as learned;
//! parameters in latent units (Torricelli's k, the constant accelerations) need the latent's
//! scale α (z = α·q + c for the physical quantity q), which two or more reference frames of
//! known q give: `--reference CLIP:FRAME=VALUE,...`, or meta.json for `gen` data. This module
//! holds the resolved `Calibration` and the helpers the models' `derive` use; `positions.rs`
//! the bodies' positions of a vector latent.

mod plane;
mod positions;
mod stick;

use physvid_shared::cli::num;
use physvid_shared::AffineFit;
pub use plane::Plane;
pub use positions::{position_scale, POSITION_FIT_R2};
pub use stick::Stick;

/// What turns latent units into SI units, resolved from the flags and meta.json.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct Calibration {
    /// (clip, frame, physical value) of reference frames.
    pub reference: Vec<(usize, usize, f64)>,
    /// (clip, frame, body positions x1, y1, x2, y2, …) of reference frames of a vector latent.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub positions: Vec<(usize, usize, Vec<f64>)>,
    pub incline_deg: Option<f64>,
    pub g: f64,
    /// Where the reference frames came from: "flags", "meta.json" or "none".
    pub source: String,
    /// Where the incline's angle and g came from: the flag, "meta.json", or (g) "default".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub incline_source: Option<&'static str>,
    pub g_source: &'static str,
}

/// The largest reference value taken (SI): a million metres or radians is no measurement.
pub const MAX_REFERENCE: f64 = 1e6;

/// What a model's answers can be calibrated by (each given by one flag of the command line or
/// by meta.json); a model lists those it reads (`ModelInfo::calibration`), and the others are
/// refused for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CalibrationInput {
    /// The physical quantity at reference frames or times (`--reference`).
    Reference,
    /// An incline's angle (`--incline-deg`).
    InclineDeg,
    /// The gravitational acceleration (`--g`).
    G,
}

impl CalibrationInput {
    pub const ALL: [CalibrationInput; 3] = [
        CalibrationInput::Reference,
        CalibrationInput::InclineDeg,
        CalibrationInput::G,
    ];

    /// The flag (and the request's field) that gives it, as written on the command line.
    pub fn flag(self) -> &'static str {
        match self {
            CalibrationInput::Reference => "--reference",
            CalibrationInput::InclineDeg => "--incline-deg",
            CalibrationInput::G => "--g",
        }
    }
}

/// A point of the displayed frame `p` (`X,Y`, pixels from its top left) of the flag's value
/// `text`, as `--stick` and `--plane` give them; `bad` the message for what is no point.
fn frame_point(
    text: &str,
    p: &str,
    what: &str,
    bad: impl Fn() -> String,
) -> Result<(f64, f64), String> {
    let (x, y) = p.split_once(',').ok_or_else(&bad)?;
    let x: f64 = x.trim().parse().map_err(|_| bad())?;
    let y: f64 = y.trim().parse().map_err(|_| bad())?;
    if !(x.is_finite() && y.is_finite() && x >= 0.0 && y >= 0.0) {
        return Err(format!(
            "'{text}': the {what} {},{} must be in the frame (pixels from its top left, 0 or \
             more)",
            num(x),
            num(y)
        ));
    }
    Ok((x, y))
}

/// Refused where one of `points` (the flag's `what`s) lies outside a `width`×`height` frame,
/// naming it.
fn within_frame(
    flag: &str,
    what: &str,
    points: &[(f64, f64)],
    width: usize,
    height: usize,
) -> Result<(), String> {
    match points
        .iter()
        .find(|p| p.0 > width as f64 || p.1 > height as f64)
    {
        Some(p) => Err(format!(
            "{flag}: the {what} {},{} is outside the {width}×{height} frame; give pixels of the \
             frame as displayed (an image viewer's coordinates)",
            num(p.0),
            num(p.1)
        )),
        None => Ok(()),
    }
}

/// Gravitational acceleration assumed when neither `--g` nor meta.json gives it (m/s²).
pub const DEFAULT_G: f64 = 9.81;

impl Calibration {
    /// The flags' reference frames, falling back on meta.json's; `--incline-deg` and `--g`
    /// likewise (g defaults to [`DEFAULT_G`]).
    pub fn resolve(
        reference: &[(usize, usize, f64)],
        positions: &[(usize, usize, Vec<f64>)],
        times_given: bool,
        incline_deg: Option<f64>,
        g: Option<f64>,
        meta: Option<&physvid_shared::Calibration>,
    ) -> Calibration {
        let (meta_points, meta_bodies) = meta.map_or((&[][..], &[][..]), |m| {
            (&m.reference_points[..], &m.reference_positions[..])
        });
        let meta_refs: Vec<_> = meta_points
            .iter()
            .map(|p| (p.clip, p.frame, p.value))
            .collect();
        let meta_positions: Vec<_> = meta_bodies
            .iter()
            .map(|p| (p.clip, p.frame, p.positions.clone()))
            .collect();
        let flags = !reference.is_empty() || !positions.is_empty() || times_given;
        let (reference, positions, source) = if flags {
            (reference.to_vec(), positions.to_vec(), "flags")
        } else if !meta_refs.is_empty() || !meta_positions.is_empty() {
            (meta_refs, meta_positions, "meta.json")
        } else {
            (Vec::new(), Vec::new(), "none")
        };
        let meta_incline = meta.and_then(|m| m.incline_deg);
        let meta_g = meta.and_then(|m| m.g);
        Calibration {
            reference,
            positions,
            incline_deg: incline_deg.or(meta_incline),
            incline_source: match (incline_deg, meta_incline) {
                (Some(_), _) => Some("--incline-deg"),
                (None, Some(_)) => Some("meta.json"),
                (None, None) => None,
            },
            g: g.or(meta_g).unwrap_or(DEFAULT_G),
            g_source: match (g, meta_g) {
                (Some(_), _) => "--g",
                (None, Some(_)) => "meta.json",
                (None, None) => "default",
            },
            source: source.into(),
        }
    }

    /// Checks the reference values: finite and within ±[`MAX_REFERENCE`], each frame once, two
    /// or more frames of different values, and none below zero where the quantity cannot be
    /// (`nonnegative`: what it is, e.g. Torricelli's water level).
    pub fn check_values(&self, nonnegative: Option<&str>) -> Result<(), String> {
        let origin = self.origin();
        for (i, &(c, f, v)) in self.reference.iter().enumerate() {
            if v.is_nan() || v.abs() > MAX_REFERENCE {
                return Err(format!(
                    "{origin} {c}:{f}={}: must be within ±{MAX_REFERENCE:e} (SI units: rad, m, relative brightness)",
                    num(v)
                ));
            }
            if let (Some(what), true) = (nonnegative, v < 0.0) {
                return Err(format!(
                    "{origin} {c}:{f}={}: below zero, and {what} cannot be",
                    num(v)
                ));
            }
            if let Some((_, _, v2)) = self.reference[..i]
                .iter()
                .find(|(c2, f2, _)| (*c2, *f2) == (c, f))
            {
                return Err(format!(
                    "{origin} {c}:{f} is given twice ({} and {}); give each frame once",
                    num(*v2),
                    num(v)
                ));
            }
        }
        match self.reference.as_slice() {
            [] => Ok(()),
            [(c, f, _)] => Err(format!(
                "{origin}: one frame ({c}:{f}) gives no scale; give two or more frames of different values"
            )),
            [(_, _, v), rest @ ..] if rest.iter().all(|r| r.2 == *v) => Err(format!(
                "{origin}: every frame has the value {}; the scale needs two or more different values",
                num(*v)
            )),
            _ => Ok(()),
        }
    }

    /// How a reference point is named in messages: the flag or the file it came from.
    pub fn origin(&self) -> &'static str {
        if self.source == "flags" {
            "--reference"
        } else {
            "meta.json reference point"
        }
    }

    /// α of z = α·q + c, least squares over the reference frames; `None` with fewer than two
    /// distinct values.
    pub fn latent_scale(&self, latents: &[f64]) -> Option<f64> {
        let q: Vec<f64> = self.reference.iter().map(|r| r.2).collect();
        slope(&q, latents)
    }

    /// Torricelli's scale: the slope q of √u against √h over the reference frames, for the
    /// block's u = |z − base|. The law is invariant under √u = p + q·√h (any such latent drains
    /// by the same law, with k_latent = q·k), so this, unlike α of an affine latent, holds
    /// whichever p the encoder settled on.
    pub fn root_scale(&self, latents: &[f64], base: f64) -> Option<f64> {
        if self.reference.iter().any(|r| r.2 < 0.0) {
            return None;
        }
        let root_h: Vec<f64> = self.reference.iter().map(|r| r.2.sqrt()).collect();
        let root_u: Vec<f64> = latents.iter().map(|z| (z - base).abs().sqrt()).collect();
        slope(&root_h, &root_u)
    }
}

/// Least-squares slope of `y` against `x`; `None` unless both vary and the slope is not 0
/// (it divides the latent-unit answers).
fn slope(x: &[f64], y: &[f64]) -> Option<f64> {
    AffineFit::of(x, y).map(|f| f.slope).filter(|s| *s != 0.0)
}

/// The latent read through the physics at the calibration's reference frames: one number at
/// each scalar reference, and the whole latent at each body-position reference.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct Readings {
    pub values: Vec<f64>,
    pub positions: Vec<Vec<f64>>,
}

/// One reported value.
#[derive(Debug, Clone, serde::Serialize)]
pub struct DerivedValue {
    pub name: String,
    pub estimate: f64,
    /// "SI" or "latent".
    pub units: &'static str,
    /// The unit's symbol ("m/s^2", "1/s", "1" for a pure number, "px"; "latent" in latent
    /// units).
    pub unit: &'static str,
    /// Key of the ground truth in meta.json's model parameters.
    #[serde(skip)]
    pub truth_key: Option<&'static str>,
}

impl DerivedValue {
    /// A value in SI units, compared with meta.json's `truth_key` when given.
    pub fn si(
        name: &str,
        unit: &'static str,
        estimate: f64,
        truth_key: Option<&'static str>,
    ) -> DerivedValue {
        DerivedValue {
            name: name.into(),
            estimate,
            units: "SI",
            unit,
            truth_key,
        }
    }

    /// A value in latent units (no ground truth to compare with).
    pub fn latent(name: &str, estimate: f64) -> DerivedValue {
        DerivedValue {
            name: name.into(),
            estimate,
            units: "latent",
            unit: "latent",
            truth_key: None,
        }
    }
}

/// The warning for an answer left in latent units for want of reference frames.
pub fn needs_reference(what: &str) -> String {
    format!(
        "{what} is reported in latent units only: the latent's scale is not determined by \
         the video; give the physical value at two or more frames with --reference \
         CLIP:FRAME=VALUE,... to get it in SI units"
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use physvid_shared::ReferencePoint;

    #[test]
    fn flags_win_over_meta_json_and_g_defaults() {
        let meta = physvid_shared::Calibration {
            g: Some(9.7),
            incline_deg: Some(25.0),
            reference_points: vec![ReferencePoint {
                clip: 1,
                frame: 2,
                value: 0.5,
            }],
            ..Default::default()
        };
        let with_meta = |r: &[(usize, usize, f64)], times, incline, g| {
            Calibration::resolve(r, &[], times, incline, g, Some(&meta))
        };
        let c = with_meta(&[], false, None, None);
        assert_eq!(
            (c.reference.clone(), c.g, c.source.as_str()),
            (vec![(1, 2, 0.5)], 9.7, "meta.json")
        );
        assert_eq!(c.incline_deg, Some(25.0));
        let c = with_meta(&[(0, 0, 1.0)], false, Some(10.0), Some(9.8));
        assert_eq!(
            (c.reference, c.g, c.incline_deg),
            (vec![(0, 0, 1.0)], 9.8, Some(10.0))
        );
        // `--reference` times alone (placed on frames once a recording is cut) are flags too.
        let c = with_meta(&[], true, None, None);
        assert_eq!((c.reference.len(), c.source.as_str()), (0, "flags"));
        let c = Calibration::resolve(&[], &[], false, None, None, None);
        assert_eq!((c.g, c.source.as_str()), (DEFAULT_G, "none"));
    }
}
