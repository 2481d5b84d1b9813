//! A patch of the object's picture and where it matches a frame best: normalised
//! cross-correlation of the zero-mean patch over a window about a guess, to a fraction of a
//! pixel by a parabola through the peak and its neighbours (`template` follows an object so).

use physvid_shared::video::SmallFrames;

/// A match below this correlation is no sighting (hidden, blurred, turned away).
pub const LEAST_SCORE: f64 = 0.6;

/// One frame's match: the patch's centre (pixels of the frames read) and its correlation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Match {
    pub x: f64,
    pub y: f64,
    pub score: f64,
}

/// The zero-mean patch and its norm.
pub(super) struct Patch {
    values: Vec<f64>,
    norm: f64,
    pub half: usize,
}

impl Patch {
    pub(super) fn cut(
        frame: &[u8],
        (w, h): (usize, usize),
        (cx, cy): (usize, usize),
        half: usize,
    ) -> Option<Patch> {
        if cx < half || cy < half || cx + half >= w || cy + half >= h {
            return None;
        }
        let side = 2 * half + 1;
        let mut values = Vec::with_capacity(side * side);
        for y in cy - half..=cy + half {
            for x in cx - half..=cx + half {
                values.push(frame[y * w + x] as f64);
            }
        }
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        values.iter_mut().for_each(|v| *v -= mean);
        let norm = values.iter().map(|v| v * v).sum::<f64>().sqrt();
        (norm > 0.0).then_some(Patch { values, norm, half })
    }

    /// The correlation of this patch with `frame` centred at (cx, cy) (inside).
    fn score(&self, frame: &[u8], w: usize, (cx, cy): (usize, usize)) -> f64 {
        let half = self.half;
        let side = 2 * half + 1;
        // The pixels' sums in integers (exact, as the f64 sums of bytes are).
        let (mut sum, mut sum_sq, mut cross) = (0u64, 0u64, 0.0);
        for (r, y) in (cy - half..=cy + half).enumerate() {
            let row = &frame[y * w + cx - half..y * w + cx + half + 1];
            let t = &self.values[r * side..(r + 1) * side];
            // A row's sums fit in 32 bits (255² × 66 000 < 2³²: no picture is that wide).
            sum += row.iter().map(|&p| p as u32).sum::<u32>() as u64;
            sum_sq += row.iter().map(|&p| (p as u32) * (p as u32)).sum::<u32>() as u64;
            for (p, q) in row.iter().zip(t) {
                cross += *p as f64 * q;
            }
        }
        let (sum, sum_sq) = (sum as f64, sum_sq as f64);
        let n = (side * side) as f64;
        let var = sum_sq - sum * sum / n;
        if var <= 0.0 {
            return 0.0;
        }
        // The template has zero mean, so the frame's mean drops out of the cross term.
        cross / (self.norm * var.sqrt())
    }
}

/// The patch's best match in frame `k` within `reach` pixels of `guess`, to a fraction of a
/// pixel; `None` below [`LEAST_SCORE`].
pub(super) fn best_match(
    frames: &SmallFrames,
    patch: &Patch,
    (gx, gy): (f64, f64),
    reach: usize,
    k: usize,
) -> Option<Match> {
    let (w, h) = frames.size;
    let half = patch.half;
    let frame = frames.frame(k);
    let lo = |g: f64| (g.round() as isize - reach as isize).max(half as isize) as usize;
    let (x0, y0) = (lo(gx), lo(gy));
    let x1 = ((gx.round().max(0.0) as usize) + reach).min(w - half - 1);
    let y1 = ((gy.round().max(0.0) as usize) + reach).min(h - half - 1);
    if x0 > x1 || y0 > y1 {
        return None;
    }
    let (sw, sh) = (x1 - x0 + 1, y1 - y0 + 1);
    let scores: Vec<f64> = (0..sw * sh)
        .map(|i| patch.score(frame, w, (x0 + i % sw, y0 + i / sw)))
        .collect();
    let (best, score) = scores
        .iter()
        .copied()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .expect("a search window has a place");
    if score < LEAST_SCORE {
        return None;
    }
    let (bx, by) = (best % sw, best / sw);
    let vertex = |a: f64, b: f64, c: f64| {
        let d = a - 2.0 * b + c;
        if d < 0.0 {
            (0.5 * (a - c) / d).clamp(-0.5, 0.5)
        } else {
            0.0
        }
    };
    let dx = if bx > 0 && bx + 1 < sw {
        vertex(scores[best - 1], score, scores[best + 1])
    } else {
        0.0
    };
    let dy = if by > 0 && by + 1 < sh {
        vertex(scores[best - sw], score, scores[best + sw])
    } else {
        0.0
    };
    Some(Match {
        x: (x0 + bx) as f64 + dx,
        y: (y0 + by) as f64 + dy,
        score,
    })
}
