//! Recordings as input: `load_recording` decodes a video or a folder of images through
//! `physvid_shared::video` (ffmpeg) as its probe planned (the frame rate, Table 5's clip or the
//! flags': `probe`), frames and trims it, and cuts the frames into clips.

use super::probe::RecordingPlan;
use super::summary::RecordingSummary;
use super::{framing, kept, object, stillness};
use super::{Framing, LoadRequest, RecordingRequest, Source};
use crate::error::{input_error, EstimateError};
use crate::physics::ModelRef;
use physvid_shared::contact_sheet::{contact_sheet, encode_png};
use physvid_shared::video::free::FreeSpan;
use physvid_shared::video::VideoOptions;
use std::path::Path;

/// At most this many clips by default: the hop between clip starts grows to stay below it.
pub const MAX_DEFAULT_CLIPS: usize = 1000;

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
            .map(|&s| rec.summary.since_release(s))
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
    // What the encoder sees: the flag's rectangle, the whole frame, a fall's or slide's path on
    // its track, or where it moves.
    let on_path;
    let framed_by = match (flags.crop, flags.tracked.and_then(|t| t.frame)) {
        (None, Some(c)) if model.released_from_rest() => {
            on_path = RecordingRequest {
                crop: Some(Framing::Track(c)),
                ..flags.clone()
            };
            &on_path
        }
        _ => flags,
    };
    let framing::Framed {
        crop,
        how: framing,
        survey,
        size,
    } = framing::frame(input, info.as_ref(), framed_by, keep)?;
    let survey_s = started.elapsed().as_secs_f64();
    let mut opts = VideoOptions {
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
    if let Some(shake) = &flags.shake {
        // The first frame's time on the file's timeline, as the track read it.
        let times = decoded.info.times_within(opts.start, opts.end);
        let first = times.first().copied().unwrap_or(opts.start.unwrap_or(0.0));
        shake.steady(&mut decoded, first, crop);
    }
    warnings.extend(decoded.clock_note.clone());
    // Frames at the start off the even clock were left out: the part starts at the first kept,
    // and every time below counts from it.
    if decoded.first_s > 0.0 {
        opts.start = Some(opts.start.unwrap_or(0.0) + decoded.first_s);
    }
    // A fall or slide from rest: its release, and the descent alone where no flag trims;
    // anything else: the frames where it moves.
    let timeline_fps = decoded.timeline_fps.unwrap_or(fps);
    let kept = if model.released_from_rest() {
        kept::trim_to_descent(
            input,
            &mut decoded,
            &opts,
            (timeline_fps, flags.tracked),
            &mut warnings,
        )
    } else {
        // The survey's free motion, in frames of the decode (by their times where the frames
        // were put on their clock).
        let free = survey.as_ref().and_then(|s| s.free).map(|f| {
            let times = info
                .as_ref()
                .map(|i| i.times_within(opts.start, opts.end))
                .unwrap_or_default();
            let at = |i: usize| match times.get(i) {
                Some(t) => ((t - times[0]) * timeline_fps).round() as usize,
                None => i,
            };
            // A time the user measured the system at (a --reference) is in the free motion.
            let frame_of = |t: f64| (t - opts.start.unwrap_or(0.0)) * timeline_fps;
            let early = flags
                .measured_at
                .iter()
                .map(|&t| frame_of(t))
                .fold(f64::INFINITY, f64::min);
            FreeSpan {
                first: at(f.first).min(early.max(0.0).floor() as usize),
                ..f
            }
        });
        stillness::trim(&mut decoded, &opts, timeline_fps, free, &mut warnings)
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
        timeline_fps,
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
