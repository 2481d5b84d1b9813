//! When the track's law guides the latent route (`guide::guided`) and judges its answer
//! (`verdict::routes`): an oscillation or a swing that holds over several periods, or a
//! brightness's decay over several e-folds (or its drain over most of its level), with its rate
//! known to a percent.

use super::laws::{TrackLaw, Value};
use super::{LawSpan, TrackRoute};

/// The names a rate goes by among the laws' values (the oscillations' γ0, the swing's g/L, a
/// decay's γ, a drain's k in its level's units) and the models' alike.
pub const RATE_NAMES: [&str; 4] = ["gamma0", "g_over_l", "gamma", "drain_k"];

/// The track's oscillation guides the latent where its span holds at least this many periods…
pub const GUIDING_PERIODS: f64 = 2.0;
/// …and its rate's (γ0's, g/L's) standard error is at most this share of it.
pub const GUIDING_ERROR: f64 = 0.01;
/// A decay guides where its span holds at least this many e-folds (what decays falls to
/// e^−2, 14 %, of where it started), as an oscillation its two periods: the law seen to hold
/// over most of its course, not over a stretch a line or a parabola would fit as well.
pub const GUIDING_EFOLDS: f64 = 2.0;
/// A drain guides where its span holds at least this share (%) of its fall: the root of its
/// level (what falls linearly) halved, the half of the way to empty where the curve has
/// turned. `gen`'s tanks, filmed from 0.07 m to 0.01 m, hold 77–81 %; the shared jar 87 %, where
/// an exponential explains its light as closely and the drain is not chosen.
pub const GUIDING_DRAINED: f64 = 75.0;

/// The rate (`RATE_NAMES`) among a law's `values`, where it oscillates or decays.
pub fn rate_of(values: &[Value]) -> Option<&Value> {
    values.iter().find(|v| RATE_NAMES.contains(&v.name))
}

impl LawSpan {
    /// Its rate (`rate_of`).
    pub fn rate(&self) -> Option<&Value> {
        rate_of(&self.values)
    }

    /// The span's length (seconds).
    pub fn held_s(&self) -> f64 {
        self.last_s - self.first_s
    }

    /// How long the object moves by the law: its span, from the release where it is read from
    /// rest (the still frames before it are no motion held; a reading that scatters more
    /// reaches further back into them).
    pub fn moving_s(&self) -> f64 {
        let release = self.values.iter().find(|v| v.name == "vertex");
        match release.filter(|_| self.from_rest) {
            Some(r) => self.last_s - r.value.max(self.first_s),
            None => self.held_s(),
        }
    }

    /// Its rate refitted on the span's earlier and later half (`segment::halves`); `None`
    /// where either half gives none.
    pub fn rate_halves(&self) -> Option<[&Value; 2]> {
        match self.halves.as_slice() {
            [a, b] => Some([rate_of(a)?, rate_of(b)?]),
            _ => None,
        }
    }

    /// How much of its course the span holds: an oscillation's periods, a decay's e-folds
    /// (its rate times the span's length), a drain's share of its level (`laws::drained`);
    /// `None` for a law that has none of them.
    pub fn extent(&self) -> Option<(f64, &'static str)> {
        match self.law {
            TrackLaw::Decay => {
                let g = self.rate()?;
                Some((g.value * self.held_s(), "e-folds"))
            }
            TrackLaw::Drain => {
                let empty = self.values.iter().find(|v| v.name == "empty")?.value;
                let share = super::laws::drained(empty, self.first_s, self.last_s);
                Some((100.0 * share, "% of its level drained"))
            }
            _ => self.periods.map(|p| (p, "periods")),
        }
    }

    /// Its extent (`extent`) in words, "2.1 periods".
    pub fn extent_words(&self) -> String {
        self.extent()
            .map_or(String::new(), |(v, what)| format!("{v:.1} {what}"))
    }
}

impl TrackRoute {
    /// The chosen law's span where it is an oscillation or a swing, or a decay, clear enough
    /// to set the latent's law, span and start (`GUIDING_PERIODS`, `GUIDING_EFOLDS`,
    /// `GUIDING_ERROR`).
    pub fn guiding(&self) -> Option<&LawSpan> {
        let l = self.chosen_span()?;
        let g = l.rate()?;
        let least = match l.law {
            TrackLaw::Oscillation | TrackLaw::AngularOscillation | TrackLaw::Swing => {
                GUIDING_PERIODS
            }
            TrackLaw::Decay => GUIDING_EFOLDS,
            TrackLaw::Drain => GUIDING_DRAINED,
            TrackLaw::ConstantAcceleration => return None,
        };
        (l.holds
            && l.extent().map_or(0.0, |e| e.0) >= least
            && g.error <= GUIDING_ERROR * g.value.abs()
            && self.shown(l))
        .then_some(l)
    }

