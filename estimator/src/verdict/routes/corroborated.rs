//! Whether the object's track corroborates the latent's rate: it guides the run, its own halves
//! agree, and its whole rate is the latent's within the routes' limit. The law and the rate are
//! then measured twice, once with no encoder between the picture and the law; what the latent's
//! own evidence finds against it at the doubtful tier (its halves' gains, a noisy law fit, a
//! share of the picture it leaves to a shaking camera or a hand, values still moving when
//! training stopped) is its encoder's, not the answer's, and the checks that find it say so in
//! a note (`Grade::Ok`) instead of doubting.

use super::separation;
use crate::agreement::apart;
use crate::analysis::parameters::ParameterResult;
use crate::analysis::Run;
use crate::track::laws::Value;
use crate::track::{TrackRoute, RATE_NAMES};
use physvid_shared::cli::approx;

/// Whether the track corroborates the latent's rate `p`: it guides the run
/// (`TrackRoute::guiding`), its rate refitted on the span's earlier and later half agrees by the
/// consistency check's own rule (the law holds alike over the span, read with no encoder
/// between the picture and it), and its whole rate agrees with `p`'s (`separation`). The
/// latent's answer is then the one an independent measurement gives.
pub(in crate::verdict) fn corroborates(r: &Run, p: &ParameterResult) -> bool {
    r.track
        .as_ref()
        .and_then(|t| corroborated_by(t, p))
        .is_some()
}

/// [`corroborates`] by the track `route`: its rate where it corroborates `p`.
fn corroborated_by(route: &TrackRoute, p: &ParameterResult) -> Option<Value> {
    let span = route.guiding()?;
    let g = span.rate()?.clone();
    let [a, b] = span.rate_halves()?;
    let (measured, limit) = separation(p, &g);
    // Halves without finite errors cannot be weighed (`apart` leaves them be): no corroboration.
    (RATE_NAMES.contains(&p.name.as_str())
        && a.error.is_finite()
        && b.error.is_finite()
        && apart([a.value, b.value], [a.error, b.error]).is_none()
        && measured <= limit)
        .then_some(g)
}

/// Whether the answer to `r`'s value `name` is the track's own, its halves in its error: the
/// track corroborates the run's rate (`corroborates`) and measures `name` beside it with a
/// finite error (`LawSpan::error_of`: the larger of its fit's and half its halves'
/// difference), as `guide::combine` reports it.
pub(in crate::verdict) fn answered_by_track(r: &Run, name: &str) -> bool {
    let rate = r
        .parameters
        .iter()
        .find(|p| RATE_NAMES.contains(&p.name.as_str()));
    r.track
        .as_ref()
        .zip(rate)
        .is_some_and(|(route, rate)| measured_beside(route, rate, name))
}

/// [`answered_by_track`] on the track `route` and the latent's rate `rate`.
fn measured_beside(route: &TrackRoute, rate: &ParameterResult, name: &str) -> bool {
    corroborated_by(route, rate).is_some()
        && route
            .guiding()
            .and_then(|s| s.error_of(name))
            .is_some_and(f64::is_finite)
}

/// Where the track corroborates `r`'s rate (`corroborates`), the words a check's note adds to
/// what it found in the latent: why that is not held against the answer.
pub(in crate::verdict) fn note(r: &Run) -> Option<String> {
    let p = r
        .parameters
        .iter()
        .find(|p| RATE_NAMES.contains(&p.name.as_str()))?;
    let g = corroborated_by(r.track.as_ref()?, p)?;
    Some(format!(
        "not held against the answer: the object's track, read with no encoder, measures the \
         same {} ({} ± {} against the latent's {}) and its halves agree, so the law and the \
         rate are not in question, only how closely the encoder reads the motion",
        p.name,
        approx(g.value),
        approx(g.error),
        approx(p.estimate)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::laws::TrackLaw;
    use crate::track::test_route as route;

    fn gamma0(value: f64, error: f64) -> Value {
        Value {
            name: "gamma0",
            value,
            error,
            unit: "1/s^2",
        }
    }

    #[test]
    fn the_track_corroborates_a_rate_it_measures_alike_where_its_halves_agree() {
        // The shaken rod and bob's (shake-3): the track 4.0014 ± 0.00017 over 2.5 periods, its
        // halves alike; the latent's 4.0037 ± 0.023.
        let (mut route, mut span) = route();
        span.law = TrackLaw::AngularOscillation;
        span.values = vec![gamma0(4.0014, 0.00017)];
        span.halves = vec![vec![gamma0(4.0013, 0.0003)], vec![gamma0(4.0016, 0.0003)]];
        route.laws = vec![span];
        route.chosen = Some(TrackLaw::AngularOscillation);
        let latent = |estimate| ParameterResult::si("gamma0", estimate, "1/s^2", Some(0.023));
        let g = corroborated_by(&route, &latent(4.0037)).expect("corroborated");
        assert_eq!((g.value, g.error), (4.0014, 0.00017));
        // More than three joint errors away: two measurements that disagree.
        assert!(corroborated_by(&route, &latent(4.0014 + 3.1 * 0.023)).is_none());
        // Not the rate: the damping is weighed by the routes check, not corroborated; its answer
        // is the track's where the track measures it beside the corroborated rate, its halves
        // (0.04 and 0.12: a damping that grows as the swing dies down) in its error.
        let damping = ParameterResult::si("gamma1", 0.08, "1/s", Some(0.01));
        assert!(corroborated_by(&route, &damping).is_none());
        assert!(!measured_beside(&route, &latent(4.0037), "gamma1"));
        let gamma1 = |value, error| Value {
            name: "gamma1",
            value,
            error,
            unit: "1/s",
        };
        route.laws[0].values.push(gamma1(0.08, 0.004));
        route.laws[0].halves[0].push(gamma1(0.04, 0.005));
        route.laws[0].halves[1].push(gamma1(0.12, 0.01));
        let e = route.laws[0].error_of("gamma1").expect("measured");
        assert!((e - 0.04).abs() < 1e-12, "{e}");
        assert!(measured_beside(&route, &latent(4.0037), "gamma1"));
        // A latent at another rate: the track corroborates nothing, and answers for no damping.
        assert!(!measured_beside(
            &route,
            &latent(4.0014 + 3.1 * 0.023),
            "gamma1"
        ));
        // The track's halves 5 % apart at 10 errors: the law does not hold alike on it.
        route.laws[0].halves = vec![vec![gamma0(3.9, 0.01)], vec![gamma0(4.1, 0.01)]];
        assert!(corroborated_by(&route, &latent(4.0037)).is_none());
        // Halves without errors cannot be weighed.
        route.laws[0].halves = vec![vec![gamma0(4.0, f64::NAN)], vec![gamma0(4.0, 0.1)]];
        assert!(corroborated_by(&route, &latent(4.0037)).is_none());
        // A track that does not guide (under two periods) corroborates nothing.
        route.laws[0].halves = vec![vec![gamma0(4.0013, 0.0003)], vec![gamma0(4.0016, 0.0003)]];
        route.laws[0].periods = Some(1.9);
        assert!(corroborated_by(&route, &latent(4.0037)).is_none());
    }
}
