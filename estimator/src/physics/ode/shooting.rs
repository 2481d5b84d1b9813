//! Shooting: the initial state whose trajectory fits a clip's observed values best (least
//! squares over every frame), found by Levenberg–Marquardt on the exact sensitivities, and the
//! trajectory's derivatives there.

use super::rk4::{integrate, Span};
use super::OdeSystem;
use crate::linalg::solve;

/// Levenberg–Marquardt iterations at most (each one integration, more when a step is refused).
const MAX_ITERATIONS: usize = 12;
/// A step smaller than this (relative to the state) ends the fit.
const STEP_TOLERANCE: f64 = 1e-6;
/// A relative decrease of the cost smaller than this ends the fit.
const COST_TOLERANCE: f64 = 1e-6;

/// A clip's fit: the observed trajectory through the best initial state and its derivatives.
#[derive(Debug, Clone)]
pub struct ClipFit {
    pub x0: Vec<f64>,
    /// The fitted observed values \[R\] (R = frames × observed, frame-major).
    pub y: Vec<f64>,
    /// ∂y/∂x0 [R × n].
    pub jx: Vec<f64>,
    /// ∂y/∂p [R × m].
    pub jp: Vec<f64>,
    /// (jxᵀ·jx)⁻¹ [n × n], so the projection onto the trajectories near y is jx·ainv·jxᵀ.
    pub ainv: Vec<f64>,
    /// Sum of squared residuals.
    pub cost: f64,
}

/// Frames of the first stage of the horizon continuation.
const FIRST_HORIZON: usize = 3;

/// A fit leaving a mean squared misfit above this fraction of the latent's variance (over the
/// batch) is retried by continuation.
pub const POOR_FIT: f64 = 1e-2;

/// Fits the initial state of `sys` with parameters `p` to `target` [frames × observed]: from
/// `warm` (the clip's last fitted state) or the system's first guess over the whole clip, and,
/// when that leaves a misfit above `poor_cost`, by a horizon continuation from the guess too,
/// keeping the better. Over a long clip (several
/// swings) the cost has a minimum per basin of phase, and a guess from finite differences may
/// sit in the wrong one; the continuation fits a horizon that doubles from `FIRST_HORIZON`
/// frames to the whole clip, each stage starting where the last ended: a short horizon has one
/// basin, and each longer one starts inside the right one.
pub fn fit_clip(
    sys: &dyn OdeSystem,
    p: &[f64],
    target: &[f64],
    span: Span,
    observed: &[usize],
    poor_cost: f64,
    warm: Option<&[f64]>,
) -> ClipFit {
    let guess = sys.guess(target, observed, span.dt);
    let first = warm.map_or_else(|| guess.clone(), <[f64]>::to_vec);
    let (mut x, mut cost) = least_squares(sys, p, target, span, observed, first);
    // A NaN cost counts as poor.
    if cost.is_nan() || cost > poor_cost {
        let o = observed.len();
        let mut y = guess;
        let mut horizon = FIRST_HORIZON.min(span.frames);
        let c = loop {
            let stage = Span {
                frames: horizon,
                ..span
            };
            let (next, c) = least_squares(sys, p, &target[..horizon * o], stage, observed, y);
            y = next;
            if horizon == span.frames {
                break c;
            }
            horizon = (2 * horizon).min(span.frames);
        };
        if c < cost || !cost.is_finite() {
            (x, cost) = (y, c);
        }
    }
    let _ = cost;
    finish(sys, p, target, span, observed, x)
}

