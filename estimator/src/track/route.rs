//! The track route's answer: each law's span on the track, the law chosen, how much motion it
//! explains and how long it holds, and the times of its span (its place in the picture:
//! `frame`).

use super::laws::{TrackLaw, Value};
use super::Reading;
use super::Track;
use crate::calibration::{Plane, Stick};
use crate::data::CameraShake;
use crate::digits::{sig, significant};
use serde::Serialize;

/// A law fitted on the track where it holds.
#[derive(Debug, Clone, Serialize)]
pub struct LawSpan {
    pub law: TrackLaw,
    pub holds: bool,
    /// The span, seconds of the track's times, and its samples.
    pub first_s: f64,
    pub last_s: f64,
    pub samples: usize,
    pub values: Vec<Value>,
    /// The values refitted on the span's earlier and later half (`segment::halves`; empty
    /// where a half gives no fit).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub halves: Vec<Vec<Value>>,
    pub rms_px: f64,
    /// The lag-one correlation of its residuals (`laws::lag_one`).
    #[serde(skip)]
    pub follow: f64,
    /// The values in SI units where a stick gives the scale (`metres`): the pixel lengths in
    /// metres; empty without one.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub si: Vec<Value>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub periods: Option<f64>,
    /// The law's curve over the span (along its axis, pixels), for the figure.
    #[serde(skip)]
    pub curve: Vec<f64>,
    #[serde(skip)]
    pub first: usize,
    /// Whether a constant acceleration's span is read from rest (`release`): the object still
    /// until its vertex, then accelerating.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub from_rest: bool,
}

impl LawSpan {
    /// The standard error of its value `name`: its fit's, or half the difference of its
    /// halves' values where that is more (a bias that changes over the span, as a light
    /// circling the scene or a perspective gives, shows there and not in the fit's residuals).
    pub fn error_of(&self, name: &str) -> Option<f64> {
        let v = self.values.iter().find(|v| v.name == name)?;
        let of = |half: &Vec<Value>| half.iter().find(|h| h.name == name).map(|h| h.value);
        let apart = match self.halves.as_slice() {
            [a, b] => of(a).zip(of(b)).map_or(0.0, |(a, b)| 0.5 * (a - b).abs()),
            _ => 0.0,
        };
        Some(v.error.max(apart))
    }
}

/// The track route's answer: the track, every law's span, and the law chosen (the one that
/// holds over the longest time; an oscillation only where its span holds a whole period).
#[derive(Debug, Clone, Serialize)]
pub struct TrackRoute {
    pub track: Track,
    pub laws: Vec<LawSpan>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub chosen: Option<TrackLaw>,
    /// The length in the picture that puts the track in metres (`--stick`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stick: Option<Stick>,
    /// The rectangle in the plane of the motion the track is read on (`--plane`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plane: Option<Plane>,
    /// Pixels a metre along a constant acceleration's line that the `--reference` readings
    /// give where neither of the above does (`with_readings`): the track's acceleration in
    /// metres beside the latent's, for the routes check; the latent is calibrated by the
    /// readings themselves.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub by_readings: Option<f64>,
    /// The camera's shake, where this was read on frames steadied against it (`steady`), or
    /// where that shake changes from frame to frame (`steady::JITTER`): the latent route reads
    /// its frames steadied by the same shifts.
    #[serde(skip)]
    pub shake: Option<CameraShake>,
}

impl TrackRoute {
    /// The route of `track` with its laws' spans and the law chosen, read in the picture's own
    /// pixels (no stick, plane or readings yet: `metres`, `plane`).
    pub(super) fn read(track: Track, laws: Vec<LawSpan>, chosen: Option<TrackLaw>) -> TrackRoute {
        TrackRoute {
            track,
            laws,
            chosen,
            stick: None,
            plane: None,
            by_readings: None,
            shake: None,
        }
    }

