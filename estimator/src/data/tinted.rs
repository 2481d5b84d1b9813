//! A descent's release read again by the object's colour where its grey difference was
//! crowded where it starts (`crowd`: the hand that held it opening beside it): the descent's
//! frames decoded in colour (`colour_frames`), the object followed by its colour (`hue`), and
//! the release read from those positions as from the grey ones (`descent::along`); the
//! descent's end and bend stay the grey reading's.

use super::crowd::{crowded_against, EARLY};
use super::descent::{along, Descent, Path as AlongPath, Seen};
use super::hue::Hue;
use physvid_shared::video::{colour_frames, Crop, DecodedVideo, VideoOptions};
use std::path::Path;

/// Colour pixels per grey pixel at most (the object's edge to a fraction of a grey pixel).
const SCALE: usize = 2;

/// Frames read before the grey release at least (it comes late where a hand crowds it).
const BEFORE: usize = 10;

/// The colour frames held at most (a long descent at a large size is read in grey only).
const MAX_BYTES: usize = 256 << 20;

/// The descent `grey` (found at `seen`) with its release read again by the object's colour,
/// where the grey one was crowded, `input` is a video whose decoded frames are its own
/// (`decoded`, cut with `opts`), its colour frames fit in [`MAX_BYTES`], and the object's
/// colour tells it apart from the background; `None` otherwise.
pub fn in_colour(
    input: &Path,
    decoded: &DecodedVideo,
    opts: &VideoOptions,
    grey: &Descent,
    seen: &Seen,
) -> Option<Descent> {
    if grey.crowded == 0.0 || input.is_dir() || decoded.clock_note.is_some() {
        return None;
    }
    let size = decoded.size;
    let info = &decoded.info;
    let crop = Crop::of(opts, info);
    let n = decoded.frame_count();
    let lead = BEFORE.max((0.15 * (grey.last as f64 - grey.release)).ceil() as usize);
    let from = (grey.release.floor().max(0.0) as usize).saturating_sub(lead);
    let to = (grey.last + BEFORE).min(n - 1);
    // Twice the grey size where the recording has it and the frames fit in MAX_BYTES.
    let bytes = |s: usize| (to + 1 - from) * 3 * size.0 * size.1 * s * s * 4;
    let scale = (1..=SCALE.min(crop.w / size.0).min(crop.h / size.1).max(1))
        .rev()
        .find(|&s| bytes(s) <= MAX_BYTES)?;
    let frames = colour_frames(
        input,
        info,
        opts,
        from..to + 1,
        (size.0 * scale, size.1 * scale),
    )
    .ok()?;
    let hue = Hue {
        frames: &frames,
        first: from,
        scale,
        grey: size,
    };
    let axis = grey.line.axis;
    let on_axis = |p: [f64; 2]| p[0] * axis[0] + p[1] * axis[1];
    // The object's colour read where it is clear of what crowds its start (past the early
    // part of the way, `crowd::EARLY`), against the first frame read (the object at rest).
    let moving: Vec<(usize, f64)> = seen
        .iter()
        .filter(|s| s.0 as f64 >= grey.release && s.0 <= grey.last)
        .map(|s| (s.0, on_axis(s.1)))
        .collect();
    let (&(_, p0), &(_, p1)) = (moving.first()?, moving.last()?);
    let clean = moving.iter().find(|m| m.1 - p0 > EARLY * (p1 - p0))?.0;
    let followed = hue.follow(seen, clean, from)?;
    // Followed from the first frame read without a gap (a moving object blurs with the wall
    // behind it, and its colour fades: the shared ball's past two thirds of its fall).
    let run = followed
        .iter()
        .zip(from..)
        .take_while(|(f, k)| f.0 == *k)
        .count();
    let followed = &followed[..run];
    let mut colour: AlongPath = followed.iter().map(|f| (f.0, on_axis(f.1))).collect();
    let mut spread = vec![0.0; to + 1];
    for f in followed {
        spread[f.0] = f.2;
    }
    // The frames at rest before the release left out, as the grey difference leaves them (it
    // sees only what moves): those within a tenth of a pixel, or five times the rest's own
    // jitter, of where the object rests.
    let mut first: Vec<f64> = colour.iter().take(5).map(|q| q.1).collect();
    first.sort_by(f64::total_cmp);
    let rest = *first.get(first.len() / 2)?;
    let mut jitter: Vec<f64> = first.iter().map(|p| (p - rest).abs()).collect();
    jitter.sort_by(f64::total_cmp);
    let near = (5.0 * jitter[jitter.len() / 2]).max(0.1);
    let start = colour.iter().rposition(|q| q.1 < rest + near)? + 1;
    // The object's own spread in colour, at rest (what spreads further as it starts is
    // something beside it of its colour: a hand the ball's colour opening).
    let mut alone: Vec<f64> = colour[..start].iter().map(|q| spread[q.0]).collect();
    if alone.len() < 3 {
        return None;
    }
    alone.sort_by(f64::total_cmp);
    let alone = alone[alone.len() / 2];
    colour.drain(..start);
    let &(end, _) = colour.last()?;
    if end < clean + 4 {
        // Not followed past the early part: nothing to read the release against.
        return None;
    }
    // The release read on the colour's path alone, the rest of the descent (its end, its
    // bend) as the grey difference read it: joined to the colour's, the grey positions after
    // the colour fades bend the fit (on the shared ball at 16×160, a frame early).
    let own = along(&colour, axis, size.0.max(size.1) as f64)?;
    Some(Descent {
        crowded: crowded_against(&colour, &spread, end, alone),
        colour: true,
        rising: false,
        ..grey.released_at(own.release)
    })
}
