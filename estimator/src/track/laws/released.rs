//! A constant acceleration from rest: the object still at p0 until its release r, then
//! p0 + a ((t − r)₊)²/2 in x and y; r searched (Levenberg–Marquardt from a vertex), p0 and a
//! solved for at each (variable projection); seen in perspective, through its bend (`bent`)
//! as the plain law is. What a span that reaches back over the rest before a release is read
//! by (`track::release`): a parabola through those still samples puts its vertex early.

use super::acceleration::{finish, Plain};
use super::{covariance, jacobian, least_squares, linear, Fitted};

/// ½((t − r)₊)² at times `t`: the distance per unit of acceleration from a release at `r`.
fn since(t: &[f64], r: f64) -> Vec<f64> {
    t.iter().map(|&s| 0.5 * (s - r).max(0.0).powi(2)).collect()
}

/// The acceleration from rest fitted to the picture positions `xy` at times `t`, its release
/// searched from `r0`: the values of the constant acceleration's law (its vertex the release).
/// `None` for fewer than six samples or no fit.
pub(crate) fn released(t: &[f64], xy: &[(f64, f64)], r0: f64) -> Option<Fitted> {
    let n = t.len();
    if n < 6 || !r0.is_finite() {
        return None;
    }
    let x: Vec<f64> = xy.iter().map(|p| p.0).collect();
    let y: Vec<f64> = xy.iter().map(|p| p.1).collect();
    let ones = vec![1.0; n];
    type Solved = (Vec<f64>, Vec<f64>);
    // p0 and a in x and in y for a release at r.
    let fits = |r: f64| -> Option<(Solved, Solved)> {
        let cols = [ones.clone(), since(t, r)];
        Some((linear(&cols, &x)?, linear(&cols, &y)?))
    };
    let residual = |p: &[f64]| {
        let ((_, mut rx), (_, ry)) = fits(p[0])?;
        rx.extend(ry);
        Some(rx)
    };
    let (p, _) = least_squares(&[r0], &residual)?;
    let r = p[0];
    let ((cx, rx), (cy, ry)) = fits(r)?;
    // Standard errors from the whole model's Jacobian (r, then p0 and a in x and in y).
    let whole = |q: &[f64]| -> Option<Vec<f64>> {
        let w = since(t, q[0]);
        let mut out: Vec<f64> = x.iter().zip(&w).map(|(v, w)| v - q[1] - q[2] * w).collect();
        out.extend(y.iter().zip(&w).map(|(v, w)| v - q[3] - q[4] * w));
        Some(out)
    };
    let q = [r, cx[0], cx[1], cy[0], cy[1]];
    let res = whole(&q)?;
    let cov = covariance(&jacobian(&q, &res, &whole)?, &res)?;
    let var = |i: usize| cov[i * 5 + i].max(0.0);
    let plain = Plain {
        x,
        y,
        rx,
        ry,
        a: (cx[1], cy[1]),
        a_var: (var(2), var(4)),
        vertex: (r, var(0).sqrt()),
    };
    finish(t, plain, None, true)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Still at (40, 100) until 0.5 s, then falling at 400 px/s² down and 30 px/s² across,
    /// seen at 60 fps from 0.3 s for 40 frames, ±0.2 px of alternating noise.
    #[test]
    fn a_fall_from_rest_gives_its_release_and_acceleration() {
        let t: Vec<f64> = (18..58).map(|k| k as f64 / 60.0).collect();
        let xy: Vec<(f64, f64)> = t
            .iter()
            .enumerate()
            .map(|(i, &s)| {
                let w = 0.5 * (s - 0.5f64).max(0.0).powi(2);
                let e = if i % 2 == 0 { 0.2 } else { -0.2 };
                (40.0 + 30.0 * w + e, 100.0 + 400.0 * w - e)
            })
            .collect();
        let f = released(&t, &xy, 0.45).unwrap();
        let v = |name: &str| f.value(name).unwrap().clone();
        assert!((v("vertex").value - 0.5).abs() < 0.002, "{f:?}");
        assert!(v("vertex").error < 0.005, "{f:?}");
        let a = v("acceleration");
        assert!((a.value / 400f64.hypot(30.0) - 1.0).abs() < 0.005, "{a:?}");
        assert!(a.error > 0.0 && a.error < 5.0, "{a:?}");
        let across = 30f64.atan2(400.0).to_degrees();
        assert!(
            (v("direction").value - (90.0 - across)).abs() < 0.5,
            "{f:?}"
        );
        // A plain parabola through the same samples puts the release early.
        let plain = super::super::acceleration::acceleration(&t, &xy, None).unwrap();
        assert!(plain.value("vertex").unwrap().value < 0.48, "{plain:?}");
    }
}
