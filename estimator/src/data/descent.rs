//! A fall or slide from rest found in a recording's frames: the object's path (the centroid
//! encoder's position, `encoder::centroid`), the release as the vertex of the parabola it
//! traces, and the end of the descent (where the object stops moving away: an impact, a
//! bounce, the edge of the frame), its path's bend by perspective where it shows
//! (`perspective`). Systems released from rest read their clips' start times from the release,
//! and the recording is trimmed to the descent (`kept::trim_to_descent`) where `--start`/`--end`
//! do not say otherwise.

use super::crowd::{crowded, EARLY};
use super::perspective::{self, Bend};
use super::swing;
use crate::encoder::centroid::{self, Line};
use serde::Serialize;
use tch::Tensor;

/// An object that moves less than this share of the larger frame side is not a descent
/// across the frame (a ball receding from the camera, a dimming light).
pub const MIN_TRAVEL: f64 = 0.1;

/// Frames at rest kept before the release, as a share of the descent's frames (the clips'
/// rollout holds them at rest; a reference taken at rest stays in the part kept).
const REST_MARGIN: f64 = 0.1;

/// The share of the step its two frames before predict under which the descent's last frame
/// holds the impact (the object met the floor between it and the frame before: a fall drawn
/// to a floor at 1.2 m, 60 fps, had its release 0.6 frame late and g 1.4 % high with that
/// frame in, 0.1 frame and −0.8 % without; tilted, g +5 % against +0.4–1.3 %).
const IMPACT: f64 = 0.75;

/// A descent found in the frames.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Descent {
    /// The release, in frames of the decoded recording (fractional: the parabola's vertex).
    pub release: f64,
    /// The first and last frames of the descent kept (a few frames at rest before the release,
    /// the last frame before the object stops moving away).
    pub first: usize,
    pub last: usize,
    /// How far the object travels, as a share of the larger frame side.
    pub travel: f64,
    /// The path's bend by perspective, where it shows (`perspective`): the release is then
    /// the bent parabola's.
    pub bend: Option<Bend>,
    /// The path's direction in the frame (x, y), and how the centroid encoder reads positions
    /// along it: a (in its units, half the larger side from the centre) as a/(1 + bend·a),
    /// the bend by perspective undone (0 without one).
    pub line: Line,
    /// The share of the early frames (the first 30 % of the way, where the release is read)
    /// on which what is measured spreads over 1.3× as far as later: something else moves or
    /// differs where the object starts (the shared ball: the hand that held it opening beside
    /// it), which pulls those positions and the release with them (0 for the track's release).
    pub crowded: f64,
    /// Whether the release was read on the object's path in colour (`tinted`: the grey
    /// difference was crowded where it starts, and its colour tells it apart) rather than on
    /// its grey difference's.
    pub colour: bool,
    /// A toss's rise seen by the track (`TrackedMotion::moving_before`): the law holds on both
    /// sides of the vertex, the part kept from the track's span's start, not at rest.
    pub rising: bool,
}

impl Descent {
    /// The descent released at frame `release`, with the frames at rest kept before it.
    pub fn released_at(self, release: f64) -> Descent {
        let frames = self.last as f64 - release;
        let first = (release - REST_MARGIN * frames).floor().max(0.0) as usize;
        Descent {
            release,
            first,
            ..self
        }
    }
}

/// The positions the grey difference found, (frame, [x, y] in pixels from the frame's centre):
/// the frames where something moves clearly.
pub type Seen = Vec<(usize, [f64; 2])>;

/// The descent in frames `[F, H·W]` of `size` = (W, H), or `None` when no object crosses
/// the frame from rest, or what does comes back to where it began and swings (`swing`); with
/// the positions it was read from.
pub fn find(frames: &[f32], size: (usize, usize)) -> Option<(Descent, Seen)> {
    let (w, h) = (size.0 as i64, size.1 as i64);
    let n = frames.len() as i64 / (w * h);
    if n < 8 {
        return None;
    }
    let frame = (1, h, w);
    let (path, spread, peak) = tch::no_grad(|| {
        let x = Tensor::from_slice(frames).view([n, h * w]);
        // Against the median frame (the background, where the object spends under half its
        // time); found where the frame differs from one `lag` frames earlier (what moves now,
        // not what was moved once and stays: a hand, a door).
        let (d, polarity, window) = centroid::from_background(&x, frame);
        let lag = (n / 40).max(1);
        let earlier = Tensor::cat(&[d.narrow(0, 0, lag), d.narrow(0, 0, n - lag)], 0);
        let moved = &d - earlier;
        let peak = (&moved * polarity).amax(1, false);
        let (path, spread) = centroid::located(&moved, &d, frame, polarity, window);
        (path, spread, peak)
    });
    let half = (w.max(h) as f64) / 2.0;
    let p: Vec<f64> = Vec::<f32>::try_from(path.reshape([-1]))
        .ok()?
        .into_iter()
        .map(|v| f64::from(v) * half)
        .collect();
    let spread: Vec<f64> = Vec::<f32>::try_from(spread)
        .ok()?
        .into_iter()
        .map(f64::from)
        .collect();
    let peak: Vec<f64> = Vec::<f32>::try_from(peak)
        .ok()?
        .into_iter()
        .map(f64::from)
        .collect();
    // Frames where something moves clearly (a peak at least 0.4 of the 90th percentile's).
    let mut sorted = peak.clone();
    sorted.sort_by(f64::total_cmp);
    let strong = 0.4 * sorted[sorted.len() * 9 / 10];
    let seen: Seen = (0..n as usize)
        .filter(|&k| peak[k] >= strong && peak[k] > 0.0)
        .map(|k| (k, [p[2 * k], p[2 * k + 1]]))
        .collect();
    let (path, axis) = project(&seen)?;
    let d = along(&path, axis, 2.0 * half)?;
    if swing::swings(&path, d.last) {
        return None;
    }
    let d = Descent {
        crowded: crowded(&path, &spread, d.last),
        ..d
    };
    Some((d, seen))
}

