//! The frames on their clock's grid: one per slot, a frame within [`ROUNDING`] of its slot
//! as it is, else (and for an empty slot) the blend of the two frames nearest the slot's
//! time on either side.

use super::{Clock, ROUNDING};

impl Clock {
    /// The frames `frames` ([n, len], one per time fitted) on the grid, one per slot from the
    /// first kept frame's to the last's (those left out at the ends dropped): a frame within
    /// [`ROUNDING`] of its slot as it is, else (and for an empty slot) the blend of the two
    /// frames nearest the slot's time on either side.
    pub fn resample(&self, times: &[f64], frames: &[f32], len: usize) -> Vec<f32> {
        let n = times.len();
        let times = &times[self.head..n - self.tail];
        let frames = &frames[self.head * len..(n - self.tail) * len];
        let slots = self.slots.last().map_or(0, |s| s + 1);
        let mut out = Vec::with_capacity(slots * len);
        let frame = |i: usize| &frames[i * len..(i + 1) * len];
        let mut j = 0; // the last frame at or before the slot's time
        for k in 0..slots {
            let tau = self.start + k as f64 * self.interval;
            while j + 1 < times.len() && times[j + 1] <= tau {
                j += 1;
            }
            // The frame nearest the slot, if close enough to stand for it.
            let near = [j, (j + 1).min(times.len() - 1)]
                .into_iter()
                .min_by(|&a, &b| (times[a] - tau).abs().total_cmp(&(times[b] - tau).abs()))
                .filter(|&i| {
                    (times[i] - tau).abs() <= ROUNDING * self.interval
                        || (self.jitter <= ROUNDING && self.slots[i] == k)
                });
            match near {
                Some(i) => out.extend_from_slice(frame(i)),
                None => {
                    let (a, b) = if times[j] > tau || j + 1 >= times.len() {
                        (j, j)
                    } else {
                        (j, j + 1)
                    };
                    let w = if b == a {
                        0.0
                    } else {
                        ((tau - times[a]) / (times[b] - times[a])) as f32
                    };
                    out.extend(
                        frame(a)
                            .iter()
                            .zip(frame(b))
                            .map(|(&x, &y)| x + w * (y - x)),
                    );
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_even_recording_is_its_own_grid_and_is_not_touched() {
        let t: Vec<f64> = (0..50).map(|i| i as f64 * 1001.0 / 30000.0).collect();
        let c = Clock::fit(&t).unwrap();
        assert!(c.is_even(), "{c:?}");
        let frames: Vec<f32> = (0..100).map(|v| v as f32).collect();
        assert_eq!(c.resample(&t, &frames, 2), frames);
    }
}
