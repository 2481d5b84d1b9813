//! A recording's clock, read from its frames' own times (the container's timestamps, a GIF's
//! delays, an image folder's numbering), never guessed from a typical interval: the even grid
//! that fits the times best (least squares over every frame), each frame's slot on it, and
//! what does not sit on it. Times within a tenth of an interval of their slot (a
//! container's rounding) are taken as they are; a recording whose frames sit further off (a
//! GIF's whole centiseconds, an uneven capture) is resampled onto the grid by blending each
//! slot's two nearest frames in time; a doubled frame (two in one slot) keeps the one nearer
//! its slot; a dropped frame (an empty slot) is blended from its neighbours, at most
//! [`MAX_MISSING`] in a row. A frame further than a quarter of an interval off its slot is
//! left out at either end of the recording (at most [`END_FRAMES`] there: a capture's first
//! interval is often its own) and resampled from its neighbours in the middle (at most a
//! [`MAX_MISSING_SHARE`] of the frames); times that no even grid carries so are refused with
//! the numbers and the frames. `grid.rs` fits the grid, `resample.rs` puts the frames on it,
//! `uneven.rs` words a refusal.

mod grid;
mod resample;
mod uneven;

use grid::Grid;
pub use uneven::{Uneven, NAMED};

/// Deviation from the grid, in intervals, below which frames are used as they are.
pub const ROUNDING: f64 = 0.1;
/// Deviation from the grid, in intervals, beyond which no even clock is taken to fit.
pub const MAX_JITTER: f64 = 0.25;
/// The most slots in a row without a frame that are filled in.
pub const MAX_MISSING: usize = 2;
/// The largest share of slots without a frame: beyond it the grid explains the times by
/// dropped frames that were never there.
pub const MAX_MISSING_SHARE: f64 = 0.1;
/// The most frames at either end that are left out for lying off the grid.
pub const END_FRAMES: usize = 2;

/// The even grid a recording's frames sit on.
#[derive(Debug, Clone, PartialEq)]
pub struct Clock {
    /// Time of slot 0 (the first frame's, up to its deviation), in the times' unit.
    pub start: f64,
    /// Time between slots.
    pub interval: f64,
    /// Each kept frame's slot (non-decreasing), the frames `head..n - tail` of those fitted.
    pub slots: Vec<usize>,
    /// Largest distance of a slot's nearest frame from the slot, in intervals.
    pub jitter: f64,
    /// Frames at the start and at the end left out for lying off the grid.
    pub head: usize,
    pub tail: usize,
    /// Slots whose nearest frame lies over [`MAX_JITTER`] off (resampled from their neighbours).
    pub off: usize,
}

impl Clock {
    /// What reading the frames on this clock did, for a warning (None: nothing; the frames
    /// are the grid); `timeline`: the times are seconds of a file's timeline (else an image
    /// folder's numbers).
    pub fn note(&self, timeline: bool) -> Option<String> {
        if self.is_even() {
            return None;
        }
        let mut parts = Vec::new();
        let plural = |n: usize| if n == 1 { "" } else { "s" };
        for (n, end) in [(self.head, "first"), (self.tail, "last")] {
            if n > 0 {
                parts.push(format!(
                    "the {end} {}frame{} (off the clock by more than a quarter of an interval) \
                     left out",
                    if n == 1 {
                        String::new()
                    } else {
                        format!("{n} ")
                    },
                    plural(n)
                ));
            }
        }
        let (doubled, missing) = (self.doubled(), self.missing());
        if doubled > 0 {
            parts.push(format!(
                "{doubled} doubled frame{} (two in one interval) left out",
                if doubled == 1 { "" } else { "s" }
            ));
        }
        if missing > 0 {
            parts.push(format!(
                "{missing} dropped frame{} filled in by blending the frames on either side",
                if missing == 1 { "" } else { "s" }
            ));
        }
        if self.jitter > ROUNDING {
            parts.push(format!(
                "frames up to {:.0} % of an interval off the even clock resampled onto it",
                self.jitter * 100.0
            ));
        }
        let clock = match timeline {
            true => format!(
                "the even clock that fits them ({} frames a second of the file's timeline)",
                crate::cli::approx(1.0 / self.interval)
            ),
            false => "the images' numbers".into(),
        };
        Some(format!(
            "the frames' own times are uneven; read on {clock}: {}",
            parts.join(", ")
        ))
    }

