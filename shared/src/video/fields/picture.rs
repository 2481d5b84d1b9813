//! What the picture says of a recording's fields: pairs of frames spread over its start, each
//! voting for the order in which a frame's fields were taken where the weaves with the next
//! frame tell (see the module above for the measurements).

use super::super::kept::Wholes;
use super::super::tools::{raw_frames, read_full, tool};
use super::super::VideoError;
use super::beside::Beside;
use super::FieldOrder;
use std::path::Path;
use std::process::Stdio;

/// Frames looked at: pairs spread over the recording's first [`WITHIN`] frames (every frame of
/// a short one), each narrowed to at most [`WIDTH`] columns (the rows, where fields differ,
/// kept whole). The pass goes on to the end, for the whole at the track's size it also reads
/// (0.7 s on a 1080p spring, where the look alone cost 0.6 s and the track's decode as much).
const LOOKED_AT: usize = 90;
const WITHIN: usize = 480;
const WIDTH: usize = 480;
/// The share of the pairs that move which must vote, the share of the votes that must agree,
/// and the fewest votes, for the picture to say the recording is interlaced.
const VOTING: f64 = 0.5;
const AGREE: f64 = 0.9;
const MIN_VOTES: usize = 8;
/// How much less one weave must comb than the other for a pair to vote.
const CLEARLY: f64 = 0.8;

/// What the picture says: the moving pairs of frames looked at, and their votes; and the whole
/// recording decoded in the same pass (`Beside`: at the track's size, the survey's, its own,
/// and in colour), for `kept`.
pub(super) fn look(
    path: &Path,
    (w, h): (usize, usize),
    frames: Option<usize>,
) -> Result<(Look, Wholes), VideoError> {
    if h < 8 || w == 0 {
        return Ok((Look::Unknown, Wholes::default()));
    }
    let every = frames.map_or(2, |n| (n.min(WITHIN) / (LOOKED_AT / 2)).max(2));
    let beside = Beside::plan((w, h), frames);
    let w = w.min(WIDTH);
    let looked = format!("select='lt(mod(n\\,{every})\\,2)',scale={w}:{h}:flags=area");
    let mut cmd = tool("ffmpeg");
    cmd.args(["-v", "error", "-nostdin", "-noautorotate", "-i"])
        .arg(path);
    beside.args(&mut cmd, &looked);
    cmd.args([
        "-fps_mode",
        "passthrough",
        "-frames:v",
        &LOOKED_AT.to_string(),
    ]);
    let complaints = (beside.log.as_ref())
        .and_then(|l| std::fs::File::create(l).ok())
        .map_or(Stdio::null(), Stdio::from);
    let (mut child, mut stdout) = raw_frames(cmd, path, "gray", complaints)?;
    let (mut moving, mut votes) = (0usize, [0usize; 2]);
    let mut prev: Option<Vec<u8>> = None;
    let mut buf = vec![0u8; w * h];
    let mut read = 0usize;
    while read_full(&mut stdout, &mut buf).is_ok_and(|n| n == buf.len()) {
        read += 1;
        // Pairs: every two frames of a recording read in pairs, each frame with the next in
        // a short one read whole.
        let first = every > 2 && read % 2 == 1;
        if let Some(a) = prev.as_ref().filter(|_| !first) {
            match vote(a, &buf, (w, h)) {
                Vote::Still => {}
                Vote::Moves(order) => {
                    moving += 1;
                    match order {
                        Some(FieldOrder::TopFirst) => votes[0] += 1,
                        Some(FieldOrder::BottomFirst) => votes[1] += 1,
                        None => {}
                    }
                }
            }
        }
        prev = Some(buf.clone());
    }
    drop(stdout);
    let done = child.wait().is_ok_and(|s| s.success());
    let clean = (beside.log.as_ref())
        .and_then(|l| std::fs::metadata(l).ok())
        .is_some_and(|m| m.len() == 0);
    let wholes = beside.read(done, clean);
    Ok((judge(moving, votes), wholes))
}

/// What the picture says of a recording.
#[derive(Debug, PartialEq)]
pub(super) enum Look {
    /// Interlaced, in this order, with the share of the moving pairs that voted for it.
    Interlaced(FieldOrder, f64),
    /// Enough pairs move, and they do not say interlaced.
    Progressive,
    /// Too few pairs move to tell.
    Unknown,
}

/// The picture's word from `moving` pairs and their `votes` (top first, bottom first).
fn judge(moving: usize, votes: [usize; 2]) -> Look {
    if moving < MIN_VOTES {
        return Look::Unknown;
    }
    let total = votes[0] + votes[1];
    if total < MIN_VOTES || (total as f64) < VOTING * moving as f64 {
        return Look::Progressive;
    }
    let share = |n: usize| n as f64 / moving as f64;
    if votes[0] as f64 >= AGREE * total as f64 {
        Look::Interlaced(FieldOrder::TopFirst, share(votes[0]))
    } else if votes[1] as f64 >= AGREE * total as f64 {
        Look::Interlaced(FieldOrder::BottomFirst, share(votes[1]))
    } else {
        Look::Progressive
    }
}

/// What a pair of frames says.
#[derive(Debug, PartialEq)]
enum Vote {
    /// Too little changes to tell.
    Still,
    /// Something moves; the order its fields were taken in, where the weaves tell.
    Moves(Option<FieldOrder>),
}

