//! Both routes' answer: where the track oscillates clearly (`TrackRoute::guiding`), a value both
//! routes measured (the oscillator's γ0 and γ1) on which they agree within the routes check's
//! [`ERRORS`] joint standard errors is reported as their precision-weighted mean, two
//! measurements of one number, each route's own kept beside it (`ParameterResult::routes`).
//! The track's error is the larger of its fit's and half the difference of its span's halves
//! (a bias that changes over the span, as a light circling the scene gives, shows there and not
//! in the fit's residuals). Where they disagree, or the latent's value has no standard error,
//! the latent's stands (the `routes` check names a γ0 that disagrees). The verdict is judged
//! on the latent's own values before this, and the checks of the answer's values themselves
//! (how well they are determined, whether they are physical) again after it
//! (`verdict::rejudge_answer`).

use crate::analysis::parameters::{ParameterResult, RouteValues};
use crate::track::TrackRoute;
use crate::verdict::routes::ERRORS;

/// `p` combined with the track's value `v` (standard error `e`), where both have a standard
/// error and they agree.
fn combined(p: &ParameterResult, v: f64, e: f64) -> Option<ParameterResult> {
    let s = p.standard_error.filter(|s| *s > 0.0 && s.is_finite())?;
    if !(e > 0.0 && e.is_finite() && v.is_finite()) || (p.estimate - v).abs() > ERRORS * s.hypot(e)
    {
        return None;
    }
    let (wl, wt) = (1.0 / (s * s), 1.0 / (e * e));
    let estimate = (wl * p.estimate + wt * v) / (wl + wt);
    Some(ParameterResult {
        estimate,
        standard_error: Some((wl + wt).sqrt().recip()),
        relative_error: p.truth.filter(|t| *t != 0.0).map(|t| (estimate - t) / t),
        routes: Some(RouteValues {
            latent: p.estimate,
            latent_error: s,
            track: v,
            track_error: e,
        }),
        ..p.clone()
    })
}

/// `parameters` with each value that the clearly oscillating track measured too combined with
/// it where the two agree (`combined`); the rest as they are. Whether any was.
pub fn combine(parameters: &mut [ParameterResult], route: &TrackRoute) -> bool {
    let Some(span) = route.guiding() else {
        return false;
    };
    let mut any = false;
    for p in parameters.iter_mut() {
        let Some(v) = span.values.iter().find(|v| v.name == p.name) else {
            continue;
        };
        let error = span.error_of(v.name).unwrap_or(v.error);
        if let Some(c) = combined(p, v.value, error) {
            *p = c;
            any = true;
        }
    }
    any
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::laws::Value;
    use crate::track::LawSpan;

    fn latent(estimate: f64, error: f64) -> ParameterResult {
        ParameterResult {
            name: "gamma1".into(),
            estimate,
            units: "SI".into(),
            unit: "1/s".into(),
            truth: Some(0.08),
            relative_error: Some(estimate / 0.08 - 1.0),
            standard_error: Some(error),
            splits: Vec::new(),
            routes: None,
        }
    }

    #[test]
    fn two_measurements_that_agree_are_weighed_by_their_errors() {
        // The latent's 0.117 ± 0.030 and the track's 0.076 ± 0.0015 (a light circling a
        // rod and bob): the track's weighs 400 times more.
        let c = combined(&latent(0.117, 0.030), 0.076, 0.0015).unwrap();
        let w = (1.0 / 0.03f64.powi(2), 1.0 / 0.0015f64.powi(2));
        let want = (w.0 * 0.117 + w.1 * 0.076) / (w.0 + w.1);
        assert!((c.estimate - want).abs() < 1e-12, "{}", c.estimate);
        assert!((c.standard_error.unwrap() - (w.0 + w.1).sqrt().recip()).abs() < 1e-12);
        assert!((c.relative_error.unwrap() - (want / 0.08 - 1.0)).abs() < 1e-12);
        let r = c.routes.unwrap();
        assert_eq!((r.latent, r.track), (0.117, 0.076));
    }

    #[test]
    fn two_that_disagree_or_a_latent_without_an_error_stay_the_latents() {
        // 4 joint standard errors apart.
        let far = 0.076 + 4.0 * 0.010f64.hypot(0.0015);
        assert!(combined(&latent(far, 0.010), 0.076, 0.0015).is_none());
        let mut bare = latent(0.08, 0.01);
        bare.standard_error = None;
        assert!(combined(&bare, 0.076, 0.0015).is_none());
        assert!(combined(&latent(0.08, 0.01), 0.076, f64::NAN).is_none());
    }

    #[test]
    fn the_tracks_error_is_widened_by_its_halves() {
        let v = |value: f64, error: f64| Value {
            name: "gamma1",
            value,
            error,
            unit: "1/s",
        };
        let mut span = LawSpan {
            law: crate::track::laws::TrackLaw::AngularOscillation,
            holds: true,
            first_s: 0.0,
            last_s: 7.8,
            samples: 157,
            values: Vec::new(),
            halves: Vec::new(),
            rms_px: 0.4,
            si: Vec::new(),
            periods: Some(2.5),
            curve: Vec::new(),
            first: 0,
        };
        let error = |span: &LawSpan, whole: Value| {
            let mut span = span.clone();
            span.values = vec![whole];
            span.error_of("gamma1").unwrap()
        };
        span.halves = vec![vec![v(0.0686, 0.003)], vec![v(0.0533, 0.004)]];
        assert!((error(&span, v(0.059, 0.0038)) - 0.00765).abs() < 1e-12);
        assert_eq!(error(&span, v(0.059, 0.01)), 0.01);
        span.halves.clear();
        assert_eq!(error(&span, v(0.059, 0.0038)), 0.0038);
    }
}
