//! A camera's shake taken off the frames the track reads: each frame's shift against the
//! background's picture by phase correlation (the whitened cross-power spectrum's peak,
//! refined between pixels by Lucas–Kanade), and the frame moved back by it
//! (bilinear, the edge repeated). A hand-held camera's shake moves every edge of a still
//! picture, whose differences from the background then outgrow the object's or the light's;
//! steadied, the picture differs where the object moves or the light changes.

use physvid_shared::video::SmallFrames;
use rayon::prelude::*;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// Frames all shifted by less than this (pixels of the frames read) are left as they are: the
/// camera held still.
const STILL: f64 = 1.0;

/// Frames moved back by the camera's shake, and the largest shift taken off (pixels of the
/// frames read).
pub struct Steadied {
    pub frames: SmallFrames,
    pub largest: f64,
}

/// A 2-D transform of one size: its rows', then its columns'.
struct Plane {
    size: (usize, usize),
    rows: Arc<dyn Fft<f64>>,
    columns: Arc<dyn Fft<f64>>,
}

impl Plane {
    fn new((w, h): (usize, usize), inverse: bool) -> Plane {
        let mut planner = FftPlanner::new();
        let (rows, columns) = if inverse {
            (planner.plan_fft_inverse(w), planner.plan_fft_inverse(h))
        } else {
            (planner.plan_fft_forward(w), planner.plan_fft_forward(h))
        };
        Plane {
            size: (w, h),
            rows,
            columns,
        }
    }

    /// Transforms `data` (row-major, w × h) in place.
    fn apply(&self, data: &mut [Complex<f64>]) {
        let (w, h) = self.size;
        self.rows.process(data);
        let mut column = vec![Complex::default(); h];
        for x in 0..w {
            for (y, c) in column.iter_mut().enumerate() {
                *c = data[y * w + x];
            }
            self.columns.process(&mut column);
            for (y, c) in column.iter().enumerate() {
                data[y * w + x] = *c;
            }
        }
    }
}

/// A Hann window over a picture of `size` (the picture's edges, which the transform joins to
/// the opposite ones, weigh nothing).
fn window((w, h): (usize, usize)) -> Vec<f64> {
    let hann = |i: usize, n: usize| 0.5 - 0.5 * (std::f64::consts::TAU * i as f64 / n as f64).cos();
    (0..h)
        .flat_map(|y| (0..w).map(move |x| hann(x, w) * hann(y, h)))
        .collect()
}

/// A picture less its mean, windowed, as complex numbers.
fn centred(picture: &[u8], window: &[f64]) -> Vec<Complex<f64>> {
    let mean = picture.iter().map(|&v| f64::from(v)).sum::<f64>() / picture.len().max(1) as f64;
    picture
        .iter()
        .zip(window)
        .map(|(&v, k)| Complex::new((f64::from(v) - mean) * k, 0.0))
        .collect()
}

/// Gauss–Newton steps that refine a shift (Lucas–Kanade), and the step under which it stops.
const STEPS: usize = 8;
const SETTLED: f64 = 1e-3;

/// `frame` read at the real point (x, y), bilinear, the edge repeated.
fn sample(frame: &[u8], (w, h): (usize, usize), x: f64, y: f64) -> f64 {
    let x = x.clamp(0.0, (w - 1) as f64);
    let y = y.clamp(0.0, (h - 1) as f64);
    let (x0, y0) = (x.floor() as usize, y.floor() as usize);
    let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
    let (ax, ay) = (x - x0 as f64, y - y0 as f64);
    let v = |xx: usize, yy: usize| f64::from(frame[yy * w + xx]);
    let top = v(x0, y0) * (1.0 - ax) + v(x1, y0) * ax;
    let bottom = v(x0, y1) * (1.0 - ax) + v(x1, y1) * ax;
    top * (1.0 - ay) + bottom * ay
}

