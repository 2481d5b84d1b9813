//! A constant acceleration seen in perspective (a camera tilted to the path): the path along
//! the acceleration a projective map of the parabola, c + s·v/(1 + b·v) with v = (t − r)², as
//! `data::perspective` reads a descent in the picture; or, from rest, v = ((t − r)₊)².

use super::{covariance, jacobian, least_squares, linear, sum_sq, Fitted, Value};
use crate::data::perspective::{LEAST_DENOMINATOR, MIN_GAIN};

/// The path `along` the acceleration at times `t` fitted as a parabola seen in perspective,
/// c + s·v/(1 + b·v) with v = (t − r)² (or, `from_rest`, ((t − r)₊)²: still before the
/// release r), from a vertex and the plain parabola's residuals (`plain`), or with its bend
/// `held`: its acceleration at the vertex (2s), vertex and bend (the
/// picture's scale where the path is farthest from its vertex against at it, less one, in per
/// cent), with the fitted path and its residuals along. `None` where a bend of its own fits no
/// better than [`MIN_GAIN`] times the plain parabola, or only with a pole near the span (the
/// scale changing more than the denominator allows).
pub(super) fn bent(
    t: &[f64],
    along: &[f64],
    plain: (f64, &[f64]),
    held: Option<f64>,
    from_rest: bool,
) -> Option<Fitted> {
    let n = t.len();
    let (r0, plain) = plain;
    let rms = |r: &[f64]| (sum_sq(r) / r.len() as f64).sqrt();
    // The squared time from the vertex (from the release alone, before it none).
    let v = |s: f64, r: f64| if from_rest { (s - r).max(0.0) } else { s - r }.powi(2);
    let farthest = |r: f64| t.iter().map(|&s| v(s, r)).fold(0.0, f64::max);
    // For a vertex `r` and bend `b`: the weights v/(1 + b·v), or none near a pole.
    let weights = |r: f64, b: f64| -> Option<Vec<f64>> {
        let den: Vec<f64> = t.iter().map(|&s| 1.0 + b * v(s, r)).collect();
        let (lo, hi) = den
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), d| (l.min(*d), h.max(*d)));
        (lo > 0.0 && lo >= LEAST_DENOMINATOR * hi)
            .then(|| t.iter().zip(&den).map(|(&s, d)| v(s, r) / d).collect())
    };
    // c and s solved for at each (r, b) (variable projection): the residuals along.
    let ones = vec![1.0; n];
    let solved = |p: &[f64]| linear(&[ones.clone(), weights(p[0], p[1])?], along);
    let residual = |p: &[f64]| solved(p).map(|(_, r)| r);
    let p = match held {
        Some(b) => {
            let (p, _) = least_squares(&[r0], &|p: &[f64]| residual(&[p[0], b]))?;
            [p[0], b]
        }
        None => {
            let big_v = farthest(r0).max(f64::MIN_POSITIVE);
            let (p, r) = [-0.5, 0.0, 0.5]
                .iter()
                .filter_map(|bv| least_squares(&[r0, bv / big_v], &residual))
                .min_by(|a, b| sum_sq(&a.1).total_cmp(&sum_sq(&b.1)))?;
            if p[1] == 0.0 || rms(&r) * MIN_GAIN > rms(plain) {
                return None;
            }
            [p[0], p[1]]
        }
    };
    let (cs, _) = solved(&p)?;
    let [vertex, b] = p;
    let (c, s) = (cs[0], cs[1]);
    if s <= 0.0 {
        return None;
    }
    // Standard errors from the whole model's Jacobian (r, b, c, s; b left out where held).
    let whole = |q: &[f64]| -> Option<Vec<f64>> {
        let (r, b, c, s) = match held {
            Some(b) => (q[0], b, q[1], q[2]),
            None => (q[0], q[1], q[2], q[3]),
        };
        let w = weights(r, b)?;
        Some(along.iter().zip(&w).map(|(p, w)| p - c - s * w).collect())
    };
    let q = match held {
        Some(_) => vec![vertex, c, s],
        None => vec![vertex, b, c, s],
    };
    let k = q.len();
    let residuals = whole(&q)?;
    let cov = covariance(&jacobian(&q, &residuals, &whole)?, &residuals)?;
    let err = |i: usize| cov[i * k + i].max(0.0).sqrt();
    // In per cent, as the descent's perspective is named.
    let scale = |b: f64| 100.0 * (1.0 / (1.0 + b * farthest(vertex)).powi(2) - 1.0);
    let bend_err = match held {
        Some(_) => 0.0,
        None => (scale(b + err(1)) - scale(b)).abs(),
    };
    let curve = along.iter().zip(&residuals).map(|(p, e)| p - e).collect();
    Some(Fitted {
        values: vec![
            Value {
                name: "acceleration",
                value: 2.0 * s,
                error: 2.0 * err(k - 1),
                unit: "px/s^2",
            },
            Value {
                name: "vertex",
                value: vertex,
                error: err(0),
                unit: "s",
            },
            Value {
                name: "bend",
                value: scale(b),
                error: bend_err,
                unit: "%",
            },
        ],
        residuals,
        curve,
        periods: None,
        shape: [b, vertex],
    })
}
