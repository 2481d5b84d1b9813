//! Both routes' answer: where the track oscillates clearly (`TrackRoute::guiding`), a value both
//! routes measured (the oscillator's γ0 and γ1, the pendulum's g/L and damping) is reported as
//! the track's, with its error: it is read off the object's own path with no encoder between
//! the picture and the law, and the latent's is the second opinion, which `verdict::routes`
//! compares with it (agreement within their joint errors can be ok; disagreement is doubtful
//! and names both). The two are not weighed as independent measurements: the latent is trained
//! on the same frames, started from the track's answer, and its stated errors understate its
//! spread (the others' occlusion-3 render: its damping 0.0629 ± 0.0038 for 0.08, weighed with
//! the track's right 0.0812 ± 0.0079, gave an answer 17 % off graded ok). Each route's own
//! value is kept beside the answer (`ParameterResult::routes`), with whether they agree (by the
//! routes check's own rule, `routes::compared`: the rate by the track's fit's error) and, where
//! they disagree on the rate (γ0, g/L), the rate's name on every value (`unlike`): a latent at
//! another rate followed another motion, and its damping, however close, is no second opinion
//! on this one's. A value the model derives from one that changed (the pendulum's length from
//! g/L) is carried with it.
//! The track's error is the larger of its fit's and half the difference of its span's halves
//! (a bias that changes over the span, as a light circling the scene gives, shows there and not
//! in the fit's residuals). The verdict is judged on the latent's own values before this, and
//! the checks of the answer's values themselves (how well they are determined, whether they are
//! physical) again after it (`verdict::rejudge_answer`).

use crate::analysis::parameters::{ParameterResult, RouteValues};
use crate::analysis::Run;
use crate::calibration::{Calibration, DerivedValue, Readings};
use crate::physics::ModelRef;
use crate::track::laws::Value;
use crate::track::TrackRoute;
use crate::verdict::routes::{compared, separation};

/// Whether the track's `v` measures the latent's `p` more precisely: `p` has a finite, positive
/// standard error, larger than `v`'s (where the track's answer replaces the latent's only then:
/// `guide::acceleration`, `guide::tank`).
pub(super) fn more_precise(p: &ParameterResult, v: &Value) -> bool {
    p.standard_error
        .filter(|e| e.is_finite() && *e > 0.0)
        .is_some_and(|e| v.error < e)
}

/// The answer to `p` from the track's value `v` (standard error `e`): the track's, the
/// latent's kept beside it with whether the two agree as the routes check judges them, by
/// `v`'s own error (`routes::compared`); `None` where the track's is not a measurement (no
/// finite value or error).
pub(super) fn combined(p: &ParameterResult, v: &Value, e: f64) -> Option<ParameterResult> {
    if !(e > 0.0 && e.is_finite() && v.value.is_finite()) {
        return None;
    }
    let (apart, limit) = separation(p, v);
    let s = p.standard_error.filter(|s| *s > 0.0 && s.is_finite());
    Some(ParameterResult {
        estimate: v.value,
        standard_error: Some(e),
        relative_error: p.truth.filter(|t| *t != 0.0).map(|t| (v.value - t) / t),
        routes: Some(RouteValues {
            latent: p.estimate,
            latent_error: s,
            track: v.value,
            track_error: e,
            agree: apart <= limit,
            unlike: None,
        }),
        ..p.clone()
    })
}

/// `run`'s values with each one the clearly oscillating track measured too made the track's
/// (`combined`), and the values the model derives from them carried along (`carry`); the rest
/// as they are. Whether any changed.
pub fn combine(run: &mut Run, route: &TrackRoute) -> bool {
    let Some(span) = route.guiding() else {
        return false;
    };
    let mut params = run.final_values.clone();
    let names = run.config.model.parameter_names();
    let mut made: Vec<(usize, ParameterResult)> = Vec::new();
    for (k, p) in run.parameters.iter().enumerate() {
        let Some(v) = span.values.iter().find(|v| v.name == p.name) else {
            continue;
        };
        let error = span.error_of(v.name).unwrap_or(v.error);
        let judged = compared(span, v).unwrap_or_else(|| v.clone());
        made.extend(combined(p, &judged, error).map(|c| (k, c)));
    }
    unlike(&mut made, span.rate().map(|v| v.name));
    let mut changed = Vec::new();
    for (k, c) in made {
        if let Some(i) = names.iter().position(|n| *n == c.name) {
            params[i] = c.estimate;
        }
        changed.push(c.name.clone());
        run.parameters[k] = c;
    }
    if !changed.is_empty() {
        let (model, cal) = (run.config.model, &run.calibration);
        let was = &run.final_values;
        carry(model, cal, [was, &params], &mut run.parameters, &changed);
    }
    !changed.is_empty()
}

