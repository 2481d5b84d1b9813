//! Recordings as input: `load_recording` decodes a video or a folder of images through
//! `physvid_shared::video` (ffmpeg) as its probe planned (the frame rate, Table 5's clip or the
//! flags': `probe`), frames and trims it, and cuts the frames into clips.

use super::kept::Outside;
use super::probe::RecordingPlan;
use super::{descent, framing, kept, object, stillness};
use super::{LoadRequest, RecordingRequest, Source};
use crate::error::{input_error, EstimateError};
use crate::physics::ModelRef;
use physvid_shared::cli::{approx, num};
use physvid_shared::contact_sheet::{contact_sheet, encode_png};
use physvid_shared::video::{Crop, Survey, VideoInfo, VideoOptions};
use serde::Serialize;
use std::path::Path;

/// At most this many clips by default: the hop between clip starts grows to stay below it.
pub const MAX_DEFAULT_CLIPS: usize = 1000;

/// A reference placed on a clip frame: (clip, frame in it, value).
pub type ReferenceFrame = (usize, usize, f64);

/// What was made of a recording, for the report and the plots.
#[derive(Debug, Clone, Serialize)]
pub struct RecordingSummary {
    pub info: VideoInfo,
    /// The frame rate used and where it came from ("--fps" or "container").
    pub fps: f64,
    pub fps_source: &'static str,
    pub frames_decoded: usize,
    pub frames_per_clip: usize,
    pub stride: usize,
    pub hop: usize,
    pub clips: usize,
    pub size: (usize, usize),
    /// The part of the frame the encoder saw (`None`: all of it), and how it was chosen.
    pub crop: Option<Crop>,
    pub framing: &'static str,
    /// `--crop auto`: where the picture moves (the survey's region and its share of the frame
    /// and of the motion).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub survey: Option<Survey>,
    /// `--preview`: clips.png written beside the report.
    pub preview: bool,
    /// The part kept, in seconds of the file's timeline (`--start`/`--end`, or the descent's).
    pub start: Option<f64>,
    pub end: Option<f64>,
    /// What the frames left out before and after the part kept show (a `--reference` time
    /// among them is taken at the part's first or last frame where they are still or at rest).
    pub before: Outside,
    pub after: Outside,
    /// An object that moves about the frames kept (not a descent), read by its position.
    pub object: Option<object::MovingObject>,
    /// Motion from rest: the descent found in the frames (frames of the whole decode).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub descent: Option<descent::Descent>,
    /// The release, in frames of the part kept (clips' start times count from it).
    pub release: f64,
    /// Seconds spent decoding (ffmpeg, the pipe, crop and resize, and the survey of where the
    /// picture moves) and frames per second.
    pub decode_s: f64,
    pub survey_s: f64,
    pub decode_fps: f64,
    /// First recording frame of each clip (index into the decoded frames).
    #[serde(skip)]
    pub clip_starts: Vec<usize>,
}

impl RecordingSummary {
    /// The clip frame (clip, frame in it) nearest to `t` seconds of the recording's own
    /// timeline (as `--start` counts, at the container's frame rate; an image folder's at
    /// `--fps`), or why there is none. A time among the still frames left out at either end
    /// (or before a release, at rest) is taken at the part kept's end, and said so.
    pub fn clip_frame_at(&self, t: f64) -> Result<((usize, usize), Option<String>), String> {
        let start = self.start.unwrap_or(0.0);
        let last = self.frames_decoded.saturating_sub(1);
        let timeline_fps = self.info.container_fps.unwrap_or(self.fps);
        let at = (t - start) * timeline_fps;
        let end = start + last as f64 / timeline_fps;
        let outside = if at <= -0.5 {
            Some((self.before, 0, start, "before"))
        } else if at >= last as f64 + 0.5 {
            Some((self.after, last, end, "after"))
        } else {
            None
        };
        let (f, note) = match outside {
            None => (at.round() as usize, None),
            Some((Outside::Unknown, ..)) => {
                return Err(format!(
                    "{}s: outside the part of the recording kept, {}–{} s",
                    num(t),
                    approx(start),
                    approx(end)
                ))
            }
            Some((how, f, at, side)) => {
                let what = match how {
                    Outside::AtRest => "the object at rest before its release",
                    _ => "the picture still",
                };
                let note = format!(
                    "--reference {}s: {side} the part kept ({}–{} s), {what}: taken at its \
                     {} frame, {} s",
                    num(t),
                    approx(start),
                    approx(end),
                    if f == 0 { "first" } else { "last" },
                    approx(at)
                );
                (f, Some(note))
            }
        };
        let nearest = |s: usize| {
            let k = (f.saturating_sub(s) + self.stride / 2) / self.stride;
            let k = k.min(self.frames_per_clip - 1);
            ((s + k * self.stride).abs_diff(f), k)
        };
        self.clip_starts
            .iter()
            .enumerate()
            .map(|(c, &s)| (nearest(s), c))
            .min()
            .map(|((_, k), c)| ((c, k), note))
            .ok_or_else(|| format!("{}s: the recording has no clips", num(t)))
    }

