//! What differs from the background in each frame: each frame's level (a camera's exposure or
//! a drifting light moves the whole picture at once, and is taken off), the sensor's noise read
//! off the differences from each pixel's median over the recording, the object's polarity (darker or
//! lighter than what it passes: the sign most of the large differences take), the background
//! as each pixel's value that the object leaves alone (a high percentile for a dark object, a
//! low one for a light one: a slow or small motion puts the object on the same pixels for much
//! of the recording, where a median would keep its ghost), and the connected blobs of the
//! pixels that differ from it by well over the noise, in the object's sense.

use physvid_shared::video::region::components;
use physvid_shared::video::SmallFrames;

/// At most this many frames, evenly spread, make the median background.
const BACKGROUND_FRAMES: usize = 255;

/// A pixel differs from the background when its difference is this many noise spreads…
const NOISE_SPREADS: f64 = 6.0;
/// …and at least this many grey levels (a GIF's or a clean render's noise is near zero).
const LEAST_LEVELS: f64 = 10.0;

/// The background is each pixel's value at this share of its frames from the object's side: a
/// pixel the object covers for less than the rest of the time keeps the wall's value.
const BACKGROUND_SHARE: f64 = 0.85;

/// Blobs smaller than this many pixels are noise.
const LEAST_AREA: usize = 3;

/// One connected region that differs from the background, in the frame's pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Blob {
    pub area: f64,
    /// The centroid weighted by the difference.
    pub x: f64,
    pub y: f64,
}

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

