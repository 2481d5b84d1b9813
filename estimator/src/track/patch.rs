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

/// The patch's pixels, with their sum and spread: what the correlation needs, in integers.
pub(super) struct Patch {
    pixels: Vec<u8>,
    /// The pixels' sum.
    sum: i64,
    /// n·Σq² − (Σq)² over its n pixels q: n² times their variance.
    spread: i64,
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
        let mut pixels = Vec::with_capacity(side * side);
        for y in cy - half..=cy + half {
            pixels.extend_from_slice(&frame[y * w + cx - half..=y * w + cx + half]);
        }
        let n = pixels.len() as i64;
        let sum: i64 = pixels.iter().map(|&q| i64::from(q)).sum();
        let squares: i64 = pixels.iter().map(|&q| i64::from(q) * i64::from(q)).sum();
        let spread = n * squares - sum * sum;
        (spread > 0).then_some(Patch {
            pixels,
            sum,
            spread,
            half,
        })
    }

    /// The normalised cross-correlation of this patch with `frame` centred at (cx, cy)
    /// (inside): (nΣpq − ΣpΣq) / √((nΣp² − (Σp)²)(nΣq² − (Σq)²)), every sum an exact integer
    /// (a byte row's sums fit in 32 bits: 255² × 66 000 < 2³², no picture is that wide).
    #[cfg(test)]
    fn score(&self, frame: &[u8], w: usize, (cx, cy): (usize, usize)) -> f64 {
        let half = self.half;
        let (mut sum, mut squares) = (0i64, 0i64);
        for y in cy - half..=cy + half {
            let row = &frame[y * w + cx - half..y * w + cx + half + 1];
            sum += row.iter().map(|&p| i64::from(p)).sum::<i64>();
            squares += row
                .iter()
                .map(|&p| i64::from(p) * i64::from(p))
                .sum::<i64>();
        }
        self.score_given(frame, w, (cx, cy), (sum, squares))
    }

    /// [`Patch::score`] where the frame's pixels under the patch sum to `sum` and their
    /// squares to `squares` (a window's [`Boxes`]): only Σpq is summed here.
    fn score_given(
        &self,
        frame: &[u8],
        w: usize,
        (cx, cy): (usize, usize),
        (sum, squares): (i64, i64),
    ) -> f64 {
        let half = self.half;
        let side = 2 * half + 1;
        let mut cross = 0i64;
        for (r, y) in (cy - half..=cy + half).enumerate() {
            let row = &frame[y * w + cx - half..y * w + cx + half + 1];
            let t = &self.pixels[r * side..(r + 1) * side];
            cross += i64::from(
                row.iter()
                    .zip(t)
                    .map(|(&p, &q)| u32::from(p) * u32::from(q))
                    .sum::<u32>(),
            );
        }
        let n = (side * side) as i64;
        let spread = n * squares - sum * sum;
        if spread <= 0 {
            return 0.0;
        }
        (n * cross - sum * self.sum) as f64 / (spread as f64 * self.spread as f64).sqrt()
    }
}

/// A frame's pixels and their squares summed over every box of a region (summed-area tables,
/// exact integers): the sums under the patch at each place of a search window in four reads
/// each, where summing them cost as much as the correlation itself.
struct Boxes {
    /// The region's first column and row in the frame, and its width.
    x0: usize,
    y0: usize,
    w: usize,
    /// Entry (x, y): the sum over the region's columns before x and rows before y.
    sum: Vec<i64>,
    squares: Vec<i64>,
}