/// Where the routes disagree on the rate (`rate`: γ0, g/L), every value whose two agree names
/// the rate (`RouteValues::unlike`): a latent at another rate followed another motion (a
/// harmonic, a detail), so its damping, however close, is no second opinion on this one's. A
/// damping alone apart leaves the others' agreement standing: the same motion, its decay read
/// less well by one route.
fn unlike(made: &mut [(usize, ParameterResult)], rate: Option<&str>) {
    let apart = made
        .iter()
        .find(|(_, c)| Some(c.name.as_str()) == rate)
        .filter(|(_, c)| c.routes.as_ref().is_some_and(|r| !r.agree))
        .map(|(_, c)| c.name.clone());
    let Some(other) = apart else {
        return;
    };
    for (_, c) in made.iter_mut() {
        if let Some(r) = c.routes.as_mut().filter(|r| r.agree) {
            r.unlike = Some(other.clone());
        }
    }
}

/// Each value of `parameters` not in `changed` that `model` derives from its block's
/// parameters differently at `now` (the changed values put in) than at `was` (the latent's):
/// scaled by the ratio of the two derivations, its standard error alike (the pendulum's length,
/// g over g/L).
pub(super) fn carry(
    model: ModelRef,
    cal: &Calibration,
    [was, now]: [&[f64]; 2],
    parameters: &mut [ParameterResult],
    changed: &[String],
) {
    let readings = Readings::default();
    let (was, now) = (
        model.derive(was, cal, &readings).0,
        model.derive(now, cal, &readings).0,
    );
    for p in parameters.iter_mut().filter(|p| !changed.contains(&p.name)) {
        let of = |rows: &[DerivedValue]| rows.iter().find(|v| v.name == p.name).map(|v| v.estimate);
        let Some((a, b)) = of(&was).zip(of(&now)) else {
            continue;
        };
        let ratio = b / a;
        if a == b || !ratio.is_finite() || ratio == 0.0 {
            continue;
        }
        p.estimate *= ratio;
        p.standard_error = p.standard_error.map(|s| s * ratio.abs());
        p.relative_error = p.truth.filter(|t| *t != 0.0).map(|t| (p.estimate - t) / t);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::laws::Value;
    use crate::track::LawSpan;

    fn latent(estimate: f64, error: f64) -> ParameterResult {
        ParameterResult {
            truth: Some(0.08),
            relative_error: Some(estimate / 0.08 - 1.0),
            ..ParameterResult::si("gamma1", estimate, "1/s", Some(error))
        }
    }

    fn track(value: f64, error: f64) -> Value {
        Value {
            name: "gamma1",
            value,
            error,
            unit: "1/s",
        }
    }

    #[test]
    fn the_answer_is_the_tracks_and_the_latent_its_second_opinion() {
        // occlusion-3's damping: the latent's 0.0629 ± 0.0038 and the track's 0.0812 ± 0.0079,
        // 2.1 joint errors apart. Weighed as two measurements they gave 0.066 (−17 %); the
        // answer is the track's, the latent's kept beside it as agreeing.
        let c = combined(&latent(0.0629, 0.0038), &track(0.0812, 0.0079), 0.0079).unwrap();
        assert_eq!((c.estimate, c.standard_error), (0.0812, Some(0.0079)));
        assert!((c.relative_error.unwrap() - (0.0812 / 0.08 - 1.0)).abs() < 1e-12);
        let r = c.routes.unwrap();
        assert_eq!(
            (r.latent, r.latent_error, r.track, r.track_error, r.agree),
            (0.0629, Some(0.0038), 0.0812, 0.0079, true)
        );
        // Judged by the error the track's value carries (a rate's: its fit's), reported with
        // the wider one (its halves'): 4.7 joint errors apart by the first.
        let c = combined(&latent(0.0629, 0.0038), &track(0.0812, 0.001), 0.0079).unwrap();
        assert_eq!((c.estimate, c.standard_error), (0.0812, Some(0.0079)));
        assert!(!c.routes.unwrap().agree);
        // 4 joint standard errors apart: the track's still, the two said to disagree.
        let far = 0.076 + 4.0 * 0.010f64.hypot(0.0015);
        let c = combined(&latent(far, 0.010), &track(0.076, 0.0015), 0.0015).unwrap();
        assert_eq!((c.estimate, c.standard_error), (0.076, Some(0.0015)));
        assert!(!c.routes.unwrap().agree);
        // 2.9 apart: they agree.
        let near = 0.076 + 2.9 * 0.010f64.hypot(0.0015);
        let c = combined(&latent(near, 0.010), &track(0.076, 0.0015), 0.0015).unwrap();
        assert!(c.routes.unwrap().agree);
        // A latent without an error: agreeing within 2 %, else not; the answer the track's.
        let mut bare = latent(0.08, 0.01);
        bare.standard_error = None;
        let c = combined(&bare, &track(0.076, 0.0015), 0.0015).unwrap();
        assert_eq!(
            (c.estimate, c.routes.as_ref().unwrap().latent_error),
            (0.076, None)
        );
        assert!(!c.routes.unwrap().agree);
        bare.estimate = 0.0765;
        let c = combined(&bare, &track(0.076, 0.0015), 0.0015).unwrap();
        assert_eq!(c.estimate, 0.076);
        assert!(c.routes.unwrap().agree);
        // A track's value that is no measurement changes nothing.
        assert!(combined(&latent(0.08, 0.01), &track(0.076, f64::NAN), f64::NAN).is_none());
        assert!(combined(&latent(0.08, 0.01), &track(f64::NAN, 0.001), 0.001).is_none());
    }

    #[test]
    fn where_the_rate_disagrees_every_value_names_it() {
        // k506's latent at a quarter of the track's γ0 (a motion at half its frequency), its
        // γ1 1.4 joint errors from the track's: the γ1 agrees, but names the rate.
        let mut rate = latent(62.55, 0.24);
        rate.name = "gamma0".into();
        let mut made = vec![
            (0, combined(&rate, &track(253.1, 1.7), 1.7).unwrap()),
            (
                1,
                combined(&latent(-0.020, 0.032), &track(0.243, 0.19), 0.19).unwrap(),
            ),
        ];
        assert!(made[1].1.routes.as_ref().unwrap().agree);
        // The rate agrees (here γ1 stands for it), another value apart: nothing named.
        let mut apart = made.clone();
        unlike(&mut apart, Some("gamma1"));
        assert!(apart
            .iter()
            .all(|(_, c)| c.routes.as_ref().unwrap().unlike.is_none()));
        unlike(&mut made, Some("gamma0"));
        let damping = &made[1].1;
        assert_eq!(
            (damping.estimate, damping.standard_error),
            (0.243, Some(0.19))
        );
        let r = damping.routes.as_ref().unwrap();
        assert_eq!((r.agree, r.unlike.as_deref()), (true, Some("gamma0")));
        assert_eq!(made[0].1.routes.as_ref().unwrap().unlike, None);
        assert_eq!(made[0].1.estimate, 253.1);
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
            follow: 0.0,
            si: Vec::new(),
            periods: Some(2.5),
            curve: Vec::new(),
            first: 0,
            from_rest: false,
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

    #[test]
    fn a_value_derived_from_one_that_changed_is_carried_with_it() {
        // The pendulum's length is g over g/L: the latent's g/L 123.4 put at the track's 18.02.
        let model = ModelRef::by_name("pendulum").unwrap();
        let cal = Calibration {
            g: 9.81,
            ..Calibration::default()
        };
        let was = [123.43, 5e-4, 1.0, 0.0];
        let now = [18.02, 5e-4, 1.0, 0.0];
        let length = cal.g / was[0];
        let mut parameters = vec![latent(length, 0.01 * length), latent(5e-4, 1e-4)];
        parameters[0].name = "length".into();
        parameters[1].name = "damping".into();
        carry(
            model,
            &cal,
            [&was, &now],
            &mut parameters,
            &["g_over_l".into()],
        );
        assert!((parameters[0].estimate - cal.g / 18.02).abs() < 1e-12);
        assert!(
            (parameters[0].standard_error.unwrap() / parameters[0].estimate - 0.01).abs() < 1e-12
        );
        // The damping did not change: as it was.
        assert_eq!(parameters[1].estimate, 5e-4);
    }
}
