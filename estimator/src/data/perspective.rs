//! A fall or slide from rest seen in perspective. A camera tilted to the plane of the motion
//! (or an object nearer than the wall it is seen against) draws equal steps of the path as
//! unequal steps in the picture: the position along the picture's line is a projective map of
//! the position along the path, p = (α·z + β)/(1 + γ·z). From rest, z ∝ (t − r)², so the
//! picture shows p(t) = c + s·v/(1 + b·v) with v = (t − r)² after the release r. Fitted to a
//! whole descent, this gives the release (the parabola's vertex read through the bend) and the
//! map that undoes the bend (`Bend::per_pixel`), which the centroid encoder applies to its
//! positions (`encoder::centroid::Line`). Measured on the shared ball (a 10° tilt, the ball
//! nearer than the wall): the plain parabola leaves residuals 2.5 times larger, smooth in time
//! (autocorrelation 0.92, against 0.41), and puts the release five frames early.

use serde::Serialize;

/// Fewest frames of a descent whose bend is fitted (the bend and the release trade off on
/// short ones).
pub(crate) const MIN_FRAMES: usize = 24;
/// How much smaller than the plain parabola's the bent one's residuals must be to be kept
/// (a path drawn without perspective fits both alike: one more parameter takes a few % off).
pub(crate) const MIN_GAIN: f64 = 1.5;
/// The least the map's denominator may come to over the path against its most (no pole near
/// the frame; the picture's scale changing at most tenfold along the path).
pub(crate) const LEAST_DENOMINATOR: f64 = 0.3;

/// A whole descent fitted: its release, and its bend where one shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fitted {
    /// The release, in frames.
    pub release: f64,
    pub bend: Option<Bend>,
}

/// The bend of a descent's path.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Bend {
    /// The picture's scale along the path at its end against at its start, minus one (the
    /// shared ball: the last metre of the fall drawn smaller).
    pub change: f64,
    /// κ per pixel along the path: the path's true position is affine in p/(1 + κ·p).
    pub per_pixel: f64,
}

/// One fit of the path at release `r` and bend `b`: (rms residual, c, s).
fn at(path: &[(f64, f64)], r: f64, b: f64) -> Option<(f64, f64, f64)> {
    let (mut n, mut su, mut sp, mut suu, mut sup) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for &(k, p) in path {
        let v = (k - r).max(0.0).powi(2);
        let u = v / (1.0 + b * v);
        n += 1.0;
        su += u;
        sp += p;
        suu += u * u;
        sup += u * p;
    }
    let det = n * suu - su * su;
    if det.abs() < 1e-12 {
        return None;
    }
    let s = (n * sup - su * sp) / det;
    let c = (sp - s * su) / n;
    let ss: f64 = path
        .iter()
        .map(|&(k, p)| {
            let v = (k - r).max(0.0).powi(2);
            (c + s * v / (1.0 + b * v) - p).powi(2)
        })
        .sum();
    Some(((ss / n).sqrt(), c, s))
}

/// The best (rms, release, b, c, s) over a grid of releases in `releases` at steps of `step`
/// frames and bends with b·V in `bends` (V the largest v).
fn best(
    path: &[(f64, f64)],
    (releases, step): ((f64, f64), f64),
    bends: &[f64],
) -> Option<(f64, f64, f64, f64, f64)> {
    let last = path.last()?.0;
    let mut out: Option<(f64, f64, f64, f64, f64)> = None;
    let steps = ((releases.1 - releases.0) / step).ceil().max(1.0) as usize;
    for i in 0..=steps {
        let r = releases.0 + (releases.1 - releases.0) * i as f64 / steps as f64;
        let big_v = (last - r).max(1.0).powi(2);
        for &bv in bends {
            let b = bv / big_v;
            if let Some((e, c, s)) = at(path, r, b) {
                if out.is_none_or(|o| e < o.0) {
                    out = Some((e, r, b, c, s));
                }
            }
        }
    }
    out
}

