//! The second route's part in a run: the object's own track read for a video file
//! (`track::follow`), and the request it guides: where its oscillation is clear, the
//! oscillator on the track's span (in place of a choice among every model on frames a hand
//! may share); with a stick or a plane, its constant acceleration in metres; without either, a
//! release from rest it saw. `run` calls both before the estimation, and `settle` after it.

use crate::choice;
use crate::config::Request;
use crate::data::{falls, Framing, TrackedMotion};
use crate::physics::ModelRef;
use crate::report::Report;
use crate::track::{LawSpan, TrackRoute};
use crate::verdict;

mod combine;
mod reading;
pub use combine::combine;
pub use reading::second_route;

/// Where the model and the span are the tool's to choose (`chooses`: no `--model`, or `auto`;
/// no model files, no `--start`/`--end`, no `--init`) and the track oscillates clearly
/// (`TrackRoute::guiding`): the request for the latent route on the oscillator over the track's
/// span, started from the track's answer, with the warning that says so. The latent moves off
/// that start where its frames say otherwise, so the verdict still compares two measurements
/// (`verdict::routes`); one that learns nothing is caught by the training, motion and law checks.
pub fn guided(req: &Request, route: &TrackRoute, chooses: bool) -> Option<(Request, String)> {
    let r = &req.load.recording;
    let free = chooses
        && req.candidates.is_empty()
        && req.init.is_empty()
        && r.start.is_none()
        && r.end.is_none();
    let span = route.guiding().filter(|_| free)?;
    let model = ModelRef::by_name("damped-oscillator")?;
    let (first, last) = route.file_span(span);
    let mut g = req.clone();
    g.choose = false;
    g.load.model = Some(model);
    let framed = framed(&mut g, route, span);
    // Started from the track's answer (the oscillator's values by the same names).
    g.init = span
        .values
        .iter()
        .filter(|v| model.parameters().iter().any(|p| p.name == v.name))
        .map(|v| (v.name.to_string(), v.value))
        .collect();
    g.load.recording.start = Some(first);
    // The end is excluded: half a frame past the last sample.
    let step = (last - first) / (span.samples.max(2) - 1) as f64;
    g.load.recording.end = Some(last + 0.5 * step);
    let why = format!(
        "the object's track oscillates over {:.2}–{:.2} s of the file ({:.1} periods): the \
         latent route trained the damped-oscillator there{framed}, started from the track's \
         answer (give --model or --start to choose yourself)",
        first,
        last,
        span.periods.unwrap_or(0.0)
    );
    Some((g, why))
}

