//! What was made of a recording (`RecordingSummary`: decoded, framed, trimmed, cut), for the
//! report and the plots, and `--reference` times placed on its clip frames: the nearest one,
//! or the kept part's nearest end for a time among frames left out still or at rest.

use super::kept::Outside;
use super::{descent, object};
use physvid_shared::cli::{approx, num};
use physvid_shared::video::{Crop, Survey, VideoInfo};
use serde::Serialize;

/// A reference placed on a clip frame: (clip, frame in it, value).
pub type ReferenceFrame = (usize, usize, f64);

/// What was made of a recording, for the report and the plots.
#[derive(Debug, Clone, Serialize)]
pub struct RecordingSummary {
    pub info: VideoInfo,
    /// The frame rate used and where it came from ("--fps" or "container").
    pub fps: f64,
    pub fps_source: &'static str,
    /// Frames a second of the file's own timeline (the container's rate, or the frames'
    /// clock where it differs; an image folder's `--fps`): frame k of the decode is at
    /// `start + k / timeline_fps`.
    #[serde(skip)]
    pub timeline_fps: f64,
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
    /// The time (s) from the release to `frame` of the part kept: a clip's or a window's start
    /// time for a motion from rest (negative before it: the rest kept, or a toss's rise).
    pub fn since_release(&self, frame: usize) -> f64 {
        (frame as f64 - self.release) / self.fps
    }

    /// The clip frame (clip, frame in it) nearest to `t` seconds of the recording's own
    /// timeline (as `--start` counts, at the container's frame rate; an image folder's at
    /// `--fps`), or why there is none. A time among the still frames left out at either end
    /// (or before a release, at rest) is taken at the part kept's end, and said so. Where the
    /// law's rollout runs past a clip (`past_end`), a time within half a clip's span after the
    /// part kept (the floor at a fall's impact) is placed past a clip's end, on its rollout,
    /// and said so: its frame in the clip is then `frames_per_clip` or more.
    pub fn clip_frame_at(
        &self,
        t: f64,
        past_end: bool,
    ) -> Result<((usize, usize), Option<String>), String> {
        let start = self.start.unwrap_or(0.0);
        let last = self.frames_decoded.saturating_sub(1);
        let timeline_fps = self.timeline_fps;
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
            Some((how, f, edge, side)) => {
                let beyond = at - last as f64;
                let reach = ((self.frames_per_clip - 1) * self.stride) as f64 / 2.0;
                if let (true, "after", Outside::Unknown, true) =
                    (past_end, side, how, beyond <= reach.max(1.0))
                {
                    return self.on_rollout(t, at, end);
                }
                let what = match how {
                    Outside::Unknown => {
                        return Err(format!(
                            "{}s: outside the part of the recording kept, {}–{} s",
                            num(t),
                            approx(start),
                            approx(end)
                        ))
                    }
                    Outside::Still => "the picture still",
                    Outside::AtRest => "the object at rest before its release",
                };
                let note = format!(
                    "--reference {}s: {side} the part kept ({}–{} s), {what}: taken at its \
                     {} frame, {} s",
                    num(t),
                    approx(start),
                    approx(end),
                    if f == 0 { "first" } else { "last" },
                    approx(edge)
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

    /// Frame `at` (of the decode, `t` s of the timeline) past the part kept, which ends at
    /// `end` s, on a clip's rollout carried past its end: (clip, frame in it) and the note.
    fn on_rollout(
        &self,
        t: f64,
        at: f64,
        end: f64,
    ) -> Result<((usize, usize), Option<String>), String> {
        // The clip whose frames, carried on at its stride, land nearest the frame; of those
        // as near, the latest (the shortest carry).
        let f = at.round() as usize;
        let (_, c, k) = self
            .clip_starts
            .iter()
            .enumerate()
            .filter(|(_, &s)| s <= f)
            .map(|(c, &s)| {
                let k = (f - s + self.stride / 2) / self.stride;
                ((s + k * self.stride).abs_diff(f), c, k)
            })
            .min_by(|a, b| a.0.cmp(&b.0).then(b.1.cmp(&a.1)))
            .ok_or_else(|| format!("{}s: the recording has no clips", num(t)))?;
        let note = format!(
            "--reference {}s: after the part kept ({}–{} s), {} frame(s) past its last: read \
             where the law carries a clip's latent (its rollout), not on a frame seen",
            num(t),
            approx(self.start.unwrap_or(0.0)),
            approx(end),
            approx(at - (self.frames_decoded.saturating_sub(1)) as f64)
        );
        Ok(((c, k), Some(note)))
    }

    /// `--reference` times as (clip, frame, value) at their nearest clip frames (past a clip's
    /// end on its rollout where `past_end` lets them, as [`RecordingSummary::clip_frame_at`]
    /// says), and what was said of those taken at an end of the part kept; two times on one
    /// frame with different values are refused.
    pub fn reference_frames(
        &self,
        times: &[(f64, f64)],
        past_end: bool,
    ) -> Result<(Vec<ReferenceFrame>, Vec<String>), String> {
        let mut out: Vec<(usize, usize, f64, f64)> = Vec::new();
        let mut notes = Vec::new();
        for &(t, v) in times {
            let ((c, f), note) = self.clip_frame_at(t, past_end)?;
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
                fields: None,
                frame_times: Vec::new(),
            },
            fps: 10.0,
            fps_source: "container",
            timeline_fps: 10.0,
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
        assert_eq!(rec.clip_frame_at(5.0, false).unwrap(), ((20, 0), None));
        let ((c, f), note) = rec.clip_frame_at(1.0, false).unwrap();
        assert_eq!((c, f), (0, 0));
        let note = note.expect("said");
        assert!(
            note.contains("before the part kept (3–12.9 s), the picture still"),
            "{note}"
        );
        // After the end the frames left out are not known to be still (a flag cut them).
        let err = rec.clip_frame_at(20.0, false).unwrap_err();
        assert!(
            err.contains("outside the part of the recording kept"),
            "{err}"
        );
        // At rest before a release, and still after a settling: the last frame kept.
        let rec = kept_from_3s(Outside::AtRest, Outside::Still);
        let (_, note) = rec.clip_frame_at(0.5, false).unwrap();
        assert!(note.unwrap().contains("at rest before its release"));
        let ((c, f), _) = rec.clip_frame_at(30.0, false).unwrap();
        assert_eq!((c, f), (80, 19));
    }

    #[test]
    fn a_reference_just_after_the_part_kept_is_read_on_the_rollout_where_the_law_runs_on() {
        // Frames end at 12.9 s; a clip spans 19 frames, so up to 9.5 frames after it.
        let rec = kept_from_3s(Outside::Unknown, Outside::Unknown);
        let ((c, f), note) = rec.clip_frame_at(13.2, true).unwrap();
        assert_eq!((c, f), (80, 22));
        assert!(note.unwrap().contains("3 frame(s) past its last"));
        assert!(rec.clip_frame_at(13.2, false).is_err());
        let err = rec.clip_frame_at(14.0, true).unwrap_err();
        assert!(err.contains("outside the part"), "{err}");
        // On a stride of 4 the clip whose frames land on the frame is chosen.
        let rec = RecordingSummary {
            stride: 4,
            frames_per_clip: 4,
            clip_starts: (0..88).collect(),
            ..kept_from_3s(Outside::Unknown, Outside::Unknown)
        };
        let ((c, f), _) = rec.clip_frame_at(13.0, true).unwrap();
        assert_eq!(c + 4 * f, 100, "{c}, {f}");
    }
}