/// The shift `start` refined to a fraction of a pixel by Gauss–Newton on the pictures
/// themselves (Lucas–Kanade, the reference's gradients), each pixel weighed down where it
/// differs by more than twice the differences' robust spread (what moves: Huber's weights).
fn refined(
    frame: &[u8],
    reference: &[u8],
    (w, h): (usize, usize),
    start: (f64, f64),
) -> (f64, f64) {
    let (mut sx, mut sy) = start;
    let mut d = Vec::with_capacity(w * h);
    for _ in 0..STEPS {
        let margin = (sx.abs().max(sy.abs()).ceil() as usize + 2).min(w.min(h) / 2 - 1);
        d.clear();
        let mut at = Vec::with_capacity(w * h);
        for y in margin..h - margin {
            for x in margin..w - margin {
                let p = y * w + x;
                let v = sample(frame, (w, h), x as f64 + sx, y as f64 + sy);
                d.push(v - f64::from(reference[p]));
                at.push(p);
            }
        }
        if d.is_empty() {
            break;
        }
        let mut magnitude: Vec<f64> = d.iter().map(|v| v.abs()).collect();
        let mid = magnitude.len() / 2;
        let spread = 1.4826 * *magnitude.select_nth_unstable_by(mid, f64::total_cmp).1;
        let limit = 2.0 * spread.max(0.5);
        let (mut a, mut b) = ([0.0f64; 3], [0.0f64; 2]);
        for (&p, &r) in at.iter().zip(&d) {
            let gx = 0.5 * (f64::from(reference[p + 1]) - f64::from(reference[p - 1]));
            let gy = 0.5 * (f64::from(reference[p + w]) - f64::from(reference[p - w]));
            let weight = if r.abs() <= limit {
                1.0
            } else {
                limit / r.abs()
            };
            a[0] += weight * gx * gx;
            a[1] += weight * gx * gy;
            a[2] += weight * gy * gy;
            b[0] += weight * gx * r;
            b[1] += weight * gy * r;
        }
        let det = a[0] * a[2] - a[1] * a[1];
        if det.abs() < 1e-9 {
            break;
        }
        let step_x = -(a[2] * b[0] - a[1] * b[1]) / det;
        let step_y = -(a[0] * b[1] - a[1] * b[0]) / det;
        sx += step_x;
        sy += step_y;
        if step_x.hypot(step_y) < SETTLED {
            break;
        }
    }
    (sx, sy)
}

/// Each frame's shift against `reference` (x, y in pixels: the frame shows the reference's
/// point p at p + shift), by phase correlation.
pub fn shifts(frames: &SmallFrames, reference: &[u8]) -> Vec<(f64, f64)> {
    let (w, h) = frames.size;
    let forward = Plane::new((w, h), false);
    let inverse = Plane::new((w, h), true);
    let window = window((w, h));
    let mut fixed = centred(reference, &window);
    forward.apply(&mut fixed);
    (0..frames.len())
        .into_par_iter()
        .map(|i| {
            let mut spectrum = centred(frames.frame(i), &window);
            forward.apply(&mut spectrum);
            for (s, f) in spectrum.iter_mut().zip(&fixed) {
                let cross = *s * f.conj();
                let norm = cross.norm();
                *s = if norm > 1e-12 {
                    cross / norm
                } else {
                    Complex::default()
                };
            }
            inverse.apply(&mut spectrum);
            let at = |x: usize, y: usize| spectrum[(y % h) * w + (x % w)].re;
            let (mut px, mut py, mut top) = (0, 0, f64::NEG_INFINITY);
            for y in 0..h {
                for x in 0..w {
                    if at(x, y) > top {
                        (px, py, top) = (x, y, at(x, y));
                    }
                }
            }
            // Past half the picture, the peak is a shift the other way.
            let wrap = |p: usize, n: usize| {
                if 2 * p > n {
                    p as f64 - n as f64
                } else {
                    p as f64
                }
            };
            refined(
                frames.frame(i),
                reference,
                (w, h),
                (wrap(px, w), wrap(py, h)),
            )
        })
        .collect()
}