/// Where a stick (`--stick`) or a plane (`--plane`) gives the track's scale and the track's
/// chosen law is a constant acceleration that holds (`TrackRoute::accelerating`): the request
/// whose latent route is calibrated by the track's readings (`TrackRoute::readings`, where no
/// `--reference` is given, or one that fixes their origin); where the model is the tool's to
/// choose, trained for the law the acceleration's direction names (`data::falls`: free-fall, else
/// sliding-block); for a motion from rest, its release and line read from the track
/// (`tracked_motion`). With the warning that says so.
pub fn measured(req: &Request, route: &TrackRoute, chooses: bool) -> Option<(Request, String)> {
    route.per_metre()?;
    let span = route.accelerating()?;
    let c = &req.calibration;
    let typed = !(c.values.is_empty() && c.times.is_empty() && c.positions.is_empty());
    // One reading typed beside the stick: the stick gives the scale, the reading the origin.
    let origin = match (
        c.values.is_empty() && c.positions.is_empty(),
        c.times.as_slice(),
    ) {
        (true, [one]) => Some(*one),
        _ => None,
    };
    let free = chooses && req.candidates.is_empty() && req.init.is_empty();
    let (first, last) = route.file_span(span);
    let mut g = req.clone();
    let mut did = Vec::new();
    let direction = direction(span);
    if free {
        // In the picture, whichever way a plane's corners were given.
        let axis = route.picture_axis(span, direction);
        let drawn = axis[1].atan2(axis[0]).to_degrees();
        let name = if falls(axis) {
            "free-fall"
        } else {
            "sliding-block"
        };
        g.choose = false;
        g.load.model = ModelRef::by_name(name);
        did.push(format!(
            "trained the {name} (the acceleration points {drawn:.0}° from the picture's \
             right, y down; give --model to choose yourself)"
        ));
    }
    if g.load.model.is_some_and(|m| m.released_from_rest()) {
        g.load.recording.tracked = Some(tracked_motion(route, span, direction));
        did.push("read its release and line from the track".into());
    }
    if !typed || origin.is_some() {
        let from = g
            .load
            .recording
            .tracked
            .and_then(|t| t.release)
            .unwrap_or(f64::NEG_INFINITY);
        let mut readings = route.readings(span, from);
        let mut how = String::new();
        if let Some((t, value)) = origin {
            // Where the track saw the object then, its distance there is the value typed.
            let shift = route.distance_at(span, t).map(|d| value - d);
            readings
                .iter_mut()
                .for_each(|r| r.1 += shift.unwrap_or(0.0));
            how = match shift {
                Some(_) => format!(", their origin from --reference {t}s={value}"),
                None => format!(
                    " (--reference {t}s={value} lies outside the track's span: its origin is \
                     the span's start)"
                ),
            };
        }
        g.calibration.times = readings;
        g.load.recording.measured_at = g.calibration.times.iter().map(|t| t.0).collect();
        did.push(format!(
            "calibrated it by the track's {} positions in metres{how}",
            g.calibration.times.len()
        ));
    }
    if did.is_empty() {
        return None;
    }
    let framed = framed(&mut g, route, span);
    let why = format!(
        "the object's track accelerates at a constant rate over {first:.2}–{last:.2} s of the \
         file, read in metres ({}): the latent route {}{framed}",
        route.scale_flag().unwrap_or_default(),
        did.join(", and ")
    );
    Some((g, why))
}

/// `g` framed on the object's path over `span` (`TrackRoute::frame_of`) where no `--crop` is
/// given (in place of where the picture moves most: a hand beside a toss), and the words that
/// say so.
fn framed(g: &mut Request, route: &TrackRoute, span: &LawSpan) -> String {
    if g.load.recording.crop.is_some() {
        return String::new();
    }
    let crop = route.frame_of(span);
    g.load.recording.crop = Some(Framing::Track(crop));
    format!(
        ", framed on the object's path (--crop {},{},{},{})",
        crop.x, crop.y, crop.w, crop.h
    )
}