    /// How much motion the chosen law explains: its span's samples times their variance
    /// (pixels², a brightness's grey levels²) in what the law is fitted to: along the axis for an
    /// oscillation or a swing, in the picture's plane (x and y) for an acceleration, fitted in
    /// both (a toss's bent path read along one axis would favour a shorter span of it); 0 where
    /// no law was chosen. Of several things followed, the object is the one a law explains the
    /// most motion of.
    pub fn explained(&self) -> f64 {
        let Some(l) = self.chosen_span() else {
            return 0.0;
        };
        let span = l.first..l.first + l.samples;
        let spread = |u: &[f64]| {
            let m = u.iter().sum::<f64>() / u.len() as f64;
            u.iter().map(|v| (v - m) * (v - m)).sum::<f64>()
        };
        let t = &self.track;
        match l.law {
            TrackLaw::ConstantAcceleration => spread(&t.x[span.clone()]) + spread(&t.y[span]),
            TrackLaw::Oscillation
            | TrackLaw::Swing
            | TrackLaw::AngularOscillation
            | TrackLaw::Decay
            | TrackLaw::Drain => spread(&t.along[span]),
        }
    }

    /// How long the chosen law holds (s; 0 where none was chosen).
    pub fn held_s(&self) -> f64 {
        self.chosen_span().map_or(0.0, LawSpan::held_s)
    }

    /// How long its chosen law's span moves (`LawSpan::moving_s`).
    pub fn moving_s(&self) -> f64 {
        self.chosen_span().map_or(0.0, LawSpan::moving_s)
    }

    /// Whether `other` follows the same thing: at the frames both saw, their positions lie
    /// (the median of them) within this thing's size of each other.
    pub fn same_thing(&self, other: &TrackRoute) -> bool {
        let (a, b) = (&self.track, &other.track);
        let mut d: Vec<f64> = Vec::new();
        let mut j = 0;
        for i in 0..a.t.len() {
            while j < b.t.len() && b.t[j] < a.t[i] - 1e-9 {
                j += 1;
            }
            if j < b.t.len() && (b.t[j] - a.t[i]).abs() <= 1e-9 {
                d.push((a.x[i] - b.x[j]).hypot(a.y[i] - b.y[j]));
            }
        }
        if d.is_empty() {
            return false;
        }
        d.sort_by(f64::total_cmp);
        d[d.len() / 2] <= a.size
    }

    /// The span's first and last times on the file's own timeline.
    pub fn file_span(&self, l: &LawSpan) -> (f64, f64) {
        let f = &self.track.file_s;
        (f[l.first], f[l.first + l.samples - 1])
    }

    /// The time `t` of the track's real clock on the file's own timeline (the two differ by an
    /// offset, and by a factor for a slow-motion capture).
    pub fn file_time(&self, t: f64) -> f64 {
        let k = &self.track;
        let n = k.t.len();
        let ratio = if n > 1 && k.t[n - 1] > k.t[0] {
            (k.file_s[n - 1] - k.file_s[0]) / (k.t[n - 1] - k.t[0])
        } else {
            1.0
        };
        k.file_s.first().map_or(t, |f0| f0 + (t - k.t[0]) * ratio)
    }

    /// The middle of the chosen law's span on the file's own timeline (the object in motion):
    /// the frame report.html shows.
    pub fn shown_at(&self) -> Option<f64> {
        let (a, b) = self.file_span(self.chosen_span()?);
        Some((a + b) / 2.0)
    }

    /// The chosen law's span.
    pub fn chosen_span(&self) -> Option<&LawSpan> {
        self.laws.iter().find(|l| Some(l.law) == self.chosen)
    }

