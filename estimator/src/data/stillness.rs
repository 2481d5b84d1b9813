//! The still frames of a recording: before its motion starts (a bob held before the release, a
//! tank before the tap opens) and after it ends (settled). A held object does not follow the
//! law, so the frames before the release are left out; the settled state does (it is the law's
//! end: a drained tank's level, a pendulum at rest), so one clip's span of it is kept and only
//! the frames beyond, which add clips that show nothing, are left out. Both where
//! `--start`/`--end` do not say otherwise. Falls and slides from rest keep their descent
//! instead (`descent`).

use super::kept::{Kept, Outside};
use physvid_shared::cli::approx;
use physvid_shared::video::free::FreeSpan;
use physvid_shared::video::{DecodedVideo, VideoOptions};

/// A frame is still while it differs from the recording's first (or last) frames by less than
/// this share of the most any frame does (above the noise): a bob moved by 1–2 % of its width,
/// an LED within 5 % of its final brightness.
const STILL: f64 = 0.05;

/// A frame is still, too, while it differs from the first (or last) frames by less than this
/// many times the noise between two frames.
const NOISE: f64 = 1.5;

/// Nothing is trimmed unless the motion stands this many times above the frame-to-frame noise
/// (a static scene with sensor noise keeps every frame).
const CLEAR: f64 = 4.0;

/// A still part shorter than this (seconds) is not left out: a swing's turning point stays
/// within the threshold for about 7 % of its period (0.2 s of a 3-s swing, as a recording
/// starting at one does), a held bob for longer.
const MIN_STILL_S: f64 = 0.5;

/// The frames (of `frames`, `[F, H·W]` with `per` pixels each) where the motion starts and
/// ends: the last still frame before it (the release: at rest where it starts; 0 unless the
/// frames before are still for `min_still` or more) and the first still frame after it; `None`
/// when neither end is still or nothing clearly moves.
pub fn moving_span(frames: &[f32], per: usize, min_still: usize) -> Option<(usize, usize)> {
    let n = frames.len() / per.max(1);
    if n < 8 {
        return None;
    }
    let frame = |t: usize| &frames[t * per..(t + 1) * per];
    let rms = |a: &[f32], b: &[f32]| {
        let s: f64 = a.iter().zip(b).map(|(x, y)| f64::from(x - y).powi(2)).sum();
        (s / per as f64).sqrt()
    };
    // The noise: the lower decile of the differences between frames `min_still` apart (a
    // codec copies much of a frame into the next, so consecutive frames differ less than
    // distant ones do at rest).
    let lag = min_still.clamp(1, n - 1);
    let mut steps: Vec<f64> = (lag..n).map(|t| rms(frame(t), frame(t - lag))).collect();
    steps.sort_by(f64::total_cmp);
    let floor = steps[steps.len() / 10];
    // Against the mean of the first (last) `lag` frames, whose noise is then small beside a
    // frame's (a codec's key frame is noisier than the frames after it).
    let from = |ends: std::ops::Range<usize>| -> Vec<f64> {
        let mut mean = vec![0.0f32; per];
        for t in ends.clone() {
            for (m, v) in mean.iter_mut().zip(frame(t)) {
                *m += v / ends.len() as f32;
            }
        }
        (0..n).map(|t| rms(frame(t), &mean)).collect()
    };
    let (head, tail) = (from(0..lag), from(n - lag..n));
    let top = |d: &[f64]| d.iter().copied().fold(0.0, f64::max);
    let threshold = |d: &[f64]| (NOISE * floor).max(floor + STILL * (top(d) - floor));
    if top(&head).max(top(&tail)) <= CLEAR * floor {
        return None;
    }
    let t_head = threshold(&head);
    let first = head.iter().position(|&d| d > t_head)?.saturating_sub(1);
    let first = if first >= min_still { first } else { 0 };
    let t_tail = threshold(&tail);
    let last = (tail.iter().rposition(|&d| d > t_tail)? + 1).min(n - 1);
    (first > 0 || last < n - 1).then_some((first, last))
}

