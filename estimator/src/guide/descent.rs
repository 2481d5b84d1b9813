//! A descent the track saw: a constant acceleration's direction, its release, line and rise as
//! a fall or slide from rest reads them (`tracked_motion`), and the request it guides without a
//! stick or a plane (`sighted`).

use crate::config::Request;
use crate::data::{falls, TrackedMotion};
use crate::physics::ModelRef;
use crate::track::{LawSpan, TrackRoute};
use physvid_shared::video::Crop;

/// The direction of a constant acceleration's span (degrees from the picture's right, y down).
pub(super) fn direction(span: &LawSpan) -> f64 {
    span.values
        .iter()
        .find(|v| v.name == "direction")
        .map_or(0.0, |d| d.value)
}

/// The constant acceleration of `route` over `span` (pointing `direction` degrees from the
/// picture's right) as a descent reads it: the release where the track saw it (the vertex
/// within the span where the law holds, give or take a frame or three of its standard errors:
/// one extrapolated from a span that starts later is the law's guess, not a sighting), the
/// line, and whether the track saw it move before the release (the law's travel from the
/// span's start to its vertex over the object's size: a toss's rise, no rest).
pub(super) fn tracked_motion(route: &TrackRoute, span: &LawSpan, direction: f64) -> TrackedMotion {
    let value = |name: &str| span.values.iter().find(|v| v.name == name);
    let vertex = value("vertex").filter(|v| {
        let frame = span.held_s() / (span.samples.max(2) - 1) as f64;
        let slack = frame.max(3.0 * v.error);
        (span.first_s - slack..=span.last_s + slack).contains(&v.value)
    });
    let rise = match (vertex, value("acceleration")) {
        (Some(v), Some(a)) => 0.5 * a.value.abs() * (v.value - span.first_s).max(0.0).powi(2),
        _ => 0.0,
    };
    TrackedMotion {
        span: route.file_span(span),
        release: vertex.map(|v| route.file_time(v.value)),
        axis: route.picture_axis(span, direction),
        travel: route.travel(span),
        moving_before: rise > route.track.size,
        frame: Some(route.frame_of(span)),
    }
}

/// Where no `--crop` is given, the words that say a descent's frames are its path's
/// (`TrackedMotion::frame`).
pub(super) fn on_path(req: &Request, t: &TrackedMotion) -> String {
    match (req.load.recording.crop, t.frame) {
        (None, Some(c)) => format!(", its frames{}", path_words(c)),
        _ => String::new(),
    }
}

/// The words that say frames are framed on the object's path `c`.
pub(super) fn path_words(c: Crop) -> String {
    format!(
        " framed on the object's path (--crop {},{},{},{})",
        c.x, c.y, c.w, c.h
    )
}

/// A descent's acceleration points above the picture's horizontal by at most this many degrees
/// (a camera's roll: levelled within a few, the shared drop's and toss's 1.4° and 1.7°; a cart
/// pulled along a level track accelerates along it, a hair either side of the horizontal).
pub const LEVEL_DEG: f64 = 10.0;

/// Where the model is the tool's to choose (`chooses`, no model files, no `--init`): `g` set to
/// the law the direction of `span`'s acceleration names (`data::falls`: free-fall, else
/// sliding-block; an incline typed, the slide), in place of training every candidate, and the
/// words that say so.
pub(super) fn named_by_direction(
    g: &mut Request,
    route: &TrackRoute,
    span: &LawSpan,
    chooses: bool,
) -> Option<String> {
    if !(chooses && g.candidates.is_empty() && g.init.is_empty()) {
        return None;
    }
    // In the picture, whichever way a plane's corners were given.
    let axis = route.picture_axis(span, direction(span));
    let drawn = axis[1].atan2(axis[0]).to_degrees();
    // An incline typed is a slide's, as in the model choice (`choice::SAME_LAW`).
    let (name, why) = match (g.calibration.incline_deg, falls(axis)) {
        (Some(deg), _) => ("sliding-block", format!("--incline-deg {deg}")),
        (None, fall) => (
            if fall { "free-fall" } else { "sliding-block" },
            format!("the acceleration points {drawn:.0}° from the picture's right, y down"),
        ),
    };
    g.choose = false;
    g.load.model = ModelRef::by_name(name);
    Some(format!(
        "trained the {name} ({why}; give --model to choose yourself)"
    ))
}