/// A path: (frame, pixels along it).
pub(super) type Path = Vec<(usize, f64)>;

/// Positions `seen` (frame, [x, y]) projected on their principal axis, oriented so that the
/// first half of them moves forward: (frame, pixels along the path), and the axis.
fn project(seen: &[(usize, [f64; 2])]) -> Option<(Path, [f64; 2])> {
    if seen.len() < 5 {
        return None;
    }
    let m = seen.len() as f64;
    let mean = seen
        .iter()
        .fold([0.0, 0.0], |a, (_, q)| [a[0] + q[0] / m, a[1] + q[1] / m]);
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for (_, q) in seen {
        let (dx, dy) = (q[0] - mean[0], q[1] - mean[1]);
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    // The covariance's leading eigenvector.
    let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let u = [angle.cos(), angle.sin()];
    let along: Vec<(usize, f64)> = seen
        .iter()
        .map(|(k, q)| (*k, q[0] * u[0] + q[1] * u[1]))
        .collect();
    let mid = along.len() / 2;
    let sign = if along[mid].1 >= along[0].1 {
        1.0
    } else {
        -1.0
    };
    Some((
        along.into_iter().map(|(k, v)| (k, sign * v)).collect(),
        u.map(|c| c * sign),
    ))
}

/// The descent in `path` (frame, position along the path in pixels, time order; the path's
/// direction `axis`) on a frame whose larger side is `side` pixels.
pub(super) fn along(path: &[(usize, f64)], axis: [f64; 2], side: f64) -> Option<Descent> {
    let lo = path.iter().map(|q| q.1).fold(f64::INFINITY, f64::min);
    let hi = path.iter().map(|q| q.1).fold(f64::NEG_INFINITY, f64::max);
    if hi - lo < MIN_TRAVEL * side {
        return None;
    }
    // What moves the other way before the descent (a hand pulled back as it lets go, seen
    // first) is not part of it: the descent starts at the nearest point before the furthest.
    let furthest = path
        .iter()
        .enumerate()
        .max_by(|a, b| a.1 .1.total_cmp(&b.1 .1))
        .map_or(0, |(i, _)| i);
    let start = path[..=furthest]
        .iter()
        .enumerate()
        .min_by(|a, b| a.1 .1.total_cmp(&b.1 .1))
        .map_or(0, |(i, _)| i);
    let path = &path[start..];
    // The end: the furthest point before the object first comes back (by more than 2 % of
    // its travel): an impact, a bounce, a stop.
    let tol = 0.02 * (hi - lo);
    let mut top = f64::NEG_INFINITY;
    let back = path
        .iter()
        .position(|q| {
            top = top.max(q.1);
            q.1 < top - tol
        })
        .unwrap_or(path.len());
    let out = &path[..back];
    let far = out.iter().map(|q| q.1).fold(f64::NEG_INFINITY, f64::max);
    let mut end = out.iter().position(|q| q.1 >= far - tol / 2.0)?;
    let (first_k, first_p) = out[0];
    // An impact: past a third of the way, a step per frame under half the one before it, or
    // frames where the object no longer moves clearly (at rest on the floor: a falling object
    // moves in every frame).
    let step = |i: usize| (out[i].1 - out[i - 1].1) / (out[i].0 - out[i - 1].0) as f64;
    if let Some(i) = (2..=end)
        .filter(|&i| out[i - 1].1 - first_p > (far - first_p) / 3.0)
        .find(|&i| step(i) < 0.5 * step(i - 1) || out[i].0 - out[i - 1].0 > 2)
    {
        end = i - 1;
    }
    // The impact's own frame: the object meets the floor between two frames, so the last one
    // falls short of its path (a step under [`IMPACT`] of the one the two before predict).
    if end >= 3 && out[end - 1].1 - first_p > (far - first_p) / 3.0 {
        let predicted = 2.0 * step(end - 1) - step(end - 2);
        if step(end) < IMPACT * predicted {
            end -= 1;
        }
    }
    let last = out[end].0;
    let reach = out[end].1 - first_p;
    if reach < MIN_TRAVEL * side {
        return None;
    }
    // The release: on a descent long enough, the vertex of the parabola through all of it seen
    // through a projective bend (`perspective`); on a short one, the vertex of the parabola
    // through its first part (the least extrapolated: perspective and drag bend the later).
    let early: Vec<(f64, f64)> = out[..=end]
        .iter()
        .filter(|q| q.1 - first_p <= EARLY * reach)
        .map(|q| (q.0 as f64, q.1))
        .collect();
    let fit = if early.len() >= 4 {
        early
    } else {
        out[..=end].iter().map(|q| (q.0 as f64, q.1)).collect()
    };
    let [_, b, c] = physvid_shared::linalg::quadratic(&fit)?;
    if c <= 0.0 {
        return None;
    }
    let whole: Vec<(f64, f64)> = out[..=end].iter().map(|q| (q.0 as f64, q.1)).collect();
    let fitted = perspective::fit(&whole, first_k as f64);
    let bend = fitted.and_then(|f| f.bend);
    // A release before the recording's first frame (the object already moving when filming
    // began: a pipe let go a tenth of a second before) stands where the parabola puts it, as far
    // back as the projective fit looks (a third of the descent).
    let before = 0.3 * (last - first_k) as f64;
    let release = fitted
        .map_or(-b / (2.0 * c), |f| f.release)
        .clamp((first_k as f64 - before).min(0.0), first_k as f64);
    let d = Descent {
        release,
        first: 0,
        last,
        travel: (hi - lo) / side,
        bend,
        line: Line {
            axis,
            // κ in the centroid's units: half the larger side per unit.
            bend: bend.map_or(0.0, |b| b.per_pixel * side / 2.0),
        },
        crowded: 0.0,
        colour: false,
        rising: false,
    };
    Some(d.released_at(release))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fall_from_rest_is_found_with_its_release_and_its_impact() {
        // Seen moving from frame 33 (released at 30.4, 2 px/frame²), a bounce after 69.
        let release = 30.4;
        let mut path: Vec<(usize, f64)> = (33..70)
            .map(|k| {
                let t = k as f64 - release;
                (k, 100.0 + t * t + 0.05 * ((k * 7 % 5) as f64 - 2.0))
            })
            .collect();
        let top = path.last().unwrap().1;
        path.extend((0..10).map(|k| (70 + k, top - 30.0 * (k + 1) as f64)));
        let d = along(&path, [0.0, 1.0], 2000.0).expect("a descent");
        assert_eq!(d.last, 69);
        assert!((d.release - release).abs() < 0.3, "{}", d.release);
        assert!(d.first >= 25 && d.first <= 30, "{}", d.first);
    }

    #[test]
    fn the_frame_that_holds_the_impact_is_not_part_of_the_descent() {
        // Released at 30, 0.3 px/frame², on the floor at 150 px from frame 61.6: frame 62
        // shows it there, 3.6 px short of its path, and then at rest.
        let at = |k: f64| (0.15 * (k - 30.0).powi(2)).min(150.0);
        let path: Vec<(usize, f64)> = (32..75).map(|k| (k, at(k as f64))).collect();
        let d = along(&path, [0.0, 1.0], 1000.0).expect("a descent");
        assert_eq!(d.last, 61);
        assert!((d.release - 30.0).abs() < 0.1, "{}", d.release);
    }

    #[test]
    fn what_moves_back_before_the_descent_is_not_part_of_it() {
        // A hand pulled back 8 px over frames 20–24 as it lets go, then the fall from 25
        // (seen first: the hand, moving the other way; the descent had been cut there).
        let release = 25.0;
        let mut path: Vec<(usize, f64)> = (20..25).map(|k| (k, -2.0 * (k - 20) as f64)).collect();
        path.extend((26..60).map(|k| (k, -8.0 + (k as f64 - release).powi(2))));
        let d = along(&path, [0.0, 1.0], 2000.0).expect("a descent");
        assert_eq!(d.last, 59);
        // Its release no later than the first frame seen (the hand's last, frame 24).
        assert!((d.release - release).abs() <= 1.0, "{}", d.release);
    }

    #[test]
    fn an_object_already_moving_in_the_first_frame_was_released_before_it() {
        // Released at frame −3.6 (a pipe let go 0.12 s before filming began), 40 frames seen.
        let path: Vec<(usize, f64)> = (0..40).map(|k| (k, (k as f64 + 3.6).powi(2))).collect();
        let d = along(&path, [0.0, 1.0], 2000.0).expect("a descent");
        assert!((d.release + 3.6).abs() < 0.3, "{}", d.release);
        assert_eq!(d.first, 0);
    }

    #[test]
    fn a_small_motion_is_no_descent() {
        let path: Vec<(usize, f64)> = (0..50).map(|k| (k, 0.1 * k as f64)).collect();
        assert!(along(&path, [0.0, 1.0], 200.0).is_none());
    }

    #[test]
    fn the_path_is_projected_forward_on_its_axis() {
        let seen: Vec<(usize, [f64; 2])> = (0..10)
            .map(|k| (k, [5.0 - 0.6 * k as f64, 3.0 - 0.8 * k as f64]))
            .collect();
        let (p, _) = project(&seen).unwrap();
        assert!((p[9].1 - p[0].1 - 9.0).abs() < 1e-9, "{:?}", p);
    }
}
