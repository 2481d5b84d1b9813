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
    let (ax, ay) = (x - x0 as f64, y - y0 as f64);
    let v = |xx: usize, yy: usize| f64::from(frame[yy * w + xx]);
    let top = v(x0, y0) * (1.0 - ax) + v(x1, y0) * ax;
    let bottom = v(x0, y1) * (1.0 - ax) + v(x1, y1) * ax;
    top * (1.0 - ay) + bottom * ay
}

/// The differences of `frame` read at each point p + `shift` from `reference` at p, over the
/// picture less `margin` pixels at each edge, less their median (a camera's exposure moves
/// the whole picture at once), and the points they are at.
fn differences(
    frame: &[u8],
    reference: &[u8],
    (w, h): (usize, usize),
    (sx, sy): (f64, f64),
    margin: usize,
) -> (Vec<f64>, Vec<usize>) {
    let mut d = Vec::new();
    let mut at = Vec::new();
    for y in margin..h.saturating_sub(margin) {
        for x in margin..w.saturating_sub(margin) {
            let p = y * w + x;
            d.push(sample(frame, (w, h), x as f64 + sx, y as f64 + sy) - f64::from(reference[p]));
            at.push(p);
        }
    }
    if !d.is_empty() {
        let mut sorted = d.clone();
        let mid = sorted.len() / 2;
        let level = *sorted.select_nth_unstable_by(mid, f64::total_cmp).1;
        d.iter_mut().for_each(|v| *v -= level);
    }
    (d, at)
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
    reference: &[u8],
    (w, h): (usize, usize),
    start: (f64, f64),
) -> Option<(f64, f64)> {
    let (mut sx, mut sy) = start;
    for _ in 0..STEPS {
        let margin = margin_for((w, h), (sx, sy))?;
        let (d, at) = differences(frame, reference, (w, h), (sx, sy), margin);
        let limit = 2.0 * spread(&d).max(0.5);
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
    margin_for((w, h), (sx, sy)).map(|_| (sx, sy))
}
