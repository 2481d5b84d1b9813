//! The object's own track read for a run (`second_route`): for a video file, on the scale of a
//! stick or the plane of a rectangle where one is given, which are checked against it here, or
//! on the scale the `--reference` readings give its constant acceleration where neither is.

use crate::config::Request;
use crate::error::{input_error, EstimateError};
use crate::track::{self, TrackRoute};
use physvid_shared::video;

/// The object's own track and the laws fitted on it (`track`), for a video file (not an image
/// folder, not frames in memory), on a stick's or a plane's scale where one is given
/// (`check_stick`); where it cannot be read, a warning says why and the latent's answer stands
/// alone.
pub fn second_route(
    req: &Request,
    warnings: &mut Vec<String>,
) -> Result<Option<TrackRoute>, EstimateError> {
    let route = read_track(req, warnings);
    check_stick(req, route.as_ref(), warnings)?;
    Ok(route)
}

/// Whether the request reads a video file (not an image folder, not frames in memory): what
/// a track is read on.
fn on_video(req: &Request) -> bool {
    let load = &req.load;
    load.frames.is_none() && load.input.is_file() && video::is_recording(&load.input)
}

/// The track of a video file, on the plane or the stick's scale where one is given, else on
/// the readings' (`TrackRoute::with_readings`), its law's span one the readings lie in
/// (`TrackRoute::through_readings`); none where its acceleration holds no reading
/// (`TrackRoute::holds_readings`).
fn read_track(req: &Request, warnings: &mut Vec<String>) -> Option<TrackRoute> {
    if !on_video(req) {
        return None;
    }
    let (input, r) = (&req.load.input, &req.load.recording);
    let found = video::probe_as(input, r.fields)
        .and_then(|info| track::follow(input, &info, (r.start, r.end), r.fps));
    match found {
        Ok(route) => route
            .map(|r| match (req.calibration.plane, req.calibration.stick) {
                (Some(p), _) => r.on_plane(p),
                (None, Some(s)) => r.with_stick(s),
                (None, None) => r
                    .through_readings(&req.calibration.times)
                    .with_readings(&req.calibration.times)
                    .drain_in_metres(&req.calibration.times),
            })
            .filter(|r| {
                let holds = r.holds_readings(&req.calibration.times);
                if !holds {
                    warnings.push(
                        "the object's track was not used: its constant acceleration holds none of \
                     the times the motion was measured at (--reference), so it follows \
                     something else"
                            .to_string(),
                    );
                }
                holds
            }),
        Err(e) => {
            warnings.push(format!("the object's track could not be read: {e}"));
            None
        }
    }
}

/// A stick (`--stick`) or a plane (`--plane`) needs a video file's track and must lie in its
/// picture: refused (the input's error) on anything else, or for a point outside the frame; a
/// warning where the track gives nothing to read in metres.
fn check_stick(
    req: &Request,
    route: Option<&TrackRoute>,
    warnings: &mut Vec<String>,
) -> Result<(), EstimateError> {
    let c = &req.calibration;
    let flag = match (c.plane, c.stick) {
        (Some(p), _) => format!("--plane {}", p.flag()),
        (None, Some(s)) => format!("--stick {}", s.flag()),
        (None, None) => return Ok(()),
    };
    let what = flag.split(' ').next().unwrap_or_default();
    if !on_video(req) {
        return Err(input_error(format!(
            "{what} scales the object's track in a video file, and {} is none: give \
             --reference for a data set, an array or an image folder",
            req.load.input.display()
        )));
    }
    let Some(route) = route else {
        warnings.push(format!(
            "{flag} was not used: nothing in the recording was followed long enough"
        ));
        return Ok(());
    };
    let (w, h) = route.track.picture;
    if let Some(s) = c.stick {
        s.check_within(w, h).map_err(input_error)?;
    }
    if let Some(p) = c.plane {
        p.check_within(w, h).map_err(input_error)?;
    }
    if route.chosen_span().is_none_or(|l| l.si.is_empty()) {
        warnings.push(format!(
            "{flag} gave nothing in metres: the object's track holds no law with a length \
             (a constant acceleration, an oscillation's amplitude)"
        ));
    }
    Ok(())
}