/// Leaves out what is not the free motion of `decoded` (cut with `opts`) at each end
/// `--start`/`--end` do not fix, where at least two clips still fit, saying so in `warnings`:
/// the frames before `free.first` (something beside the object takes the picture: a hand
/// holding, pulling or steadying it; a frame of the decode), then the still frames at either
/// end of the rest.
pub fn trim(
    decoded: &mut DecodedVideo,
    opts: &VideoOptions,
    timeline_fps: f64,
    free: Option<FreeSpan>,
    warnings: &mut Vec<String>,
) -> Kept {
    let mut kept = Kept::untrimmed(opts);
    let n = decoded.frame_count();
    let min_still = ((MIN_STILL_S * decoded.fps).round() as usize).max(2);
    let per = decoded.size.0 * decoded.size.1;
    // The free motion's first frame (the flag's start stands).
    let lo = free
        .filter(|_| opts.start.is_none())
        .map_or(0, |f| f.first.min(n - 1));
    let inner = &decoded.frames[lo * per..];
    let (still_first, still_last) =
        moving_span(inner, per, min_still).map_or((lo, n - 1), |(a, b)| (lo + a, lo + b));
    let span = (opts.frames_per_clip - 1) * opts.stride;
    let first = if opts.start.is_none() { still_first } else { 0 };
    // One clip's span of the settled state kept.
    let settled = still_last;
    let last = (still_last + span).min(n - 1);
    let last = if opts.end.is_none() && n - 1 - last >= min_still {
        last
    } else {
        n - 1
    };
    if first == 0 && last == n - 1 {
        return kept;
    }
    let at = |f: usize| Kept::time_of(opts, timeline_fps, f as f64);
    let mut why = Vec::new();
    if let Some(f) = free.filter(|_| lo > 0) {
        why.push(format!(
            "something beside the object takes up to {:.0} % of the picture until {} s (the \
             object {:.1} %: a hand holding, pulling or steadying it?)",
            100.0 * f.intrusion_share,
            approx(at(lo)),
            100.0 * f.object_share
        ));
    }
    if still_first > lo || still_last < n - 1 {
        why.push(format!(
            "the picture is still before {} s and after {} s",
            approx(at(still_first)),
            approx(at(settled))
        ));
    }
    let why = why.join("; ");
    if !kept.keep(decoded, opts, (first, last), timeline_fps) {
        warnings.push(format!(
            "{why}, but two clips of {} frames at stride {} do not fit between: every frame \
             kept (lower --stride, or trim with --start/--end)",
            opts.frames_per_clip, opts.stride
        ));
        return kept;
    }
    // A reference among still frames is taken at the kept end; among a hand's, refused.
    if still_first > lo && lo == 0 {
        kept.before = Outside::Still;
    }
    if last < n - 1 {
        kept.after = Outside::Still;
    }
    warnings.push(format!(
        "{why}: kept {}–{} s, the free motion (--start/--end choose)",
        approx(kept.start.unwrap_or(0.0)),
        approx(kept.end.unwrap_or(at(last)))
    ));
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` frames of a 16×16 picture with a 4×4 square whose left edge is at `x(t)`, plus a
    /// little deterministic noise.
    fn square(n: usize, x: impl Fn(usize) -> f64) -> Vec<f32> {
        let mut frames = vec![0.0f32; n * 256];
        for t in 0..n {
            for r in 6..10 {
                for c in 0..16 {
                    let cover = ((c as f64 + 1.0).min(x(t) + 4.0) - (c as f64).max(x(t))).max(0.0);
                    frames[t * 256 + r * 16 + c] = cover.min(1.0) as f32;
                }
            }
            for (i, v) in frames[t * 256..(t + 1) * 256].iter_mut().enumerate() {
                *v += 0.01 * (((t * 256 + i) * 2654435761 % 1000) as f32 / 1000.0 - 0.5);
            }
        }
        frames
    }

    #[test]
    fn a_held_then_swinging_then_settled_square_keeps_its_swing() {
        // Held at x = 10 for 20 frames, released into a decaying swing about x = 6 for 60,
        // settled for 20.
        let x = |t: usize| match t {
            0..20 => 10.0,
            20..80 => {
                let s = (t - 20) as f64;
                6.0 + 4.0 * (-s / 12.0).exp() * (s * 0.4).cos()
            }
            _ => 6.0,
        };
        let (first, last) = moving_span(&square(100, x), 256, 5).expect("still ends");
        assert!((18..=20).contains(&first), "first {first}");
        assert!((45..=80).contains(&last), "last {last}");
    }

    #[test]
    fn a_motion_from_first_to_last_frame_or_none_at_all_trims_nothing() {
        let swing = |t: usize| 6.0 + 4.0 * (t as f64 * 0.4).cos();
        assert_eq!(moving_span(&square(100, swing), 256, 5), None);
        assert_eq!(moving_span(&square(100, |_| 6.0), 256, 5), None);
    }
}
