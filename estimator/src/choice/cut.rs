//! One clip cut for every candidate on a recording. Each model's own default (appendix Table
//! 5's clip) cuts a recording differently (the pendulum's 2-s clips, the tank's 20-s ones), and
//! a law compared on clips of another length is not compared at all: a slow feature of a
//! pendulum's frames fits a drain on long clips better than the swing fits the pendulum on
//! short ones. So the candidates share one cut, taken from the motion's own time scale: a clip
//! spans one period where the picture's change repeats (`video::timescale`), else half the
//! frames kept (a decay, a drain). The falls and slides from rest keep their own (the descent
//! alone, found in the frames).

use crate::data::{shared_survey, RecordingRequest};
use crate::error::EstimateError;
use physvid_shared::cli::approx;
use physvid_shared::video::{self, is_recording};
use std::path::Path;

/// Frames per clip of the common cut (Table 5's for every system with a clip of 20).
pub const FRAMES: usize = 20;

/// The cut every candidate is fitted on, and why.
#[derive(Debug, Clone)]
pub struct CommonCut {
    pub frames_per_clip: usize,
    pub stride: usize,
    pub why: String,
}

/// The common cut for `input` with the recording `flags`: `None` for a data set or a bare
/// array (clips of their own), an image folder, or where `--frames-per-clip` and `--stride`
/// both say it.
pub fn common_cut(
    input: &Path,
    flags: &RecordingRequest,
) -> Result<Option<CommonCut>, EstimateError> {
    if !is_recording(input) || input.is_dir() {
        return Ok(None);
    }
    if flags.frames_per_clip.is_some() && flags.stride.is_some() {
        return Ok(None);
    }
    let info = video::probe_as(input, flags.fields)?;
    let frames = flags.frames_per_clip.unwrap_or(FRAMES);
    let kept = info
        .frames_within(flags.start, flags.end)
        .unwrap_or(info.frame_times.len());
    let fps = flags
        .fps
        .map(|f| info.read_rate(f))
        .or(info.capture_fps)
        .or(info.container_fps);
    let seconds = |frames: f64| match fps {
        Some(f) => format!("{} s", approx(frames / f)),
        None => format!("{} frames", approx(frames)),
    };
    let (stride, why) = match flags.stride {
        Some(s) => (s, "--stride".to_string()),
        None => {
            // Kept for the candidates' framing (`data::shared_survey`).
            let survey = shared_survey(input, &info, (flags.start, flags.end), true, true)?;
            // Where a hand takes the picture at an end, the free motion is what is kept.
            let kept = survey.free.map_or(kept, |f| f.last + 1 - f.first);
            stride_for(survey.period_frames, frames, kept, &seconds)
        }
    };
    Ok(Some(CommonCut {
        frames_per_clip: frames,
        stride,
        why: format!(
            "every candidate on clips of {frames} frames at stride {stride} ({} between frames): \
             {why}; the falls and slides from rest on the descent alone",
            seconds(stride as f64)
        ),
    }))
}

/// The stride at which a clip of `frames` spans one `period` (frames of the recording), or
/// half of the `kept` frames where nothing repeats; never more than half of them.
fn stride_for(
    period: Option<f64>,
    frames: usize,
    kept: usize,
    seconds: &dyn Fn(f64) -> String,
) -> (usize, String) {
    let gaps = frames.saturating_sub(1).max(1);
    let half = (kept / 2 / gaps).max(1);
    match period {
        // A motion faster than a clip's frames (under 2/3 of them a period): every frame, and
        // the recording said to sample it sparsely.
        Some(p) if gaps as f64 > 1.5 * p => (
            1,
            format!(
                "the motion repeats every {} (only {} frames of the recording): every frame is \
                 used, a clip spans {} periods; so few frames a period may be too few to follow \
                 it (a spring filmed at 12 a period came out at half its frequency): film at a \
                 higher frame rate",
                seconds(p),
                approx(p),
                approx(gaps as f64 / p),
            ),
        ),
        Some(p) if ((p / gaps as f64).round() as usize) <= half => (
            ((p / gaps as f64).round() as usize).max(1),
            format!(
                "a clip spans one period of the motion ({}, where the picture's change repeats)",
                seconds(p)
            ),
        ),
        Some(p) => (
            half,
            format!(
                "the motion repeats every {}, but a clip spans at most half of the {kept} frames kept",
                seconds(p)
            ),
        ),
        None => (
            half,
            format!("nothing repeats: a clip spans half of the {kept} frames kept"),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at_60(f: f64) -> String {
        format!("{} s", approx(f / 60.0))
    }

    #[test]
    fn a_clip_spans_a_period_or_half_the_recording() {
        // The shared pendulum: 125 frames a period, 1299 kept.
        let (s, why) = stride_for(Some(125.0), 20, 1299, &at_60);
        assert_eq!(s, 7);
        assert!(why.contains("one period"), "{why}");
        // The jar: nothing repeats in 842 frames.
        let (s, why) = stride_for(None, 20, 842, &at_60);
        assert_eq!(s, 22);
        assert!(why.contains("nothing repeats"), "{why}");
        // A slow swing on a short recording: at most half of it.
        let (s, _) = stride_for(Some(400.0), 20, 500, &at_60);
        assert!(19 * s <= 250, "{s}");
        // A fast flicker: every frame, and the recording said to sample it sparsely.
        let (s, why) = stride_for(Some(5.0), 20, 500, &at_60);
        assert_eq!(s, 1);
        assert!(
            why.contains("every frame") && why.contains("too few"),
            "{why}"
        );
        // Fast, a clip of 20 frames about a period: every frame, read as a period.
        let (s, why) = stride_for(Some(16.0), 20, 500, &at_60);
        assert_eq!(s, 1);
        assert!(why.contains("one period"), "{why}");
    }
}
