//! The second route's part in a run: the object's own track read for a video file
//! (`track::follow`), and the request it guides where its oscillation is clear (the
//! oscillator on the track's span, in place of a choice among every model on frames a hand
//! may share). `run` calls both before the estimation, and `settle` after it.

use crate::choice;
use crate::config::Request;
use crate::data::Framing;
use crate::physics::ModelRef;
use crate::report::Report;
use crate::track::{self, TrackRoute};
use crate::verdict;
use physvid_shared::video;

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
    let framed = match r.crop {
        None => {
            let crop = route.frame_of(span);
            g.load.recording.crop = Some(Framing::Track(crop));
            format!(
                ", framed on the object's path (--crop {},{},{},{})",
                crop.x, crop.y, crop.w, crop.h
            )
        }
        Some(_) => String::new(),
    };
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

/// The object's own track and the laws fitted on it (`track`), for a video file (not an image
/// folder, not frames in memory); where it cannot be read, a warning says why and the latent's
/// answer stands alone.
pub fn second_route(req: &Request, warnings: &mut Vec<String>) -> Option<TrackRoute> {
    let load = &req.load;
    let input = &load.input;
    if load.frames.is_some() || !input.is_file() || !video::is_recording(input) {
        return None;
    }
    let r = &load.recording;
    let found = video::probe_as(input, r.fields)
        .and_then(|info| track::follow(input, &info, (r.start, r.end), r.fps));
    match found {
        Ok(route) => route,
        Err(e) => {
            warnings.push(format!("the object's track could not be read: {e}"));
            None
        }
    }
}

/// `report` with the track and the route's warnings set on its run, and its verdict judged
/// again with them (the model choice's close call kept).
pub fn settle(report: &mut Report, route: Option<TrackRoute>, warnings: Vec<String>) {
    report.run.warnings.extend(warnings);
    if let Some(route) = route {
        report.run.track = Some(route);
        let close = report
            .model_choice
            .as_ref()
            .and_then(choice::close::close_call);
        report.verdict = verdict::judge(&report.run).with(close);
    }
}
