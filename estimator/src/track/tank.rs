//! A drain's k in metres: where the track's chosen law is Torricelli's drain (`laws::drain`),
//! its empty time tₑ from the level's own curve, and the water levels a user read (`--reference`:
//! times and heights in metres) give k, as √h = (k/2)(tₑ − t) has it, by least squares over
//! the readings. The readings need not lie in the span (a jar's first, read while its surface
//! still sloshed): the level follows its law there too, only its picture does not.

use super::laws::{TrackLaw, Value};
use super::TrackRoute;

impl TrackRoute {
    /// The route with its chosen drain's k in metres (`LawSpan::si`) from the readings `times`
    /// ((seconds of the file's timeline, height in metres)) before its empty time: at least one
    /// of positive height. Its error: the readings' scatter about the law (with two or more)
    /// and the empty time's (its fit's, or half its halves' difference where that is more:
    /// `LawSpan::error_of`), together. As it was otherwise.
    pub fn drain_in_metres(mut self, times: &[(f64, f64)]) -> TrackRoute {
        let Some(i) = self
            .laws
            .iter()
            .position(|l| Some(l.law) == self.chosen && l.law == TrackLaw::Drain && l.holds)
        else {
            return self;
        };
        let Some(empty) = self.laws[i].values.iter().find(|v| v.name == "empty") else {
            return self;
        };
        let te = self.file_time(empty.value);
        let te_error = self.laws[i].error_of("empty").unwrap_or(empty.error);
        if let Some(k) = k_of(times, te, te_error) {
            self.laws[i].si = vec![k];
        }
        self
    }
}

/// k (m^0.5/s) from the readings `times` (s, m) and the empty time `te` (± `te_error`), with its
/// standard error; `None` without a reading of positive height before `te`.
fn k_of(times: &[(f64, f64)], te: f64, te_error: f64) -> Option<Value> {
    let k_at = |te: f64| -> Option<(f64, f64)> {
        let read: Vec<(f64, f64)> = times
            .iter()
            .filter(|(t, h)| *h > 0.0 && *t < te)
            .map(|&(t, h)| (te - t, h.sqrt()))
            .collect();
        let dd: f64 = read.iter().map(|(d, _)| d * d).sum();
        if read.is_empty() || dd <= 0.0 {
            return None;
        }
        // √h = (k/2)·d by least squares through the origin.
        let half = read.iter().map(|(d, r)| d * r).sum::<f64>() / dd;
        let n = read.len();
        let scatter = match n {
            1 => 0.0,
            _ => {
                let ss: f64 = read.iter().map(|(d, r)| (r - half * d).powi(2)).sum();
                (ss / (n - 1) as f64 / dd).sqrt()
            }
        };
        Some((2.0 * half, 2.0 * scatter))
    };
    let (k, scatter) = k_at(te)?;
    let shifted = k_at(te + te_error.max(0.0)).map_or(0.0, |(k2, _)| (k2 - k).abs());
    (k.is_finite() && k > 0.0).then(|| Value {
        name: "k",
        value: k,
        error: scatter.hypot(shifted),
        unit: "m^0.5/s",
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tanks_k_from_its_empty_time_and_the_levels_read() {
        // k = 0.0095 m^0.5/s from 0.07 m at 0 s: empty at 2·√0.07/0.0095 = 55.7 s.
        let (k, h0) = (0.0095f64, 0.07f64);
        let te = 2.0 * h0.sqrt() / k;
        let h = |t: f64| (h0.sqrt() - 0.5 * k * t).powi(2);
        let times = [(2.2, h(2.2)), (18.2, h(18.2)), (25.5, h(25.5))];
        let v = k_of(&times, te, 0.1).unwrap();
        assert!((v.value / k - 1.0).abs() < 1e-9, "{v:?}");
        // The error is the empty time's alone here: a tenth of a second in 30–54 s.
        assert!(v.error > 0.0 && v.error < 0.005 * k, "{v:?}");
        // A level read as 1 % too high moves k by about half of that.
        let off = [(2.2, 1.01 * h(2.2))];
        assert!((k_of(&off, te, 0.0).unwrap().value / k - 1.005).abs() < 1e-3);
        // Nothing read before it empties, or of no height: none.
        assert!(k_of(&[(60.0, 0.01)], te, 0.1).is_none());
        assert!(k_of(&[(10.0, 0.0)], te, 0.1).is_none());
    }
}
