//! The motion's own time scale, read off the survey's frames without any model: thumbnails of
//! every frame (blocks of survey pixels, each frame's mean taken out), their leading principal
//! components (what changes most in the picture), and the period of the slowest of them that
//! repeats (an oscillation), or none (a decay, a drain, a fall: a motion that does not come
//! back). A swinging bob's left–right component repeats at the swing's period; its height
//! repeats at half of it, so the longest period among the leading components is the
//! fundamental's.

use crate::stats::correlation;

/// Survey pixels averaged into one thumbnail pixel along each side.
const BLOCK: usize = 4;

/// At most this many frames (evenly spaced) enter the principal components; every frame is
/// projected on them.
const PCA_FRAMES: usize = 600;

/// The leading components searched for a period, and the least share of the picture's change
/// one must carry to count.
const COMPONENTS: usize = 3;
const MIN_SHARE: f64 = 0.05;

/// A component's correlation with itself one period later must reach this for the motion to
/// count as repeating.
pub const REPEATS: f64 = 0.5;

/// A period is searched up to a third of the frames: at least three must be seen.
const PERIODS_SEEN: usize = 3;

/// The signal is averaged down to at most this many samples before its autocorrelation.
const MAX_SAMPLES: usize = 4000;

/// Thumbnails of the surveyed frames.
pub struct Thumbnails {
    /// The survey frame's size and the thumbnail's.
    size: (usize, usize),
    thumb: (usize, usize),
    /// Block means, frame-major (u8: a minute at 600 fps stays within 32 MB).
    pixels: Vec<u8>,
    n: usize,
}

impl Thumbnails {
    /// For survey frames of `size` (w, h).
    pub fn new(size: (usize, usize)) -> Thumbnails {
        let thumb = ((size.0 / BLOCK).max(1), (size.1 / BLOCK).max(1));
        Thumbnails {
            size,
            thumb,
            pixels: Vec::new(),
            n: 0,
        }
    }

    /// Adds a frame (grey bytes of the survey's size).
    pub fn add(&mut self, frame: &[u8]) {
        let (w, _) = self.size;
        let (tw, th) = self.thumb;
        for ty in 0..th {
            for tx in 0..tw {
                let mut sum = 0u32;
                for y in ty * BLOCK..(ty + 1) * BLOCK {
                    for x in tx * BLOCK..(tx + 1) * BLOCK {
                        sum += frame.get(y * w + x).copied().unwrap_or(0) as u32;
                    }
                }
                self.pixels.push((sum / (BLOCK * BLOCK) as u32) as u8);
            }
        }
        self.n += 1;
    }

    /// The frames added.
    pub fn len(&self) -> usize {
        self.n
    }

    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// The motion's period in frames, where one of the picture's leading changes repeats,
    /// within `region` (x, y, w, h in survey pixels: where the picture moves most; something
    /// moving elsewhere, a passer-by, a drifting light, has periods of its own) or the whole
    /// frame.
    pub fn period(&self, region: Option<(usize, usize, usize, usize)>) -> Option<f64> {
        let (tw, th) = self.thumb;
        let d = tw * th;
        if self.n < 4 * PERIODS_SEEN || d == 0 {
            return None;
        }
        // The thumbnail blocks the region touches.
        let (x0, y0, x1, y1) = region.map_or((0, 0, tw, th), |(x, y, w, h)| {
            let x1 = (x + w).div_ceil(BLOCK).clamp(1, tw);
            let y1 = (y + h).div_ceil(BLOCK).clamp(1, th);
            ((x / BLOCK).min(x1 - 1), (y / BLOCK).min(y1 - 1), x1, y1)
        });
        let kept: Vec<usize> = (y0..y1)
            .flat_map(|ty| (x0..x1).map(move |tx| ty * tw + tx))
            .collect();
        // Each frame's mean out (a light that flickers moves every pixel alike).
        let rows: Vec<Vec<f64>> = self
            .pixels
            .chunks(d)
            .map(|f| {
                let f: Vec<f64> = kept.iter().map(|&i| f[i] as f64).collect();
                let m = f.iter().sum::<f64>() / f.len() as f64;
                f.iter().map(|v| v - m).collect()
            })
            .collect();
        leading_components(&rows, COMPONENTS)
            .into_iter()
            .filter(|(_, share)| *share >= MIN_SHARE)
            .filter_map(|(signal, _)| period_of(&signal))
            .max_by(f64::total_cmp)
    }
}

/// The projections of `rows` (frames × pixels) on their `k` leading principal components, each
/// with its share of the total variance.
fn leading_components(rows: &[Vec<f64>], k: usize) -> Vec<(Vec<f64>, f64)> {
    let (n, d) = (rows.len(), rows[0].len());
    let mean: Vec<f64> = (0..d)
        .map(|j| rows.iter().map(|r| r[j]).sum::<f64>() / n as f64)
        .collect();
    let picked: Vec<usize> = (0..n.min(PCA_FRAMES))
        .map(|i| i * n / n.min(PCA_FRAMES))
        .collect();
    let mut cov = vec![0.0; d * d];
    for &i in &picked {
        let x: Vec<f64> = rows[i].iter().zip(&mean).map(|(a, m)| a - m).collect();
        for a in 0..d {
            if x[a] == 0.0 {
                continue;
            }
            for b in 0..d {
                cov[a * d + b] += x[a] * x[b];
            }
        }
    }
    let total: f64 = (0..d).map(|a| cov[a * d + a]).sum();
    if total <= 0.0 {
        return Vec::new();
    }
    let mut out = Vec::new();
    for _ in 0..k {
        // Power iteration from a fixed start, then deflation.
        let mut v: Vec<f64> = (0..d).map(|j| 1.0 + (j % 7) as f64 * 0.1).collect();
        let mut lambda = 0.0;
        for _ in 0..100 {
            let w: Vec<f64> = (0..d)
                .map(|a| (0..d).map(|b| cov[a * d + b] * v[b]).sum())
                .collect();
            let norm = w.iter().map(|x| x * x).sum::<f64>().sqrt();
            if norm <= 0.0 {
                return out;
            }
            lambda = norm;
            v = w.into_iter().map(|x| x / norm).collect();
        }
        for a in 0..d {
            for b in 0..d {
                cov[a * d + b] -= lambda * v[a] * v[b];
            }
        }
        let signal = rows
            .iter()
            .map(|r| {
                r.iter()
                    .zip(&mean)
                    .zip(&v)
                    .map(|((x, m), e)| (x - m) * e)
                    .sum()
            })
            .collect();
        out.push((signal, lambda / total));
    }
    out
}

