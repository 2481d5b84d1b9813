//! The swing in angles: where the track swings about a pivot (`laws::swing`), the angle of its
//! fitted path from the rest at samples of its span, in radians: the readings the latent
//! route's pendulum is calibrated by (its angle scale), in place of angles typed with
//! `--reference`.

use super::laws::swing::circle;
use super::laws::TrackLaw;
use super::metres::READINGS;
use super::{LawSpan, TrackRoute};

impl TrackRoute {
    /// The readings the swing `l` gives the latent's pendulum: at [`READINGS`] samples spread
    /// evenly over it short of its last (as `readings` picks a stick's), each the sample's
    /// time on the file's own timeline and the swing's fitted angle there from its rest
    /// (radians: the track's angle about the pivot of the span's circle, less its residual
    /// along the arc, less the rest `laws::swing` fitted). Empty for any other law.
    pub fn angles(&self, l: &LawSpan) -> Vec<(f64, f64)> {
        let rest = l.values.iter().find(|v| v.name == "rest");
        let (TrackLaw::Swing, Some(rest)) = (l.law, rest) else {
            return Vec::new();
        };
        let t = &self.track;
        let span = l.first..l.first + l.samples;
        let xy: Vec<(f64, f64)> = match t.on_plane.is_empty() {
            true => span.clone().map(|i| (t.x[i], t.y[i])).collect(),
            false => t.on_plane[span.clone()].to_vec(),
        };
        let Some(((cx, cy), radius)) = circle(&xy) else {
            return Vec::new();
        };
        let n = l.samples.saturating_sub(1);
        let k = READINGS.min(n);
        (0..k)
            .map(|j| j * (n - 1) / (k - 1).max(1))
            .map(|j| {
                let (x, y) = xy[j];
                // The curve is the position along the axis less the arc's residual.
                let residual = t.along[l.first + j] - l.curve.get(j).copied().unwrap_or(0.0);
                let theta = (x - cx).atan2(y - cy) - residual / radius;
                (t.file_s[l.first + j], theta - rest.value.to_radians())
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::track::laws::TrackLaw;
    use crate::track::reading::{route_of, Clock, Reading};
    use crate::track::template::Match;

    #[test]
    fn a_swing_s_angles_are_read_from_its_rest() {
        // θ = 0.25 cos(4 t) + 0.1 rad about a pivot at (200, 20), 300 px below it, 30 fps for
        // 4 s: a camera rolled by 0.1 rad, so the rest is 0.1 rad off the picture's vertical.
        let t: Vec<f64> = (0..120).map(|i| i as f64 / 30.0).collect();
        let theta = |s: f64| 0.25 * (4.0 * s).cos() + 0.1;
        let matches: Vec<(usize, Match)> = t
            .iter()
            .enumerate()
            .map(|(k, &s)| {
                let (x, y) = (
                    200.0 + 300.0 * theta(s).sin(),
                    20.0 + 300.0 * theta(s).cos(),
                );
                // `route_of` reads pixel centres.
                let (x, y) = (x - 0.5, y - 0.5);
                (k, Match { x, y, score: 1.0 })
            })
            .collect();
        let clock = Clock::shown(&t, (400, 400), 100.0);
        let route = route_of(&matches, Reading::Centroids, 10.0, &clock, t.len(), 10.0).unwrap();
        let l = route
            .laws
            .iter()
            .find(|l| l.law == TrackLaw::Swing)
            .unwrap();
        let angles = route.angles(l);
        assert_eq!(angles.len(), crate::track::metres::READINGS);
        for (at, a) in angles {
            assert!((a - (theta(at) - 0.1)).abs() < 2e-3, "{at}: {a}");
        }
        // An oscillation gives none.
        let o = route
            .laws
            .iter()
            .find(|l| l.law == TrackLaw::Oscillation)
            .unwrap();
        assert!(route.angles(o).is_empty());
    }
}
