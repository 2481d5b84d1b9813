//! The swing read by its rod: where the thing followed is a long blob (a rod, or a string with
//! its bob) moving on an arc below a pivot, each sighting's angle about the pivot is its blob's
//! long axis, which a shaking camera does not turn (it moves the whole picture, the centroid
//! with it, by pixels); the pivot is where the axes meet, and each sighting is put on the
//! circle about it at its axis's angle. A reading of its own beside the centroids': the law
//! that holds longer chooses between them, and of readings alike, this one (`object::chosen`).

use super::blobs::Blob;
use super::link::Tracklet;
use super::reading::{alike_in_size, WHOLE};
use super::template::Match;

/// A blob has a direction where its second moment along its long axis is at least this many
/// times the one across it: a bar twice as long as it is wide ((L/W)² = 4). A disc's ratio is 1
/// and its axis is its pixels' noise.
const ELONGATED: f64 = 4.0;

/// The middle of `values` (the upper one of an even count); `None` where there are none.
fn median(mut values: Vec<f64>) -> Option<f64> {
    let mid = values.len() / 2;
    (!values.is_empty()).then(|| *values.select_nth_unstable_by(mid, f64::total_cmp).1)
}

/// The point nearest every blob's axis, the line through its centroid along its long axis (least
/// squares: Σ nnᵀ p = Σ nnᵀ c, n each axis's normal): the pivot a rod turns about, which a
/// shaking camera moves with the rod, so that the lines meet there as nearly as the shake is
/// small against the rod. `None` where the axes are too nearly parallel to meet.
fn pivot(sightings: &[(usize, Match)], blobs: &[&Blob]) -> Option<(f64, f64)> {
    let (mut a, mut b) = ([0.0; 3], [0.0; 2]);
    for ((_, m), blob) in sightings.iter().zip(blobs) {
        let (nx, ny) = (-blob.axis.sin(), blob.axis.cos());
        let along = nx * m.x + ny * m.y;
        a[0] += nx * nx;
        a[1] += nx * ny;
        a[2] += ny * ny;
        b[0] += nx * along;
        b[1] += ny * along;
    }
    let det = a[0] * a[2] - a[1] * a[1];
    // The normals' spread: det / trace² is sin² of their angles' spread, near 0 for parallel.
    if det <= 1e-6 * (a[0] + a[2]).powi(2) {
        return None;
    }
    Some((
        (a[2] * b[0] - a[1] * b[1]) / det,
        (a[0] * b[1] - a[1] * b[0]) / det,
    ))
}

