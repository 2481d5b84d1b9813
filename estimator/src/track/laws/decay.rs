//! The exponential decay c + a e^(−γt) of a quantity that is not a position (an LED's light as
//! its capacitor drains: the LED's I' = −γ I, its offset the picture's level where the light is
//! out) by variable projection: γ searched (a log grid, then Levenberg–Marquardt), c and a
//! solved for at each.

use super::{covariance, from_first, linear, searched, Fitted, Value};

/// The decay's columns at rate `g`: the level and the decaying part.
fn basis(t: &[f64], g: f64) -> Vec<Vec<f64>> {
    vec![
        vec![1.0; t.len()],
        t.iter().map(|&s| (-g * s).exp()).collect(),
    ]
}

/// The decay fitted to `u` at times `t`, from the rate `start[0]` or else from the best rate
/// of a log grid between a tenth of an e-fold over the span and one a sample step. `None` where
/// nothing decays (a rate at the grid's ends, a level that rises or stays).
pub(super) fn decay(t: &[f64], u: &[f64], start: Option<[f64; 2]>) -> Option<Fitted> {
    let (t, span, step) = from_first(t, 6)?;
    let (lo, hi) = (0.1 / span, 1.0 / step);
    let residual = |g: f64| linear(&basis(&t, g), u).map(|(_, r)| r);
    let g = searched(
        (lo, hi),
        start.map(|s| s[0]).filter(|g| *g > 0.0),
        &residual,
    )?;
    if !(g > lo && g < hi) {
        return None;
    }
    let cols = basis(&t, g);
    let (c, r) = linear(&cols, u)?;
    // Jacobian of the curve in (level, amplitude, rate).
    let dg: Vec<f64> = t.iter().zip(&cols[1]).map(|(s, e)| -c[1] * s * e).collect();
    let jac = [cols[0].clone(), cols[1].clone(), dg];
    let cov = covariance(&jac, &r)?;
    let error = |i: usize| cov[i * 3 + i].max(0.0).sqrt();
    let curve: Vec<f64> = u.iter().zip(&r).map(|(a, b)| a - b).collect();
    Some(Fitted {
        values: vec![
            Value {
                name: "gamma",
                value: g,
                error: error(2),
                unit: "1/s",
            },
            Value {
                name: "level",
                value: c[0],
                error: error(0),
                unit: "grey",
            },
            Value {
                name: "amplitude",
                value: c[1],
                error: error(1),
                unit: "grey",
            },
        ],
        residuals: r,
        curve,
        periods: None,
        shape: [g, 0.0],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_decay_gives_back_its_rate_level_and_amplitude() {
        let t: Vec<f64> = (0..120).map(|k| 1.0 + k as f64 / 30.0).collect();
        let u: Vec<f64> = t
            .iter()
            .map(|&s| 50.0 + 120.0 * (-0.5 * (s - 1.0)).exp() + 0.1 * (37.1 * s).sin())
            .collect();
        let f = decay(&t, &u, None).expect("a decay");
        let g = f.value("gamma").unwrap();
        assert!((g.value - 0.5).abs() < 2e-3, "{g:?}");
        assert!(g.error > 0.0 && g.error < 0.01, "{g:?}");
        assert!((f.value("level").unwrap().value - 50.0).abs() < 0.2);
        assert!((f.value("amplitude").unwrap().value - 120.0).abs() < 0.3);
        // Started near the answer, the same answer.
        let again = decay(&t, &u, Some([0.45, 0.0])).unwrap();
        assert!((again.value("gamma").unwrap().value - g.value).abs() < 1e-6);
    }

    #[test]
    fn a_level_that_stays_or_rises_without_bound_is_no_decay() {
        let t: Vec<f64> = (0..60).map(|k| k as f64 / 30.0).collect();
        let flat: Vec<f64> = t.iter().map(|s| 80.0 + 0.2 * (41.0 * s).sin()).collect();
        let line: Vec<f64> = t.iter().map(|s| 80.0 + 3.0 * s).collect();
        // A straight line is the decay's slow end: its rate falls off the grid.
        assert!(decay(&t, &line, None).is_none());
        // A ripple about a level: whatever decay is fitted leaves nearly all of it (`segment`
        // then finds that the law explains nothing there).
        let spread = {
            let m = flat.iter().sum::<f64>() / flat.len() as f64;
            (flat.iter().map(|v| (v - m).powi(2)).sum::<f64>() / flat.len() as f64).sqrt()
        };
        if let Some(f) = decay(&t, &flat, None) {
            assert!(f.rms() > 0.9 * spread, "{} of {spread}", f.rms());
        }
    }
}
