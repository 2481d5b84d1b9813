//! A swing about a pivot, in the motion's own coordinate: the pivot and the radius fitted to
//! the path (a circle by algebraic least squares), the angle from the vertical below the pivot,
//! and θ'' = −Ω² sin(θ − θe) − c θ' (a pendulum at any amplitude; θe a camera's roll)
//! integrated by RK4 and fitted by Levenberg–Marquardt, its residuals the arc's (pixels); θe is
//! its value `rest` (degrees).

use super::oscillation::oscillation;
use super::{covariance, jacobian, least_squares, linear, median_step, sum_sq, Fitted, Value};
use std::f64::consts::{PI, TAU};

/// A path whose angle about its pivot spans less than this (radians: 20°) is read along a line:
/// a swing of ±10° runs 0.2 % slower than at small angles, within what the oscillation leaves.
pub const LEAST_ARC: f64 = 0.35;

/// RK4 steps per radian of the swing's phase.
const STEPS_PER_RADIAN: f64 = 10.0;

/// The circle through the points (Kåsa: x² + y² + D x + E y + F = 0 by least squares): its
/// centre and radius.
pub fn circle(xy: &[(f64, f64)]) -> Option<((f64, f64), f64)> {
    let cols = vec![
        xy.iter().map(|p| p.0).collect::<Vec<f64>>(),
        xy.iter().map(|p| p.1).collect(),
        vec![1.0; xy.len()],
    ];
    let y: Vec<f64> = xy.iter().map(|p| -(p.0 * p.0 + p.1 * p.1)).collect();
    let (c, _) = linear(&cols, &y)?;
    let (cx, cy) = (-c[0] / 2.0, -c[1] / 2.0);
    let r2 = cx * cx + cy * cy - c[2];
    (r2 > 0.0 && r2.is_finite()).then(|| ((cx, cy), r2.sqrt()))
}

/// The angle at times `t` of θ'' = −w2 sin(θ − e) − c θ' from θ(t[0]) = a0, θ'(t[0]) = v0.
fn integrate(t: &[f64], [w2, c, e, a0, v0]: [f64; 5]) -> Vec<f64> {
    let f = |a: f64, v: f64| (v, -w2 * (a - e).sin() - c * v);
    let rate = w2.abs().sqrt().max(1e-9);
    let mut s = (a0, v0);
    let mut out = Vec::with_capacity(t.len());
    out.push(a0);
    for w in t.windows(2) {
        let dt = w[1] - w[0];
        let m = ((dt * rate * STEPS_PER_RADIAN).ceil() as usize).clamp(1, 10_000);
        let h = dt / m as f64;
        for _ in 0..m {
            let k1 = f(s.0, s.1);
            let k2 = f(s.0 + 0.5 * h * k1.0, s.1 + 0.5 * h * k1.1);
            let k3 = f(s.0 + 0.5 * h * k2.0, s.1 + 0.5 * h * k2.1);
            let k4 = f(s.0 + h * k3.0, s.1 + h * k3.1);
            s.0 += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            s.1 += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        }
        out.push(s.0);
    }
    out
}

/// A path read as an arc below a pivot: the circle's radius and each point's angle from the
/// vertical below its centre (radians).
struct Arc {
    radius: f64,
    theta: Vec<f64>,
}

/// The arc of the picture positions `xy`; `None` where the path is no arc below a pivot
/// spanning [`LEAST_ARC`].
fn arc(xy: &[(f64, f64)]) -> Option<Arc> {
    if xy.len() < 8 {
        return None;
    }
    let ((cx, cy), radius) = circle(xy)?;
    // The pivot above the whole path (the picture's y runs down).
    if xy.iter().any(|p| p.1 <= cy) {
        return None;
    }
    let theta: Vec<f64> = xy.iter().map(|p| (p.0 - cx).atan2(p.1 - cy)).collect();
    let (lo, hi) = theta
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &a| {
            (l.min(a), h.max(a))
        });
    (hi - lo >= LEAST_ARC).then_some(Arc { radius, theta })
}

/// The angle about the pivot as the damped oscillator, θ'' + γ1 θ' + γ0 (θ − θe) = 0 (a swing
/// whose restoring turn grows with its angle, as the oscillator's; `oscillation` on the
/// angle), its residuals the arc's (pixels) and its amplitude in degrees; from (ζ, ω) = `start`
/// where given. `None` where the path is no arc (`arc`) or the fit fails.
pub(super) fn angular(
    t: &[f64],
    u: &[f64],
    xy: &[(f64, f64)],
    start: Option<[f64; 2]>,
) -> Option<Fitted> {
    let Arc { radius, theta } = arc(xy)?;
    let mut f = oscillation(t, &theta, start)?;
    f.residuals.iter_mut().for_each(|r| *r *= radius);
    f.curve = u.iter().zip(&f.residuals).map(|(u, r)| u - r).collect();
    for v in f.values.iter_mut().filter(|v| v.name == "amplitude") {
        v.value = v.value.to_degrees();
        v.error = v.error.to_degrees();
        v.unit = "deg";
    }
    Some(f)
}