/// Levenberg–Marquardt from `x` on `target` over `span`: the state and its cost.
fn least_squares(
    sys: &dyn OdeSystem,
    p: &[f64],
    target: &[f64],
    span: Span,
    observed: &[usize],
    mut x: Vec<f64>,
) -> (Vec<f64>, f64) {
    let n = sys.states();
    let cost_of = |y: &[f64]| -> f64 { y.iter().zip(target).map(|(a, b)| (a - b).powi(2)).sum() };
    let mut track = integrate(sys, &x, p, span, observed, false);
    let mut cost = cost_of(&track.y);
    let mut lambda = 1e-3;
    for _ in 0..MAX_ITERATIONS {
        if !cost.is_finite() || cost < 1e-24 {
            break;
        }
        let (a, g) = normal_equations(&track.dy, &track.y, target, n, track.k);
        let mut accepted = false;
        for _ in 0..6 {
            let mut m = a.clone();
            for i in 0..n {
                m[i * n + i] += lambda * a[i * n + i] + 1e-12;
            }
            let Some(delta) = solve(&m, &g.iter().map(|v| -v).collect::<Vec<_>>(), n) else {
                lambda *= 8.0;
                continue;
            };
            let trial: Vec<f64> = x.iter().zip(&delta).map(|(a, d)| a + d).collect();
            let t = integrate(sys, &trial, p, span, observed, false);
            let c = cost_of(&t.y);
            if c.is_finite() && c < cost {
                // The surrogate's Gauss–Newton correction absorbs what is left to second
                // order, so the fit need not polish the last digits.
                let small = delta
                    .iter()
                    .zip(&x)
                    .all(|(d, v)| d.abs() <= STEP_TOLERANCE * (1.0 + v.abs()));
                let flat = cost - c <= COST_TOLERANCE * cost;
                x = trial;
                track = t;
                cost = c;
                lambda = (lambda / 3.0).max(1e-9);
                accepted = !(small || flat);
                break;
            }
            lambda *= 8.0;
        }
        if !accepted {
            break;
        }
    }
    (x, cost)
}

/// The final integration with parameter sensitivities, split into the fit's parts.
fn finish(
    sys: &dyn OdeSystem,
    p: &[f64],
    target: &[f64],
    span: Span,
    observed: &[usize],
    x0: Vec<f64>,
) -> ClipFit {
    let (n, m) = (sys.states(), sys.params());
    let t = integrate(sys, &x0, p, span, observed, true);
    let rows = t.y.len();
    let (mut jx, mut jp) = (Vec::with_capacity(rows * n), Vec::with_capacity(rows * m));
    for r in 0..rows {
        jx.extend_from_slice(&t.dy[r * t.k..r * t.k + n]);
        jp.extend_from_slice(&t.dy[r * t.k + n..(r + 1) * t.k]);
    }
    let (a, _) = normal_equations(&jx, &t.y, target, n, n);
    let trace = (0..n).map(|i| a[i * n + i]).sum::<f64>() / n as f64;
    let ainv = inverse(&a, n, 1e-12 * trace.max(1e-300)).unwrap_or_else(|| vec![0.0; n * n]);
    let cost = t.y.iter().zip(target).map(|(a, b)| (a - b).powi(2)).sum();
    ClipFit {
        x0,
        y: t.y,
        jx,
        jp,
        ainv,
        cost,
    }
}

/// JᵀJ [n × n] and Jᵀ(y − target) [n] from the first n of `k` columns of `dy` [R × k].
fn normal_equations(
    dy: &[f64],
    y: &[f64],
    target: &[f64],
    n: usize,
    k: usize,
) -> (Vec<f64>, Vec<f64>) {
    let (mut a, mut g) = (vec![0.0; n * n], vec![0.0; n]);
    for (r, (yv, tv)) in y.iter().zip(target).enumerate() {
        let row = &dy[r * k..r * k + n];
        let res = yv - tv;
        for i in 0..n {
            g[i] += row[i] * res;
            for j in 0..n {
                a[i * n + j] += row[i] * row[j];
            }
        }
    }
    (a, g)
}

/// (a + ridge·I)⁻¹ for an n×n `a`.
pub(super) fn inverse(a: &[f64], n: usize, ridge: f64) -> Option<Vec<f64>> {
    let mut m = a.to_vec();
    for i in 0..n {
        m[i * n + i] += ridge;
    }
    let mut inv = vec![0.0; n * n];
    for c in 0..n {
        let e: Vec<f64> = (0..n).map(|i| if i == c { 1.0 } else { 0.0 }).collect();
        let col = solve(&m, &e, n)?;
        for r in 0..n {
            inv[r * n + c] = col[r];
        }
    }
    Some(inv)
}