    /// `--reference` times as (clip, frame, value) at their nearest clip frames, and what was
    /// said of those taken at an end of the part kept; two times on one frame with different
    /// values are refused.
    pub fn reference_frames(
        &self,
        times: &[(f64, f64)],
    ) -> Result<(Vec<ReferenceFrame>, Vec<String>), String> {
        let mut out: Vec<(usize, usize, f64, f64)> = Vec::new();
        let mut notes = Vec::new();
        for &(t, v) in times {
            let ((c, f), note) = self.clip_frame_at(t)?;
            notes.extend(note);
            if let Some(&(_, _, v2, t2)) = out.iter().find(|o| (o.0, o.1) == (c, f) && o.2 != v) {
                return Err(format!(
                    "{}s={} and {}s={} fall on the same frame with different values",
                    num(t2),
                    num(v2),
                    num(t),
                    num(v)
                ));
            }
            out.push((c, f, v, t));
        }
        Ok((
            out.into_iter().map(|(c, f, v, _)| (c, f, v)).collect(),
            notes,
        ))
    }
}

/// A decoded recording cut into clips (by index: the frames are held once).
pub struct LoadedRecording {
    /// Every decoded frame, [F, H·W] row-major, values in [0, 1].
    pub frames: Vec<f32>,
    /// The recording frame of every clip frame, [N·T].
    pub clip_index: Vec<i64>,
    /// [N, T, 1, H, W] of the clips.
    pub shape: [usize; 5],
    /// The first clips as the model sees them (report.html; clips.png with `--preview`).
    pub preview_png: Option<Vec<u8>>,
    pub summary: RecordingSummary,
    pub warnings: Vec<String>,
}

/// A video or image folder (probed: `plan`), cut into clips for `model`.
pub(crate) fn recording_source(
    req: &LoadRequest,
    plan: &RecordingPlan,
    model: ModelRef,
) -> Result<Source, EstimateError> {
    let rec = load_recording(&req.input, model, &req.recording, plan, req.trying)?;
    // Systems released from rest: clip start times count from the release (found in the
    // frames, else the first frame kept).
    let start_times = model.released_from_rest().then(|| {
        rec.summary
            .clip_starts
            .iter()
            .map(|&s| (s as f64 - rec.summary.release) / rec.summary.fps)
            .collect()
    });
    Ok(Source {
        preview_png: rec.preview_png,
        frames: rec.frames,
        clip_index: Some(rec.clip_index),
        shape: rec.shape,
        meta: None,
        start_times,
        recording: Some(rec.summary),
        warnings: rec.warnings,
    })
}