    /// Whether an oscillation's amplitude lies within the track's range over its span: near
    /// the samples' Nyquist frequency a fit reaches amplitudes no sample shows (10¹⁵ px on a
    /// shaken phone's frames, steadied).
    fn shown(&self, l: &LawSpan) -> bool {
        let amplitude = l.values.iter().find(|v| v.name == "amplitude");
        let (TrackLaw::Oscillation, Some(a)) = (l.law, amplitude) else {
            return true;
        };
        let along = &self.track.along[l.first..(l.first + l.samples).min(self.track.along.len())];
        let (lo, hi) = along
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        a.value.abs() <= hi - lo
    }

    /// The model the guiding law sets (`guiding`): the pendulum for a swing (its period
    /// depends on its amplitude), the LED for a decay, the draining tank for a drain, else the
    /// damped oscillator.
    pub fn guided_model(&self) -> Option<&'static str> {
        Some(match self.guiding()?.law {
            TrackLaw::Swing => "pendulum",
            TrackLaw::Decay => "led",
            TrackLaw::Drain => "torricelli",
            _ => "damped-oscillator",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::route::tests::route;

    #[test]
    fn a_clear_swing_guides_by_its_g_over_l() {
        let (mut route, mut span) = route();
        span.law = TrackLaw::Swing;
        let g = |error| crate::track::laws::Value {
            name: "g_over_l",
            value: 18.0,
            error,
            unit: "1/s^2",
        };
        span.values = vec![g(0.05)];
        route.laws = vec![span.clone()];
        route.chosen = Some(TrackLaw::Swing);
        assert_eq!(route.guiding().and_then(|l| l.rate()), Some(&g(0.05)));
        // Known to worse than a percent, or over less than two periods: not.
        route.laws[0].values = vec![g(0.2)];
        assert!(route.guiding().is_none());
        route.laws[0].values = vec![g(0.05)];
        route.laws[0].periods = Some(1.9);
        assert!(route.guiding().is_none());
    }

    #[test]
    fn a_decay_guides_the_led_over_two_e_folds() {
        let (mut route, mut span) = route();
        span.law = TrackLaw::Decay;
        span.periods = None;
        span.values = vec![crate::track::laws::Value {
            name: "gamma",
            value: 0.5,
            error: 0.002,
            unit: "1/s",
        }];
        // 0.5/s over 0.2–0.7 s: a quarter of an e-fold.
        route.laws = vec![span.clone()];
        route.chosen = Some(TrackLaw::Decay);
        assert!(route.guiding().is_none());
        route.laws[0].last_s = 5.0;
        assert_eq!(
            route.guiding().map(|l| l.extent_words()),
            Some("2.4 e-folds".into())
        );
        assert_eq!(route.guided_model(), Some("led"));
    }

    #[test]
    fn a_drain_guides_the_tank_over_three_quarters_of_its_level() {
        let (mut route, mut span) = route();
        span.law = TrackLaw::Drain;
        span.periods = None;
        let value = |name: &'static str, value: f64, error: f64| crate::track::laws::Value {
            name,
            value,
            error,
            unit: "",
        };
        // Empty at 20.7 s, seen from 0.2 s: to 0.7 s, 5 % of its level drained.
        span.values = vec![value("drain_k", 0.65, 0.001), value("empty", 20.7, 0.07)];
        route.laws = vec![span.clone()];
        route.chosen = Some(TrackLaw::Drain);
        assert!(route.guiding().is_none());
        // To 10.45 s: the root of its level halved, 75 %.
        route.laws[0].last_s = 10.45;
        assert_eq!(
            route.guiding().map(|l| l.extent_words()),
            Some("75.0 % of its level drained".into())
        );
        assert_eq!(route.guided_model(), Some("torricelli"));
        // Its k known to worse than a percent: not.
        route.laws[0].values[0].error = 0.01;
        assert!(route.guiding().is_none());
    }
}
