//! Interlaced recordings: a camera that writes two fields a frame (the even rows, then the odd
//! rows a half interval later) shows a moving object twice, combed, in every frame; read as
//! frames it is measured at half its rate between two places. Such a recording is read as its
//! fields, each made a whole frame by ffmpeg's `yadif` (the field's rows kept, the others
//! interpolated), at twice the frame rate, in the order they were taken.
//!
//! Found from the picture ([`vote`]): where two frames differ, the rows woven from one frame's
//! field and the next frame's other field comb less than the other weave when the fields were
//! taken half an interval apart in that order, and alike when both fields of a frame were taken
//! at once. Where nothing moves enough to tell, the container's field-order tag says. Measured
//! on frame pairs that move: recordings interlaced here with ffmpeg's `tinterlace` (a square and
//! a disc swinging, a disc falling, the shared pendulum; both orders) vote 70–99 % for their
//! order and none for the other (a disc swinging 3 pixels: 35 %); the shared recordings and the
//! same drawings progressive 0–6 %, split evenly.

use super::tools::{gray_frames, read_full, tool};
use super::VideoError;
use serde::Serialize;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

/// Which field was taken first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FieldOrder {
    TopFirst,
    BottomFirst,
}

impl FieldOrder {
    /// In words, for messages.
    pub fn words(self) -> &'static str {
        match self {
            FieldOrder::TopFirst => "top field first",
            FieldOrder::BottomFirst => "bottom field first",
        }
    }
}

/// How a recording's fields are read (`--fields`): found from the picture or the tag
/// (`auto`), never split (`frames`), or split in the order given.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum FieldsChoice {
    #[default]
    Auto,
    Frames,
    TopFirst,
    BottomFirst,
}

/// An interlaced recording's fields: their order and what said so.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Fields {
    pub order: FieldOrder,
    /// "picture" (its rows comb where it moves), "container" (its field-order tag, where
    /// nothing moves enough to tell) or "--fields".
    pub by: &'static str,
    /// The share of the frame pairs that move which voted for this order (the picture's; see
    /// the module's measurements).
    pub voting: Option<f64>,
}

impl Fields {
    /// ffmpeg's filter that makes each field a frame, in the order they were taken.
    pub fn filter(&self) -> String {
        let parity = match self.order {
            FieldOrder::TopFirst => "tff",
            FieldOrder::BottomFirst => "bff",
        };
        format!("yadif=mode=send_field:parity={parity}:deint=all")
    }
}

/// Frames looked at: pairs spread over the recording's first [`WITHIN`] frames (every frame of
/// a short one), each narrowed to at most [`WIDTH`] columns (the rows, where fields differ,
/// kept whole): the look costs a decode of at most those frames (0.7 s on a 1080p spring, under
/// 0.2 s at 640×360).
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

/// The fields `choice` gives without looking (`frames`: none; an order: that order), or
/// `None` where the picture and the tag are to say (`auto`).
pub fn chosen(choice: FieldsChoice) -> Option<Option<Fields>> {
    let order = match choice {
        FieldsChoice::Auto => return None,
        FieldsChoice::Frames => return Some(None),
        FieldsChoice::TopFirst => FieldOrder::TopFirst,
        FieldsChoice::BottomFirst => FieldOrder::BottomFirst,
    };
    Some(Some(Fields {
        order,
        by: "--fields",
        voting: None,
    }))
}

/// The order a container's `field_order` tag says (ffprobe's tt, bb, tb, bt: the first
/// letter the field coded first, the second the one shown first).
pub fn from_tag(tag: &str) -> Option<FieldOrder> {
    match tag {
        "tt" | "bt" => Some(FieldOrder::TopFirst),
        "bb" | "tb" => Some(FieldOrder::BottomFirst),
        _ => None,
    }
}

/// The fields of the recording at `path` (stored `size` (w, h), `frames` in all, `tag` its
/// container's field order), or `None` when it is progressive. Decodes up to [`WITHIN`]
/// frames; remembered per file for the process (probed again by model choice and the run).
pub fn find(
    path: &Path,
    size: (usize, usize),
    frames: Option<usize>,
    tag: Option<FieldOrder>,
) -> Result<Option<Fields>, VideoError> {
    static SEEN: OnceLock<Mutex<HashMap<PathBuf, Option<Fields>>>> = OnceLock::new();
    let seen = SEEN.get_or_init(Default::default);
    if let Some(f) = seen.lock().ok().and_then(|s| s.get(path).copied()) {
        return Ok(f);
    }
    let fields = match (look(path, size, frames)?, tag) {
        (Some((order, share)), _) => Some(Fields {
            order,
            by: "picture",
            voting: Some(share),
        }),
        (None, Some(order)) => Some(Fields {
            order,
            by: "container",
            voting: None,
        }),
        _ => None,
    };
    if let Ok(mut s) = seen.lock() {
        s.insert(path.to_path_buf(), fields);
    }
    Ok(fields)
}

/// The order the picture votes for and the share of the moving pairs that vote for it, when
/// it says the recording is interlaced.
fn look(
    path: &Path,
    (w, h): (usize, usize),
    frames: Option<usize>,
) -> Result<Option<(FieldOrder, f64)>, VideoError> {
    if h < 8 || w == 0 {
        return Ok(None);
    }
    let every = frames.map_or(2, |n| (n.min(WITHIN) / (LOOKED_AT / 2)).max(2));
    let w = w.min(WIDTH);
    let mut cmd = tool("ffmpeg")?;
    cmd.args(["-v", "error", "-nostdin", "-noautorotate", "-i"])
        .arg(path)
        .args([
            "-map",
            "0:v:0",
            "-vf",
            &format!("select='lt(mod(n\\,{every})\\,2)',scale={w}:{h}:flags=area"),
            "-fps_mode",
            "passthrough",
            "-frames:v",
            &LOOKED_AT.to_string(),
        ]);
    let (mut child, mut stdout) = gray_frames(cmd, path)?;
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
    let _ = child.wait();
    let total = votes[0] + votes[1];
    if total < MIN_VOTES || (total as f64) < VOTING * moving as f64 {
        return Ok(None);
    }
    let share = |n: usize| n as f64 / moving as f64;
    Ok(if votes[0] as f64 >= AGREE * total as f64 {
        Some((FieldOrder::TopFirst, share(votes[0])))
    } else if votes[1] as f64 >= AGREE * total as f64 {
        Some((FieldOrder::BottomFirst, share(votes[1])))
    } else {
        None
    })
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

/// The fields' times: each frame's time, and half its interval after it (the last frame's
/// interval the one before it).
pub fn times(frames: &[f64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(2 * frames.len());
    for (i, &t) in frames.iter().enumerate() {
        let next = frames.get(i + 1).copied();
        let step = match (next, i.checked_sub(1).map(|j| frames[j])) {
            (Some(n), _) => n - t,
            (None, Some(p)) => t - p,
            (None, None) => 0.0,
        };
        out.push(t);
        out.push(t + step / 2.0);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn fields_fall_half_way_between_frames_and_tags_read_as_ffmpeg_writes_them() {
        let t = times(&[0.0, 0.1, 0.3]);
        let want = [0.0, 0.05, 0.1, 0.2, 0.3, 0.4];
        assert!(t.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-12) && t.len() == 6);
        assert_eq!(from_tag("tt"), Some(FieldOrder::TopFirst));
        assert_eq!(from_tag("bb"), Some(FieldOrder::BottomFirst));
        assert_eq!(from_tag("progressive"), None);
        assert_eq!(from_tag("unknown"), None);
    }
}
