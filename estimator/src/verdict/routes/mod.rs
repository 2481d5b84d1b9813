//! The two routes compared: where the object's own track (`track`) oscillates clearly
//! (`TrackRoute::guiding`: several periods, a rate known to a percent), its rate and damping
//! are measurements of the same γ0 and γ1 (or g/L and damping) the latent's answer gives, with
//! no encoder between the picture and the law; a brightness's decay over several e-folds, of
//! the LED's γ; a tank's drain, of its k in metres where heights were read. An answer whose
//! model does not oscillate, or one of whose values lies away from the track's by more than
//! both errors allow (two measurements of one number that disagree: one of them is wrong), is
//! doubtful, and the reason names both (the answer is the track's either way:
//! `guide::combine`); a latent value without a standard error is held to the 2 % that
//! separates a right answer from a wrong one. A constant
//! acceleration in metres (by a stick or on a plane) is compared alike; by one stick, a track
//! whose own halves disagree names perspective and `--plane`. Where they agree and the track's
//! own halves do too, the track corroborates the rate (`corroborated`): what the latent's own
//! evidence finds at the doubtful tier is its encoder's, and the checks say so in a note.

use super::{Check, Grade, Reason};
use crate::analysis::parameters::ParameterResult;
use crate::analysis::Run;
use crate::track::laws::{TrackLaw, Value};
use crate::track::{LawSpan, GUIDING_PERIODS, RATE_NAMES};
use physvid_shared::cli::approx;

mod acceleration;
mod corroborated;
use acceleration::accelerations;
pub use acceleration::{si_acceleration, ACCELERATION_NAMES};
pub(super) use corroborated::{answered_by_track, corroborates, note as corroborated};

pub struct Routes;

/// Rates further apart than [`ERRORS`] joint standard errors disagree (the usual three: a
/// chance of about 0.3 % for two right answers with errors as stated)…
pub const ERRORS: f64 = 3.0;
/// …or, where the latent's rate has no standard error, further apart than this share.
pub const APART: f64 = 0.02;

/// How far the latent's rate `p` lies from the track's `g`, and the limit beyond which they
/// disagree: joint standard errors against [`ERRORS`], or, where `p` has none, the share of
/// the value against [`APART`].
pub fn separation(p: &ParameterResult, g: &Value) -> (f64, f64) {
    let gap = (p.estimate - g.value).abs();
    let joint = p.standard_error.unwrap_or(0.0).hypot(g.error);
    match p.standard_error {
        Some(_) if joint > 0.0 => (gap / joint, ERRORS),
        Some(_) => (if gap > 0.0 { f64::INFINITY } else { 0.0 }, ERRORS),
        None => (gap / g.value.abs().max(f64::MIN_POSITIVE), APART),
    }
}

impl Check for Routes {
    fn name(&self) -> &'static str {
        "routes"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let Some((route, span)) = r.track.as_ref().and_then(|t| Some((t, t.guiding()?))) else {
            return accelerations(self.name(), r);
        };
        let periods = span.periods.unwrap_or(0.0);
        let Some(g) = span.rate() else {
            return Vec::new();
        };
        let (extent, what) = span.extent().unwrap_or((0.0, "periods"));
        let track = format!(
            "{} {} over {}–{} s ({} {what}) with {} {} ± {} {}",
            route.subject(),
            span.law.verb(),
            approx(span.first_s),
            approx(span.last_s),
            approx(extent),
            g.symbol(),
            approx(g.value),
            approx(g.error),
            g.unit
        );
        let level = matches!(span.law, TrackLaw::Decay | TrackLaw::Drain);
        if !level && !r.config.model.oscillates(&r.final_values) {
            return vec![Reason::new(
                self.name(),
                Grade::Doubtful,
                format!(
                    "{track}, but the answer is a {} that does not: try --model \
                     damped-oscillator (or pendulum), with --start {} to keep the free motion",
                    r.model,
                    approx(span.first_s)
                ),
            )
            .measured(periods, GUIDING_PERIODS)];
        }
        r.parameters
            .iter()
            .filter_map(|p| differs(self.name(), p, &of_track(span, &p.name)?, &track))
            .collect()
    }
}

/// The track's value the latent's value `name` is compared with, and its error: the guiding
/// `span`'s own by that name (`compared`), or, for a drain, its k in metres
/// (`TrackRoute::drain_in_metres`: its error the readings' and the empty time's).
fn of_track(span: &LawSpan, name: &str) -> Option<Value> {
    match span.values.iter().find(|v| v.name == name) {
        Some(v) => compared(span, v),
        None if span.law == TrackLaw::Drain => span.si.iter().find(|v| v.name == name).cloned(),
        None => None,
    }
}

