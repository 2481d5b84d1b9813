//! A constant acceleration in the picture's plane, p0 + v0 t + a t²/2 in x and y (a fall, a
//! toss, a roll; the release's velocity free): two linear fits.

use super::{covariance, linear, Fitted, Value};

/// The constant acceleration fitted to the picture positions `xy` at times `t`: its size (px/s²
/// of the displayed frame) and direction.
pub(super) fn acceleration(t: &[f64], xy: &[(f64, f64)]) -> Option<Fitted> {
    let n = t.len();
    if n < 6 {
        return None;
    }
    let t0 = t[n / 2];
    let cols = vec![
        vec![1.0; n],
        t.iter().map(|s| s - t0).collect::<Vec<f64>>(),
        t.iter().map(|s| 0.5 * (s - t0) * (s - t0)).collect(),
    ];
    let x: Vec<f64> = xy.iter().map(|p| p.0).collect();
    let y: Vec<f64> = xy.iter().map(|p| p.1).collect();
    let (cx, rx) = linear(&cols, &x)?;
    let (cy, ry) = linear(&cols, &y)?;
    let vx = covariance(&cols, &rx)?[8];
    let vy = covariance(&cols, &ry)?[8];
    let (ax, ay) = (cx[2], cy[2]);
    let a = ax.hypot(ay);
    let a_err = if a > 0.0 {
        ((ax * ax * vx + ay * ay * vy) / (a * a)).sqrt()
    } else {
        vx.max(vy).sqrt()
    };
    let (dx, dy) = if a > 0.0 {
        (ax / a, ay / a)
    } else {
        (0.0, 1.0)
    };
    let curve = (0..n)
        .map(|i| (x[i] - rx[i]) * dx + (y[i] - ry[i]) * dy)
        .collect();
    let mut residuals = rx;
    residuals.extend(ry);
    Some(Fitted {
        values: vec![
            Value {
                name: "acceleration",
                value: a,
                error: a_err,
                unit: "px/s^2",
            },
            Value {
                name: "direction",
                value: dy.atan2(dx).to_degrees(),
                error: if a > 0.0 {
                    ((dx * dx * vy + dy * dy * vx) / (a * a))
                        .sqrt()
                        .to_degrees()
                } else {
                    180.0
                },
                unit: "deg",
            },
        ],
        residuals,
        curve,
        periods: None,
        shape: [0.0, 0.0],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_toss_gives_back_its_acceleration_and_direction() {
        let t: Vec<f64> = (0..20).map(|i| i as f64 / 30.0).collect();
        let xy: Vec<(f64, f64)> = t
            .iter()
            .map(|&s| (10.0 + 60.0 * s, 200.0 - 150.0 * s + 0.5 * 400.0 * s * s))
            .collect();
        let f = acceleration(&t, &xy).unwrap();
        let a = f.value("acceleration").unwrap();
        assert!((a.value - 400.0).abs() < 1e-6, "{a:?}");
        assert!((f.value("direction").unwrap().value - 90.0).abs() < 1e-6);
        assert!(f.rms() < 1e-6);
    }
}