/// The direction of a constant acceleration's span (degrees from the picture's right, y down).
fn direction(span: &LawSpan) -> f64 {
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
fn tracked_motion(route: &TrackRoute, span: &LawSpan, direction: f64) -> TrackedMotion {
    let value = |name: &str| span.values.iter().find(|v| v.name == name);
    let vertex = value("vertex").filter(|v| {
        let frame = (span.last_s - span.first_s) / (span.samples.max(2) - 1) as f64;
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
    }
}

/// A descent's acceleration points above the picture's horizontal by at most this many degrees
/// (a camera's roll: levelled within a few, the shared drop's and toss's 1.4° and 1.7°; a cart
/// pulled along a level track accelerates along it, a hair either side of the horizontal).
pub const LEVEL_DEG: f64 = 10.0;

/// Without a stick or a plane, where the track's chosen law is a constant acceleration that
/// holds, does not point up the picture (gravity's pull, a fall's, a slide's or a roll's from
/// rest, or a cart's pulled by a hanging mass, along a level track: [`LEVEL_DEG`]; one that
/// points up is no descent, whatever else moves so for a second, as a pendulum's bob past its
/// lowest point) and its vertex lies where the track saw the object
/// (`tracked_motion`): a motion from rest (the model given, or each such candidate tried)
/// released there and on the track's line, in place of the picture's guess; the model and its
/// calibration as asked.
pub fn sighted(req: &Request, route: &TrackRoute) -> Option<(Request, String)> {
    let span = route
        .accelerating()
        .filter(|_| route.per_metre().is_none())
        .filter(|s| direction(s).to_radians().sin() >= -LEVEL_DEG.to_radians().sin())?;
    if req.load.model.is_some_and(|m| !m.released_from_rest()) {
        return None;
    }
    let tracked = tracked_motion(route, span, direction(span));
    let release = tracked.release?;
    let (first, last) = route.file_span(span);
    let mut g = req.clone();
    g.load.recording.tracked = Some(tracked);
    let framed = framed(&mut g, route, span);
    let why = format!(
        "the object's track accelerates at a constant rate over {first:.2}–{last:.2} s of the \
         file from its vertex at {release:.4} s: a fall or slide from rest is released there, on \
         the track's line{framed}"
    );
    Some((g, why))
}

/// The request the track guides: its clear oscillation's (`guided`), else, with a stick or a
/// plane, its constant acceleration's (`measured`), else a release it saw (`sighted`).
pub fn request(req: &Request, route: &TrackRoute, chooses: bool) -> Option<(Request, String)> {
    guided(req, route, chooses)
        .or_else(|| measured(req, route, chooses))
        .or_else(|| sighted(req, route))
}

/// `report` with the track and the route's warnings set on its run, its verdict judged again
/// with them (the model choice's close call kept), then each value both routes measured alike
/// combined (`combine`) and the answer's own checks judged again on it
/// (`verdict::rejudge_answer`).
pub fn settle(report: &mut Report, route: Option<TrackRoute>, warnings: Vec<String>) {
    report.run.warnings.extend(warnings);
    if let Some(route) = route {
        report.run.track = Some(route);
        let close = report
            .model_choice
            .as_ref()
            .and_then(choice::close::close_call);
        let judged = verdict::judge(&report.run).with(close);
        let combined = report
            .run
            .track
            .as_ref()
            .is_some_and(|route| combine(&mut report.run.parameters, route));
        report.verdict = if combined {
            verdict::rejudge_answer(judged, &report.run)
        } else {
            judged
        };
    }
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
        let (g, why) = sighted(&req, &route).unwrap();
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
        assert!(sighted(&req, &up).is_none());
        // One along the picture's horizontal, a hair above it either way, is a cart's pulled
        // along a level track.
        for level in [-0.003, -179.999, 3.0] {
            let mut cart = route.clone();
            cart.laws[0]
                .values
                .iter_mut()
                .filter(|v| v.name == "direction")
                .for_each(|v| v.value = level);
            assert!(sighted(&req, &cart).is_some(), "{level}");
        }
        // With one, `measured` does the work; for a model not from rest, nothing.
        let stuck = route
            .clone()
            .with_stick(crate::calibration::Stick::parse("0,0:0,200=1").unwrap());
        assert!(sighted(&req, &stuck).is_none());
        let mut osc = req.clone();
        osc.load.model = ModelRef::by_name("damped-oscillator");
        assert!(sighted(&osc, &route).is_none());
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
    fn with_a_stick_one_reading_fixes_the_origin() {
        let stick = crate::calibration::Stick::parse("0,0:0,200=1").unwrap();
        let route = tossed().with_stick(stick);
        let span = route.accelerating().unwrap();
        let mut req = Request::new("toss.mp4");
        req.load.model = ModelRef::by_name("damped-oscillator");
        // No reading typed: the track's, from the span's start.
        let (g, _) = measured(&req, &route, false).unwrap();
        let plain = g.calibration.times.clone();
        assert_eq!(plain.len(), crate::track::metres::READINGS);
        // One reading typed: the same readings, shifted so that the track passes through it.
        let at = (plain[1].0 + plain[2].0) / 2.0;
        req.calibration.times = vec![(at, 5.0)];
        let (g, why) = measured(&req, &route, false).unwrap();
        let shift = 5.0 - route.distance_at(span, at).unwrap();
        for (a, b) in g.calibration.times.iter().zip(&plain) {
            assert_eq!(a.0, b.0);
            assert!((a.1 - b.1 - shift).abs() < 1e-12);
        }
        assert!(why.contains("origin from --reference"), "{why}");
        // Two typed: they are the calibration, the track's readings left out.
        req.calibration.times = vec![(at, 5.0), (plain[4].0, 6.0)];
        assert!(measured(&req, &route, false).is_none());
    }
}