/// Each frame's level (the median of its differences from `median`, whole grey levels).
fn levels(frames: &SmallFrames, median: &[u8]) -> Vec<i16> {
    (0..frames.len())
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
    let picked: Vec<usize> = if n <= BACKGROUND_FRAMES {
        (0..n).collect()
    } else {
        (0..BACKGROUND_FRAMES)
            .map(|k| k * (n - 1) / (BACKGROUND_FRAMES - 1))
            .collect()
    };
    let mut values = Vec::with_capacity(picked.len());
    let flat = vec![0i16; n];
    let raw: Vec<u8> = (0..pixels)
        .map(|p| {
            column(frames, &picked, &flat, p, &mut values);
            values[values.len() / 2].clamp(0, 255) as u8
        })
        .collect();
    let level = levels(frames, &raw);
    let mut median = vec![0i16; pixels];
    let mut low = vec![0u8; pixels];
    let mut high = vec![0u8; pixels];
    let at = |share: f64, len: usize| ((share * (len - 1) as f64).round() as usize).min(len - 1);
    let grey = |v: i16| v.clamp(0, 255) as u8;
    for p in 0..pixels {
        column(frames, &picked, &level, p, &mut values);
        median[p] = values[values.len() / 2];
        low[p] = grey(values[at(1.0 - BACKGROUND_SHARE, values.len())]);
        high[p] = grey(values[at(BACKGROUND_SHARE, values.len())]);
    }
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

/// The blobs of frame `k` against `bg`: pixels beyond the threshold in the object's sense (the
/// frame taken at the common level), opened by a 3×3 cross (a speck or a one-pixel line goes),
/// 8-connected, at least [`LEAST_AREA`] pixels.
pub fn blobs(frames: &SmallFrames, k: usize, bg: &Background) -> Vec<Blob> {
    let (w, h) = frames.size;
    let level = bg.level[k] as f64;
    let diff: Vec<f64> = frames
        .frame(k)
        .iter()
        .zip(&bg.median)
        .map(|(a, b)| (bg.polarity * (*a as f64 - level - *b as f64)).max(0.0))
        .collect();
    let on: Vec<bool> = diff.iter().map(|&d| d > bg.threshold).collect();
    let on = dilate(&erode(&on, w, h), w, h);
    let (labels, count) = components(&on, w, h);
    let mut sums = vec![(0usize, 0.0, 0.0, 0.0); count];
    for (i, l) in labels.iter().enumerate() {
        if let Some(l) = l {
            let s = &mut sums[*l];
            let d = diff[i];
            s.0 += 1;
            s.1 += d;
            s.2 += d * (i % w) as f64;
            s.3 += d * (i / w) as f64;
        }
    }
    sums.into_iter()
        .filter(|s| s.0 >= LEAST_AREA && s.1 > 0.0)
        .map(|(area, wsum, xs, ys)| Blob {
            area: area as f64,
            x: xs / wsum,
            y: ys / wsum,
        })
        .collect()
}

/// The 3×3 cross's erosion (a pixel stays on where it and its four neighbours are on).
fn erode(on: &[bool], w: usize, h: usize) -> Vec<bool> {
    cross(on, w, h, true)
}

/// The 3×3 cross's dilation (a pixel is on where it or one of its four neighbours is).
fn dilate(on: &[bool], w: usize, h: usize) -> Vec<bool> {
    cross(on, w, h, false)
}

fn cross(on: &[bool], w: usize, h: usize, all: bool) -> Vec<bool> {
    (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let neighbours = [
                Some(i),
                (x > 0).then(|| i - 1),
                (x + 1 < w).then(|| i + 1),
                (y > 0).then(|| i - w),
                (y + 1 < h).then(|| i + w),
            ];
            let mut cells = neighbours.iter().flatten().map(|&j| on[j]);
            if all {
                cells.all(|b| b)
            } else {
                cells.any(|b| b)
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Frames of a grey wall with a dark 4×4 square at `(x, y)` (its top-left corner).
    fn square_at(places: &[(usize, usize)], (w, h): (usize, usize)) -> SmallFrames {
        let mut pixels = Vec::new();
        for &(x, y) in places {
            let mut f = vec![200u8; w * h];
            for r in y..y + 4 {
                for c in x..x + 4 {
                    f[r * w + c] = 40;
                }
            }
            pixels.extend(f);
        }
        SmallFrames {
            pixels,
            size: (w, h),
        }
    }

    #[test]
    fn a_moving_square_is_one_blob_at_its_centre() {
        let places: Vec<(usize, usize)> = (0..9).map(|k| (2 + 3 * k, 5)).collect();
        let frames = square_at(&places, (40, 16));
        let bg = background(&frames);
        assert_eq!(bg.median[0], 200);
        for (k, &(x, y)) in places.iter().enumerate() {
            let b = blobs(&frames, k, &bg);
            assert_eq!(b.len(), 1, "frame {k}: {b:?}");
            assert!((b[0].x - (x as f64 + 1.5)).abs() < 1e-9);
            assert!((b[0].y - (y as f64 + 1.5)).abs() < 1e-9);
            // The opening by a cross rounds off the square's four corners.
            assert_eq!(b[0].area, 12.0);
        }
    }

    #[test]
    fn a_picture_brightening_and_dimming_as_a_whole_keeps_one_blob() {
        // A camera's exposure moving the wall 12–30 grey levels from frame to frame (more than
        // the threshold of 10): the frame's level is taken off before it is compared.
        let places: Vec<(usize, usize)> = (0..9).map(|k| (2 + 3 * k, 5)).collect();
        let mut frames = square_at(&places, (40, 16));
        let pixels = 40 * 16;
        for k in 0..places.len() {
            let shift = [0i16, 30, -12, 18, -25, 0, 12, -30, 20][k];
            for v in &mut frames.pixels[k * pixels..(k + 1) * pixels] {
                *v = (*v as i16 + shift).clamp(0, 255) as u8;
            }
        }
        let bg = background(&frames);
        assert_eq!(bg.level[1] - bg.level[0], 30);
        for (k, &(x, _)) in places.iter().enumerate() {
            let b = blobs(&frames, k, &bg);
            assert_eq!(b.len(), 1, "frame {k}: {b:?}");
            assert!((b[0].x - (x as f64 + 1.5)).abs() < 1e-9, "frame {k}: {b:?}");
        }
    }

    #[test]
    fn a_still_picture_has_no_blobs() {
        let frames = square_at(&[(3, 3); 5], (20, 12));
        let bg = background(&frames);
        assert!(blobs(&frames, 2, &bg).is_empty());
    }
}