/// The period (in samples) at which `signal` repeats: the first lag past its autocorrelation's
/// first zero where the correlation of the signal with itself reaches [`REPEATS`], climbed to
/// its peak; `None` where it does not repeat within a third of its length.
pub fn period_of(signal: &[f64]) -> Option<f64> {
    // Averaged down to at most MAX_SAMPLES, a linear trend out.
    let g = signal.len().div_ceil(MAX_SAMPLES).max(1);
    let s: Vec<f64> = signal
        .chunks(g)
        .map(|c| c.iter().sum::<f64>() / c.len() as f64)
        .collect();
    let n = s.len();
    let tm = (n as f64 - 1.0) / 2.0;
    let sm = s.iter().sum::<f64>() / n as f64;
    let (mut num, mut den) = (0.0, 0.0);
    for (t, v) in s.iter().enumerate() {
        num += (t as f64 - tm) * (v - sm);
        den += (t as f64 - tm).powi(2);
    }
    let slope = if den > 0.0 { num / den } else { 0.0 };
    let s: Vec<f64> = s
        .iter()
        .enumerate()
        .map(|(t, v)| v - sm - slope * (t as f64 - tm))
        .collect();
    let max_lag = n / PERIODS_SEEN;
    let r = |lag: usize| correlation(&s[..n - lag], &s[lag..]);
    let zero = (1..=max_lag).find(|&l| r(l) < 0.0)?;
    let mut lag = (zero..=max_lag).find(|&l| r(l) >= REPEATS)?;
    while lag < max_lag && r(lag + 1) > r(lag) {
        lag += 1;
    }
    Some((lag * g) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Frames of 64×36 with a bright 4×4 square at (x, y).
    fn frame(x: usize, y: usize) -> Vec<u8> {
        let (w, h) = (64, 36);
        let mut f = vec![40u8; w * h];
        for dy in 0..4 {
            for dx in 0..4 {
                f[(y + dy) * w + x + dx] = 220;
            }
        }
        f
    }

    #[test]
    fn a_swing_repeats_at_its_period_not_at_half_of_it() {
        // A bob on an arc: x swings at the period (50 frames), y (its height) at half of it.
        let mut t = Thumbnails::new((64, 36));
        for k in 0..400 {
            let a = (k as f64 * std::f64::consts::TAU / 50.0).sin();
            let x = 30.0 + 20.0 * a;
            let y = 10.0 + 12.0 * a * a;
            t.add(&frame(x.round() as usize, y.round() as usize));
        }
        let p = t.period(None).expect("a period");
        assert!((p - 50.0).abs() <= 2.0, "{p}");
    }

    #[test]
    fn within_the_region_that_moves_most_a_slower_motion_elsewhere_is_not_the_period() {
        // A square swinging at 30 frames in the left half, another drifting to and fro at 150
        // frames in the right half.
        let mut t = Thumbnails::new((64, 36));
        for k in 0..600 {
            let x = 14.0 + 10.0 * (k as f64 * std::f64::consts::TAU / 30.0).sin();
            let mut f = frame(x.round() as usize, 10);
            let u = 46.0 + 10.0 * (k as f64 * std::f64::consts::TAU / 150.0).sin();
            for dy in 0..4 {
                for dx in 0..4 {
                    f[(24 + dy) * 64 + u.round() as usize + dx] = 220;
                }
            }
            t.add(&f);
        }
        let whole = t.period(None).expect("a period");
        assert!((whole - 150.0).abs() <= 5.0, "{whole}");
        let p = t.period(Some((0, 4, 32, 14))).expect("a period");
        assert!((p - 30.0).abs() <= 2.0, "{p}");
    }

    #[test]
    fn a_fall_or_a_drain_does_not_repeat() {
        let mut t = Thumbnails::new((64, 36));
        for k in 0..300 {
            // A level sinking as a tank drains: (1 − t)².
            let y = 30.0 * (1.0 - (1.0 - k as f64 / 300.0).powi(2));
            t.add(&frame(30, y.round() as usize));
        }
        assert_eq!(t.period(None), None);
        // A still picture has no period either.
        let mut still = Thumbnails::new((64, 36));
        for _ in 0..100 {
            still.add(&frame(10, 10));
        }
        assert_eq!(still.period(None), None);
    }

    #[test]
    fn noise_does_not_repeat() {
        let mut x: u64 = 7;
        let noise: Vec<f64> = (0..2000)
            .map(|_| {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (x >> 33) as f64 / (1u64 << 31) as f64
            })
            .collect();
        assert_eq!(period_of(&noise), None);
        let sine: Vec<f64> = (0..2000).map(|t| (t as f64 * 0.05).sin()).collect();
        let p = period_of(&sine).unwrap();
        assert!((p - std::f64::consts::TAU / 0.05).abs() < 2.0, "{p}");
    }
}
