//! A constant acceleration in the picture's plane, p0 + v0 t + a t²/2 in x and y (a fall, a
//! toss, a roll; the release's velocity free): two linear fits, and the vertex along the
//! acceleration (the release of a motion from rest, found rather than assumed). Seen in
//! perspective (a camera tilted to the path), the path along the acceleration is a projective
//! map of the parabola, c + s·v/(1 + b·v) with v = (t − r)² (as `data::perspective` reads a
//! descent in the picture): on a span long enough, that bend is fitted too, and kept where it
//! fits the path along the acceleration that much better; the vertex and the acceleration are
//! then read through it.

use super::{covariance, jacobian, least_squares, linear, sum_sq, Fitted, Value};
use crate::data::perspective::{LEAST_DENOMINATOR, MIN_FRAMES, MIN_GAIN};

/// The constant acceleration fitted to the picture positions `xy` at times `t`: its size (px/s²
/// of the displayed frame) and direction.
/// Where `near` is the shape of a bent fit (its bend and vertex, `Fitted::shape`) and the span
/// is too short to fit a bend of its own (a half of a bent span), the bend is held at `near`'s.
pub(super) fn acceleration(t: &[f64], xy: &[(f64, f64)], near: Option<[f64; 2]>) -> Option<Fitted> {
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
    let curve: Vec<f64> = (0..n)
        .map(|i| (x[i] - rx[i]) * dx + (y[i] - ry[i]) * dy)
        .collect();
    let direction = Value {
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
    };
    let held = near.filter(|s| s[0] != 0.0 && n < MIN_FRAMES);
    // A held bend starts from the vertex it was found with, and the later part of a path bent
    // hard may slow in the picture, its plain acceleration pointing back: both ways are tried.
    let (from, ways) = match held {
        Some(s) => (s[1], &[1.0, -1.0][..]),
        None => (vertex, &[1.0][..]),
    };
    if a > 0.0 && (n >= MIN_FRAMES || held.is_some()) {
        // The plain parabola's residuals along its acceleration (their size is either way's).
        let plain: Vec<f64> = (0..n).map(|i| x[i] * dx + y[i] * dy - curve[i]).collect();
        for &way in ways {
            let (ex, ey) = (way * dx, way * dy);
            let along: Vec<f64> = (0..n).map(|i| x[i] * ex + y[i] * ey).collect();
            if let Some(mut bent) = bent(t, &along, (from, &plain), held.map(|s| s[0])) {
                bent.values.insert(
                    1,
                    Value {
                        value: ey.atan2(ex).to_degrees(),
                        ..direction
                    },
                );
                // Across the acceleration, the plain fit's residuals.
                bent.residuals
                    .extend((0..n).map(|i| ry[i] * ex - rx[i] * ey));
                return Some(bent);
            }
        }
    }
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
            direction,
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

/// The path `along` the acceleration at times `t` fitted as a parabola seen in perspective,
/// c + s·v/(1 + b·v) with v = (t − r)², from a vertex and the plain parabola's residuals
/// (`plain`), or with its bend `held`: its acceleration at the vertex (2s), vertex and bend (the
/// picture's scale where the path is farthest from its vertex against at it, less one, in per
/// cent), with the fitted path and its residuals along. `None` where a bend of its own fits no
/// better than [`MIN_GAIN`] times the plain parabola, or only with a pole near the span (the
/// scale changing more than the denominator allows).
fn bent(t: &[f64], along: &[f64], plain: (f64, &[f64]), held: Option<f64>) -> Option<Fitted> {
    let n = t.len();
    let (r0, plain) = plain;
    let rms = |r: &[f64]| (sum_sq(r) / r.len() as f64).sqrt();
    let farthest = |r: f64| t.iter().map(|s| (s - r).powi(2)).fold(0.0, f64::max);
    // For a vertex `r` and bend `b`: the weights v/(1 + b·v), or none near a pole.
    let weights = |r: f64, b: f64| -> Option<Vec<f64>> {
        let den: Vec<f64> = t.iter().map(|s| 1.0 + b * (s - r).powi(2)).collect();
        let (lo, hi) = den
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), d| (l.min(*d), h.max(*d)));
        (lo > 0.0 && lo >= LEAST_DENOMINATOR * hi).then(|| {
            t.iter()
                .zip(&den)
                .map(|(s, d)| (s - r).powi(2) / d)
                .collect()
        })
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
        let f = acceleration(&t, &xy, None).unwrap();
        let a = f.value("acceleration").unwrap();
        assert!((a.value - 400.0).abs() < 1e-6, "{a:?}");
        assert!((f.value("direction").unwrap().value - 90.0).abs() < 1e-6);
        // Up at 150 px/s against 400 px/s² down: the apex 0.375 s in.
        assert!((f.value("vertex").unwrap().value - 0.375).abs() < 1e-9);
        assert!(f.rms() < 1e-6);
    }

    /// A fall from rest at 0.5 s (400 px/s² near the release), seen for 36 frames at 60 fps
    /// through p = 20 + z/(1 + 0.01·z), z = 200 (t − 0.5)², the last drawn at a third of the
    /// first's scale; rounded to a hundredth of a pixel.
    fn foreshortened(bend: f64) -> (Vec<f64>, Vec<(f64, f64)>) {
        let t: Vec<f64> = (30..66).map(|k| k as f64 / 60.0).collect();
        let xy = t
            .iter()
            .map(|&s| {
                let z = 200.0 * (s - 0.5f64).max(0.0).powi(2);
                (
                    40.0,
                    (100.0 * (20.0 + z / (1.0 + bend * z))).round() / 100.0,
                )
            })
            .collect();
        (t, xy)
    }

    #[test]
    fn a_fall_seen_in_perspective_gives_its_release_through_the_bend() {
        let (t, xy) = foreshortened(0.01);
        let f = acceleration(&t, &xy, None).unwrap();
        let vertex = f.value("vertex").unwrap().value;
        assert!((vertex - 0.5).abs() < 0.003, "{f:?}");
        assert!(
            (f.value("acceleration").unwrap().value - 400.0).abs() < 20.0,
            "{f:?}"
        );
        assert!(f.value("bend").unwrap().value < -50.0, "{f:?}");
        assert!(f.rms() < 0.05, "{f:?}");
        // The plain parabola alone puts the release frames early.
        let (cols, y) = (
            vec![
                vec![1.0; t.len()],
                t.clone(),
                t.iter().map(|s| s * s).collect::<Vec<f64>>(),
            ],
            xy.iter().map(|p| p.1).collect::<Vec<f64>>(),
        );
        let (c, _) = linear(&cols, &y).unwrap();
        assert!(0.5 + c[1] / (2.0 * c[2]) > 0.03, "{c:?}");
    }

    #[test]
    fn a_half_of_a_bent_fall_holds_its_bend() {
        let (t, xy) = foreshortened(0.01);
        let whole = acceleration(&t, &xy, None).unwrap();
        let a = whole.value("acceleration").unwrap().value;
        // Each half, too short for a bend of its own, read through the whole's: the same
        // acceleration at the vertex, where a plain parabola on the later half gives far less.
        for (from, to) in [(0, 18), (18, 36)] {
            let half = acceleration(&t[from..to], &xy[from..to], Some(whole.shape)).unwrap();
            let h = half.value("acceleration").unwrap().value;
            assert!((h / a - 1.0).abs() < 0.02, "{half:?}");
            assert_eq!(half.shape[0], whole.shape[0]);
        }
        let plain = acceleration(&t[18..36], &xy[18..36], None).unwrap();
        assert!(
            plain.value("acceleration").unwrap().value < 0.5 * a,
            "{plain:?}"
        );
    }

    #[test]
    fn a_fall_seen_square_on_keeps_the_plain_parabola() {
        let (t, xy) = foreshortened(0.0);
        let f = acceleration(&t, &xy, None).unwrap();
        assert_eq!(f.value("bend"), None, "{f:?}");
        assert!(
            (f.value("vertex").unwrap().value - 0.5).abs() < 0.003,
            "{f:?}"
        );
    }
}