/// The release and the bend of `path` (frame, pixels along the path, from its first frame that
/// moves to the end of the descent), released at or before frame `first_moving`; `None` where
/// the path is too short to fit whole. The bend is kept where it fits the path
/// `MIN_GAIN` times better than a plain parabola; the release is the bent fit's either way
/// (a whole path places it better than its first part: on a level 60-fps fall drawn here with
/// a hand's wobble before the release, 1.2 frames nearer).
pub fn fit(path: &[(f64, f64)], first_moving: f64) -> Option<Fitted> {
    if path.len() < MIN_FRAMES {
        return None;
    }
    let span = path.last()?.0 - first_moving;
    let releases = (first_moving - 0.3 * span, first_moving);
    let plain = best(path, (releases, 0.05), &[0.0])?;
    // b·V from −0.9 (no pole before the path's end) to 1.5 (the end drawn at a sixth of the
    // start's scale), then a finer grid about the best.
    let bends: Vec<f64> = (-36..=60).map(|i| i as f64 * 0.025).collect();
    let (_, r, b, ..) = best(path, (releases, 0.05), &bends)?;
    let big_v = (path.last()?.0 - r).max(1.0).powi(2);
    let finer: Vec<f64> = (-10..=10)
        .map(|i| b * big_v + i as f64 * 0.0025)
        .filter(|bv| *bv > -0.95)
        .collect();
    let near = ((r - 0.05).max(releases.0), (r + 0.05).min(releases.1));
    let (e, release, b, c, s) = best(path, (near, 0.005), &finer)?;
    // p = c + s·w with w = v/(1 + b·v), so v = w/(1 − b·w): affine in p/(1 + κ·p) with
    // κ = −b/(s + b·c).
    let per_pixel = -b / (s + b * c);
    let den = |p: f64| 1.0 + per_pixel * p;
    let lo = path.iter().map(|q| den(q.1)).fold(f64::INFINITY, f64::min);
    let hi = path
        .iter()
        .map(|q| den(q.1))
        .fold(f64::NEG_INFINITY, f64::max);
    if !per_pixel.is_finite() || lo <= 0.0 || lo < LEAST_DENOMINATOR * hi {
        // A pole near the frame: not a camera's bend; the plain parabola's release.
        return Some(Fitted {
            release: plain.1,
            bend: None,
        });
    }
    // The picture's scale dp/dz ∝ den(p)²; at the path's end against its start.
    let (p0, p1) = (path[0].1, path.last()?.1);
    let change = (den(p1) / den(p0)).powi(2) - 1.0;
    let shows = e * MIN_GAIN <= plain.0 && b != 0.0;
    Some(Fitted {
        release,
        bend: shows.then_some(Bend { change, per_pixel }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fall released at frame 20.3, z = (k − r)², seen through p = 40 + 0.5·z/(1 + b·z) and
    /// rounded to a tenth of a pixel.
    fn bent(b: f64) -> Vec<(f64, f64)> {
        (22..80)
            .map(|k| {
                let z = (k as f64 - 20.3).powi(2);
                let p = 40.0 + 0.5 * z / (1.0 + b * z);
                (k as f64, (p * 10.0).round() / 10.0)
            })
            .collect()
    }

    #[test]
    fn a_bent_fall_gives_its_release_and_the_map_that_straightens_it() {
        // The end drawn at 0.35 of the start's scale.
        let path = bent(0.0002);
        let fitted = fit(&path, 22.0).expect("a fit");
        assert!((fitted.release - 20.3).abs() < 0.15, "{fitted:?}");
        let f = fitted.bend.expect("a bend");
        // Straightened, the path is a parabola in time again.
        let straight: Vec<(f64, f64)> = path
            .iter()
            .map(|&(k, p)| (k, p / (1.0 + f.per_pixel * p)))
            .collect();
        let r = fitted.release;
        let (e, ..) = best(&straight, ((r, r), 1.0), &[0.0]).unwrap();
        let range = straight.last().unwrap().1 - straight[0].1;
        assert!(e < 2e-3 * range.abs(), "rms {e} of {range}");
        assert!(f.change < -0.2, "{f:?}");
    }

    #[test]
    fn a_fall_drawn_without_perspective_has_no_bend_and_its_release() {
        let level = fit(&bent(0.0), 22.0).expect("a fit");
        assert_eq!(level.bend, None);
        assert!((level.release - 20.3).abs() < 0.15, "{level:?}");
        assert_eq!(fit(&bent(0.0002)[..20], 22.0), None);
    }
}
