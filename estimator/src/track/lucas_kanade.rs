//! A camera's shift between a frame and a reference picture refined to a fraction of a pixel
//! by Lucas–Kanade (Gauss–Newton on the pictures themselves, Huber's weights against what
//! moves): the step `steady` takes at each size of its coarse-to-fine search.

/// Gauss–Newton steps that refine a shift (Lucas–Kanade), and the step under which it stops.
const STEPS: usize = 8;
const SETTLED: f64 = 1e-3;

/// `frame` read at the real point (x, y), bilinear, the edge repeated.
pub(super) fn sample(frame: &[u8], (w, h): (usize, usize), x: f64, y: f64) -> f64 {
    let x = x.clamp(0.0, (w - 1) as f64);
    let y = y.clamp(0.0, (h - 1) as f64);
    let (x0, y0) = (x.floor() as usize, y.floor() as usize);
    let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
    bilinear(frame, w, (x0, x1, y0, y1), (x - x0 as f64, y - y0 as f64))
}

/// [`sample`] at a point at least a pixel inside the picture on every side, where its clamps
/// change nothing: the same reads and arithmetic without them.
fn sample_inside(frame: &[u8], w: usize, x: f64, y: f64) -> f64 {
    let (x0, y0) = (x.floor() as usize, y.floor() as usize);
    bilinear(
        frame,
        w,
        (x0, x0 + 1, y0, y0 + 1),
        (x - x0 as f64, y - y0 as f64),
    )
}

/// The pixels at columns x0, x1 and rows y0, y1 of `frame` (`w` wide) blended by the
/// fractions (ax, ay) of the way from the first to the second.
fn bilinear(
    frame: &[u8],
    w: usize,
    (x0, x1, y0, y1): (usize, usize, usize, usize),
    (ax, ay): (f64, f64),
) -> f64 {
    let v = |xx: usize, yy: usize| f64::from(frame[yy * w + xx]);
    let top = v(x0, y0) * (1.0 - ax) + v(x1, y0) * ax;
    let bottom = v(x0, y1) * (1.0 - ax) + v(x1, y1) * ax;
    top * (1.0 - ay) + bottom * ay
}

/// A reference picture and its central differences (x, y) at every pixel off its edges (0 on
/// them, never read): what each frame's refinement against it reads, worked out once.
pub(super) struct Reference<'a> {
    pixels: &'a [u8],
    size: (usize, usize),
    gradients: Vec<(f64, f64)>,
}

impl<'a> Reference<'a> {
    pub(super) fn new(pixels: &'a [u8], (w, h): (usize, usize)) -> Reference<'a> {
        let mut gradients = vec![(0.0, 0.0); w * h];
        for y in 1..h.saturating_sub(1) {
            for x in 1..w - 1 {
                let p = y * w + x;
                gradients[p] = (
                    0.5 * (f64::from(pixels[p + 1]) - f64::from(pixels[p - 1])),
                    0.5 * (f64::from(pixels[p + w]) - f64::from(pixels[p - w])),
                );
            }
        }
        Reference {
            pixels,
            size: (w, h),
            gradients,
        }
    }
}

/// The differences of `frame` read at each point p + `shift` from `reference` at p, row by
/// row over the picture less `margin` pixels at each edge (`margin_for` the shift: every read
/// inside), less their median (a camera's exposure moves the whole picture at once).
fn differences(
    frame: &[u8],
    reference: &Reference,
    (sx, sy): (f64, f64),
    margin: usize,
) -> Vec<f64> {
    let (w, h) = reference.size;
    let mut d = Vec::with_capacity((w - 2 * margin) * (h - 2 * margin));
    for y in margin..h - margin {
        for x in margin..w - margin {
            let p = y * w + x;
            let read = sample_inside(frame, w, x as f64 + sx, y as f64 + sy);
            d.push(read - f64::from(reference.pixels[p]));
        }
    }
    if !d.is_empty() {
        let mut sorted = d.clone();
        let mid = sorted.len() / 2;
        let level = *sorted.select_nth_unstable_by(mid, f64::total_cmp).1;
        d.iter_mut().for_each(|v| *v -= level);
    }
    d
}

/// The differences' robust spread (1.4826 × their median absolute value).
fn spread(d: &[f64]) -> f64 {
    let mut magnitude: Vec<f64> = d.iter().map(|v| v.abs()).collect();
    let mid = magnitude.len() / 2;
    1.4826 * *magnitude.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// The margin that keeps every point read at `shift` inside a picture of `size`, if the
/// picture has room for it.
fn margin_for((w, h): (usize, usize), (sx, sy): (f64, f64)) -> Option<usize> {
    let m = sx.abs().max(sy.abs()).ceil() + 2.0;
    (m.is_finite() && m < (w.min(h) / 2) as f64).then_some(m as usize)
}

/// The shift `start` refined to a fraction of a pixel by Gauss–Newton on the pictures
/// themselves (Lucas–Kanade, the reference's gradients), each pixel weighed down where it
/// differs by more than twice the differences' robust spread (what moves: Huber's weights);
/// `None` where it runs off the picture.
pub(super) fn refined(
    frame: &[u8],
    reference: &Reference,
    start: (f64, f64),
) -> Option<(f64, f64)> {
    let (w, h) = reference.size;
    let (mut sx, mut sy) = start;
    for _ in 0..STEPS {
        let margin = margin_for((w, h), (sx, sy))?;
        let d = differences(frame, reference, (sx, sy), margin);
        let limit = 2.0 * spread(&d).max(0.5);
        let (mut a, mut b) = ([0.0f64; 3], [0.0f64; 2]);
        let at = (margin..h - margin).flat_map(|y| (margin..w - margin).map(move |x| y * w + x));
        for (p, &r) in at.zip(&d) {
            let (gx, gy) = reference.gradients[p];
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
    margin_for((w, h), (sx, sy)).map(|_| (sx, sy))
}
