//! Where the user read the motion: a `--reference` reading's time lies where the law holds, so
//! where the track's constant acceleration holds more than once (a ball's drop, then each
//! bounce's arc), the span kept is one the readings lie in, not the longest
//! (`TrackRoute::through_readings`); a route whose acceleration holds none of the readings
//! follows something else (`TrackRoute::holds_readings`).

use super::laws::TrackLaw;
use super::{fit, Reading, TrackRoute};

impl TrackRoute {
    /// The route with its chosen law's span, a constant acceleration's, grown from a window that
    /// holds one of the readings `times` ((seconds of the file's timeline, value)), where no
    /// reading lies in the span (give or take a sample: a reading at rest just before a
    /// release) and one lies within the track, and the law holds there too; as it was
    /// otherwise. Positions in the picture only: not a brightness, not the plane of a rectangle.
    pub fn through_readings(mut self, times: &[(f64, f64)]) -> TrackRoute {
        let t = &self.track;
        if t.reading == Reading::Brightness || !t.on_plane.is_empty() || t.file_s.len() < 2 {
            return self;
        }
        // A constant acceleration holds piecewise (a drop, then each bounce); an oscillation
        // or a swing holds over one stretch, which a reading taken elsewhere (the mass held
        // still before it was let go) only calibrates.
        let Some(l) = self
            .chosen_span()
            .filter(|l| l.law == TrackLaw::ConstantAcceleration)
        else {
            return self;
        };
        let f = &t.file_s;
        let step = (f[f.len() - 1] - f[0]) / (f.len() - 1) as f64;
        let (first, last) = (f[l.first], f[l.first + l.samples - 1]);
        if times
            .iter()
            .any(|(s, _)| (first - step..=last + step).contains(s))
        {
            return self;
        }
        let near: Vec<usize> = times
            .iter()
            .filter(|(s, _)| (f[0]..=f[f.len() - 1]).contains(s))
            .filter_map(|(s, _)| {
                (0..f.len()).min_by(|&a, &b| (f[a] - s).abs().total_cmp(&(f[b] - s).abs()))
            })
            .collect();
        if near.is_empty() {
            return self;
        }
        let law = l.law;
        let xy: Vec<(f64, f64)> = t.x.iter().copied().zip(t.y.iter().copied()).collect();
        let Some(span) = fit::through(&t.t, &t.along, &xy, law, t.noise, &near) else {
            return self;
        };
        if span.holds {
            if let Some(slot) = self.laws.iter_mut().find(|k| k.law == law) {
                *slot = span;
            }
        }
        self
    }

    /// Whether the route's chosen constant acceleration is the motion the user read at `times`
    /// ((seconds of the file's timeline, value)): at least one reading lies in its span (give
    /// or take a sample), or before it where its vertex is (at rest before a release). True
    /// without readings or without an acceleration chosen. One that holds none follows another
    /// thing (a jar's sloshing surface, not its level), and its law and release are not the
    /// reading's.
    pub fn holds_readings(&self, times: &[(f64, f64)]) -> bool {
        let Some(l) = self.accelerating() else {
            return true;
        };
        let f = &self.track.file_s;
        if times.is_empty() || f.len() < 2 {
            return true;
        }
        let step = (f[f.len() - 1] - f[0]) / (f.len() - 1) as f64;
        let (first, last) = (f[l.first], f[l.first + l.samples - 1]);
        let vertex = l.values.iter().find(|v| v.name == "vertex");
        let rest = vertex.is_some_and(|v| self.file_time(v.value) <= first);
        times
            .iter()
            .any(|&(t, _)| (first - step..=last + step).contains(&t) || (rest && t < first))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::laws::TrackLaw;
    use crate::track::Track;

    /// A ball at rest from 0.1 s until 0.2 s, dropped at 400 px/s² onto a floor it meets at
    /// 0.45 s, then kicked up faster than it came (0.75 s up and down again, three times the
    /// drop); 60 frames a second, a few hundredths of a pixel of noise.
    fn bouncing() -> TrackRoute {
        let t: Vec<f64> = (6..72).map(|k| k as f64 / 60.0).collect();
        let y: Vec<f64> = t
            .iter()
            .enumerate()
            .map(|(k, &s)| {
                let h = if s < 0.2 {
                    0.0
                } else if s < 0.45 {
                    200.0 * (s - 0.2) * (s - 0.2)
                } else if s < 1.2 {
                    let u = s - 0.45;
                    12.5 - 150.0 * u + 200.0 * u * u
                } else {
                    12.5
                };
                10.0 + h + 0.03 * (7.3 * k as f64).sin()
            })
            .collect();
        let x = vec![40.0; t.len()];
        let xy: Vec<(f64, f64)> = x.iter().copied().zip(y.iter().copied()).collect();
        let f = fit::fit(&t, &xy);
        TrackRoute {
            track: Track {
                file_s: t.clone(),
                quality: vec![1.0; t.len()],
                along: f.along,
                x,
                y,
                axis: f.axis,
                noise: f.noise,
                size: 6.0,
                picture: (80, 80),
                frames: t.len(),
                threshold: 10.0,
                on_plane: Vec::new(),
                region: None,
                steadied: None,
                reading: Reading::Centroids,
                t,
            },
            laws: f.laws,
            chosen: f.chosen,
            stick: None,
            plane: None,
            by_readings: None,
            shake: None,
        }
    }

    #[test]
    fn readings_in_the_drop_keep_the_drop_not_the_longer_bounce() {
        let route = bouncing();
        assert_eq!(route.chosen, Some(TrackLaw::ConstantAcceleration));
        let arc = route.chosen_span().unwrap().clone();
        assert!(arc.first_s > 0.4 && arc.last_s > 1.1, "{arc:?}");
        // Read at rest and in the drop: the drop's span, its vertex the release.
        let read = route.through_readings(&[(0.15, 0.0), (0.35, 0.02)]);
        let drop = read.chosen_span().unwrap();
        assert!(drop.first_s < 0.25 && drop.last_s < 0.5, "{drop:?}");
        let vertex = drop.values.iter().find(|v| v.name == "vertex").unwrap();
        // Its vertex is the drop's release (not the kicked arc's apex, 0.825 s), to about a
        // frame: the rest samples the span takes in pull a plain parabola's vertex (0.183 s).
        assert!((vertex.value - 0.2).abs() < 0.02, "{vertex:?}");
        // Readings within the span (or none within the track) leave it as it was.
        let again = bouncing().through_readings(&[(0.6, 0.0), (1.0, 0.1)]);
        assert_eq!(again.chosen_span().unwrap().first_s, arc.first_s);
        let outside = bouncing().through_readings(&[(5.0, 0.0)]);
        assert_eq!(outside.chosen_span().unwrap().first_s, arc.first_s);
    }

    #[test]
    fn a_route_holds_readings_in_its_span_or_at_rest_before_its_release() {
        let arc = bouncing();
        // The kicked arc (from 0.45 s, its apex within it): read in it, or with nothing read.
        assert!(arc.holds_readings(&[(0.6, 0.0), (1.0, 0.1)]));
        assert!(arc.holds_readings(&[]));
        // Read only before it and after it: another motion's readings.
        assert!(!arc.holds_readings(&[(0.1, 0.0), (5.0, 0.1)]));
        // The drop re-read through its readings: at rest before its release holds.
        let drop = bouncing().through_readings(&[(0.15, 0.0), (0.35, 0.02)]);
        assert!(drop.holds_readings(&[(0.1, 0.0)]));
    }
}
