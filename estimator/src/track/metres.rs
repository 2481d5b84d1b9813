//! The track in metres: a stick (`calibration::Stick`) scales its pixel lengths (a constant
//! acceleration's px/s², an oscillation's amplitude) to SI, and gives the readings the latent
//! route is calibrated by: the object's distance along its acceleration at each sample of the
//! span where the law holds, in place of positions typed with `--reference`. Where no stick is
//! given, `--reference` readings along a constant acceleration scale it (`with_readings`) for
//! the routes check alone.

use super::laws::{TrackLaw, Value};
use super::{LawSpan, TrackRoute};
use crate::calibration::Stick;

/// The readings a stick gives the latent route: this many (two fix a scale; more average its
/// noise).
pub const READINGS: usize = 6;

/// The value `v` in metres where its unit is a pixel length (`px`, `px/s^2`).
fn in_metres(v: &Value, per_metre: f64) -> Option<Value> {
    let unit = match v.unit {
        "px" => "m",
        "px/s^2" => "m/s^2",
        _ => return None,
    };
    Some(Value {
        name: v.name,
        value: v.value / per_metre,
        error: v.error / per_metre,
        unit,
    })
}

impl TrackRoute {
    /// The route with its pixel lengths also in metres by the `--reference` readings `times`
    /// ((seconds of the file's timeline, metres)) where no stick or plane scales it: where its
    /// chosen law is a constant acceleration that holds and at least two readings fall within
    /// its span, the readings' least-squares line against the object's distance along the
    /// acceleration there (the law's, from its vertex) gives the pixels a metre (`by_readings`; on
    /// a path seen in perspective, at its vertex's scale, as its acceleration is), and readings
    /// at rest before a release the track puts before its span count too. The readings are the
    /// latent's calibration too, so the two routes' accelerations are two measurements on one
    /// scale. As it was otherwise.
    pub fn with_readings(mut self, times: &[(f64, f64)]) -> TrackRoute {
        if self.per_metre().is_some() {
            return self;
        }
        let Some(l) = self.accelerating() else {
            return self;
        };
        // The span on the file's timeline.
        let f = &self.track.file_s;
        let (first, last) = (f[l.first], f[l.first + l.samples - 1]);
        // The distance a reading gives is the law's own, ½a(t − r)² from its vertex r: seen in
        // perspective (a bend kept, `laws::acceleration`), at the scale of the vertex, the
        // picture's own positions bent away from it. With the vertex before the span (nothing
        // seen rising to it: a release from rest), a reading before the vertex is at rest there.
        let value = |name: &str| l.values.iter().find(|v| v.name == name).map(|v| v.value);
        let (Some(a), Some(r)) = (value("acceleration"), value("vertex")) else {
            return self;
        };
        let r = self.file_time(r);
        let rest = r <= first;
        let inside: Vec<(f64, f64)> = times
            .iter()
            .filter(|(t, _)| (first..=last).contains(t) || (rest && *t < first))
            .map(|&(t, value)| {
                let from = if rest { (t - r).max(0.0) } else { t - r };
                (0.5 * a * from * from, value)
            })
            .filter(|p| p.0.is_finite())
            .collect();
        if inside.len() < 2 {
            return self;
        }
        // value = c + b·px by least squares: b metres a pixel.
        let n = inside.len() as f64;
        let (mx, my) = inside
            .iter()
            .fold((0.0, 0.0), |(x, y), p| (x + p.0 / n, y + p.1 / n));
        let (sxy, sxx) = inside.iter().fold((0.0, 0.0), |(xy, xx), p| {
            (xy + (p.0 - mx) * (p.1 - my), xx + (p.0 - mx).powi(2))
        });
        let b = sxy / sxx;
        if !(b.is_finite() && b != 0.0) {
            return self;
        }
        self.by_readings = Some(1.0 / b.abs());
        self.in_metres(1.0 / b.abs())
    }

    /// The route read on the scale of `stick`: every law's pixel lengths also in metres
    /// (`LawSpan::si`).
    pub fn with_stick(mut self, stick: Stick) -> TrackRoute {
        self.stick = Some(stick);
        self.in_metres(stick.per_metre())
    }

    /// Every law's pixel lengths also in metres at `per_metre` pixels a metre.
    pub(super) fn in_metres(mut self, per_metre: f64) -> TrackRoute {
        for l in &mut self.laws {
            l.si = l
                .values
                .iter()
                .filter_map(|v| in_metres(v, per_metre))
                .collect();
        }
        self
    }

    /// The chosen law's span where it is a constant acceleration that holds: the span the
    /// stick's readings come from and the model's law is read from.
    pub fn accelerating(&self) -> Option<&LawSpan> {
        self.chosen_span()
            .filter(|l| l.law == TrackLaw::ConstantAcceleration && l.holds)
    }

