//! From the block's parameters to answers in SI units. Scale-free parameters (rates, g/L) are
//! SI as learned; parameters in latent units (Torricelli's k, the constant accelerations) need
//! the latent's scale α (z = α·q + c for the physical quantity q), which two or more reference
//! frames of known q give: `--reference CLIP:FRAME=VALUE,...`, or meta.json for `gen` data.

use crate::config::{EstimateConfig, ModelKind};
use crate::report::AffineFit;
use physvid_shared::DatasetMeta;

/// What turns latent units into SI units.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct Calibration {
    /// (clip, frame, physical value) of reference frames.
    pub reference: Vec<(usize, usize, f64)>,
    pub incline_deg: Option<f64>,
    pub g: f64,
    /// Where it came from: "flags", "meta.json" or "none".
    pub source: String,
}

/// One reported value.
#[derive(Debug, Clone, serde::Serialize)]
pub struct DerivedValue {
    pub name: String,
    pub estimate: f64,
    /// "SI" or "latent".
    pub units: &'static str,
    /// Key of the ground truth in meta.json's model parameters.
    #[serde(skip)]
    pub truth_key: Option<&'static str>,
}

/// The calibration from flags, falling back on meta.json.
pub fn resolve(cfg: &EstimateConfig, meta: Option<&DatasetMeta>) -> Calibration {
    let cal = meta.map(|m| &m.calibration);
    let from_meta = |k: &str| cal.and_then(|c| c.get(k)).and_then(|v| v.as_f64());
    let meta_refs: Vec<(usize, usize, f64)> = cal
        .and_then(|c| c.get("reference_points"))
        .and_then(|v| v.as_array())
        .map(|a| {
            a.iter()
                .filter_map(|p| {
                    Some((
                        p.get("clip")?.as_u64()? as usize,
                        p.get("frame")?.as_u64()? as usize,
                        p.get("value")?.as_f64()?,
                    ))
                })
                .collect()
        })
        .unwrap_or_default();
    let (reference, source) = if !cfg.reference.is_empty() {
        (cfg.reference.clone(), "flags")
    } else if !meta_refs.is_empty() {
        (meta_refs, "meta.json")
    } else {
        (Vec::new(), "none")
    };
    Calibration {
        reference,
        incline_deg: cfg.incline_deg.or_else(|| from_meta("incline_deg")),
        g: cfg.g.or_else(|| from_meta("g")).unwrap_or(9.81),
        source: source.into(),
    }
}

/// α of z = α·q + c, least squares over the reference frames; `None` with fewer than two
/// distinct values.
fn latent_scale(cal: &Calibration, latents: &[f64]) -> Option<f64> {
    let q: Vec<f64> = cal.reference.iter().map(|r| r.2).collect();
    slope(&q, latents)
}

/// Torricelli's scale: the slope q of √u against √h over the reference frames, for the block's
/// u = |z − base|. The law is invariant under √u = p + q·√h (any such latent drains by the same
/// law, with k_latent = q·k), so this, unlike α of an affine latent, holds whichever p the
/// encoder settled on.
fn root_scale(cal: &Calibration, latents: &[f64], base: f64) -> Option<f64> {
    if cal.reference.iter().any(|r| r.2 < 0.0) {
        return None;
    }
    let root_h: Vec<f64> = cal.reference.iter().map(|r| r.2.sqrt()).collect();
    let root_u: Vec<f64> = latents.iter().map(|z| (z - base).abs().sqrt()).collect();
    slope(&root_h, &root_u)
}

/// Least-squares slope of `y` against `x`; `None` unless both vary and the slope is not 0
/// (it divides the latent-unit answers).
fn slope(x: &[f64], y: &[f64]) -> Option<f64> {
    AffineFit::of(x, y).map(|f| f.slope).filter(|s| *s != 0.0)
}

