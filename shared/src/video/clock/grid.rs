//! The even grid through a recording's frame times: each frame's slot, the least-squares
//! line through them, and how far each frame lies off it.

use super::{MAX_JITTER, NAMED};

/// An even grid fitted to frame times: each frame's slot and the line through them.
#[derive(Debug, Clone)]
pub(super) struct Grid {
    pub(super) start: f64,
    pub(super) interval: f64,
    pub(super) slots: Vec<usize>,
}

impl Grid {
    /// Slots step by step at the `median` interval (a frame doubled or dropped is a step of
    /// zero or two), then the least-squares grid through them, twice.
    pub(super) fn of(times: &[f64], median: f64) -> Grid {
        let n = times.len();
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
        Grid {
            start,
            interval,
            slots,
        }
    }

    /// Frame `i`'s distance from its slot, in intervals.
    pub(super) fn deviation(&self, times: &[f64], i: usize) -> f64 {
        (times[i] - self.start - self.slots[i] as f64 * self.interval).abs() / self.interval
    }

    /// Each slot's nearest frame's distance from it (of a doubled pair, the one kept).
    pub(super) fn nearest(&self, times: &[f64]) -> Vec<f64> {
        let mut out = Vec::new();
        let mut i = 0;
        while i < times.len() {
            let (slot, mut best) = (self.slots[i], f64::INFINITY);
            while i < times.len() && self.slots[i] == slot {
                best = best.min(self.deviation(times, i));
                i += 1;
            }
            out.push(best);
        }
        out
    }

    /// The worst slot's nearest frame's distance from it, in intervals.
    pub(super) fn jitter(&self, times: &[f64]) -> f64 {
        self.nearest(times).into_iter().fold(0.0, f64::max)
    }

    /// Slots whose nearest frame lies over [`MAX_JITTER`] off.
    pub(super) fn slots_off(&self, times: &[f64]) -> usize {
        self.nearest(times)
            .into_iter()
            .filter(|d| *d > MAX_JITTER || d.is_nan())
            .count()
    }

    /// The [`NAMED`] frames furthest off (their number from 1 among all, the first fitted
    /// being frame `first` from 0; their time), those over [`MAX_JITTER`] only.
    pub(super) fn furthest(&self, times: &[f64], first: usize) -> Vec<(usize, f64)> {
        let mut off: Vec<(usize, f64)> = (0..times.len().min(self.slots.len()))
            .map(|i| (i, self.deviation(times, i)))
            .filter(|(_, d)| *d > MAX_JITTER)
            .collect();
        off.sort_by(|a, b| b.1.total_cmp(&a.1));
        off.into_iter()
            .take(NAMED)
            .map(|(i, _)| (first + i + 1, times[i]))
            .collect()
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
