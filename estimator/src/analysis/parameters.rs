//! `ParameterResult`: one reported value with its units and, when the data's metadata knows
//! it, the ground truth and the relative error.

use super::uncertainty::SplitValue;
use crate::calibration::DerivedValue;
use crate::digits::{sig, significant};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One estimated parameter.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ParameterResult {
    pub name: String,
    pub estimate: f64,
    /// "SI" or "latent" (latent units: not determined by the video without a calibration).
    pub units: String,
    /// The unit's symbol ("m/s^2", "1/s", "1" for a pure number; "latent").
    pub unit: String,
    pub truth: Option<f64>,
    /// (estimate − truth) / truth.
    pub relative_error: Option<f64>,
    /// Its standard error from the final fit's curvature with the encoder held (clusters of
    /// clips as independent draws); `None` where it could not be computed.
    pub standard_error: Option<f64>,
    /// The value refitted on halves of the training clips (see `evidence::SplitBy`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub splits: Vec<SplitValue>,
    /// Where the value reported combines the latent's and the track's (`guide::combine`): each
    /// route's own, with its standard error.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub routes: Option<RouteValues>,
}

/// One value as each route measured it (the track's error the larger of its fit's and half
/// its halves' difference; the latent's `None` where it has none), and whether they agree; the
/// answer is the track's, the latent's its second opinion (`guide::combine`). `unlike` names
/// the rate (γ0, g/L) of the same answer where the routes disagree on it: the latent followed
/// another motion than the track, so its value here is no second opinion, though the two agree.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RouteValues {
    pub latent: f64,
    pub latent_error: Option<f64>,
    pub track: f64,
    pub track_error: f64,
    #[serde(default = "agreed")]
    pub agree: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unlike: Option<String>,
}

/// Reports written before `agree` was: every value combined agreed.
fn agreed() -> bool {
    true
}

impl ParameterResult {
    /// Where the value is the track's with the latent's beside it: each one's, in a phrase
    /// ("the track's 0.0812 ± 0.0079; the latent's 0.0629 ± 0.0038 agrees with it, 2.1 joint
    /// errors apart").
    pub fn routes_phrase(&self) -> Option<String> {
        let r = self.routes.as_ref()?;
        let latent = match r.latent_error {
            Some(e) => format!("{} ± {}", sig(r.latent), significant(e)),
            None => format!("{} (no standard error)", sig(r.latent)),
        };
        let track = format!("{} ± {}", sig(r.track), significant(r.track_error));
        // How many joint errors apart they lie, where more than one.
        let apart = r
            .latent_error
            .map(|e| (r.latent - r.track).abs() / e.hypot(r.track_error))
            .filter(|a| *a > 1.0)
            .map(|a| format!(", {} joint errors apart", significant(a)))
            .unwrap_or_default();
        Some(match (r.agree, &r.unlike) {
            (true, Some(other)) => format!(
                "the track's {track}; the latent's {latent} is no second opinion: its {other} \
                 disagrees with the track's (the routes check), so it followed another motion"
            ),
            (true, None) => {
                format!("the track's {track}; the latent's {latent} agrees with it{apart}")
            }
            (false, _) => format!(
                "the track's {track}; the latent's {latent} disagrees with it (the routes check)"
            ),
        })
    }

    /// A value in SI named `name`, in `unit`, with no truth, splits or routes: the tests'
    /// fixture.
    #[cfg(test)]
    pub fn si(name: &str, estimate: f64, unit: &str, standard_error: Option<f64>) -> Self {
        ParameterResult {
            name: name.into(),
            estimate,
            units: "SI".into(),
            unit: unit.into(),
            truth: None,
            relative_error: None,
            standard_error,
            splits: Vec::new(),
            routes: None,
        }
    }

    /// The result for a derived value, with the truth looked up in `truth` by its key.
    pub fn new(value: DerivedValue, truth: &BTreeMap<String, f64>) -> ParameterResult {
        let t = value.truth_key.and_then(|k| truth.get(k).copied());
        ParameterResult {
            relative_error: t.filter(|t| *t != 0.0).map(|t| (value.estimate - t) / t),
            name: value.name,
            estimate: value.estimate,
            units: value.units.into(),
            unit: value.unit.into(),
            truth: t,
            standard_error: None,
            splits: Vec::new(),
            routes: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_routes_phrase_says_whose_value_and_how_far_the_other() {
        let mut p = ParameterResult::si("gamma1", 0.0769, "1/s", Some(0.0042));
        assert_eq!(p.routes_phrase(), None);
        // 2.2 joint errors apart (a shaken rod and bob): they agree, and how far is said.
        let mut r = RouteValues {
            latent: 0.0609,
            latent_error: Some(0.0059),
            track: 0.0769,
            track_error: 0.0042,
            agree: true,
            unlike: None,
        };
        p.routes = Some(r.clone());
        let both = p.routes_phrase().unwrap();
        assert!(
            both.starts_with("the track's 0.0769000 ± 0.0042; the latent's 0.0609000 ± 0.0059"),
            "{both}"
        );
        assert!(
            both.ends_with("agrees with it, 2.2 joint errors apart"),
            "{both}"
        );
        // Within one joint error: no distance.
        r.latent = 0.0760;
        p.routes = Some(r.clone());
        assert!(p.routes_phrase().unwrap().ends_with("agrees with it"));
        // Another value of the answer disagrees: this one's latent is no second opinion.
        r.unlike = Some("gamma0".into());
        p.routes = Some(r.clone());
        assert!(p
            .routes_phrase()
            .unwrap()
            .contains("no second opinion: its gamma0 disagrees"));
        r.unlike = None;
        r.agree = false;
        r.latent_error = None;
        p.routes = Some(r.clone());
        assert_eq!(
            p.routes_phrase().unwrap(),
            "the track's 0.0769000 ± 0.0042; the latent's 0.0760000 (no standard error) \
             disagrees with it (the routes check)"
        );
    }
}
