//! The free motion in time: where the system moves under its law alone, found in a survey's
//! low-resolution frames before anything else is measured on them. A hand that pulls the mass
//! down and lets go, or holds and steadies it for seconds, or a hand that stops it at the end,
//! is far more picture than the object: against the recording's background (each pixel's
//! median, the frame's level taken out) it lights up many times the pixels the object does.
//! Frames where that is so, in a steady run from the recording's start, are not the law's; the
//! free motion starts a couple of frames clear of them. (A hand that stops the object at the
//! end is not looked for yet: the still frames after it are `stillness`'s, and a run at the
//! end moved a draining tank's cut.)

/// A frame is intruded on when more of it differs from the background than this many times
/// what the object alone makes differ (the later half's median)…
const TIMES_THE_OBJECT: f64 = 3.0;
/// …and than the object's share plus this share of the frame (a hand is several per cent of a
/// frame; a swinging object's own share wanders by less).
const MORE_THAN: f64 = 0.01;
/// A run of intruded frames at the start counts where at least this share of the frames up to
/// its last intrusion are intruded on (a passer-by in the middle cuts nothing).
const RUN: f64 = 0.5;
/// Frames kept clear of the last intrusion (a hand's fingers leaving).
const MARGIN: usize = 2;
/// The free motion must keep at least this share of the frames, else nothing is trimmed.
const MIN_SHARE: f64 = 0.25;
/// A hand holding, pulling or stopping the object takes a steady share of the picture: the
/// run's intruded frames (their middle 80 %) within this factor of each other. The object's own
/// progression (a tank draining from full, a light dimming) departs from the background more
/// the further it is from the middle of the recording: not steady, and never trimmed.
const STEADY: f64 = 2.5;

/// Where the free motion lies in a survey's frames (indices, inclusive), and what was left out.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FreeSpan {
    pub first: usize,
    pub last: usize,
    /// The share of the frame the intrusion took at its largest, and the object's own.
    pub intrusion_share: f64,
    pub object_share: f64,
}

/// How far each frame of a survey departs from the recording's background: the share of the
/// frame that differs from each pixel's median (the frame's level taken out), what the object
/// alone usually makes differ, and the share above which a frame is intruded on (a hand). The
/// report draws it over time with the span fitted (`change.png`).
#[derive(Debug, Clone, PartialEq)]
pub struct Departures {
    pub shares: Vec<f64>,
    pub object: f64,
    pub limit: f64,
}

/// The departures of `frames` (`n` grey frames of `w`·`h` bytes) from their background; `None`
/// for fewer than 16 frames.
pub fn departures(frames: &[u8], (w, h): (usize, usize)) -> Option<Departures> {
    let px = w * h;
    let n = frames.len() / px.max(1);
    if n < 16 || px == 0 {
        return None;
    }
    let frame = |t: usize| &frames[t * px..(t + 1) * px];
    let level = |f: &[u8]| f.iter().map(|&v| v as f64).sum::<f64>() / px as f64;
    let levels: Vec<f64> = (0..n).map(|t| level(frame(t))).collect();
    // Each pixel's median over the frames (a histogram a pixel: bytes).
    let mut background = vec![0f64; px];
    let mut hist = vec![0u32; 256];
    for (p, b) in background.iter_mut().enumerate() {
        hist.iter_mut().for_each(|c| *c = 0);
        for t in 0..n {
            hist[frames[t * px + p] as usize] += 1;
        }
        let (mut seen, half) = (0, n.div_ceil(2) as u32);
        *b = hist
            .iter()
            .position(|&c| {
                seen += c;
                seen >= half
            })
            .unwrap_or(0) as f64;
    }
    let base_level = background.iter().sum::<f64>() / px as f64;
    // How far each pixel of a frame is from the background, its level taken out.
    let departure = |t: usize| -> Vec<f64> {
        frame(t)
            .iter()
            .zip(&background)
            .map(|(&v, &b)| (v as f64 - levels[t] - (b - base_level)).abs())
            .collect()
    };
    // The noise: the median departure over a sample of frames (most pixels are background).
    let mut sample: Vec<f64> = (0..n)
        .step_by((n / 16).max(1))
        .flat_map(departure)
        .collect();
    sample.sort_by(f64::total_cmp);
    let noise = sample[sample.len() / 2];
    let threshold = (4.0 * noise).max(6.0);
    let shares: Vec<f64> = (0..n)
        .map(|t| departure(t).iter().filter(|&&d| d > threshold).count() as f64 / px as f64)
        .collect();
    let mut later: Vec<f64> = shares[n / 2..].to_vec();
    later.sort_by(f64::total_cmp);
    let object = later[later.len() / 2];
    let limit = (TIMES_THE_OBJECT * object).max(object + MORE_THAN);
    Some(Departures {
        shares,
        object,
        limit,
    })
}