/// `frame` moved back by `shift` (its point p + shift put at p), bilinear, the edge repeated.
fn moved(frame: &[u8], (w, h): (usize, usize), (sx, sy): (f64, f64)) -> Vec<u8> {
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let v = sample(frame, (w, h), x as f64 + sx, y as f64 + sy);
            v.round().clamp(0.0, 255.0) as u8
        })
        .collect()
}

/// `frames` moved back by their shifts against `reference` (the background's picture), or
/// `None` where every shift is under [`STILL`].
pub fn steadied(frames: &SmallFrames, reference: &[u8]) -> Option<Steadied> {
    let found = shifts(frames, reference);
    let largest = found.iter().map(|s| s.0.hypot(s.1)).fold(0.0, f64::max);
    if largest < STILL {
        return None;
    }
    let size = frames.size;
    let pixels = (0..frames.len())
        .into_par_iter()
        .flat_map_iter(|i| moved(frames.frame(i), size, found[i]))
        .collect();
    Some(Steadied {
        frames: SmallFrames { pixels, size },
        largest,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A textured wall (smooth enough to be moved between pixels), seen shifted by `shift`.
    fn wall((w, h): (usize, usize), (sx, sy): (f64, f64)) -> Vec<u8> {
        let mut out = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let (u, v) = (x as f64 - sx, y as f64 - sy);
                let value = 120.0
                    + 40.0 * (u * 0.31).sin() * (v * 0.17).cos()
                    + 30.0 * (u * 0.07 + v * 0.11).sin()
                    + 25.0 * ((u - 20.0).hypot(v - 14.0) * 0.45).cos();
                out.push(value.round() as u8);
            }
        }
        out
    }

    /// Frames of a wall shaken by up to three pixels: each shift found within a tenth of a
    /// pixel, and the steadied frames differ from the still wall by less than the shaken ones
    /// did, away from the edges the shift brings in.
    #[test]
    fn a_shaken_wall_is_found_and_steadied() {
        let size = (64, 48);
        let shaken = [
            (0.0, 0.0),
            (1.3, -0.6),
            (-2.4, 0.8),
            (0.6, 2.7),
            (-0.2, -1.9),
        ];
        let still = wall(size, (0.0, 0.0));
        let frames = SmallFrames {
            pixels: shaken.iter().flat_map(|&s| wall(size, s)).collect(),
            size,
        };
        let found = shifts(&frames, &still);
        for (f, s) in found.iter().zip(&shaken) {
            assert!(
                (f.0 - s.0).abs() < 0.1 && (f.1 - s.1).abs() < 0.1,
                "{f:?} for {s:?}"
            );
        }
        let steady = steadied(&frames, &still).expect("a shaken camera");
        assert!((steady.largest - 2.76).abs() < 0.1, "{}", steady.largest);
        let inner = |a: &[u8]| -> f64 {
            let mut sum = 0.0;
            for y in 4..size.1 - 4 {
                for x in 4..size.0 - 4 {
                    let p = y * size.0 + x;
                    sum += (f64::from(a[p]) - f64::from(still[p])).abs();
                }
            }
            sum
        };
        for i in 1..shaken.len() {
            let before = inner(frames.frame(i));
            let after = inner(steady.frames.frame(i));
            assert!(after < 0.15 * before, "frame {i}: {after} against {before}");
        }
    }

    /// A still wall is left as it is.
    #[test]
    fn a_still_camera_is_left_alone() {
        let size = (40, 30);
        let still = wall(size, (0.0, 0.0));
        let frames = SmallFrames {
            pixels: [0.0, 0.2, -0.3]
                .iter()
                .flat_map(|&s| wall(size, (s, -s)))
                .collect(),
            size,
        };
        let found = shifts(&frames, &still);
        assert!(steadied(&frames, &still).is_none(), "{found:?}");
    }
}
