//! The background a recording's object moves over: each frame's level (a camera's exposure or
//! a drifting light moves the whole picture at once, and is taken off), the sensor's noise read
//! off the differences from each pixel's median over the recording, the object's polarity
//! (darker or lighter than what it passes: the sign most of the large differences take), and
//! the background as each pixel's value that the object leaves alone (a high percentile for a
//! dark object, a low one for a light one: a slow or small motion puts the object on the same
//! pixels for much of the recording, where a median would keep its ghost).

use physvid_shared::video::SmallFrames;
use rayon::prelude::*;

/// At most this many frames, evenly spread, make the median background.
const BACKGROUND_FRAMES: usize = 255;

/// A pixel differs from the background when its difference is this many noise spreads…
const NOISE_SPREADS: f64 = 6.0;
/// …and at least this many grey levels (a GIF's or a clean render's noise is near zero).
const LEAST_LEVELS: f64 = 10.0;

/// The background is each pixel's value at this share of its frames from the object's side: a
/// pixel the object covers for less than the rest of the time keeps the wall's value.
const BACKGROUND_SHARE: f64 = 0.85;

/// The background and the difference that counts as a change.
pub struct Background {
    /// Each pixel's value without the object (`BACKGROUND_SHARE`), on the frames' common level.
    pub median: Vec<u8>,
    /// Each frame's level against the others (grey levels): the median of its differences
    /// from the median picture, a camera's exposure or a drifting light moving the whole
    /// picture at once. A frame is compared with the background less its level.
    pub level: Vec<i16>,
    /// The object's sense: −1 darker than the background, +1 lighter.
    pub polarity: f64,
    /// Grey levels.
    pub threshold: f64,
    /// The differences' robust spread (grey levels).
    pub noise: f64,
}

/// Up to `most` of `n` frames' indices, evenly spread from the first to the last (all of them
/// where there are no more).
pub(super) fn evenly(n: usize, most: usize) -> Vec<usize> {
    if n <= most {
        (0..n).collect()
    } else {
        (0..most).map(|k| k * (n - 1) / (most - 1)).collect()
    }
}

/// Each frame's level (the median of its differences from `median`, whole grey levels).
fn levels(frames: &SmallFrames, median: &[u8]) -> Vec<i16> {
    (0..frames.len())
        .into_par_iter()
        .map(|i| {
            let mut histogram = [0u64; 511];
            for (a, b) in frames.frame(i).iter().zip(median) {
                histogram[(*a as i32 - *b as i32 + 255) as usize] += 1;
            }
            let total: u64 = histogram.iter().sum();
            let mut seen = 0;
            let at = histogram
                .iter()
                .position(|&c| {
                    seen += c;
                    2 * seen >= total
                })
                .unwrap_or(255);
            at as i16 - 255
        })
        .collect()
}

/// The pictures' values at a pixel for the frames `picked`, each less its frame's level,
/// sorted.
fn column(frames: &SmallFrames, picked: &[usize], level: &[i16], p: usize, into: &mut Vec<i16>) {
    into.clear();
    into.extend(picked.iter().map(|&i| frames.frame(i)[p] as i16 - level[i]));
    into.sort_unstable();
}

/// The noise of the differences from each pixel's median over up to [`BACKGROUND_FRAMES`]
/// frames (1.4826 × their median absolute deviation, from a histogram), each frame taken at
/// the common level (`levels`), the polarity of the larger ones, and the background the object
/// leaves alone.
pub fn background(frames: &SmallFrames) -> Background {
    let n = frames.len();
    let pixels = frames.size.0 * frames.size.1;
    let picked = evenly(n, BACKGROUND_FRAMES);
    // Each pixel's column on the pool's threads (each thread its own buffer), in order.
    let buffer = || Vec::with_capacity(picked.len());
    let flat = vec![0i16; n];
    let raw: Vec<u8> = (0..pixels)
        .into_par_iter()
        .map_init(buffer, |values, p| {
            column(frames, &picked, &flat, p, values);
            values[values.len() / 2].clamp(0, 255) as u8
        })
        .collect();
    let level = levels(frames, &raw);
    let at = |share: f64, len: usize| ((share * (len - 1) as f64).round() as usize).min(len - 1);
    let grey = |v: i16| v.clamp(0, 255) as u8;
    let (median, (low, high)): (Vec<i16>, (Vec<u8>, Vec<u8>)) = (0..pixels)
        .into_par_iter()
        .map_init(buffer, |values, p| {
            column(frames, &picked, &level, p, values);
            (
                values[values.len() / 2],
                (
                    grey(values[at(1.0 - BACKGROUND_SHARE, values.len())]),
                    grey(values[at(BACKGROUND_SHARE, values.len())]),
                ),
            )
        })
        .unzip();
    let difference = |i: usize, p: usize, a: u8| (a as i16 - level[i] - median[p]) as f64;
    let mut histogram = [0u64; 256];
    for &i in &picked {
        for (p, &a) in frames.frame(i).iter().enumerate() {
            histogram[difference(i, p, a).abs().min(255.0) as usize] += 1;
        }
    }
    let med = histogram_median(&histogram);
    let mut deviations = [0u64; 256];
    for (d, &c) in histogram.iter().enumerate() {
        deviations[(d as f64 - med).abs().round().min(255.0) as usize] += c;
    }
    let noise = 1.4826 * histogram_median(&deviations);
    let threshold = (NOISE_SPREADS * noise).max(LEAST_LEVELS);
    // The polarity: which sign the differences beyond the threshold mostly take.
    let (mut darker, mut lighter) = (0.0, 0.0);
    for &i in &picked {
        for (p, &a) in frames.frame(i).iter().enumerate() {
            let d = difference(i, p, a);
            if d < -threshold {
                darker -= d;
            } else if d > threshold {
                lighter += d;
            }
        }
    }
    let (polarity, median) = if darker >= lighter {
        (-1.0, high)
    } else {
        (1.0, low)
    };
    Background {
        median,
        level,
        polarity,
        threshold,
        noise,
    }
}

fn histogram_median(h: &[u64; 256]) -> f64 {
    let total: u64 = h.iter().sum();
    let mut seen = 0;
    for (v, &c) in h.iter().enumerate() {
        seen += c;
        if 2 * seen >= total {
            return v as f64;
        }
    }
    255.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A dark 3×3 square crossing a wall of 200 on frames whose exposure rises by 2 levels a
    /// frame: the background is the wall everywhere, the object darker, each frame's level its
    /// exposure's step.
    #[test]
    fn the_background_is_the_wall_the_object_crosses() {
        let (w, h, n) = (30usize, 10usize, 9usize);
        let mut pixels = Vec::new();
        for k in 0..n {
            pixels.extend((0..w * h).map(|i| {
                let (x, y) = (i % w, i / w);
                let on = (3 * k..3 * k + 3).contains(&x) && (4..7).contains(&y);
                (if on { 40 } else { 200 }) + 2 * k as u8
            }));
        }
        let frames = SmallFrames {
            pixels,
            size: (w, h),
        };
        let bg = background(&frames);
        assert_eq!(bg.polarity, -1.0);
        let steps: Vec<i16> = bg.level.windows(2).map(|p| p[1] - p[0]).collect();
        assert!(steps.iter().all(|&s| s == 2), "{:?}", bg.level);
        let wall = bg.median[0];
        assert!(bg.median.iter().all(|&v| v == wall), "{:?}", bg.median);
        assert_eq!(bg.threshold, LEAST_LEVELS);
    }
}