    /// Fits the grid to `times` (sorted, at least two).
    pub fn fit(times: &[f64]) -> Result<Clock, Uneven> {
        let n = times.len();
        let mut steps: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
        steps.sort_by(f64::total_cmp);
        let median = steps.get(steps.len() / 2).copied().unwrap_or(1.0);
        if n < 2 || median.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Ok(Clock {
                start: times.first().copied().unwrap_or(0.0),
                interval: if median > 0.0 { median } else { 1.0 },
                slots: (0..n).collect(),
                jitter: 0.0,
                head: 0,
                tail: 0,
                off: 0,
            });
        }
        let uneven = |grid: &Grid, kept: &[f64], head: usize, gap| Uneven {
            shortest: steps.first().copied().unwrap_or(0.0),
            longest: steps.last().copied().unwrap_or(0.0),
            median,
            jitter: grid.jitter(kept),
            gap,
            frames: grid.furthest(kept, head),
        };
        // Frames off the grid at either end (a first interval of its own) are left out and the
        // grid fitted again to the rest.
        let whole = Grid::of(times, median);
        let off = |i: &usize| whole.deviation(times, *i) > MAX_JITTER;
        let head = (0..n).take_while(off).count();
        let tail = (0..n).rev().take_while(off).count();
        let (head, tail) = match head <= END_FRAMES && tail <= END_FRAMES && head + tail + 2 <= n {
            true => (head, tail),
            false => (0, 0),
        };
        let kept = &times[head..n - tail];
        let grid = if head + tail > 0 {
            Grid::of(kept, median)
        } else {
            whole
        };
        let m = kept.len();
        let slots_off = grid.slots_off(kept);
        let clock = Clock {
            start: grid.start,
            interval: grid.interval,
            jitter: grid.jitter(kept),
            slots: grid.slots.clone(),
            head,
            tail,
            off: slots_off,
        };
        if !grid.interval.is_finite() || slots_off as f64 > MAX_MISSING_SHARE * m as f64 {
            return Err(uneven(&grid, kept, head, None));
        }
        if let Some((at, missing)) = clock.longest_gap().filter(|g| g.1 > MAX_MISSING) {
            return Err(uneven(&grid, kept, head, Some((kept[at], missing))));
        }
        if clock.missing() as f64 > MAX_MISSING_SHARE * (clock.slots[m - 1] + 1) as f64 {
            return Err(uneven(&grid, kept, head, None));
        }
        Ok(clock)
    }

    /// Whether the frames are the grid itself: one in every slot, each within [`ROUNDING`],
    /// none left out.
    pub fn is_even(&self) -> bool {
        self.jitter <= ROUNDING
            && self.head + self.tail == 0
            && self.slots.iter().enumerate().all(|(i, &s)| s == i)
    }

    /// Frames that share a slot with the one before.
    pub fn doubled(&self) -> usize {
        self.slots.windows(2).filter(|w| w[1] == w[0]).count()
    }

    /// Slots without a frame.
    pub fn missing(&self) -> usize {
        self.slots
            .windows(2)
            .map(|w| (w[1] - w[0]).saturating_sub(1))
            .sum()
    }

    /// The longest run of empty slots: (the frame before it, its length).
    fn longest_gap(&self) -> Option<(usize, usize)> {
        self.slots
            .windows(2)
            .enumerate()
            .map(|(i, w)| (i, (w[1] - w[0]).saturating_sub(1)))
            .filter(|g| g.1 > 0)
            .max_by_key(|g| g.1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn times(steps: &[f64], n: usize) -> Vec<f64> {
        let mut t = vec![0.0];
        for i in 0..n - 1 {
            t.push(t[i] + steps[i % steps.len()]);
        }
        t
    }

    #[test]
    fn gif_delays_give_their_mean_rate_not_their_median() {
        // 30 fps as a GIF stores it: delays of 3, 3 and 4 centiseconds.
        let c = Clock::fit(&times(&[0.03, 0.03, 0.04], 90)).unwrap();
        assert!(
            (1.0 / c.interval - 30.0).abs() < 0.01,
            "{}",
            1.0 / c.interval
        );
        assert!(!c.is_even() && c.jitter < MAX_JITTER, "{c:?}");
        // 24 fps: 4, 4, 4, 5, 4, 4, 5 … centiseconds.
        let t24: Vec<f64> = (0..96)
            .map(|i| (i as f64 * 100.0 / 24.0).round() / 100.0)
            .collect();
        let c = Clock::fit(&t24).unwrap();
        assert!(
            (1.0 / c.interval - 24.0).abs() < 0.01,
            "{}",
            1.0 / c.interval
        );
    }

    #[test]
    fn doubled_and_dropped_frames_are_placed_and_filled() {
        // 10 fps; frame 3 doubled (twice at 0.3 s), the frame at 0.6 s dropped.
        let mut t = vec![0.0, 0.1, 0.2, 0.3, 0.3, 0.4, 0.5];
        t.extend((7..20).map(|i| i as f64 * 0.1));
        let c = Clock::fit(&t).unwrap();
        assert_eq!(&c.slots[..9], [0, 1, 2, 3, 3, 4, 5, 7, 8]);
        assert_eq!((c.doubled(), c.missing()), (1, 1));
        let mut frames: Vec<f32> = vec![0.0, 1.0, 2.0, 3.0, 99.0, 4.0, 5.0];
        frames.extend((7..20).map(|i| i as f32));
        let on_grid = c.resample(&t, &frames, 1);
        let want: Vec<f32> = (0..20).map(|i| i as f32).collect();
        assert_eq!(on_grid, want);
        assert!(c.note(true).unwrap().contains("1 doubled frame"));
    }

    #[test]
    fn uneven_times_are_resampled_onto_the_grid_or_refused_with_numbers() {
        // Spacing d, d, 1.45d: the grid at the mean interval, each slot blended to its time.
        let t = times(&[1.0, 1.0, 1.45], 30);
        let c = Clock::fit(&t).unwrap();
        assert!((c.interval - 1.15).abs() < 0.01, "{c:?}");
        let ramp: Vec<f32> = t.iter().map(|&x| x as f32).collect();
        let r = c.resample(&t, &ramp, 1);
        for (k, v) in r.iter().enumerate() {
            let tau = c.start + k as f64 * c.interval;
            // Blended to the slot's time, or a frame within a tenth of an interval of it.
            if tau >= 0.0 && tau <= *t.last().unwrap() {
                let off = (*v as f64 - tau).abs();
                assert!(off < ROUNDING * c.interval + 1e-4, "slot {k}: {v} vs {tau}");
            }
        }
        // No even clock: intervals alternating 1 and 2.6 (a grid of 0.9 would need half its
        // frames dropped), or 1 and 1.5.
        let e = Clock::fit(&times(&[1.0, 2.6], 20)).unwrap_err();
        assert!(e.longest > 2.5 && e.median == 1.0, "{e:?}");
        assert!(Clock::fit(&times(&[1.0, 1.5], 20)).is_err());
        // A pause of six frames in a 10 fps recording.
        let mut t: Vec<f64> = (0..20).map(|i| i as f64 * 0.1).collect();
        t.extend((26..40).map(|i| i as f64 * 0.1));
        let e = Clock::fit(&t).unwrap_err();
        assert_eq!(e.gap.map(|g| g.1), Some(6), "{e:?}");
    }

    #[test]
    fn a_frame_off_the_clock_is_left_out_at_an_end_and_resampled_in_the_middle() {
        // The museum's clock: 52.9 ms to the second frame, 33.3 ms after (41 % of an interval
        // off for the first frame), and the same at the end.
        let d = 1.0 / 30.0;
        let mut t = vec![0.0];
        t.extend((0..60).map(|k| 0.0529 + k as f64 * d));
        let c = Clock::fit(&t).unwrap();
        assert_eq!((c.head, c.tail, c.off), (1, 0, 0), "{c:?}");
        assert!((c.interval - d).abs() < 1e-9 && !c.is_even(), "{c:?}");
        let frames: Vec<f32> = t.iter().map(|&x| x as f32).collect();
        let grid = c.resample(&t, &frames, 1);
        assert_eq!(grid.len(), 60);
        assert_eq!(grid[0], 0.0529f32);
        assert!(
            c.note(true).unwrap().contains("the first frame"),
            "{:?}",
            c.note(true)
        );
        let mut end = t.clone();
        end.push(end[60] + 0.0529);
        let c = Clock::fit(&end).unwrap();
        assert_eq!((c.head, c.tail), (1, 1), "{c:?}");
        // One frame 40 % of an interval late in the middle: resampled on the real times.
        let mut t: Vec<f64> = (0..60).map(|k| k as f64 * 0.1).collect();
        t[30] += 0.04;
        let c = Clock::fit(&t).unwrap();
        assert_eq!((c.head, c.tail, c.off), (0, 0, 1), "{c:?}");
        let ramp: Vec<f32> = t.iter().map(|&x| x as f32).collect();
        let r = c.resample(&t, &ramp, 1);
        assert!((r[30] - 3.0).abs() < 2e-3, "{}", r[30]);
        // Every fourth frame 40 % late: more than a tenth off, refused, the frames named.
        let t: Vec<f64> = (0..60)
            .map(|k| k as f64 * 0.1 + if k % 4 == 2 { 0.04 } else { 0.0 })
            .collect();
        let e = Clock::fit(&t).unwrap_err();
        assert!(
            e.reason().contains("furthest off: frame 3 (0.24 s)"),
            "{}",
            e.reason()
        );
    }
}