/// The free motion in the frames whose `departures` these are: `None` where nothing beside the
/// object intrudes at the start.
pub fn free_in(d: &Departures) -> Option<FreeSpan> {
    let (shares, object, limit) = (&d.shares, d.object, d.limit);
    let n = shares.len();
    let intruded: Vec<bool> = shares.iter().map(|&s| s > limit).collect();
    // A run at the start: the last intrusion in the first half, with most frames before it
    // intruded on; at the end, the first in the last half, the same after it.
    // The intruded frames of `run`: many enough, and steady.
    let a_hand = |run: std::ops::Range<usize>| {
        let mut s: Vec<f64> = run
            .clone()
            .filter(|&t| intruded[t])
            .map(|t| shares[t])
            .collect();
        s.sort_by(f64::total_cmp);
        let (lo, hi) = (s[s.len() / 10], s[(s.len() * 9) / 10]);
        s.len() as f64 >= RUN * run.len() as f64 && hi <= STEADY * lo
    };
    let lead = (0..n / 2)
        .rev()
        .find(|&t| intruded[t])
        .filter(|&t| a_hand(0..t + 1));
    let lead = lead?;
    let (first, last) = ((lead + 1 + MARGIN).min(n - 1), n - 1);
    if ((last - first + 1) as f64) < MIN_SHARE * n as f64 {
        return None;
    }
    let intrusion_share = shares[..=lead].iter().copied().fold(0.0, f64::max);
    Some(FreeSpan {
        first,
        last,
        intrusion_share,
        object_share: object,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The free motion in `frames`, as the survey finds it.
    fn free_span(frames: &[u8], size: (usize, usize)) -> Option<FreeSpan> {
        departures(frames, size).and_then(|d| free_in(&d))
    }

    /// `n` frames of 40×30: a 3×3 bright mass bobbing up and down at rows 14 ± 3 on a grey
    /// wall with a little noise, and an "arm" (a dark 16×6 bar from the left edge to the mass)
    /// in frames `arm`.
    fn scene(n: usize, arm: impl Fn(usize) -> bool) -> Vec<u8> {
        let (w, h) = (40, 30);
        let mut out = vec![0u8; n * w * h];
        for t in 0..n {
            let y = (14.0 + 3.0 * (t as f64 * 0.5).sin()).round() as usize;
            for r in 0..h {
                for c in 0..w {
                    let noise = ((t * 7919 + r * 104729 + c * 1299709) % 7) as u8;
                    let mut v = 150 + noise;
                    if (y..y + 3).contains(&r) && (20..23).contains(&c) {
                        v = 240;
                    }
                    if arm(t) && (y..y + 6).contains(&r) && c < 18 {
                        v = 60;
                    }
                    out[(t * h + r) * w + c] = v;
                }
            }
        }
        out
    }

    #[test]
    fn a_hand_at_the_start_is_left_out_and_a_free_swing_keeps_every_frame() {
        let held = free_span(&scene(120, |t| t < 30), (40, 30)).expect("a hand found");
        assert_eq!((held.first, held.last), (32, 119), "{held:?}");
        assert!(held.intrusion_share > 5.0 * held.object_share, "{held:?}");
        // The departures the report draws: the arm's frames beyond the limit, the rest below.
        let d = departures(&scene(120, |t| t < 30), (40, 30)).expect("departures");
        assert_eq!(d.shares.len(), 120);
        assert!(d.shares[..30].iter().all(|&s| s > d.limit), "{d:?}");
        assert!(d.shares[32..].iter().all(|&s| s < d.limit), "{d:?}");
        assert!(d.object > 0.0 && d.object < d.limit, "{d:?}");
        assert_eq!(free_span(&scene(120, |_| false), (40, 30)), None);
        // A passer-by in the middle of the first half cuts nothing.
        assert_eq!(
            free_span(&scene(120, |t| (20..24).contains(&t)), (40, 30)),
            None
        );
        // The object's own progression (a light dimming to its floor, a tank draining to its
        // outlet: the dark column shrinks from 28 rows to 14 over the first 80 of 200 frames and
        // stays) departs from the median frame less and less: not steady, not a hand.
        let mut fading = scene(200, |_| false);
        for (t, f) in fading.chunks_exact_mut(40 * 30).enumerate() {
            let rows = (28.0 - 14.0 * (t as f64 / 80.0).min(1.0)).round() as usize;
            for r in 30 - rows..30 {
                f[r * 40..r * 40 + 12].iter_mut().for_each(|v| *v = 40);
            }
        }
        assert_eq!(free_span(&fading, (40, 30)), None);
    }
}
