//! The routes compared where the track accelerates at a constant rate in metres (by a stick,
//! on a plane, or by the `--reference` readings along its line): the latent's acceleration in SI against the track's, a plane's perspective
//! named, and by one stick, a track whose own halves disagree.

use super::{separation, with_error, APART, ERRORS};
use crate::agreement;
use crate::analysis::parameters::ParameterResult;
use crate::analysis::Run;
use crate::track::laws::Value;
use crate::track::{LawSpan, TrackRoute};
use crate::verdict::{Grade, Reason};
use physvid_shared::cli::approx;

/// The names a constant acceleration goes by among the models' values in SI (the fall's g, the
/// slide's acceleration).
pub const ACCELERATION_NAMES: [&str; 2] = ["g", "acceleration"];

/// Where a stick or a plane puts the track's constant acceleration in metres
/// (`TrackRoute::with_stick`, `TrackRoute::on_plane`): the latent's acceleration in SI compared
/// with it as two measurements of one number, by the same limits as the rates (`separation`),
/// the track's error the larger of its fit's and its halves' (`LawSpan::error_of`);
/// and, on a plane, its perspective named where the picture's scale changes along the path by
/// more than [`APART`] (what one stick would have been off by there); by one stick, where the
/// track's own halves disagree (`one_stick`).
pub(super) fn accelerations(check: &'static str, r: &Run) -> Vec<Reason> {
    let Some((route, l)) = r.track.as_ref().and_then(|t| Some((t, t.accelerating()?))) else {
        return Vec::new();
    };
    let by = match (route.plane, route.stick) {
        (Some(_), _) => "on the plane",
        (None, Some(_)) => "by the stick",
        (None, None) => "by the --reference readings",
    };
    let perspective = route.perspective(l).filter(|c| *c > APART).map(|change| {
        Reason::new(
            check,
            Grade::Ok,
            format!(
                "perspective: the picture's scale along the path changes by {} % over the \
                 track's span ({}–{} s), which one stick could not carry; the track was read \
                 on the plane given ({})",
                approx(100.0 * change),
                approx(l.first_s),
                approx(l.last_s),
                route.scale_flag().unwrap_or_default()
            ),
        )
        .measured(change, APART)
    });
    let disagree = si_acceleration(l).and_then(|a| apart(check, &a, &r.parameters, by));
    perspective
        .into_iter()
        .chain(one_stick(check, route, l))
        .chain(disagree)
        .collect()
}

/// The track's acceleration in metres over `l`, its error the larger of its fit's and its
/// halves' (`LawSpan::error_of`, in pixels, put in metres as its value is).
pub fn si_acceleration(l: &LawSpan) -> Option<Value> {
    let a = l.si.iter().find(|v| v.name == "acceleration")?;
    let halves = l
        .values
        .iter()
        .find(|v| v.name == "acceleration")
        .filter(|p| p.value != 0.0)
        .and_then(|p| Some(l.error_of("acceleration")? * (a.value / p.value).abs()));
    Some(Value {
        error: a.error.max(halves.unwrap_or(0.0)),
        ..a.clone()
    })
}

/// By one stick (no plane), where the track's acceleration refitted on its span's earlier and
/// later half disagrees by the consistency check's own rule (`agreement::apart`, each half's
/// error at least the whole span's): the picture's scale changes along the path (a camera tilted
/// to the motion draws its far part smaller, and a fall's later, faster part then accelerates
/// less in the picture), which one stick cannot carry; doubtful, naming `--plane`. Where the
/// law was read through a bend, the bend's change of scale over the span, beyond [`APART`].
fn one_stick(check: &'static str, route: &TrackRoute, l: &LawSpan) -> Option<Reason> {
    if route.plane.is_some() || route.stick.is_none() {
        return None;
    }
    // Where the law itself is read through a perspective bend (`track::laws::acceleration`),
    // its halves agree by construction: the bend says how far the scale changes.
    if let Some(bend) = l.values.iter().find(|v| v.name == "bend") {
        let change = bend.value.abs() / 100.0;
        return (change > APART).then(|| {
            let detail = format!(
                "the object's track is seen in perspective: the picture's scale changes by {} % \
                 along its span ({}–{} s, the bend its constant acceleration is read through), \
                 which one stick cannot carry; give --plane with four corners of a rectangle in \
                 the plane of the motion",
                approx(bend.value),
                approx(l.first_s),
                approx(l.last_s)
            );
            Reason::new(check, Grade::Doubtful, detail).measured(change, APART)
        });
    }
    let of = |values: &[Value]| values.iter().find(|v| v.name == "acceleration").cloned();
    let [first, second] = l.halves.as_slice() else {
        return None;
    };
    let (a, b) = (of(first)?, of(second)?);
    // As the consistency check has it: a half pins the value no better than the whole span.
    let floor = of(&l.values).map_or(0.0, |w| w.error);
    let errors = [a.error.max(floor), b.error.max(floor)];
    let (z, limit) = agreement::apart([a.value, b.value], errors)?;
    let detail = format!(
        "the object's track accelerates at {} ± {} px/s^2 over the earlier half of its span and \
         {} ± {} over the later ({} standard errors apart): the picture's scale changes along \
         the path (perspective: a camera tilted to the motion), which one stick cannot carry, or \
         the law does not hold alike over it; give --plane with four corners of a rectangle in \
         the plane of the motion",
        approx(a.value),
        approx(errors[0]),
        approx(b.value),
        approx(errors[1]),
        approx(z)
    );
    Some(Reason::new(check, Grade::Doubtful, detail).measured(z, limit))
}