/// The swing fitted to the picture positions `xy` at times `t` (their positions `u` along the
/// axis give the curve drawn), from (c, Ω) = `start` where given; `None` where the path is no
/// arc below a pivot spanning [`LEAST_ARC`], or the fit fails.
pub(super) fn swing(
    t: &[f64],
    u: &[f64],
    xy: &[(f64, f64)],
    start: Option<[f64; 2]>,
) -> Option<Fitted> {
    let Arc { radius, theta } = arc(xy)?;
    let n = t.len();
    let t0 = t[0];
    let ts: Vec<f64> = t.iter().map(|s| s - t0).collect();
    // Starts: the small-angle oscillation of the angle, its rate raised for the amplitude.
    let small = oscillation(t, &theta, None)?;
    let (z, w) = match start {
        Some([c, w]) => (c / 2.0, w),
        None => (small.shape[0], small.shape[1]),
    };
    let level = small.curve.iter().sum::<f64>() / n as f64;
    let a0 = small.curve[0];
    let v0 = (small.curve[1] - small.curve[0]) / (ts[1] - ts[0]).max(1e-9);
    // A swing faster than the samples' Nyquist frequency is not seen in them (as the
    // oscillation's): the fit is not let past it.
    let nyquist = PI / median_step(&ts);
    let residual = |p: &[f64]| -> Option<Vec<f64>> {
        if p[0] > nyquist * nyquist {
            return None;
        }
        let th = integrate(&ts, [p[0], p[1], p[2], p[3], p[4]]);
        th.iter()
            .zip(&theta)
            .map(|(a, b)| {
                let r = radius * (b - a);
                r.is_finite().then_some(r)
            })
            .collect()
    };
    // From the small-angle rate, raised for amplitudes it does not know; from a fitted swing's
    // own rate (`start`: a span grown from one), that alone.
    let raised: &[f64] = if start.is_some() {
        &[1.0]
    } else {
        &[1.0, 1.15, 1.35]
    };
    let best = raised
        .iter()
        .filter_map(|k| least_squares(&[k * w * w, 2.0 * z, level, a0, v0], &residual))
        .min_by(|a, b| sum_sq(&a.1).total_cmp(&sum_sq(&b.1)))?;
    let (p, r) = best;
    let (w2, c, e) = (p[0], p[1], p[2]);
    let amplitude = theta.iter().map(|a| (a - e).abs()).fold(0.0, f64::max);
    if !(w2 > 0.0 && c.abs() < 2.0 * w2.sqrt()) {
        return None;
    }
    let cols = jacobian(&p, &r, &residual)?;
    let cov = covariance(&cols, &r)?;
    let k = cols.len();
    // The period at this amplitude (its first correction, θa²/16): the swings the span holds.
    let period = TAU / w2.sqrt() * (1.0 + amplitude * amplitude / 16.0);
    let curve = u.iter().zip(&r).map(|(u, r)| u - r).collect();
    Some(Fitted {
        values: vec![
            Value {
                name: "g_over_l",
                value: w2,
                error: cov[0].max(0.0).sqrt(),
                unit: "1/s^2",
            },
            Value {
                name: "damping",
                value: c,
                error: cov[k + 1].max(0.0).sqrt(),
                unit: "1/s",
            },
            Value {
                name: "amplitude",
                value: amplitude * 180.0 / PI,
                error: 0.0,
                unit: "deg",
            },
            Value {
                name: "rest",
                value: e.to_degrees(),
                error: cov[2 * k + 2].max(0.0).sqrt().to_degrees(),
                unit: "deg",
            },
        ],
        residuals: r,
        curve,
        periods: Some(ts[n - 1] / period),
        shape: [c, w2.sqrt()],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_circle_through_points_of_an_arc_is_found() {
        let xy: Vec<(f64, f64)> = (0..20)
            .map(|i| {
                let a = -0.6 + 0.06 * i as f64;
                (300.0 + 250.0 * a.sin(), 40.0 + 250.0 * a.cos())
            })
            .collect();
        let ((cx, cy), r) = circle(&xy).unwrap();
        assert!((cx - 300.0).abs() < 1e-6 && (cy - 40.0).abs() < 1e-6 && (r - 250.0).abs() < 1e-6);
    }

    #[test]
    fn a_swing_from_the_horizontal_gives_back_its_g_over_l() {
        // θ'' = −17.9 sin θ − 0.2 θ' from 90°, seen at 10 fps for 3.5 s on a 340-px string
        // from a pivot at (420, 60), rounded to a tenth of a pixel.
        let truth = [17.9, 0.2, 0.0, PI / 2.0, 0.0];
        let t: Vec<f64> = (0..36).map(|i| i as f64 / 10.0).collect();
        let th = integrate(&t, truth);
        let xy: Vec<(f64, f64)> = th
            .iter()
            .map(|a| {
                let p = (420.0 + 340.0 * a.sin(), 60.0 + 340.0 * a.cos());
                ((p.0 * 10.0).round() / 10.0, (p.1 * 10.0).round() / 10.0)
            })
            .collect();
        let u: Vec<f64> = xy.iter().map(|p| p.0).collect();
        let f = swing(&t, &u, &xy, None).expect("fits");
        let g = f.value("g_over_l").unwrap();
        assert!((g.value / 17.9 - 1.0).abs() < 2e-3, "{g:?}");
        assert!(g.error > 0.0 && g.error < 0.1, "{g:?}");
        assert!((f.value("damping").unwrap().value - 0.2).abs() < 0.01);
        assert!((f.value("amplitude").unwrap().value - 90.0).abs() < 1.0);
        assert!(f.value("rest").unwrap().value.abs() < 0.1);
        assert!(f.rms() < 0.1, "{}", f.rms());
        // The small-angle oscillation cannot follow it.
        let small = oscillation(&t, &u, None).unwrap();
        assert!(small.rms() > 10.0 * f.rms(), "{} {}", small.rms(), f.rms());
    }

    #[test]
    fn a_line_is_no_swing() {
        let t: Vec<f64> = (0..40).map(|i| i as f64 / 30.0).collect();
        let xy: Vec<(f64, f64)> = t
            .iter()
            .map(|s| (100.0, 200.0 + 30.0 * (6.0 * s).cos()))
            .collect();
        let u: Vec<f64> = xy.iter().map(|p| p.1).collect();
        assert!(swing(&t, &u, &xy, None).is_none());
    }
}
