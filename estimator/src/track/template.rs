//! The object's position refined by its picture: a patch cut around its blob in the frame where
//! the blob has its usual size, matched by normalised cross-correlation in every frame of the
//! tracklet's time near where the blob (or the last match) puts it, to a fraction of a pixel
//! (a parabola through the peak and its neighbours). A spring's coils or a hand merged into the
//! blob pull its centroid; they change the match's score, not its place.

use super::link::Tracklet;
use physvid_shared::video::SmallFrames;

/// A match below this correlation is no sighting (hidden, blurred, turned away).
pub const LEAST_SCORE: f64 = 0.6;

/// The patch is at most this many pixels either side of its centre (a larger object is matched
/// by its middle), and the search at most this far from the guess.
const LARGEST_HALF: usize = 12;
const FURTHEST: usize = 24;

/// One frame's match: the patch's centre (pixels of the frames read) and its correlation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Match {
    pub x: f64,
    pub y: f64,
    pub score: f64,
}

/// The zero-mean patch and its norm.
struct Patch {
    values: Vec<f64>,
    norm: f64,
    half: usize,
}

impl Patch {
    fn cut(
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
        let (mut sum, mut sum_sq, mut cross) = (0.0, 0.0, 0.0);
        for (r, y) in (cy - half..=cy + half).enumerate() {
            let row = &frame[y * w + cx - half..y * w + cx + half + 1];
            let t = &self.values[r * side..(r + 1) * side];
            for (p, q) in row.iter().zip(t) {
                let p = *p as f64;
                sum += p;
                sum_sq += p * p;
                cross += p * q;
            }
        }
        let n = (side * side) as f64;
        let var = sum_sq - sum * sum / n;
        if var <= 0.0 {
            return 0.0;
        }
        // The template has zero mean, so the frame's mean drops out of the cross term.
        cross / (self.norm * var.sqrt())
    }
}

/// The matches of `tracklet`'s object in each frame from its first to its last (None where it
/// is not seen), the blobs moving at most `step` pixels a frame.
pub fn refine(frames: &SmallFrames, tracklet: &Tracklet) -> Vec<(usize, Match)> {
    let (w, h) = frames.size;
    let usual = tracklet.usual_area();
    let half = ((usual.sqrt() / 2.0).ceil() as usize + 2).clamp(3, LARGEST_HALF);
    // The fastest step seen between consecutive sightings widens the search.
    let fastest = tracklet
        .frames
        .windows(2)
        .zip(tracklet.blobs.windows(2))
        .map(|(f, b)| (b[1].x - b[0].x).hypot(b[1].y - b[0].y) / (f[1] - f[0]) as f64)
        .fold(0.0, f64::max);
    let reach = ((1.5 * fastest).ceil() as usize + 2).min(FURTHEST);
    // The reference: the sighting whose size is nearest the usual one, with room for the patch.
    let mut order: Vec<usize> = (0..tracklet.blobs.len()).collect();
    order.sort_by(|&a, &b| {
        (tracklet.blobs[a].area - usual)
            .abs()
            .total_cmp(&(tracklet.blobs[b].area - usual).abs())
    });
    let Some(patch) = order.iter().find_map(|&i| {
        let b = tracklet.blobs[i];
        let at = (b.x.round() as usize, b.y.round() as usize);
        Patch::cut(frames.frame(tracklet.frames[i]), (w, h), at, half)
    }) else {
        return Vec::new();
    };
    let first = tracklet.frames[0];
    let last = *tracklet.frames.last().expect("a tracklet has a frame");
    let mut blob_at = tracklet.frames.iter().zip(&tracklet.blobs).peekable();
    let mut previous: Option<(f64, f64)> = None;
    let mut found = Vec::new();
    for k in first..=last {
        let mut guess = previous;
        while let Some((f, b)) = blob_at.peek() {
            if **f < k {
                blob_at.next();
                continue;
            }
            if **f == k {
                guess = Some((b.x, b.y));
            }
            break;
        }
        let Some((gx, gy)) = guess else { continue };
        let frame = frames.frame(k);
        let lo = |g: f64| (g.round() as isize - reach as isize).max(half as isize) as usize;
        let (x0, y0) = (lo(gx), lo(gy));
        let x1 = ((gx.round() as usize) + reach).min(w - half - 1);
        let y1 = ((gy.round() as usize) + reach).min(h - half - 1);
        if x0 > x1 || y0 > y1 {
            continue;
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
            continue;
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
        let m = Match {
            x: (x0 + bx) as f64 + dx,
            y: (y0 + by) as f64 + dy,
            score,
        };
        previous = Some((m.x, m.y));
        found.push((k, m));
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::blobs::Blob;

    /// A bright 5×5 cross-shaped mark on a textured wall, moving by fractions of a pixel, drawn
    /// by area sampling; its blob's centroid is put 2 px off to stand for a hand beside it.
    #[test]
    fn the_match_finds_the_mark_to_a_tenth_of_a_pixel_whatever_pulls_its_blob() {
        let (w, h) = (48, 32);
        let places: Vec<(f64, f64)> = (0..12)
            .map(|k| (14.0 + 1.37 * k as f64, 15.0 + 0.41 * k as f64))
            .collect();
        let mut pixels = Vec::new();
        for &(px, py) in &places {
            for y in 0..h {
                for x in 0..w {
                    let mut cover = 0.0;
                    for s in 0..16 {
                        let sx = x as f64 + (s % 4) as f64 / 4.0 + 0.125 - px;
                        let sy = y as f64 + (s / 4) as f64 / 4.0 + 0.125 - py;
                        if (sx.abs() < 2.5 && sy.abs() < 0.8) || (sy.abs() < 2.5 && sx.abs() < 0.8)
                        {
                            cover += 1.0 / 16.0;
                        }
                    }
                    let wall = 60.0 + 20.0 * (((x * 7 + y * 3) % 5) as f64 / 5.0);
                    pixels.push((wall + (230.0 - wall) * cover).round() as u8);
                }
            }
        }
        let frames = SmallFrames {
            pixels,
            size: (w, h),
        };
        let tracklet = Tracklet {
            frames: (0..12).collect(),
            blobs: places
                .iter()
                .map(|&(x, y)| Blob::round(9.0, x + 2.0, y))
                .collect(),
        };
        let found = refine(&frames, &tracklet);
        assert_eq!(found.len(), 12);
        // The matches follow the mark's displacement (the patch's centre is the reference
        // frame's rounded blob place, so compare steps from the first).
        let (x0, y0) = (found[0].1.x - places[0].0, found[0].1.y - places[0].1);
        for (k, m) in &found {
            assert!((m.x - places[*k].0 - x0).abs() < 0.15, "frame {k}: {m:?}");
            assert!((m.y - places[*k].1 - y0).abs() < 0.15, "frame {k}: {m:?}");
            assert!(m.score > LEAST_SCORE, "frame {k}: {m:?}");
        }
    }
}
