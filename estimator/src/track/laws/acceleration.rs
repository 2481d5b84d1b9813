//! A constant acceleration in the picture's plane, p0 + v0 t + a t²/2 in x and y (a fall, a
//! toss, a roll; the release's velocity free): two linear fits, and the vertex along the
//! acceleration (the release of a motion from rest, found rather than assumed).

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
    let (covx, covy) = (covariance(&cols, &rx)?, covariance(&cols, &ry)?);
    let (vx, vy) = (covx[8], covy[8]);
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
    // The vertex along the acceleration: where the velocity along it is zero (a release from
    // rest, a toss's apex), t0 − v/a, its error from the velocity's and the acceleration's.
    let v = cx[1] * dx + cy[1] * dy;
    let v_var = dx * dx * covx[4] + dy * dy * covy[4];
    let (vertex, vertex_err) = if a > 0.0 {
        (
            t0 - v / a,
            (v_var / (a * a) + (v * v / (a * a * a * a)) * a_err * a_err).sqrt(),
        )
    } else {
        (f64::NAN, f64::INFINITY)
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
            Value {
                name: "vertex",
                value: vertex,
                error: vertex_err,
                unit: "s",
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
        // Up at 150 px/s against 400 px/s² down: the apex 0.375 s in.
        assert!((f.value("vertex").unwrap().value - 0.375).abs() < 1e-9);
        assert!(f.rms() < 1e-6);
    }
}
