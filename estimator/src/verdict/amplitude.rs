//! A swing answered by the oscillator where the pendulum's law follows the track as well: at
//! the swing's amplitude θa their rates differ (a pendulum's period grows as θa²/16, so the
//! oscillator's γ0 reads its g/L about θa²/8 low), and a track that both follow within its noise
//! does not tell which law it is. A swing under gravity is the pendulum's at any amplitude; the
//! oscillator's answer is doubtful there, and the reason names both.

use super::{Check, Grade, Reason};
use crate::agreement::MATERIAL;
use crate::analysis::Run;
use crate::track::laws::TrackLaw;
use crate::track::{TrackRoute, ALIKE};
use physvid_shared::cli::approx;

pub struct Amplitude;

impl Check for Amplitude {
    fn name(&self) -> &'static str {
        "amplitude"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        // Only an answer that is the oscillator's rate.
        if !r.parameters.iter().any(|p| p.name == "gamma0") {
            return Vec::new();
        }
        r.track
            .as_ref()
            .and_then(|route| undecided(self.name(), route))
            .into_iter()
            .collect()
    }
}

/// Where `route` follows a swing's angle as the oscillator and the pendulum alike (both spans
/// hold within the track's noise, alike in length) and their rates differ by [`MATERIAL`] or
/// more, the doubt.
fn undecided(check: &'static str, route: &TrackRoute) -> Option<Reason> {
    let angle = route.chosen_span()?;
    if angle.law != TrackLaw::AngularOscillation {
        return None;
    }
    let swing = route
        .laws
        .iter()
        .find(|l| l.law == TrackLaw::Swing && l.holds)?;
    let noise = route.track.noise;
    if swing.held_s() < ALIKE * angle.held_s() || angle.rms_px > noise || swing.rms_px > noise {
        return None;
    }
    let (g0, gl) = (angle.rate()?, swing.rate()?);
    let apart = (gl.value - g0.value).abs() / gl.value.abs().max(f64::MIN_POSITIVE);
    if apart.is_nan() || apart < MATERIAL {
        return None;
    }
    let amplitude = angle
        .values
        .iter()
        .find(|v| v.name == "amplitude")
        .map_or(String::new(), |a| format!(" ±{}°", approx(a.value)));
    Some(
        Reason::new(
            check,
            Grade::Doubtful,
            format!(
                "the track swings{amplitude} about a pivot, where the oscillator's law (gamma0 \
                 {}) and the pendulum's (g/L {}) follow it alike, both within its noise ({} and \
                 {} px rms against {} px), and their rates differ by {} %: the track does not \
                 tell which law it is, and a swing under gravity is the pendulum's at any \
                 amplitude; --model pendulum if gravity swings it",
                approx(g0.value),
                approx(gl.value),
                approx(angle.rms_px),
                approx(swing.rms_px),
                approx(noise),
                approx(100.0 * apart)
            ),
        )
        .measured(apart, MATERIAL),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::laws::Value;
    use crate::track::{test_route, LawSpan};

    fn law(law: TrackLaw, name: &'static str, rate: f64, rms_px: f64) -> LawSpan {
        let (_, mut span) = test_route();
        span.law = law;
        span.rms_px = rms_px;
        span.values = vec![
            Value {
                name,
                value: rate,
                error: 0.001,
                unit: "1/s^2",
            },
            Value {
                name: "amplitude",
                value: 28.0,
                error: 0.01,
                unit: "deg",
            },
        ];
        span
    }

    #[test]
    fn a_wide_swing_the_oscillator_and_the_pendulum_follow_alike_is_doubtful() {
        // The swings suite's 28° swing, lightly damped, read by its rod (noise 0.1 px).
        let (mut route, _) = test_route();
        route.laws = vec![
            law(TrackLaw::AngularOscillation, "gamma0", 9.714, 0.056),
            law(TrackLaw::Swing, "g_over_l", 9.999, 0.078),
        ];
        route.chosen = Some(TrackLaw::AngularOscillation);
        let r = undecided("amplitude", &route).expect("2.9 % apart, both within the noise");
        assert_eq!(r.grade, Grade::Doubtful);
        assert!(
            r.detail.contains("±28°") && r.detail.contains("g/L 9.999"),
            "{}",
            r.detail
        );
        // The others' rod and bob, the oscillator's law drawn at 60°: the pendulum leaves
        // twice the noise.
        route.laws[1].rms_px = 0.217;
        assert!(undecided("amplitude", &route).is_none());
        // A small swing: the rates within 2 %.
        route.laws[1] = law(TrackLaw::Swing, "g_over_l", 9.85, 0.078);
        assert!(undecided("amplitude", &route).is_none());
        // The pendulum chosen: its answer holds at any amplitude.
        route.laws[1] = law(TrackLaw::Swing, "g_over_l", 9.999, 0.078);
        route.chosen = Some(TrackLaw::Swing);
        assert!(undecided("amplitude", &route).is_none());
    }
}