/// The reason where the latent's acceleration in SI among `parameters` lies beyond
/// `separation`'s limit from the track's `a` (m/s², in metres `by` a stick or on a plane).
fn apart(
    check: &'static str,
    a: &Value,
    parameters: &[ParameterResult],
    by: &str,
) -> Option<Reason> {
    let p = parameters
        .iter()
        .find(|p| ACCELERATION_NAMES.contains(&p.name.as_str()) && p.unit == "m/s^2")?;
    let (measured, limit) = separation(p, a);
    if measured <= limit {
        return None;
    }
    let detail = format!(
        "the object's track, in metres {by}, accelerates at {} ± {} m/s^2; the latent's {} is \
         {} m/s^2 ({} {}): one of the two is wrong; look at the track in report.html",
        approx(a.value),
        approx(a.error),
        p.name,
        with_error(p),
        approx(measured),
        if limit == ERRORS {
            "joint standard errors apart"
        } else {
            "of the value apart"
        }
    );
    Some(Reason::new(check, Grade::Doubtful, detail).measured(measured, limit))
}

#[cfg(test)]
mod tests {
    use super::*;

    const BY: &str = "by the stick";

    #[test]
    fn by_one_stick_halves_that_disagree_name_the_plane() {
        use crate::calibration::Stick;
        use crate::track::metres::tests::tossed;
        let stick = Stick::parse("0,0:0,200=1").unwrap();
        let route = tossed().with_stick(stick);
        let acceleration = |value, error| Value {
            name: "acceleration",
            value,
            error,
            unit: "px/s^2",
        };
        let with_halves = |a: Value, b: Value| {
            let mut l = route.laws[0].clone();
            l.halves = vec![vec![a], vec![b]];
            l
        };
        // The shared toss's halves (3.7 % apart at 13 errors): doubtful, --plane named.
        let l = with_halves(acceleration(3913.0, 8.0), acceleration(4059.0, 8.2));
        let r = one_stick("routes", &route, &l).expect("named");
        assert_eq!(r.grade, Grade::Doubtful);
        assert!(r.detail.contains("--plane"), "{}", r.detail);
        // The 10.3° roll's (27 % apart at 2.1 errors): nothing.
        let l = with_halves(acceleration(394.4, 46.0), acceleration(288.7, 19.8));
        assert!(one_stick("routes", &route, &l).is_none());
        // Without a stick (the readings typed) nothing either.
        let l = with_halves(acceleration(3913.0, 8.0), acceleration(4059.0, 8.2));
        assert!(one_stick("routes", &tossed(), &l).is_none());
    }

    fn latent(estimate: f64, standard_error: Option<f64>) -> Vec<ParameterResult> {
        vec![ParameterResult::si("g", estimate, "m/s^2", standard_error)]
    }

    #[test]
    fn a_fall_s_g_is_held_to_the_track_s_in_metres() {
        let a = Value {
            name: "acceleration",
            value: 9.93,
            error: 0.03,
            unit: "m/s^2",
        };
        // The toss's latent from its own reading (0.04 ± 0.26): far apart, both named.
        let r = apart("routes", &a, &latent(0.04, Some(0.26)), BY).expect("apart");
        assert_eq!(r.grade, Grade::Doubtful);
        assert!(
            r.detail.contains("9.93") && r.detail.contains("0.04"),
            "{}",
            r.detail
        );
        // Within three joint errors, or within 2 % without an error of its own: nothing.
        assert!(apart("routes", &a, &latent(9.80, Some(0.1)), BY).is_none());
        assert!(apart("routes", &a, &latent(9.80, None), BY).is_none());
        assert!(apart("routes", &a, &latent(9.50, None), BY).is_some());
    }

    /// The shared 10.3° roll by its stick: the track's 0.679 ± 0.038 m/s² (339.6 px/s² over
    /// 0.13–0.67 s, halves 394.4 and 288.7): its error widened to half its halves' difference,
    /// in metres, the latent's 0.846 ± 0.015 is no disagreement; without halves it is.
    #[test]
    fn the_track_s_acceleration_error_is_widened_by_its_halves() {
        let (px, si) = (339.6, 0.679);
        let acceleration = |value, error| Value {
            name: "acceleration",
            value,
            error,
            unit: "px/s^2",
        };
        let mut l = LawSpan {
            law: crate::track::laws::TrackLaw::ConstantAcceleration,
            holds: true,
            first_s: 0.13,
            last_s: 0.67,
            samples: 17,
            values: vec![acceleration(px, 19.0)],
            halves: vec![
                vec![acceleration(394.4, 46.0)],
                vec![acceleration(288.7, 19.8)],
            ],
            rms_px: 0.5,
            follow: 0.0,
            si: vec![Value {
                unit: "m/s^2",
                ..acceleration(si, 0.038)
            }],
            periods: None,
            curve: Vec::new(),
            first: 0,
            from_rest: false,
        };
        let a = si_acceleration(&l).unwrap();
        let widened = 0.5 * (394.4 - 288.7) * si / px;
        assert!((a.error - widened).abs() < 1e-12, "{}", a.error);
        assert!(apart("routes", &a, &latent(0.846, Some(0.015)), BY).is_none());
        l.halves.clear();
        let a = si_acceleration(&l).unwrap();
        assert_eq!(a.error, 0.038);
        assert!(apart("routes", &a, &latent(0.846, Some(0.015)), BY).is_some());
    }
}