/// Without a stick or a plane, where the track's chosen law is a constant acceleration that
/// holds, does not point up the picture (gravity's pull, a fall's, a slide's or a roll's from
/// rest, or a cart's pulled by a hanging mass, along a level track: [`LEVEL_DEG`]; one that
/// points up is no descent, whatever else moves so for a second, as a pendulum's bob past its
/// lowest point) and its vertex lies where the track saw the object
/// (`tracked_motion`): a motion from rest released there and on the track's line, in place of
/// the picture's guess; the model given, or where it is the tool's to choose (`chooses`) and
/// the motion moves away from its vertex, the law the direction names (`named_by_direction`);
/// the calibration as asked.
pub fn sighted(req: &Request, route: &TrackRoute, chooses: bool) -> Option<(Request, String)> {
    let span = route
        .accelerating()
        .filter(|_| route.per_metre().is_none())
        .filter(|s| direction(s).to_radians().sin() >= -LEVEL_DEG.to_radians().sin())?;
    if req.load.model.is_some_and(|m| !m.released_from_rest()) {
        return None;
    }
    let tracked = tracked_motion(route, span, direction(span));
    let (first, last) = route.file_span(span);
    let mut g = req.clone();
    // Named where the motion moves away from its vertex, as from a release (a level that slows
    // towards one, as a draining jar's, is no fall).
    let away = span
        .values
        .iter()
        .any(|v| v.name == "vertex" && v.value <= span.last_s);
    let named = named_by_direction(&mut g, route, span, chooses && away);
    let released = match tracked.release {
        Some(release) => {
            g.load.recording.tracked = Some(tracked);
            format!(
                " from its vertex at {release:.4} s: a fall or slide from rest is released \
                 there, on the track's line{}",
                on_path(req, &tracked)
            )
        }
        // A vertex it did not see: the release is the picture's to find.
        None if named.is_some() => String::new(),
        None => return None,
    };
    let named = named
        .map(|n| format!("; the latent route {n}"))
        .unwrap_or_default();
    let why = format!(
        "the object's track accelerates at a constant rate over {first:.2}–{last:.2} s of the \
         file{released}{named}"
    );
    Some((g, why))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::metres::tests::tossed;

    #[test]
    fn a_release_the_track_saw_is_taken_and_a_rise_before_it_is_no_rest() {
        let route = tossed();
        let span = route.accelerating().unwrap();
        // The toss rises 19 px (over its 6 px size) from the span's start to its apex.
        let t = tracked_motion(&route, span, 90.0);
        let apex = t.release.unwrap();
        assert!((apex - 1.375).abs() < 1e-6, "{apex}");
        assert!(t.moving_before);
        // Without a stick, every fall or slide from rest is released there.
        let req = Request::new("toss.mp4");
        let (g, why) = sighted(&req, &route, false).unwrap();
        let got = g.load.recording.tracked.unwrap();
        assert_eq!((got.release, got.moving_before), (t.release, true));
        assert!(why.contains("released there"), "{why}");
        // An acceleration up the picture is no descent from rest (a bob past its lowest point).
        let mut up = route.clone();
        up.laws[0]
            .values
            .iter_mut()
            .filter(|v| v.name == "direction")
            .for_each(|v| v.value = -128.0);
        assert!(sighted(&req, &up, false).is_none());
        // One along the picture's horizontal, a hair above it either way, is a cart's pulled
        // along a level track.
        for level in [-0.003, -179.999, 3.0] {
            let mut cart = route.clone();
            cart.laws[0]
                .values
                .iter_mut()
                .filter(|v| v.name == "direction")
                .for_each(|v| v.value = level);
            assert!(sighted(&req, &cart, false).is_some(), "{level}");
        }
        // With one, `measured` does the work; for a model not from rest, nothing.
        let stuck = route
            .clone()
            .with_stick(crate::calibration::Stick::parse("0,0:0,200=1").unwrap());
        assert!(sighted(&req, &stuck, false).is_none());
        let mut osc = req.clone();
        osc.load.model = ModelRef::by_name("damped-oscillator");
        assert!(sighted(&osc, &route, false).is_none());
        // A vertex where the span starts (a drop from rest): no rise before it.
        let mut dropped = route.clone();
        let l = &mut dropped.laws[0];
        let first = l.first_s;
        l.values
            .iter_mut()
            .filter(|v| v.name == "vertex")
            .for_each(|v| v.value = first);
        let t = tracked_motion(&dropped, dropped.accelerating().unwrap(), 90.0);
        assert!(t.release.is_some() && !t.moving_before);
    }

    #[test]
    fn where_the_model_is_the_tools_the_direction_names_it() {
        let route = tossed();
        let req = Request::new("toss.mp4");
        // Down the picture: the fall, in place of a choice among every model.
        let (g, why) = sighted(&req, &route, true).unwrap();
        assert_eq!(g.load.model, ModelRef::by_name("free-fall"));
        assert!(!g.choose, "{why}");
        assert!(why.contains("trained the free-fall"), "{why}");
        // Along it (a cart pulled along a level track): the slide; and with the vertex not
        // seen, the model still named, its release left to the picture.
        let mut cart = route.clone();
        for v in cart.laws[0].values.iter_mut() {
            match v.name {
                "direction" => v.value = 3.0,
                "vertex" => v.value = -50.0,
                _ => {}
            }
        }
        let (g, why) = sighted(&req, &cart, true).unwrap();
        assert_eq!(g.load.model, ModelRef::by_name("sliding-block"));
        assert!(
            g.load.recording.tracked.is_none() && !why.contains("released"),
            "{why}"
        );
        // An incline typed: the slide, whatever the direction.
        let mut inclined = req.clone();
        inclined.calibration.incline_deg = Some(10.0);
        let (g, why) = sighted(&inclined, &route, true).unwrap();
        assert_eq!(g.load.model, ModelRef::by_name("sliding-block"), "{why}");
        // Slowing towards a vertex after the span (a draining level): nothing named.
        let mut slowing = cart.clone();
        let last = slowing.laws[0].last_s;
        for v in slowing.laws[0]
            .values
            .iter_mut()
            .filter(|v| v.name == "vertex")
        {
            v.value = last + 5.0;
        }
        assert!(sighted(&req, &slowing, true).is_none());
        // Not the tool's to choose: nothing named, and without a release, no request.
        assert!(sighted(&req, &cart, false).is_none());
        let mut init = req.clone();
        init.init = vec![("acceleration_latent".into(), 1.0)];
        assert!(sighted(&init, &cart, true).is_none());
    }
}