/// Decodes `input` for `model` as its probe planned (`plan`: the frame rate, the clip) and
/// cuts it into clips; with `keep` (a model choice's candidate) the decoded frames are kept
/// for, or taken from, the other candidates.
pub fn load_recording(
    input: &Path,
    model: ModelRef,
    flags: &RecordingRequest,
    plan: &RecordingPlan,
    keep: bool,
) -> Result<LoadedRecording, EstimateError> {
    let RecordingPlan {
        ref info,
        fps,
        fps_source,
        frames_per_clip,
        stride,
        ..
    } = *plan;
    let mut warnings = plan.warnings.clone();
    framing::check_memory(
        input,
        info.as_ref(),
        flags,
        flags.size.unwrap_or(framing::DEFAULT_SIZE),
        frames_per_clip,
        MAX_DEFAULT_CLIPS,
    )?;
    let started = std::time::Instant::now();
    // What the encoder sees: the flag's rectangle, the whole frame, or where it moves.
    let framing::Framed {
        crop,
        how: framing,
        survey,
        size,
    } = framing::frame(input, info.as_ref(), flags)?;
    let survey_s = started.elapsed().as_secs_f64();
    let opts = VideoOptions {
        fps: Some(fps),
        crop,
        start: flags.start,
        end: flags.end,
        size,
        frames_per_clip,
        stride,
        hop: flags.hop,
        max_clips: MAX_DEFAULT_CLIPS,
    };
    let mut decoded = super::reuse::decode(input, &opts, info.clone(), keep)?;
    // A fall or slide from rest: its release, and the descent alone where no flag trims;
    // anything else: the frames where it moves.
    let timeline_fps = decoded.info.container_fps.unwrap_or(fps);
    let kept = if model.released_from_rest() {
        kept::trim_to_descent(&mut decoded, &opts, timeline_fps, &mut warnings)
    } else {
        stillness::trim(&mut decoded, &opts, timeline_fps, &mut warnings)
    };
    let object = kept
        .descent
        .is_none()
        .then(|| object::find(&decoded.frames, decoded.size))
        .flatten();
    let decode_s = started.elapsed().as_secs_f64();
    let n = decoded.clip_starts.len();
    let shape = [n, frames_per_clip, 1, size.1, size.0];
    // Four clips spread over the recording, at the encoder's resolution, magnified 2×.
    let preview_png = Some({
        let m = n.min(4);
        let rows: Vec<usize> = (0..m).map(|k| k * (n - 1) / (m - 1).max(1)).collect();
        let (clips, shape) = decoded.clips(&rows, frames_per_clip, stride);
        let all: Vec<usize> = (0..rows.len()).collect();
        let sheet = contact_sheet(&clips, shape, &all, 2);
        encode_png(&match &survey {
            Some(s) => framing::drawn_over(s, crop, decoded.info.width, &sheet),
            None => sheet,
        })
    });
    let summary = RecordingSummary {
        info: decoded.info.clone(),
        fps,
        fps_source,
        frames_decoded: decoded.frame_count(),
        frames_per_clip,
        stride,
        hop: decoded.hop,
        clips: decoded.clip_starts.len(),
        size,
        crop,
        framing,
        survey,
        preview: flags.preview,
        start: kept.start,
        end: kept.end,
        before: kept.before,
        after: kept.after,
        object,
        descent: kept.descent,
        release: kept.release,
        decode_s: decode_s + survey_s,
        survey_s,
        decode_fps: decoded.frame_count() as f64 / decode_s.max(1e-9),
        clip_starts: decoded.clip_starts.clone(),
    };
    if summary.clips < 2 {
        return Err(input_error(format!(
            "{}: only {} clip of {frames_per_clip} frames at stride {stride} fits in {} frames; \
             at least 2 are needed (lower --frames-per-clip, --stride or --hop, or trim less)",
            input.display(),
            summary.clips,
            summary.frames_decoded
        )));
    }
    Ok(LoadedRecording {
        clip_index: decoded.clip_index(frames_per_clip, stride),
        shape,
        frames: decoded.frames,
        preview_png,
        summary,
        warnings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 100 frames kept from 3 s of a 10-fps recording, clips of 20 frames at stride 1 starting
    /// at every frame; `before`/`after` what the frames left out show.
    fn kept_from_3s(before: Outside, after: Outside) -> RecordingSummary {
        RecordingSummary {
            info: VideoInfo {
                width: 20,
                height: 20,
                container_fps: Some(10.0),
                capture_fps: None,
                rotation: 0,
                expected_frames: None,
                frame_times: Vec::new(),
            },
            fps: 10.0,
            fps_source: "container",
            frames_decoded: 100,
            frames_per_clip: 20,
            stride: 1,
            hop: 1,
            clips: 81,
            size: (20, 20),
            crop: None,
            framing: "whole frame",
            survey: None,
            preview: false,
            start: Some(3.0),
            end: Some(12.9),
            before,
            after,
            object: None,
            descent: None,
            release: 0.0,
            decode_s: 0.0,
            survey_s: 0.0,
            decode_fps: 0.0,
            clip_starts: (0..81).collect(),
        }
    }

    #[test]
    fn a_reference_among_still_frames_left_out_is_taken_at_the_end_kept_and_said() {
        let rec = kept_from_3s(Outside::Still, Outside::Unknown);
        assert_eq!(rec.clip_frame_at(5.0).unwrap(), ((20, 0), None));
        let ((c, f), note) = rec.clip_frame_at(1.0).unwrap();
        assert_eq!((c, f), (0, 0));
        let note = note.expect("said");
        assert!(
            note.contains("before the part kept (3–12.9 s), the picture still"),
            "{note}"
        );
        // After the end the frames left out are not known to be still (a flag cut them).
        let err = rec.clip_frame_at(20.0).unwrap_err();
        assert!(
            err.contains("outside the part of the recording kept"),
            "{err}"
        );
        // At rest before a release, and still after a settling: the last frame kept.
        let rec = kept_from_3s(Outside::AtRest, Outside::Still);
        let (_, note) = rec.clip_frame_at(0.5).unwrap();
        assert!(note.unwrap().contains("at rest before its release"));
        let ((c, f), _) = rec.clip_frame_at(30.0).unwrap();
        assert_eq!((c, f), (80, 19));
    }
}
