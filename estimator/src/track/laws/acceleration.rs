//! A constant acceleration in the picture's plane, p0 + v0 t + a t²/2 in x and y (a fall, a
//! toss, a roll; the release's velocity free): two linear fits, and the vertex along the
//! acceleration (the release of a motion from rest, found rather than assumed). Seen in
//! perspective (a camera tilted to the path), the path along the acceleration is a projective
//! map of the parabola (`bent`): on a span long enough, that bend is fitted too, and kept where
//! it fits the path along the acceleration that much better; the vertex and the acceleration
//! are then read through it. From rest (`released`), the same read through a release before
//! which the object is still.

use super::bent::bent;
use super::{covariance, linear, Fitted, Value};
use crate::data::perspective::MIN_FRAMES;

/// A parabola fitted to positions in x and y, plain (not bent): what `finish` reads.
pub(super) struct Plain {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// The residuals in x and in y.
    pub rx: Vec<f64>,
    pub ry: Vec<f64>,
    /// The acceleration in x and y, and their variances.
    pub a: (f64, f64),
    pub a_var: (f64, f64),
    /// The vertex (release or apex, s) and its standard error.
    pub vertex: (f64, f64),
}

/// The constant acceleration fitted to the picture positions `xy` at times `t`: its size (px/s²
/// of the displayed frame) and direction.
/// Where `near` is the shape of a bent fit (its bend and vertex, `Fitted::shape`) and the span
/// is too short to fit a bend of its own (a half of a bent span), the bend is held at `near`'s.
pub(super) fn acceleration(t: &[f64], xy: &[(f64, f64)], near: Option<[f64; 2]>) -> Option<Fitted> {
    finish(t, plain(t, xy)?, near, false)
}

/// p0 + v0 t + a t²/2 fitted to `xy` at times `t` in x and in y.
fn plain(t: &[f64], xy: &[(f64, f64)]) -> Option<Plain> {
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
    let a_err = size_error((ax, ay), (vx, vy));
    let (dx, dy) = direction((ax, ay));
    // The vertex along the acceleration: where the velocity along it is zero (a release from
    // rest, a toss's apex), t0 − v/a, its error from the velocity's and the acceleration's.
    let v = cx[1] * dx + cy[1] * dy;
    let v_var = dx * dx * covx[4] + dy * dy * covy[4];
    let vertex = if a > 0.0 {
        (
            t0 - v / a,
            (v_var / (a * a) + (v * v / (a * a * a * a)) * a_err * a_err).sqrt(),
        )
    } else {
        (f64::NAN, f64::INFINITY)
    };
    Some(Plain {
        x,
        y,
        rx,
        ry,
        a: (ax, ay),
        a_var: (vx, vy),
        vertex,
    })
}

/// The unit vector along the acceleration `(ax, ay)` (down the picture where it is none).
fn direction((ax, ay): (f64, f64)) -> (f64, f64) {
    let a = ax.hypot(ay);
    if a > 0.0 {
        (ax / a, ay / a)
    } else {
        (0.0, 1.0)
    }
}

/// The standard error of the size of the acceleration `(ax, ay)` whose parts have variances
/// `(vx, vy)`.
fn size_error((ax, ay): (f64, f64), (vx, vy): (f64, f64)) -> f64 {
    let a = ax.hypot(ay);
    if a > 0.0 {
        ((ax * ax * vx + ay * ay * vy) / (a * a)).sqrt()
    } else {
        vx.max(vy).sqrt()
    }
}

/// The law's values from the plain fit `p` at times `t`: through its bend where one fits
/// (`bent`, from rest where `from_rest`), else the plain parabola's.
pub(super) fn finish(
    t: &[f64],
    p: Plain,
    near: Option<[f64; 2]>,
    from_rest: bool,
) -> Option<Fitted> {
    let n = t.len();
    let Plain {
        x,
        y,
        rx,
        ry,
        a: (ax, ay),
        a_var: (vx, vy),
        vertex: (vertex, vertex_err),
    } = p;
    let a = ax.hypot(ay);
    let a_err = size_error((ax, ay), (vx, vy));
    let (dx, dy) = direction((ax, ay));
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
            let bend = held.map(|s| s[0]);
            if let Some(mut bent) = bent(t, &along, (from, &plain), bend, from_rest) {
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