    /// One line for the terminal.
    pub fn line(&self) -> String {
        let unit = self.unit();
        match self.chosen_span() {
            Some(l) => format!(
                "track: {} over {:.2}–{:.2} s ({} samples{}, {:.2} {unit} rms, noise {:.2} {unit}): {}",
                l.law.name(),
                l.first_s,
                l.last_s,
                l.samples,
                match self.track.reading {
                    Reading::Rod => ", read by its rod's axes",
                    Reading::Brightness => ", the brightness of what changes in place",
                    _ => "",
                }
                .to_string()
                    + &self.track.steadied.map_or(String::new(), |s| {
                        format!(", on frames steadied against the camera's shake ({s:.1} px)")
                    }),
                l.rms_px,
                self.track.noise,
                l.values
                    .iter()
                    .chain(&l.si)
                    .map(|v| {
                        let (value, error) = (sig(v.value), significant(v.error));
                        format!("{} {value} ± {error} {}", v.name, v.unit)
                    })
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            None => format!(
                "track: followed over {} of {} frames; no law explains it within its noise ({:.2} {unit})",
                self.track.t.len(),
                self.track.frames,
                self.track.noise
            ),
        }
    }

    /// What the track follows, for a sentence: the object's track, or a brightness.
    pub fn subject(&self) -> &'static str {
        match self.track.reading {
            Reading::Brightness => "the brightness of what changes in place",
            _ => "the object's track",
        }
    }

    /// The unit of what the track reads along (`along`, its noise, a law's residuals): pixels,
    /// or grey levels for a brightness.
    pub fn unit(&self) -> &'static str {
        match self.track.reading {
            Reading::Brightness => "grey",
            _ => "px",
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A route whose object moves between `x` 100–140 and `y` 50–60 of a 400×300 picture (its
    /// size 6 px), its one law holding on samples 2..8.
    pub(crate) fn route() -> (TrackRoute, LawSpan) {
        let n = 10;
        let x: Vec<f64> = (0..n)
            .map(|i| {
                if i < 2 {
                    10.0
                } else {
                    100.0 + 40.0 * ((i - 2) as f64 / 5.0).min(1.0)
                }
            })
            .collect();
        let y: Vec<f64> = (0..n).map(|i| 50.0 + (i % 2) as f64 * 10.0).collect();
        let track = Track {
            t: (0..n).map(|i| i as f64 * 0.1).collect(),
            file_s: (0..n).map(|i| i as f64 * 0.1).collect(),
            quality: vec![1.0; n],
            along: x.clone(),
            x,
            y,
            axis: (1.0, 0.0),
            noise: 0.1,
            size: 6.0,
            picture: (400, 300),
            frames: n,
            threshold: 10.0,
            on_plane: Vec::new(),
            region: None,
            steadied: None,
            reading: crate::track::Reading::Centroids,
        };
        let span = LawSpan {
            law: TrackLaw::Oscillation,
            holds: true,
            first_s: 0.2,
            last_s: 0.7,
            samples: 6,
            values: Vec::new(),
            halves: Vec::new(),
            rms_px: 0.1,
            follow: 0.0,
            si: Vec::new(),
            periods: Some(3.0),
            curve: Vec::new(),
            first: 2,
            from_rest: false,
        };
        let route = TrackRoute {
            track,
            laws: vec![span.clone()],
            chosen: Some(TrackLaw::Oscillation),
            stick: None,
            plane: None,
            by_readings: None,
            shake: None,
        };
        (route, span)
    }

    #[test]
    fn readings_of_one_thing_are_told_from_another_by_its_size() {
        let (a, _) = route();
        // The same thing read a pixel off, over the frames both saw (every other one).
        let mut b = a.clone();
        b.track.x.iter_mut().for_each(|x| *x += 1.0);
        for v in [&mut b.track.t, &mut b.track.x, &mut b.track.y] {
            *v = v.iter().step_by(2).copied().collect();
        }
        assert!(a.same_thing(&b) && b.same_thing(&a));
        // Another thing: more than its size (6 px) away.
        b.track.y.iter_mut().for_each(|y| *y += 10.0);
        assert!(!a.same_thing(&b));
        // Never seen at one time: not the same.
        b.track.t.iter_mut().for_each(|t| *t += 5.0);
        assert!(!a.same_thing(&b));
        assert!((a.held_s() - 0.5).abs() < 1e-12);
    }
}
