//! A level draining as Torricelli's law has it (water through a hole in a tank's bottom:
//! h' = −k√h, so √h falls linearly and h = (k/2)²·(tₑ − t)² until the tank is empty at tₑ),
//! read on an observable that moves with the level (the brightness of the region the surface
//! leaves: each row of it changes once, as the surface passes): c + a·((tₑ − t)₊)². tₑ is
//! searched (a grid, then Levenberg–Marquardt), c and a solved for at each (variable
//! projection). Its rate is Torricelli's k in the observable's own units, 2√|a| (√h falls by
//! k/2 a second), named apart from the model's k in metres (`drain_k`): like a frequency, the
//! same on any part of the span.

use super::{covariance, from_first, linear, searched, Fitted, Value};

/// The drain's columns for an empty time `te` (from the span's first sample): the level
/// reached, and the square of the time left.
fn basis(t: &[f64], te: f64) -> Vec<Vec<f64>> {
    vec![
        vec![1.0; t.len()],
        t.iter().map(|&s| (te - s).max(0.0).powi(2)).collect(),
    ]
}

/// The drain fitted to `u` at times `t`, from the empty time `start[0]` (s, on `t`'s clock) or
/// else from the best of a grid from two sample steps after the span's first sample to twenty
/// spans. `None` where nothing drains: no fit, a level that does not curve towards a
/// rest (`a` of either sign: the observable may brighten or darken as the level falls, but a
/// drain empties, it never empties before the span starts), or an empty time at the grid's
/// far end (a straight line).
pub(super) fn drain(t: &[f64], u: &[f64], start: Option<[f64; 2]>) -> Option<Fitted> {
    let t0 = *t.first()?;
    let (t, span, step) = from_first(t, 6)?;
    let (lo, hi) = (2.0 * step, 20.0 * span);
    let start = start.map(|[te, other]| [te - t0, other]);
    let residual = |te: f64| linear(&basis(&t, te), u).map(|(_, r)| r);
    let te = searched(
        (lo, hi),
        start.map(|s| s[0]).filter(|te| *te > lo),
        &residual,
    )?;
    if !(te > lo && te < 0.9 * hi) {
        return None;
    }
    let cols = basis(&t, te);
    let (c, r) = linear(&cols, u)?;
    if c[1] == 0.0 {
        return None;
    }
    // Jacobian of the curve in (level, amplitude, empty time).
    let dte: Vec<f64> = t.iter().map(|&s| 2.0 * c[1] * (te - s).max(0.0)).collect();
    let jac = [cols[0].clone(), cols[1].clone(), dte];
    let cov = covariance(&jac, &r)?;
    let error = |i: usize| cov[i * 3 + i].max(0.0).sqrt();
    let curve: Vec<f64> = u.iter().zip(&r).map(|(a, b)| a - b).collect();
    let k = 2.0 * c[1].abs().sqrt();
    Some(Fitted {
        values: vec![
            Value {
                name: "drain_k",
                value: k,
                // d(2√|a|)/da = 1/√|a|.
                error: error(1) / c[1].abs().sqrt(),
                unit: "√level/s",
            },
            Value {
                name: "empty",
                value: t0 + te,
                error: error(2),
                unit: "s",
            },
            Value {
                name: "level",
                value: c[0],
                error: error(0),
                unit: "level",
            },
            Value {
                name: "curvature",
                value: c[1],
                error: error(1),
                unit: "level/s^2",
            },
        ],
        residuals: r,
        curve,
        periods: None,
        shape: [t0 + te, 0.0],
    })
}

/// The share of its level (above where it rests) that a drain empty at `empty` loses from
/// `first` to `last` (s, one clock): 1 − ((tₑ − last)₊/(tₑ − first))².
pub fn drained(empty: f64, first: f64, last: f64) -> f64 {
    let left = ((empty - last) / (empty - first)).clamp(0.0, 1.0);
    1.0 - left * left
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A level 120 − 0.2·(24 − t)² grey levels (brightening as the water leaves) read from
    /// 6 s to 28 s at 10 samples a second, ±0.3 of alternating noise; the tank is empty at
    /// 24 s, and the level stays after.
    fn tank() -> (Vec<f64>, Vec<f64>) {
        let t: Vec<f64> = (60..280).map(|k| k as f64 / 10.0).collect();
        let u = t
            .iter()
            .enumerate()
            .map(|(i, &s)| {
                let e = if i % 2 == 0 { 0.3 } else { -0.3 };
                120.0 - 0.2 * (24.0 - s).max(0.0).powi(2) + e
            })
            .collect();
        (t, u)
    }

    #[test]
    fn a_draining_level_gives_when_it_empties_and_its_rate() {
        let (t, u) = tank();
        let f = drain(&t, &u, None).expect("a drain");
        let v = |name: &str| f.value(name).unwrap().clone();
        // From the first sample, at 6 s: empty 18 s later.
        assert!((v("empty").value - 24.0).abs() < 0.02, "{f:?}");
        assert!(v("empty").error > 0.0 && v("empty").error < 0.05, "{f:?}");
        assert!((v("curvature").value + 0.2).abs() < 1e-3, "{f:?}");
        assert!(
            (v("drain_k").value - 2.0 * 0.2f64.sqrt()).abs() < 2e-3,
            "{f:?}"
        );
        assert!(v("drain_k").error < 0.01 * v("drain_k").value, "{f:?}");
        assert!(f.rms() < 0.31, "{}", f.rms());
        assert_eq!(drained(v("empty").value, 6.0, 28.0), 1.0);
        assert!((drained(24.0, 6.0, 15.0) - 0.75).abs() < 1e-9);
        // Its k is the same on either half of the span.
        let half = t.len() / 2;
        let k = |a: usize, b: usize| drain(&t[a..b], &u[a..b], None).unwrap().values[0].value;
        assert!((k(0, half) / k(half, t.len()) - 1.0).abs() < 0.01);
        // Started near its empty time (a span grown from one fitted before): the same.
        let again = drain(&t, &u, Some([23.0, 0.0])).unwrap();
        assert!((again.value("empty").unwrap().value - 24.0).abs() < 0.02);
    }

    #[test]
    fn a_decay_is_read_worse_as_a_drain_than_as_itself() {
        // An LED's light over three e-folds.
        let t: Vec<f64> = (0..150).map(|k| k as f64 / 50.0).collect();
        let u: Vec<f64> = t
            .iter()
            .enumerate()
            .map(|(i, s)| 30.0 + 100.0 * (-s).exp() + if i % 2 == 0 { 0.3 } else { -0.3 })
            .collect();
        let as_decay = super::super::decay::decay(&t, &u, None).unwrap();
        let as_drain = drain(&t, &u, None).unwrap();
        assert!(as_decay.rms() < 0.31, "{}", as_decay.rms());
        assert!(as_drain.rms() > 3.0 * as_decay.rms(), "{}", as_drain.rms());
    }
}