/// The track's value `v` of its guiding `span` with the error the latent's is compared by: the
/// rate by its fit's, the others (the damping) by the larger of its fit's and its halves'
/// (`LawSpan::error_of`, the error `guide::combine` reports with every value); `None` where
/// the span has no such value.
pub fn compared(span: &LawSpan, v: &Value) -> Option<Value> {
    let error = match RATE_NAMES.contains(&v.name) {
        true => v.error,
        false => span.error_of(v.name)?,
    };
    Some(Value { error, ..v.clone() })
}

/// The latent's value `p` with its standard error, or saying it has none.
pub(super) fn with_error(p: &ParameterResult) -> String {
    match p.standard_error {
        Some(se) => format!("{} ± {}", approx(p.estimate), approx(se)),
        None => format!("{} (no standard error)", approx(p.estimate)),
    }
}

/// Where the latent's `p` and the track's `v` (the same value) lie further apart than
/// `separation` allows: doubtful, naming both (the answer is the track's: `guide::combine`).
fn differs(check: &'static str, p: &ParameterResult, v: &Value, track: &str) -> Option<Reason> {
    let share = (p.estimate - v.value).abs() / v.value.abs().max(f64::MIN_POSITIVE);
    let (measured, limit) = separation(p, v);
    if measured <= limit {
        return None;
    }
    let of_track = match RATE_NAMES.contains(&v.name) {
        true => String::new(),
        false => format!(
            " ({} {} ± {} {})",
            v.name,
            approx(v.value),
            approx(v.error),
            v.unit
        ),
    };
    // How far apart the two lie: in joint standard errors, or (where the latent's value has
    // none: `separation`) as a share alone.
    let latent = with_error(p);
    let apart = match limit == ERRORS {
        true => format!(
            "{} % away ({} joint standard errors)",
            approx(100.0 * share),
            approx(measured)
        ),
        false => format!(
            "{} % away (over {} %)",
            approx(100.0 * share),
            approx(100.0 * APART)
        ),
    };
    Some(
        Reason::new(
            check,
            Grade::Doubtful,
            format!(
                "{track}{of_track}; the latent's {} is {latent}, {apart}: one of the two is \
                 wrong; the answer is the track's, read with no encoder; look at the track in \
                 report.html",
                p.name,
            ),
        )
        .measured(measured, limit),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(name: &'static str, value: f64, error: f64) -> Value {
        Value {
            name,
            value,
            error,
            unit: "1/s",
        }
    }

    #[test]
    fn a_damping_the_routes_disagree_on_is_named_with_both() {
        // A clutter render's: the latent's γ1 −0.034 ± 0.032, the track's 0.0793 ± 0.00056.
        let p = ParameterResult::si("gamma1", -0.034, "1/s", Some(0.032));
        let v = value("gamma1", 0.0793, 0.00056);
        let r = differs("routes", &p, &v, "the track").expect("3.5 errors apart");
        assert_eq!(r.grade, Grade::Doubtful);
        assert!(
            r.detail.contains("gamma1 0.0793") && r.detail.contains("the track's"),
            "{}",
            r.detail
        );
        // 2.9 errors apart: two measurements of one number.
        let near = ParameterResult {
            estimate: 0.0793 - 2.9 * 0.032f64.hypot(0.00056),
            ..p.clone()
        };
        assert!(differs("routes", &near, &v, "the track").is_none());
    }

    #[test]
    fn a_latent_value_without_an_error_is_named_by_its_share_not_a_nan() {
        // A 10-fps swing's: the latent's damping 0.00125 with no error, the track's 0.187.
        let p = ParameterResult::si("damping", 0.00125, "1/s", None);
        let v = value("damping", 0.187, 0.022);
        let r = differs("routes", &p, &v, "the track").expect("99 % apart");
        assert!(!r.detail.contains("NaN"), "{}", r.detail);
        assert!(r.detail.contains("(no standard error)"), "{}", r.detail);
        assert!(r.detail.contains("over 2 %"), "{}", r.detail);
    }

    #[test]
    fn a_drains_k_in_metres_is_what_the_tanks_k_is_compared_with() {
        let (_, mut span) = crate::track::test_route();
        let v = |name: &'static str, value: f64| Value {
            name,
            value,
            error: 0.0001,
            unit: "",
        };
        span.law = TrackLaw::Drain;
        span.values = vec![v("drain_k", 0.65), v("empty", 54.0)];
        span.si = vec![v("k", 0.00945)];
        assert_eq!(of_track(&span, "k"), Some(v("k", 0.00945)));
        assert_eq!(of_track(&span, "k_latent"), None);
        // The latent's k away from it by more than three joint errors: named.
        let p = ParameterResult::si("k", 0.0110, "m^0.5/s", Some(0.0002));
        let reason = differs("routes", &p, &of_track(&span, "k").unwrap(), "the track");
        assert!(reason.is_some());
        // A law other than a drain compares its own values only.
        span.law = TrackLaw::Decay;
        assert_eq!(of_track(&span, "k"), None);
    }
}