    /// The readings a stick gives over the span `l`, for the latent's calibration: at
    /// [`READINGS`] samples spread evenly over it short of its last (a decode may end a frame
    /// before the time asked), as far apart as they can be (a latent trained on every second or
    /// third frame reads each on a frame of its own), and only from `from` on (seconds of the
    /// file's timeline: a fall's release, before which a descent keeps nothing). Each is the
    /// sample's time on the file's own timeline and the object's distance (metres) along the
    /// law's acceleration from where the span starts: the quantity whose second derivative the
    /// fall or the slide is. Empty without a stick or an acceleration.
    pub fn readings(&self, l: &LawSpan, from: f64) -> Vec<(f64, f64)> {
        let f = &self.track.file_s;
        let begin = (l.first..l.first + l.samples)
            .find(|&i| f[i] >= from)
            .unwrap_or(l.first + l.samples);
        let n = (l.first + l.samples).saturating_sub(begin + 1);
        let k = READINGS.min(n);
        let picked = (0..k)
            .map(|j| begin + j * (n - 1) / (k - 1).max(1))
            .collect();
        self.readings_at(l, picked)
    }

    /// The object's distance (metres) along the span `l`'s acceleration from where it starts,
    /// at the file's time `file_s`: interpolated between the samples either side; `None`
    /// outside the span, or without a scale.
    pub fn distance_at(&self, l: &LawSpan, file_s: f64) -> Option<f64> {
        let at = self.readings_at(l, (l.first..l.first + l.samples).collect());
        let k = at
            .windows(2)
            .position(|w| (w[0].0..=w[1].0).contains(&file_s))?;
        let ((t0, d0), (t1, d1)) = (at[k], at[k + 1]);
        Some(if t1 > t0 {
            d0 + (d1 - d0) * (file_s - t0) / (t1 - t0)
        } else {
            d0
        })
    }

    fn readings_at(&self, l: &LawSpan, samples: Vec<usize>) -> Vec<(f64, f64)> {
        match self.per_metre() {
            Some(per_metre) => self.along_at(l, samples, per_metre),
            None => Vec::new(),
        }
    }

