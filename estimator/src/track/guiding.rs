//! When the track's law guides the latent route (`guide::guided`) and judges its answer
//! (`verdict::routes`): an oscillation or a swing that holds over several periods with its
//! rate known to a percent.

use super::laws::{TrackLaw, Value};
use super::{LawSpan, TrackRoute};

/// The names a rate² goes by among the laws' values (the oscillations' γ0, the swing's g/L)
/// and the models' alike.
pub const RATE_NAMES: [&str; 2] = ["gamma0", "g_over_l"];

/// The track's oscillation guides the latent where its span holds at least this many periods…
pub const GUIDING_PERIODS: f64 = 2.0;
/// …and its rate's (γ0's, g/L's) standard error is at most this share of it.
pub const GUIDING_ERROR: f64 = 0.01;

impl LawSpan {
    /// Its rate² (`RATE_NAMES`), where it oscillates.
    pub fn rate(&self) -> Option<&Value> {
        self.values.iter().find(|v| RATE_NAMES.contains(&v.name))
    }
}

impl TrackRoute {
    /// The chosen law's span where it is an oscillation or a swing clear enough to set the
    /// latent's law, span and start (`GUIDING_PERIODS`, `GUIDING_ERROR`).
    pub fn guiding(&self) -> Option<&LawSpan> {
        let l = self.chosen_span()?;
        let g = l.rate()?;
        (matches!(
            l.law,
            TrackLaw::Oscillation | TrackLaw::AngularOscillation | TrackLaw::Swing
        ) && l.holds
            && l.periods.unwrap_or(0.0) >= GUIDING_PERIODS
            && g.error <= GUIDING_ERROR * g.value.abs())
        .then_some(l)
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
}