/// The reported values of `model` from its block parameters, and warnings for answers left in
/// latent units.
pub fn derive(
    model: ModelKind,
    params: &[f64],
    cal: &Calibration,
    reference_latents: &[f64],
) -> (Vec<DerivedValue>, Vec<String>) {
    let v = |name: &str, estimate: f64, units: &'static str, truth_key: Option<&'static str>| {
        DerivedValue {
            name: name.to_string(),
            estimate,
            units,
            truth_key,
        }
    };
    let alpha = latent_scale(cal, reference_latents);
    let mut warnings = Vec::new();
    let mut need_alpha = |what: &str| {
        warnings.push(format!(
            "{what} is reported in latent units only: the latent's scale is not determined by \
             the video; give the physical value at two or more frames with --reference \
             CLIP:FRAME=VALUE,... to get it in SI units"
        ));
    };
    let out = match model {
        ModelKind::DampedOscillator => vec![
            v("gamma0", params[0], "SI", Some("gamma0")),
            v("gamma1", params[1], "SI", Some("gamma1")),
        ],
        ModelKind::Pendulum => {
            if cal.reference.len() < 2 {
                warnings.push(
                    "the pendulum's angle scale was learned, not calibrated: at finite amplitude \
                     the period depends on the amplitude, so L depends on that scale, which the \
                     video pins only weakly; give the angle in rad at two or more frames with \
                     --reference CLIP:FRAME=ANGLE,... to calibrate it"
                        .into(),
                );
            }
            vec![
                v("length", cal.g / params[0], "SI", Some("length")),
                v("damping", params[1], "SI", Some("damping")),
                v("g_over_l", params[0], "SI", None),
                v("angle_scale", params[2], "latent", None),
                v("angle_offset", params[3], "latent", None),
            ]
        }
        ModelKind::Led => vec![
            v("gamma", params[0], "SI", Some("gamma")),
            v("offset", params[1], "latent", None),
        ],
        ModelKind::Torricelli => {
            let mut rows = vec![
                v("k_latent", params[0], "latent", None),
                v("base", params[1], "latent", None),
            ];
            match root_scale(cal, reference_latents, params[1]) {
                Some(q) => rows.insert(0, v("k", params[0] / q.abs(), "SI", Some("k"))),
                None => need_alpha("Torricelli's k"),
            }
            rows
        }
        ModelKind::SlidingBlock => {
            let mut rows = vec![v("acceleration_latent", params[0], "latent", None)];
            match alpha {
                Some(a) => {
                    let acc = params[0] / a;
                    rows.insert(0, v("acceleration", acc, "SI", Some("acceleration")));
                    match cal.incline_deg {
                        Some(deg) => {
                            let r = deg.to_radians();
                            rows.insert(0, v("mu", r.tan() - acc / (cal.g * r.cos()), "SI", Some("mu")));
                        }
                        None => warnings.push(
                            "the friction coefficient needs the incline's angle: pass --incline-deg"
                                .into(),
                        ),
                    }
                }
                None => need_alpha("the block's acceleration (and so μ)"),
            }
            rows
        }
        ModelKind::FreeFall => {
            let mut rows = vec![v("acceleration_latent", params[0], "latent", None)];
            match alpha {
                Some(a) => rows.insert(0, v("g", params[0] / a, "SI", Some("g"))),
                None => need_alpha("the fall's acceleration g"),
            }
            rows
        }
    };
    (out, warnings)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_from_reference_frames_turns_latent_units_into_si() {
        let cal = Calibration {
            reference: vec![(0, 0, 0.07), (3, 9, 0.01)],
            incline_deg: None,
            g: 9.81,
            source: "flags".into(),
        };
        // z = −40·h + 1 → α = −40, the empty tank's latent (base) is 1; k_latent = k·√40.
        let latents = [-40.0 * 0.07 + 1.0, -40.0 * 0.01 + 1.0];
        let (rows, warnings) = derive(
            ModelKind::Torricelli,
            &[0.0128 * 40f64.sqrt(), 1.0],
            &cal,
            &latents,
        );
        assert!(warnings.is_empty());
        assert_eq!(rows[0].name, "k");
        assert!((rows[0].estimate - 0.0128).abs() < 1e-12);
        // A latent bent by the law's own symmetry, √u = p + q·√h (here p = 0.05, q = 3, base
        // 0.2 with u = −(z − base)), still gives the SI k.
        let (p, q, k) = (0.05f64, 3.0f64, 0.0128);
        let latents = [0.07f64, 0.01].map(|h| 0.2 - (p + q * h.sqrt()).powi(2));
        let (rows, _) = derive(ModelKind::Torricelli, &[q * k, 0.2], &cal, &latents);
        assert!((rows[0].estimate - k).abs() < 1e-12, "{}", rows[0].estimate);
        let (rows, warnings) = derive(ModelKind::FreeFall, &[3.0], &Calibration::default(), &[]);
        assert_eq!(rows[0].units, "latent");
        assert!(warnings[0].contains("--reference"), "{warnings:?}");
    }
}