    /// The samples' distances along `l`'s acceleration from its first, at `per_metre`.
    fn along_at(&self, l: &LawSpan, samples: Vec<usize>, per_metre: f64) -> Vec<(f64, f64)> {
        let Some(d) = l.values.iter().find(|v| v.name == "direction") else {
            return Vec::new();
        };
        let (dx, dy) = (d.value.to_radians().cos(), d.value.to_radians().sin());
        let (x0, y0) = self.fitted_at(l.first);
        samples
            .into_iter()
            .map(|i| {
                let (x, y) = self.fitted_at(i);
                let along = (x - x0) * dx + (y - y0) * dy;
                (self.track.file_s[i], along / per_metre)
            })
            .collect()
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::track::laws::TrackLaw;
    use crate::track::Track;

    /// A ball tossed at 60 px/s across and falling at 400 px/s² (a stick of 200 px a metre:
    /// 2 m/s²), seen for 20 frames at 30 fps: its apex at 0.375 s, the span from 0.067 s.
    pub(crate) fn tossed() -> TrackRoute {
        let t: Vec<f64> = (0..20).map(|i| i as f64 / 30.0).collect();
        let x: Vec<f64> = t.iter().map(|s| 10.0 + 60.0 * s).collect();
        let y: Vec<f64> = t
            .iter()
            .map(|s| 200.0 - 150.0 * s + 200.0 * s * s)
            .collect();
        seen(t, x, y, 2)
    }

    /// The route of a track at times `t` (the file's a second later) through `x`, `y`, its
    /// constant acceleration fitted from sample `first` on.
    fn seen(t: Vec<f64>, x: Vec<f64>, y: Vec<f64>, first: usize) -> TrackRoute {
        let n = t.len();
        let xy: Vec<(f64, f64)> = x.iter().copied().zip(y.iter().copied()).collect();
        let law = TrackLaw::ConstantAcceleration;
        let f = law
            .fit(&t[first..], &y[first..], &xy[first..], None)
            .unwrap();
        let span = LawSpan {
            law,
            holds: true,
            first_s: t[first],
            last_s: t[n - 1],
            samples: n - first,
            values: f.values,
            halves: Vec::new(),
            rms_px: 0.0,
            follow: 0.0,
            si: Vec::new(),
            periods: None,
            curve: Vec::new(),
            first,
            from_rest: false,
        };
        TrackRoute {
            track: Track {
                file_s: t.iter().map(|s| s + 1.0).collect(),
                t,
                quality: vec![1.0; n],
                along: y.clone(),
                x,
                y,
                axis: (0.0, 1.0),
                noise: 0.1,
                size: 6.0,
                picture: (400, 300),
                frames: n,
                threshold: 10.0,
                on_plane: Vec::new(),
                region: None,
                steadied: None,
                reading: crate::track::Reading::Centroids,
            },
            laws: vec![span],
            chosen: Some(law),
            stick: None,
            plane: None,
            by_readings: None,
            shake: None,
        }
    }

    #[test]
    fn a_stick_puts_the_acceleration_and_the_readings_in_metres() {
        let r = tossed();
        assert!(r
            .readings(r.accelerating().unwrap(), f64::NEG_INFINITY)
            .is_empty());
        let r = r.with_stick(Stick::parse("0,0:0,200=1").unwrap());
        let l = r.accelerating().unwrap();
        let a = &l.si[0];
        assert_eq!((a.name, a.unit), ("acceleration", "m/s^2"));
        assert!((a.value - 2.0).abs() < 1e-9, "{a:?}");
        // Every sample of the span (2..20) read, as the spread ones are.
        let every = r.readings_at(l, (2..20).collect());
        assert!((every[0].0 - (1.0 + 2.0 / 30.0)).abs() < 1e-12);
        assert_eq!(every[0].1, 0.0);
        // Along the acceleration (straight down): y's own change, in metres.
        let (s0, s1) = (2.0 / 30.0, 19.0 / 30.0);
        let dy = (-150.0 * s1 + 200.0 * s1 * s1) - (-150.0 * s0 + 200.0 * s0 * s0);
        assert!((every[17].1 - dy / 200.0).abs() < 1e-9);
        let spread = r.readings(l, f64::NEG_INFINITY);
        assert_eq!(spread.len(), READINGS);
        assert_eq!((spread[0], spread[5]), (every[0], every[16]));
        // From the apex on (1.375 s of the file's timeline: sample 12 of the span's 2..20).
        let late = r.readings(l, 1.375);
        assert_eq!((late[0], late[5]), (every[10], every[16]));
        // Between samples, the distance is interpolated; outside the span there is none.
        let mid = (every[3].0 + every[4].0) / 2.0;
        let d = r.distance_at(l, mid).unwrap();
        assert!((d - (every[3].1 + every[4].1) / 2.0).abs() < 1e-12);
        assert_eq!(r.distance_at(l, 0.9), None);
    }

    #[test]
    fn readings_within_the_span_scale_its_acceleration_where_no_stick_does() {
        // The toss at 200 px a metre: its heights below the apex (1.375 s of the file's
        // timeline, y 171.875 px) at three times of the span, typed as --reference readings.
        let height = |file_s: f64| {
            let s = file_s - 1.0;
            (200.0 - 150.0 * s + 200.0 * s * s - 171.875) / 200.0
        };
        let typed: Vec<(f64, f64)> = [1.2, 1.375, 1.6].iter().map(|&t| (t, height(t))).collect();
        let r = tossed().with_readings(&typed);
        let per_metre = r.by_readings.expect("scaled");
        assert!((per_metre - 200.0).abs() < 1e-6, "{per_metre}");
        let a = &r.accelerating().unwrap().si[0];
        assert_eq!((a.name, a.unit), ("acceleration", "m/s^2"));
        assert!((a.value - 2.0).abs() < 1e-6, "{a:?}");
        // The latent route is not calibrated by the track: the stick's readings stay none.
        assert_eq!(r.per_metre(), None);
        // One reading within the span (the other before it) fixes no scale.
        let r = tossed().with_readings(&[(0.5, 0.0), (1.2, height(1.2))]);
        assert!(r.by_readings.is_none() && r.accelerating().unwrap().si.is_empty());
        // A stick's scale stands.
        let stick = Stick::parse("0,0:0,100=1").unwrap();
        let r = tossed().with_stick(stick).with_readings(&typed);
        assert_eq!(r.by_readings, None);
        assert!((r.accelerating().unwrap().si[0].value - 4.0).abs() < 1e-9);
    }

    #[test]
    fn readings_scale_a_fall_seen_in_perspective_at_its_vertex() {
        // A fall from rest at 0.1 s at 2 m/s², 200 px a metre where it starts, drawn a quarter
        // smaller by its end (p = 50 + 200·z/(1 + 0.5·z)): the readings' metres against the
        // parabola straightened through the bend, not against the picture's bent positions.
        let t: Vec<f64> = (6..40).map(|i| i as f64 / 60.0).collect();
        let z = |s: f64| (s - 0.1f64).powi(2);
        let y = t
            .iter()
            .map(|&s| 50.0 + 200.0 * z(s) / (1.0 + 0.5 * z(s)))
            .collect();
        let r = seen(t.clone(), vec![30.0; t.len()], y, 0);
        assert!(r.laws[0].values.iter().any(|v| v.name == "bend"));
        let typed: Vec<(f64, f64)> = [1.2, 1.4, 1.6].iter().map(|&f| (f, z(f - 1.0))).collect();
        let r = r.with_readings(&typed);
        let a = &r.accelerating().unwrap().si[0];
        assert!((a.value - 2.0).abs() < 0.01, "{a:?}");
    }
}