impl Boxes {
    /// The tables of `frame` (`fw` wide) over columns `x0..x1` and rows `y0..y1`.
    fn over(frame: &[u8], fw: usize, (x0, x1): (usize, usize), (y0, y1): (usize, usize)) -> Boxes {
        let (w, h) = (x1 - x0, y1 - y0);
        let mut sum = vec![0i64; (w + 1) * (h + 1)];
        let mut squares = vec![0i64; (w + 1) * (h + 1)];
        for y in 0..h {
            let row = &frame[(y0 + y) * fw + x0..][..w];
            let (mut s, mut q) = (0i64, 0i64);
            for (x, &p) in row.iter().enumerate() {
                s += i64::from(p);
                q += i64::from(p) * i64::from(p);
                let at = (y + 1) * (w + 1) + x + 1;
                sum[at] = sum[at - (w + 1)] + s;
                squares[at] = squares[at - (w + 1)] + q;
            }
        }
        Boxes {
            x0,
            y0,
            w,
            sum,
            squares,
        }
    }

    /// The sums over the `side`×`side` box of the frame from column `x`, row `y`.
    fn at(&self, (x, y): (usize, usize), side: usize) -> (i64, i64) {
        let (x, y, stride) = (x - self.x0, y - self.y0, self.w + 1);
        let corners = |t: &[i64]| {
            t[(y + side) * stride + x + side]
                - t[y * stride + x + side]
                - t[(y + side) * stride + x]
                + t[y * stride + x]
        };
        (corners(&self.sum), corners(&self.squares))
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
    let side = 2 * half + 1;
    let boxes = Boxes::over(
        frame,
        w,
        (x0 - half, x1 + half + 1),
        (y0 - half, y1 + half + 1),
    );
    let scores: Vec<f64> = (0..sw * sh)
        .map(|i| {
            let (cx, cy) = (x0 + i % sw, y0 + i / sw);
            let sums = boxes.at((cx - half, cy - half), side);
            patch.score_given(frame, w, (cx, cy), sums)
        })
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A 40×30 picture of bytes from a fixed sequence.
    fn picture() -> Vec<u8> {
        (0..40 * 30)
            .map(|i: usize| ((i * 7919 + i * i * 31) % 251) as u8)
            .collect()
    }

    /// The correlation as its definition says, in floating point.
    fn defined(frame: &[u8], w: usize, patch: &[u8], (cx, cy): (usize, usize), half: usize) -> f64 {
        let mut p = Vec::new();
        for y in cy - half..=cy + half {
            for x in cx - half..=cx + half {
                p.push(f64::from(frame[y * w + x]));
            }
        }
        let q: Vec<f64> = patch.iter().map(|&v| f64::from(v)).collect();
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        let (mp, mq) = (mean(&p), mean(&q));
        let cross: f64 = p.iter().zip(&q).map(|(a, b)| (a - mp) * (b - mq)).sum();
        let spread = |v: &[f64], m: f64| v.iter().map(|a| (a - m) * (a - m)).sum::<f64>().sqrt();
        cross / (spread(&p, mp) * spread(&q, mq))
    }

    #[test]
    fn the_integer_correlation_is_the_defined_one() {
        let frame = picture();
        let patch = Patch::cut(&frame, (40, 30), (12, 9), 4).expect("a patch");
        // On its own place it matches exactly; elsewhere it is the definition's value.
        assert_eq!(patch.score(&frame, 40, (12, 9)), 1.0);
        for at in [(20, 15), (5, 5), (35, 25), (13, 9)] {
            let got = patch.score(&frame, 40, at);
            let want = defined(&frame, 40, &patch.pixels, at, 4);
            assert!((got - want).abs() < 1e-12, "{at:?}: {got} against {want}");
            assert!((-1.0..=1.0).contains(&got), "{got}");
        }
        // The window's tables give the sums summed directly, at every place.
        let boxes = Boxes::over(&frame, 40, (3, 38), (2, 29));
        for (cx, cy) in (7..34).flat_map(|x| (6..25).map(move |y| (x, y))) {
            let sums = boxes.at((cx - 4, cy - 4), 9);
            let got = patch.score_given(&frame, 40, (cx, cy), sums);
            assert_eq!(got.to_bits(), patch.score(&frame, 40, (cx, cy)).to_bits());
        }
        // A flat patch has nothing to correlate.
        assert!(Patch::cut(&[9u8; 100], (10, 10), (5, 5), 2).is_none());
    }
}
