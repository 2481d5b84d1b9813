//! The second route's part in a run: the object's own track read for a video file
//! (`track::follow`), and the request it guides: where its oscillation (or a brightness's
//! decay) is clear, the oscillator (the LED) on the track's span (in place of a choice among
//! every model on frames a hand may share); with a stick or a plane, its constant acceleration
//! in metres; without either, a release from rest it saw. `run` calls both before the
//! estimation, and `settle` after it.

use crate::choice;
use crate::config::Request;
use crate::data::Framing;
use crate::physics::ModelRef;
use crate::report::Report;
use crate::track::laws::TrackLaw;
use crate::track::TrackRoute;
use crate::verdict;

mod acceleration;
mod combine;
mod descent;
mod followed;
mod reading;
mod tank;
use acceleration::combine_acceleration;
pub use combine::combine;
use descent::{direction, named_by_direction, on_path, path_words, tracked_motion};
pub use descent::{sighted, LEVEL_DEG};
pub use reading::second_route;
use tank::combine_drain;

/// Where the model and the span are the tool's to choose (`chooses`: no `--model`, or `auto`;
/// no model files, no `--start`/`--end`, no `--init`) and the track oscillates or decays clearly
/// (`TrackRoute::guiding`): the request for the latent route on the law's model
/// (`TrackRoute::guided_model`) over the track's span, started from the track's answer alone
/// (`--single-start`), with the warning that says so. The latent moves off that start where its
/// frames say otherwise, so the verdict still compares two measurements (`verdict::routes`); one
/// that learns nothing is caught by the training, motion and law checks.
pub fn guided(req: &Request, route: &TrackRoute, chooses: bool) -> Option<(Request, String)> {
    let r = &req.load.recording;
    let free = chooses
        && req.candidates.is_empty()
        && req.init.is_empty()
        && r.start.is_none()
        && r.end.is_none();
    let span = route.guiding().filter(|_| free)?;
    // A swing's period depends on its amplitude: the pendulum, on the track's angles.
    let swings = span.law == TrackLaw::Swing;
    let name = route.guided_model()?;
    let model = ModelRef::by_name(name)?;
    let (mut first, mut last) = route.file_span(span);
    // Half a frame, the end's margin (the end is excluded).
    let half_step = 0.5 * (last - first) / (span.samples.max(2) - 1) as f64;
    // A level's readings (a tank's heights, typed with --reference) are where the user
    // measured it: the span reaches them (a drain's law holds once the surface has settled,
    // and the jar's first reading was taken while it still sloshed).
    let (t0, t1) = (route.track.file_s.first(), route.track.file_s.last());
    if let (true, Some(&t0), Some(&t1)) = (span.law.of_a_level(), t0, t1) {
        for &(t, _) in req
            .calibration
            .times
            .iter()
            .filter(|(t, _)| (t0..=t1).contains(t))
        {
            (first, last) = (first.min(t), last.max(t));
        }
    }
    let mut g = req.clone();
    g.choose = false;
    g.load.model = Some(model);
    // Framed on the object's path where no --crop is given (not where the picture moves
    // most: a hand beside the mass).
    let framed = match r.crop {
        None => {
            let crop = route.frame_of(span);
            g.load.recording.crop = Some(Framing::Track(crop));
            match route.track.region {
                Some(_) => format!(
                    ", framed on the region whose light changes (--crop {},{},{},{})",
                    crop.x, crop.y, crop.w, crop.h
                ),
                None => format!(",{}", path_words(crop)),
            }
        }
        Some(_) => String::new(),
    };
    // A decay's clip spans at least one e-fold, as an oscillation's a period (the LED's Table 5
    // clip, a third of a second, sees a slow light barely change), where no --stride is given.
    let rate = span.rate().map(|v| v.value).filter(|v| *v > 0.0);
    if let (TrackLaw::Decay, None, Some(rate)) = (span.law, r.stride, rate) {
        let frames = r.frames_per_clip.unwrap_or(model.table5_clip().0).max(2);
        let step = span.held_s() / (span.samples.max(2) - 1) as f64;
        let stride = (1.0 / rate / ((frames - 1) as f64 * step)).ceil().max(1.0);
        g.load.recording.stride = Some(stride as usize);
    }
    // Started from the track's answer alone (the oscillator's values by the same names): the
    // starts read off the frames and a retry at half the frequency are the unguided run's
    // ways to a rate the track here measures (a latent that learned a slow drift had fitted
    // better at a quarter of γ0, and its probe won). A value outside the model's bounds (an
    // undamped swing's damping measured a hair below zero) leaves the model's own start.
    g.init = span
        .values
        .iter()
        .filter(|v| {
            let p = model.parameters().iter().find(|p| p.name == v.name);
            p.is_some_and(|p| p.bounds.contains(v.value))
        })
        .map(|v| (v.name.to_string(), v.value))
        .collect();
    // A drain's values are in its level's units, none the tank's: its own starts.
    g.training.single_start = !g.init.is_empty();
    g.load.recording.start = Some(first);
    g.load.recording.end = Some(last + half_step);
    // The pendulum's angle scale from the track's angles, where none were typed.
    let c = &req.calibration;
    let angles = match swings && c.values.is_empty() && c.times.is_empty() {
        true => route.angles(span),
        false => Vec::new(),
    };
    let calibrated = match angles.len() {
        0 => String::new(),
        k => format!(", calibrated by the track's {k} angles about its pivot"),
    };
    if !angles.is_empty() {
        g.load.recording.measured_at = angles.iter().map(|a| a.0).collect();
        g.calibration.times = angles;
    }
    let why = format!(
        "{} {} over {:.2}–{:.2} s of the file ({}): the latent route trained the {name} \
         there{framed}, started from {}{calibrated} (give --model or --start to choose \
         yourself)",
        route.subject(),
        span.law.verb(),
        first,
        last,
        span.extent_words(),
        match g.training.single_start {
            true => "the track's answer alone",
            false => "its own starts",
        }
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
    let (first, last) = route.file_span(span);
    let mut g = req.clone();
    let mut did = Vec::new();
    let direction = direction(span);
    if let Some(named) = named_by_direction(&mut g, route, span, chooses) {
        did.push(named);
    }
    if g.load.model.is_some_and(|m| m.released_from_rest()) {
        let tracked = tracked_motion(route, span, direction);
        g.load.recording.tracked = Some(tracked);
        did.push(format!(
            "read its release and line from the track{}",
            on_path(req, &tracked)
        ));
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
    let why = format!(
        "the object's track accelerates at a constant rate over {first:.2}–{last:.2} s of the \
         file, read in metres ({}): the latent route {}",
        route.scale_flag().unwrap_or_default(),
        did.join(", and ")
    );
    Some((g, why))
}

/// The request the track guides: its clear oscillation's (`guided`), else, with a stick or a
/// plane, its constant acceleration's (`measured`), else a release it saw (`sighted`); in the
/// last two, the law the acceleration's direction names where the model is the tool's.
pub fn request(req: &Request, route: &TrackRoute, chooses: bool) -> Option<(Request, String)> {
    guided(req, route, chooses)
        .or_else(|| measured(req, route, chooses))
        .or_else(|| sighted(req, route, chooses))
}

/// `req` with the latent route's frames steadied by the camera's shake, where the track was
/// read on frames steadied against it or the camera shook from frame to frame
/// (`TrackRoute::shake`): the encoder sees the frames the track that guides it saw, or a
/// still picture. With the warning that says so; `None` for a still camera or a slow drift.
pub fn steadied(req: &Request, route: &TrackRoute) -> Option<(Request, String)> {
    let shake = route.shake.as_ref()?;
    let mut g = req.clone();
    g.load.recording.shake = Some(shake.clone());
    let why = format!(
        "the camera shook (up to {:.1} px of the frame): the latent route read each frame moved \
         back by the shift the track measured in it",
        shake.largest()
    );
    Some((g, why))
}

/// `report` with the track and the route's warnings set on its run, its verdict judged again
/// with them (the model choice's close call kept), then each value both routes measured made
/// the track's (`combine`: the latent's kept beside it as its second opinion) and the answer's
/// own checks judged again on it (`verdict::rejudge_answer`).
pub fn settle(report: &mut Report, route: Option<TrackRoute>, warnings: Vec<String>) {
    report.run.warnings.extend(warnings);
    if let Some(route) = route {
        report.run.evidence.track_fold = followed::followed(&report.run, &route);
        report.run.track = Some(route);
        let close = report
            .model_choice
            .as_ref()
            .and_then(choice::close::close_call);
        let judged = verdict::judge(&report.run).with(close);
        let route = report.run.track.take();
        let combined = route.as_ref().is_some_and(|route| {
            combine(&mut report.run, route)
                || combine_acceleration(&mut report.run, route)
                || combine_drain(&mut report.run, route)
        });
        report.run.track = route;
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

    /// An undamped swing's track: its damping measured a hair below zero, outside the
    /// pendulum's bounds (positive). The latent starts from the track's g/L and the pendulum's
    /// own damping, where it was refused ("--init damping=-2.3e-5: must be > 0").
    #[test]
    fn a_start_outside_the_model_s_bounds_is_the_model_s_own() {
        let (mut route, _) = crate::track::test_route();
        let value = |name: &'static str, value: f64, error: f64| crate::track::laws::Value {
            name,
            value,
            error,
            unit: "",
        };
        route.laws[0].law = TrackLaw::Swing;
        route.chosen = Some(TrackLaw::Swing);
        route.laws[0].values = vec![
            value("g_over_l", 14.0, 0.001),
            value("damping", -2.3e-5, 1e-4),
            value("amplitude", 24.0, 0.0),
            value("rest", 0.0, 0.01),
        ];
        route.laws[0].periods = Some(4.0);
        let req = Request::new("swing.mp4");
        let (g, _) = guided(&req, &route, true).expect("a clear swing guides");
        assert_eq!(g.init, vec![("g_over_l".to_string(), 14.0)]);
        let model = g.load.model.unwrap();
        assert_eq!(model.name(), "pendulum");
        let start = crate::config::initial_values(model, &g.init).unwrap();
        assert!(start.iter().all(|v| v.is_finite()), "{start:?}");
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