/// The vote of frame `a` and the next frame `b`: where they differ, the even rows of `b` woven
/// with the odd rows of `a` comb clearly less than the even rows of `a` with the odd of `b`
/// when the top field was taken first (the two woven half an interval apart, against one and a
/// half), and the other way round when the bottom was.
fn vote(a: &[u8], b: &[u8], (w, h): (usize, usize)) -> Vote {
    let moved: Vec<bool> = a.iter().zip(b).map(|(x, y)| x.abs_diff(*y) >= 8).collect();
    if moved.iter().filter(|m| **m).count() < 4 {
        return Vote::Still;
    }
    let top_first = comb((b, a), &moved, (w, h));
    let bottom_first = comb((a, b), &moved, (w, h));
    Vote::Moves(if top_first < CLEARLY * bottom_first {
        Some(FieldOrder::TopFirst)
    } else if bottom_first < CLEARLY * top_first {
        Some(FieldOrder::BottomFirst)
    } else {
        None
    })
}

/// How much the frame woven from the even rows of `top` and the odd rows of `bottom` combs
/// where `moved`: each row's summed difference from the mean of the rows beside it.
fn comb((top, bottom): (&[u8], &[u8]), moved: &[bool], (w, h): (usize, usize)) -> f64 {
    let row = |r: usize| if r.is_multiple_of(2) { top } else { bottom };
    let mut total = 0.0;
    for r in 1..h - 1 {
        for x in 0..w {
            if !moved[r * w + x] {
                continue;
            }
            let at = |r: usize| f64::from(row(r)[r * w + x]);
            total += (at(r) - (at(r - 1) + at(r + 1)) / 2.0).abs();
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::video::{SURVEY_SIDE, TRACK_SIDE};

    const SIZE: (usize, usize) = (32, 32);

    /// A frame (32×32) of a bright 8×12 block at column `x(t)`, rows 8–19, with its even
    /// rows at time t and its odd rows at t + ½ when `interlaced` (top field first).
    fn frame(t: f64, interlaced: bool, x: impl Fn(f64) -> f64) -> Vec<u8> {
        let (w, h) = SIZE;
        let mut f = vec![20u8; w * h];
        for r in 8..20 {
            let at = if interlaced && r % 2 == 1 { t + 0.5 } else { t };
            let c = x(at).round() as usize;
            for col in c..(c + 8).min(w) {
                f[r * w + col] = 220;
            }
        }
        f
    }

    #[test]
    fn fields_taken_apart_vote_for_their_order_and_frames_taken_at_once_do_not() {
        let x = |t: f64| 4.0 + 4.0 * t;
        let (i0, i1) = (frame(0.0, true, x), frame(1.0, true, x));
        assert_eq!(
            vote(&i0, &i1, SIZE),
            Vote::Moves(Some(FieldOrder::TopFirst))
        );
        // The same frames with their rows shifted down by one: the bottom field now leads.
        let shift = |f: &[u8]| {
            let mut g = vec![20u8; f.len()];
            g[SIZE.0..].copy_from_slice(&f[..f.len() - SIZE.0]);
            g
        };
        assert_eq!(
            vote(&shift(&i0), &shift(&i1), SIZE),
            Vote::Moves(Some(FieldOrder::BottomFirst))
        );
        let (p0, p1) = (frame(0.0, false, x), frame(1.0, false, x));
        assert_eq!(vote(&p0, &p1, SIZE), Vote::Moves(None));
        assert_eq!(vote(&p0, &p0, SIZE), Vote::Still);
    }

    #[test]
    fn the_picture_says_interlaced_on_most_moving_pairs_agreeing_and_nothing_on_too_few() {
        assert_eq!(judge(5, [5, 0]), Look::Unknown);
        assert_eq!(judge(40, [1, 2]), Look::Progressive);
        assert_eq!(
            judge(40, [30, 1]),
            Look::Interlaced(FieldOrder::TopFirst, 0.75)
        );
        assert_eq!(judge(40, [15, 15]), Look::Progressive, "no agreement");
        assert_eq!(judge(40, [2, 15]), Look::Progressive, "too few vote");
    }

    #[test]
    fn the_wholes_decoded_beside_the_look_are_the_tracks_and_the_surveys_own_decodes() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("moving.mp4");
        let rendered = tool("ffmpeg")
            .args([
                "-v",
                "error",
                "-y",
                "-f",
                "lavfi",
                "-i",
                "testsrc=size=480x270:rate=25",
            ])
            .args(["-frames:v", "30", "-pix_fmt", "yuv420p"])
            .arg(&file)
            .status()
            .is_ok_and(|s| s.success());
        if !rendered {
            return; // no ffmpeg here
        }
        let info = crate::video::probe_as(&file, super::super::FieldsChoice::Frames).unwrap();
        let (_, wholes) = look(&file, (480, 270), Some(30)).unwrap();
        // Nothing kept for this file (`fields::find` keeps; `look` only reads): decoded afresh.
        let fresh = |side| crate::video::small_frames(&file, &info, (None, None), side).unwrap();
        for (side, kept, size) in [
            (TRACK_SIDE, wholes.whole, (320, 180)),
            (SURVEY_SIDE, wholes.survey, (160, 90)),
        ] {
            let kept = kept.expect("the whole read beside the look");
            let fresh = fresh(side);
            assert_eq!((kept.len(), kept.size), (30, size));
            assert!(kept.pixels == fresh.pixels, "byte for byte the same frames");
        }
        // In colour too (a short recording): the chroma the track reads of it, byte for byte.
        let (planes, n) = (wholes.colour.expect("the colour read beside"), 320 * 180);
        let mut chroma = Vec::new();
        let each = |f: &[u8]| crate::video::small::chroma(f, n, &mut chroma);
        planes.chunks_exact(3 * n).for_each(each);
        let fresh = crate::video::small_chroma(&file, &info, (None, None), TRACK_SIDE).unwrap();
        assert!(chroma == fresh.pixels, "byte for byte the same chroma");
    }
}
