//! The part of a recording kept: what `--start`/`--end` say, else the frames the data show
//! matter (the still ones trimmed by `stillness`, a fall or slide from rest's descent by
//! [`trim_to_descent`]), and where the release is in it.

use super::descent::{self, Descent};
use super::request::TrackedMotion;
use super::{tinted, tracked};
use physvid_shared::cli::approx;
use physvid_shared::video::{DecodedVideo, VideoOptions};
use std::path::Path;

/// The part of a recording kept, and its release.
pub struct Kept {
    /// In seconds of the file's timeline (`--start`/`--end`, or the descent's).
    pub start: Option<f64>,
    pub end: Option<f64>,
    /// The release in frames of the part kept (0: the first frame kept).
    pub release: f64,
    pub descent: Option<Descent>,
    /// What the frames left out at either end show, where the data (not a flag) trimmed them.
    pub before: Outside,
    pub after: Outside,
}

/// What the frames left out at one end of the part kept show, for a `--reference` time among
/// them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outside {
    /// Nothing left out there, or `--start`/`--end` left it out: its frames are not known.
    Unknown,
    /// A still picture (`stillness`): the quantity there is what the part kept's end shows.
    Still,
    /// The object at rest before its release (`descent`, the law's premise): the quantity
    /// there is what it is at the release.
    AtRest,
}

impl Kept {
    /// The part `--start`/`--end` keep, released at its first frame.
    pub fn untrimmed(opts: &VideoOptions) -> Kept {
        Kept {
            start: opts.start,
            end: opts.end,
            release: 0.0,
            descent: None,
            before: Outside::Unknown,
            after: Outside::Unknown,
        }
    }

    /// Seconds on the file's timeline of frame `f` of a decode cut with `opts`.
    pub fn time_of(opts: &VideoOptions, timeline_fps: f64, f: f64) -> f64 {
        opts.start.unwrap_or(0.0) + f / timeline_fps
    }

    /// Keeps frames `first..=last` of `decoded` (cut with `opts`) where two clips still fit
    /// between them, the ends `--start`/`--end` fix as they say; whether it did.
    pub fn keep(
        &mut self,
        decoded: &mut DecodedVideo,
        opts: &VideoOptions,
        (first, last): (usize, usize),
        timeline_fps: f64,
    ) -> bool {
        if (last + 1).saturating_sub(first) <= (opts.frames_per_clip - 1) * opts.stride + 1 {
            return false;
        }
        let at = |f: usize| Kept::time_of(opts, timeline_fps, f as f64);
        self.start = self.start.or(Some(at(first)));
        self.end = self.end.or(Some(at(last)));
        decoded.keep(first, last, opts);
        true
    }
}

/// Finds the descent in `decoded` (cut with `opts` from `input`; its release read by the
/// object's colour where that is less crowded, `tinted`, unless the track's replaces it) and
/// keeps only it where `--start` / `--end` do not say otherwise and a clip still fits, saying
/// so in `warnings`.
pub fn trim_to_descent(
    input: &Path,
    decoded: &mut DecodedVideo,
    opts: &VideoOptions,
    (timeline_fps, tracked): (f64, Option<TrackedMotion>),
    warnings: &mut Vec<String>,
) -> Kept {
    let mut kept = Kept::untrimmed(opts);
    // The picture's release, told only where the track's does not replace it.
    let by_track = tracked.and_then(|t| t.release).is_some();
    let mut colour = None;
    let found = descent::find(&decoded.frames, decoded.size).map(|(grey, seen)| {
        // The track's release replaces the picture's, read in colour or in grey alike
        // (`tracked::descent`): the colour decode would be read for nothing.
        if by_track {
            return grey;
        }
        match tinted::in_colour(input, decoded, opts, &grey, &seen) {
            Some(c) if c.crowded < grey.crowded => {
                colour = Some(format!(
                    "motion from rest: something beside the object differs where it starts (on \
                     {} % of the frames where the release is read, {} % by the object's \
                     colour): its release read by its colour (at frame {} in grey, {} by colour)",
                    approx(100.0 * grey.crowded),
                    approx(100.0 * c.crowded),
                    approx(grey.release),
                    approx(c.release)
                ));
                c
            }
            _ => grey,
        }
    });
    warnings.extend(colour);
    let geometry = tracked::Geometry::of(decoded, opts, timeline_fps);
    let Some(d) = (match tracked {
        Some(t) => tracked::descent(found, &t, &geometry),
        None => found,
    }) else {
        return kept;
    };
    kept.descent = Some(d);
    let first = if opts.start.is_none() { d.first } else { 0 };
    let last = if opts.end.is_none() {
        d.last
    } else {
        decoded.frame_count() - 1
    };
    let at = |f: f64| Kept::time_of(opts, timeline_fps, f);
    let dropped = if kept.keep(decoded, opts, (first, last), timeline_fps) {
        first
    } else {
        0
    };
    if dropped > 0 && !tracked.is_some_and(|t| t.moving_before) {
        kept.before = Outside::AtRest;
    }
    kept.release = d.release - dropped as f64;
    let vertex = match d.bend {
        Some(b) => format!(
            "the vertex of the parabola its path traces, seen in perspective: the picture's \
             scale changes by {} % along the path, undone in the positions the encoder reads",
            approx(100.0 * b.change)
        ),
        None => "the vertex of the parabola its path traces".to_string(),
    };
    let vertex = match by_track {
        true => "the vertex of the constant acceleration its track holds".to_string(),
        false => vertex,
    };
    warnings.push(format!(
        "motion from rest: the object is released at {} s ({vertex}) and moves away until {} \
         s; kept {}–{} s{}",
        approx(at(d.release)),
        approx(at(d.last as f64)),
        approx(kept.start.unwrap_or(0.0)),
        approx(kept.end.unwrap_or(at((decoded.frame_count() - 1) as f64))),
        if opts.start.is_some() || opts.end.is_some() {
            " (as --start/--end say)"
        } else {
            " (--start/--end choose)"
        }
    ));
    kept
}
