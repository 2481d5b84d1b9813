//! A recording's clock, read from its frames' own times (the container's timestamps, a GIF's
//! delays, an image folder's numbering), never guessed from a typical interval: the even grid
//! that fits the times best (least squares over every frame), each frame's slot on it, and
//! what does not sit on it. Times within a tenth of an interval of their slot (a
//! container's rounding) are taken as they are; a recording whose frames sit further off (a
//! GIF's whole centiseconds, an uneven capture) is resampled onto the grid by blending each
//! slot's two nearest frames in time; a doubled frame (two in one slot) keeps the one nearer
//! its slot; a dropped frame (an empty slot) is blended from its neighbours, at most
//! [`MAX_MISSING`] in a row. Times that fit no even grid within a quarter of an interval are
//! refused with the numbers. `resample.rs` puts the frames on the grid.

mod resample;

/// Deviation from the grid, in intervals, below which frames are used as they are.
pub const ROUNDING: f64 = 0.1;
/// Deviation from the grid, in intervals, beyond which no even clock is taken to fit.
pub const MAX_JITTER: f64 = 0.25;
/// The most slots in a row without a frame that are filled in.
pub const MAX_MISSING: usize = 2;
/// The largest share of slots without a frame: beyond it the grid explains the times by
/// dropped frames that were never there.
pub const MAX_MISSING_SHARE: f64 = 0.1;

/// The even grid a recording's frames sit on.
#[derive(Debug, Clone, PartialEq)]
pub struct Clock {
    /// Time of slot 0 (the first frame's, up to its deviation), in the times' unit.
    pub start: f64,
    /// Time between slots.
    pub interval: f64,
    /// Each frame's slot (non-decreasing).
    pub slots: Vec<usize>,
    /// Largest distance of a slot's nearest frame from the slot, in intervals.
    pub jitter: f64,
}

/// Times that fit no even clock: the numbers for the refusal.
#[derive(Debug, Clone, PartialEq)]
pub struct Uneven {
    pub shortest: f64,
    pub longest: f64,
    pub median: f64,
    /// The best grid's worst deviation, in intervals.
    pub jitter: f64,
    /// A run of empty slots longer than [`MAX_MISSING`]: (the time it starts, slots missing).
    pub gap: Option<(f64, usize)>,
}

impl Uneven {
    /// What is uneven, for a refusal, the times in seconds of the file's timeline.
    pub fn reason(&self) -> String {
        let ms = |s: f64| crate::cli::approx(s * 1e3);
        let what = match self.gap {
            Some((at, n)) => format!(
                "{n} frames are missing after {} s of the file's timeline (a pause or dropped \
                 frames; at most {MAX_MISSING} in a row are filled in)",
                crate::cli::approx(at)
            ),
            None => format!(
                "intervals from {} to {} ms (median {} ms) sit on no even clock (the best \
                 leaves a frame {:.0} % of an interval off, or too many frames missing)",
                ms(self.shortest),
                ms(self.longest),
                ms(self.median),
                self.jitter * 100.0
            ),
        };
        format!(
            "the frames are not evenly spaced in time: {what}; keep an even part with \
             --start/--end, or re-encode at a constant rate (ffmpeg -i IN -vf fps=RATE OUT.mp4)"
        )
    }
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
        let uneven = |jitter: f64, gap| Uneven {
            shortest: steps.first().copied().unwrap_or(0.0),
            longest: steps.last().copied().unwrap_or(0.0),
            median,
            jitter,
            gap,
        };
        if n < 2 || median.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Ok(Clock {
                start: times.first().copied().unwrap_or(0.0),
                interval: if median > 0.0 { median } else { 1.0 },
                slots: (0..n).collect(),
                jitter: 0.0,
            });
        }
        // Slots step by step at the median interval (a frame doubled or dropped is a step of
        // zero or two), then the least-squares grid through them, twice.
        let mut slots = vec![0usize; n];
        for i in 1..n {
            let step = ((times[i] - times[i - 1]) / median).round().max(0.0) as usize;
            slots[i] = slots[i - 1] + step;
        }
        let (mut start, mut interval) = line(times, &slots);
        for _ in 0..2 {
            for (s, &t) in slots.iter_mut().zip(times) {
                *s = ((t - start) / interval).round().max(0.0) as usize;
            }
            (start, interval) = line(times, &slots);
        }
        // The worst slot's nearest frame (of a doubled pair, the one kept).
        let mut jitter: f64 = 0.0;
        let mut i = 0;
        while i < n {
            let mut best = f64::INFINITY;
            let slot = slots[i];
            while i < n && slots[i] == slot {
                best = best.min((times[i] - start - slot as f64 * interval).abs() / interval);
                i += 1;
            }
            jitter = jitter.max(best);
        }
        let clock = Clock {
            start,
            interval,
            slots,
            jitter,
        };
        if jitter > MAX_JITTER || !interval.is_finite() {
            return Err(uneven(jitter, None));
        }
        if let Some((at, missing)) = clock.longest_gap().filter(|g| g.1 > MAX_MISSING) {
            return Err(uneven(jitter, Some((times[at], missing))));
        }
        if clock.missing() as f64 > MAX_MISSING_SHARE * (clock.slots[n - 1] + 1) as f64 {
            return Err(uneven(jitter, None));
        }
        Ok(clock)
    }

    /// Whether the frames are the grid itself: one in every slot, each within [`ROUNDING`].
    pub fn is_even(&self) -> bool {
        self.jitter <= ROUNDING && self.slots.iter().enumerate().all(|(i, &s)| s == i)
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

/// The least-squares line t = start + interval·slot.
fn line(times: &[f64], slots: &[usize]) -> (f64, f64) {
    let n = times.len() as f64;
    let ms = slots.iter().map(|&s| s as f64).sum::<f64>() / n;
    let mt = times.iter().sum::<f64>() / n;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (&s, &t) in slots.iter().zip(times) {
        let ds = s as f64 - ms;
        sxy += ds * (t - mt);
        sxx += ds * ds;
    }
    let interval = if sxx > 0.0 { sxy / sxx } else { 1.0 };
    (mt - interval * ms, interval)
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
}