/// The `sightings` of `tracklet` (its centroids, frame by frame) read by their blobs' long axes:
/// each put at their mean distance from the pivot (`pivot`) along its blob's axis (turned to
/// point from the pivot towards the sighting). Only those whose region (the rod with its bob,
/// before the opening) is whole are kept: within [`WHOLE`] of its usual size. The opening
/// breaks a thin rod into pieces at some of its tilts, leaving its bob's blob alone, smaller
/// than usual, while the region, and the axis read from it, stay whole; a hand or clutter
/// merged with the rod makes the region larger. `None` where the blobs are not long (their
/// median [`ELONGATED`]), their axes meet at no pivot above the whole path, or a sighting's
/// blob is not the tracklet's.
pub(super) fn rod(
    sightings: &[(usize, Match)],
    tracklet: &Tracklet,
) -> Option<Vec<(usize, Match)>> {
    let blobs: Vec<&Blob> = sightings
        .iter()
        .map(|(k, _)| {
            let i = tracklet.frames.binary_search(k).ok()?;
            tracklet.blobs.get(i)
        })
        .collect::<Option<_>>()?;
    let usual = median(blobs.iter().map(|b| b.region_area).collect())?;
    let (sightings, blobs): (Vec<(usize, Match)>, Vec<&Blob>) = sightings
        .iter()
        .zip(blobs)
        .filter(|(_, b)| alike_in_size(b.region_area, usual) >= WHOLE)
        .map(|(s, b)| (*s, b))
        .unzip();
    if median(blobs.iter().map(|b| b.elongation).collect())? < ELONGATED {
        return None;
    }
    let (cx, cy) = pivot(&sightings, &blobs)?;
    // The pivot above the whole path (the picture's y runs down), as a swing's.
    if sightings.iter().any(|(_, m)| m.y <= cy) {
        return None;
    }
    // The radius: the sightings' mean distance from the pivot.
    let radius = sightings
        .iter()
        .map(|(_, m)| (m.x - cx).hypot(m.y - cy))
        .sum::<f64>()
        / sightings.len() as f64;
    Some(
        sightings
            .iter()
            .zip(blobs)
            .map(|((k, m), b)| {
                let (mut vx, mut vy) = (b.axis.cos(), b.axis.sin());
                if vx * (m.x - cx) + vy * (m.y - cy) < 0.0 {
                    (vx, vy) = (-vx, -vy);
                }
                let on = Match {
                    x: cx + radius * vx,
                    y: cy + radius * vy,
                    score: m.score,
                };
                (*k, on)
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::laws::swing::circle;
    use crate::track::laws::TrackLaw;
    use crate::track::reading::{readings, Clock, Reading};
    use crate::track::{object::chosen, TrackRoute};
    use physvid_shared::video::SmallFrames;

    /// The swing's angle at frame `k` (radians from the vertical).
    fn theta(k: usize) -> f64 {
        0.6 * (k as f64 * 0.2).cos()
    }

    /// A rod swinging about (50, 10), 40 px long, its centroid 30 px below the pivot, seen by
    /// a camera that shakes by up to ±3 px: the centroids wander, the axes do not.
    fn swinging(k: usize) -> Blob {
        let (s, c) = theta(k).sin_cos();
        let (dx, dy) = (3.0 * (k as f64 * 2.7).sin(), 3.0 * (k as f64 * 1.9).cos());
        Blob {
            area: 60.0,
            x: 50.0 + 30.0 * s + dx,
            y: 10.0 + 30.0 * c + dy,
            // The axis from the picture's x: the rod points down at θ from the vertical.
            axis: (c).atan2(s),
            elongation: 12.0,
            region_area: 60.0,
        }
    }

    /// Each blob's sighting at its centroid.
    fn sighted(frames: &[usize], blobs: &[Blob]) -> Vec<(usize, Match)> {
        frames
            .iter()
            .zip(blobs)
            .map(|(&k, b)| {
                let m = Match {
                    x: b.x,
                    y: b.y,
                    score: 1.0,
                };
                (k, m)
            })
            .collect()
    }

    #[test]
    fn a_shaken_rod_is_read_on_its_circle_at_its_axis() {
        let frames: Vec<usize> = (0..40).collect();
        let blobs: Vec<Blob> = frames.iter().map(|&k| swinging(k)).collect();
        let sightings = sighted(&frames, &blobs);
        let tracklet = Tracklet { frames, blobs };
        let read = rod(&sightings, &tracklet).unwrap();
        let ((cx, cy), _) =
            circle(&read.iter().map(|(_, m)| (m.x, m.y)).collect::<Vec<_>>()).unwrap();
        for (k, m) in &read {
            let at = (m.x - cx).atan2(m.y - cy);
            assert!(
                (at - theta(*k)).abs() < 1e-9,
                "frame {k}: {at} for {}",
                theta(*k)
            );
        }
        // Round blobs give no direction.
        let round = Tracklet {
            frames: tracklet.frames.clone(),
            blobs: tracklet
                .blobs
                .iter()
                .map(|b| Blob::round(b.area, b.x, b.y))
                .collect(),
        };
        assert!(rod(&sightings, &round).is_none());
    }

    /// A rod the opening broke at some tilts, its blob there its bob's alone (half its usual
    /// area, centred further out), is read in every frame, its region being whole; a frame
    /// whose region merged with a hand (twice its size, its axis turned) is left out.
    #[test]
    fn a_rod_broken_by_the_opening_is_read_and_one_merged_with_a_hand_is_not() {
        let frames: Vec<usize> = (0..40).collect();
        let blobs: Vec<Blob> = frames
            .iter()
            .map(|&k| {
                let mut b = swinging(k);
                if k % 3 == 0 {
                    let (s, c) = theta(k).sin_cos();
                    (b.area, b.x, b.y) = (30.0, b.x + 8.0 * s, b.y + 8.0 * c);
                }
                if k == 20 {
                    (b.region_area, b.axis) = (130.0, b.axis + 0.3);
                }
                b
            })
            .collect();
        let sightings = sighted(&frames, &blobs);
        let read = rod(&sightings, &Tracklet { frames, blobs }).unwrap();
        assert_eq!(read.len(), 39);
        assert!(read.iter().all(|(k, _)| *k != 20));
        let ((cx, cy), _) =
            circle(&read.iter().map(|(_, m)| (m.x, m.y)).collect::<Vec<_>>()).unwrap();
        for (k, m) in &read {
            let at = (m.x - cx).atan2(m.y - cy);
            assert!((at - theta(*k)).abs() < 1e-6, "frame {k}: {at}");
        }
    }

    /// A shaken camera's frames of a black rod and bob swinging as θ'' + 0.08 θ' + 4.0016 θ = 0
    /// from 60° (the others' rod and bob: 64×64 grey, 20 fps, the rod 26 px from a pivot at
    /// (32, 14) and one pixel wide, which the blobs' opening takes, the bob 5 px in radius), the
    /// whole picture moved by up to 2.5 px a frame.
    fn shaken_pendulum() -> (SmallFrames, Vec<f64>) {
        let (side, n, sub) = (64usize, 157usize, 4usize);
        let (g0, g1) = (4.0016f64, 0.08f64);
        let (z, w) = (g1 / 2.0, (g0 - g1 * g1 / 4.0).sqrt());
        let t: Vec<f64> = (0..n).map(|k| k as f64 / 20.0).collect();
        let mut pixels = Vec::with_capacity(side * side * n);
        for (k, &s) in t.iter().enumerate() {
            let th = 60f64.to_radians() * (-z * s).exp() * ((w * s).cos() + z / w * (w * s).sin());
            let (dx, dy) = (2.5 * (k as f64 * 2.7).sin(), 2.5 * (k as f64 * 1.9).cos());
            let (px, py) = (32.0 + dx, 14.0 + dy);
            let (bx, by) = (px + 26.0 * th.sin(), py + 26.0 * th.cos());
            let on = |x: f64, y: f64| {
                let (ux, uy) = (bx - px, by - py);
                let u = (((x - px) * ux + (y - py) * uy) / (26.0 * 26.0)).clamp(0.0, 1.0);
                let rod = (x - px - u * ux).hypot(y - py - u * uy) <= 0.5;
                rod || (x - bx).hypot(y - by) <= 5.0
            };
            for i in 0..side * side {
                let cover = (0..sub * sub)
                    .filter(|j| {
                        let x = (i % side) as f64 + (j % sub) as f64 / sub as f64 + 0.125;
                        let y = (i / side) as f64 + (j / sub) as f64 / sub as f64 + 0.125;
                        on(x, y)
                    })
                    .count() as f64
                    / (sub * sub) as f64;
                pixels.push((217.0 - 204.0 * cover).round() as u8);
            }
        }
        let frames = SmallFrames {
            pixels,
            size: (side, side),
        };
        (frames, t)
    }

    /// On the shaken pendulum the reading by the rod's axes is the one chosen, and its angle's
    /// oscillation gives γ0 and γ1 as rendered; the centroids, shaken by pixels, do not.
    #[test]
    fn a_shaken_pendulum_is_read_by_its_rod() {
        let (frames, t) = shaken_pendulum();
        let clock = Clock::shown(&t, (64, 64), 12.8);
        let all = readings(
            &frames,
            &crate::track::background::background(&frames),
            &clock,
        );
        let route = chosen(&all).unwrap();
        assert_eq!(route.track.reading, Reading::Rod);
        let l = route.chosen_span().unwrap();
        assert_eq!(l.law, TrackLaw::AngularOscillation);
        let value = |name: &str| l.values.iter().find(|v| v.name == name).unwrap().value;
        assert!(
            (value("gamma0") / 4.0016 - 1.0).abs() < 0.002,
            "{:?}",
            l.values
        );
        assert!(
            (value("gamma1") / 0.08 - 1.0).abs() < 0.03,
            "{:?}",
            l.values
        );
        // The centroids' readings of the same frames wander with the camera by pixels.
        let centroids = |c: &&TrackRoute| c.track.reading == Reading::Centroids;
        let same: Vec<&TrackRoute> = all
            .iter()
            .filter(centroids)
            .filter(|c| route.same_thing(c))
            .collect();
        assert!(!same.is_empty());
        for c in same {
            assert!(c.track.noise > 10.0 * route.track.noise, "{}", c.line());
        }
    }
}
