//! Which law the track follows: of the laws that hold on it, the one over the longest time,
//! ties settled by penalised likelihood on common samples.

use super::laws::TrackLaw;
use super::LawSpan;
use crate::agreement::apart;

/// The law that holds over the longest time; an oscillation only where its span holds at least
/// one period (else nothing oscillated) and its amplitude does not grow by more than
/// [`GROWING_ERRORS`] standard errors of its damping (a hand shaking the object drives it; a
/// free motion loses energy) and its rate refitted on the span's earlier and later half agrees
/// by the verdict's own rule (`agreement::apart`: a hand left on a spring, read with it, makes
/// one that changes); an acceleration only where `uniform` motion does not explain its span
/// (samples `first..last`) as well, as a person walking behind the object, even one cut by the
/// picture's edge as they step in: nothing there needs a force. Of spans alike in length
/// ([`ALIKE`]), the law of the least penalised likelihood (`penalised`) on the longest span's
/// samples, where `refit` gives another law's residual there (pixels rms; `None` where it fits
/// none), charged for its rate's drift between its span's halves (`drift`).
pub(super) fn choose(
    laws: &[LawSpan],
    refit: &dyn Fn(TrackLaw, usize, usize) -> Option<f64>,
    uniform: &dyn Fn(usize, usize) -> bool,
) -> Option<TrackLaw> {
    let free = |l: &LawSpan| {
        l.values
            .iter()
            .find(|v| v.name == "gamma1" || v.name == "damping")
            .is_none_or(|d| d.value >= -GROWING_ERRORS * d.error)
    };
    // A rate in time (a frequency, a decay's) is the same under any fixed view of the picture:
    // one whose halves disagree changes over the span. (An acceleration in pixels is not: the
    // picture's scale changes along a path seen in perspective, as the tossed ball's halves
    // 3.7 % apart show.)
    let alike = |l: &LawSpan| {
        l.rate_halves()
            .is_none_or(|[a, b]| apart([a.value, b.value], [a.error, b.error]).is_none())
    };
    let lawful = |l: &LawSpan| {
        l.law != TrackLaw::ConstantAcceleration || !uniform(l.first, l.first + l.samples)
    };
    // Each span's tests once (the uniform motion's is a fit).
    let seen: Vec<&LawSpan> = laws
        .iter()
        .filter(|l| {
            l.holds && l.periods.is_none_or(|p| p >= 1.0) && free(l) && alike(l) && lawful(l)
        })
        .collect();
    let long = *seen
        .iter()
        .max_by(|a, b| a.held_s().total_cmp(&b.held_s()))?;
    let (first, n) = (long.first, long.samples);
    let score = |l: &LawSpan| {
        let rms = if l.law == long.law {
            Some(l.rms_px)
        } else {
            refit(l.law, first, first + n)
        };
        rms.map_or(f64::INFINITY, |r| penalised(l.law, r, n) + drift(l))
    };
    // Each score once: a refit is a nonlinear fit.
    seen.iter()
        .filter(|l| l.held_s() >= ALIKE * long.held_s())
        .map(|l| (score(l), l.law))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, law)| law)
}

/// A span's fit by Schwarz's criterion a sample, ln(mean square) + k ln(n) / n (its residuals'
/// Gaussian likelihood, a law's every free parameter charged ln n): a law with more freedom is
/// chosen only where it follows the track closer than its freedom buys (a swing at 60° read as
/// the angle's oscillation, not the sideways position's, whose picture is bent by the sine);
/// between laws alike in fit, the one with less freedom.
fn penalised(law: TrackLaw, rms: f64, samples: usize) -> f64 {
    let n = samples.max(2) as f64;
    (rms * rms).max(1e-12).ln() + law.freedom() as f64 * n.ln() / n
}

/// What a law's rate changing over its span costs it, on the scale of `penalised` (a sample's
/// share of the likelihood): a law's constants are constant, and halves whose rates differ by
/// z standard errors (widened for residuals that follow one another) are z²/2 of evidence against
/// it, shared over the span's samples worth n (1 − ρ)/(1 + ρ) independent ones (ρ its residuals'
/// lag-one correlation, as the errors are widened by). A pendulum's swing read as the angle's
/// oscillation fits its span as closely at 25° (the sine's third harmonic is a twentieth of a
/// pixel), but that oscillation's rate rises as the swing dies down; the pendulum's stays.
fn drift(l: &LawSpan) -> f64 {
    let Some([a, b]) = l.rate_halves() else {
        return 0.0;
    };
    let error = a.error.hypot(b.error);
    if error.is_nan() || error <= 0.0 {
        return 0.0;
    }
    let z = (b.value - a.value) / error;
    let worth = l.samples.max(2) as f64 * (1.0 - l.follow) / (1.0 + l.follow);
    z * z / worth
}

/// Spans at least this share of the longest's length are alike in length: laws (and a thing's
/// readings, `object::chosen`) are weighed among them by how they follow the track.
pub const ALIKE: f64 = 0.9;

/// An oscillation whose damping is below zero by more than this many standard errors grows:
/// something drives it.
const GROWING_ERRORS: f64 = 3.0;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::laws::Value;

    fn span(law: TrackLaw, seconds: f64, rms_px: f64) -> LawSpan {
        LawSpan {
            law,
            holds: true,
            first_s: 0.0,
            last_s: seconds,
            samples: (seconds * 20.0) as usize + 1,
            values: Vec::new(),
            halves: Vec::new(),
            rms_px,
            follow: 0.0,
            si: Vec::new(),
            periods: Some(2.5),
            curve: Vec::new(),
            first: 0,
            from_rest: false,
        }
    }

    #[test]
    fn of_spans_alike_in_length_the_law_that_follows_closer_than_its_freedom_costs() {
        let none = |_: usize, _: usize| false;
        let laws = [
            span(TrackLaw::Oscillation, 7.8, 0.97),
            span(TrackLaw::AngularOscillation, 7.8, 0.47),
        ];
        let own = |law: TrackLaw, _: usize, _: usize| {
            laws.iter().find(|l| l.law == law).map(|l| l.rms_px)
        };
        // Half the residual for three more parameters over 157 samples: the angle's.
        assert_eq!(
            choose(&laws, &own, &none),
            Some(TrackLaw::AngularOscillation)
        );
        // 2 % less residual does not pay for them (5 % would: e^(3 ln 157 / 314) = 1.049).
        let close = [
            laws[0].clone(),
            span(TrackLaw::AngularOscillation, 7.8, 0.95),
        ];
        let own = |law: TrackLaw, _: usize, _: usize| {
            close.iter().find(|l| l.law == law).map(|l| l.rms_px)
        };
        assert_eq!(choose(&close, &own, &none), Some(TrackLaw::Oscillation));
        // A shorter span is weighed by its fit refitted on the longest's samples.
        let swing = [
            span(TrackLaw::AngularOscillation, 5.1, 0.04),
            span(TrackLaw::Swing, 4.65, 0.03),
        ];
        let refit = |law: TrackLaw, _: usize, _: usize| match law {
            TrackLaw::Swing => Some(0.2),
            _ => None,
        };
        assert_eq!(
            choose(&swing, &refit, &none),
            Some(TrackLaw::AngularOscillation)
        );
        // A span under nine tenths of the longest is not weighed at all.
        let short = [swing[0].clone(), span(TrackLaw::Swing, 4.0, 0.01)];
        assert_eq!(
            choose(&short, &refit, &none),
            Some(TrackLaw::AngularOscillation)
        );
    }

    #[test]
    fn an_acceleration_is_not_followed_where_uniform_motion_explains_its_span() {
        let mut walk = span(TrackLaw::ConstantAcceleration, 8.0, 0.4);
        walk.periods = None;
        let laws = [walk, span(TrackLaw::Oscillation, 7.0, 0.1)];
        let refit = |_: TrackLaw, _: usize, _: usize| None;
        // The longer span's law where a line at constant speed leaves more than its noise…
        let none = |_: usize, _: usize| false;
        assert_eq!(
            choose(&laws, &refit, &none),
            Some(TrackLaw::ConstantAcceleration)
        );
        // …and not where one explains it as well.
        let all = |_: usize, _: usize| true;
        assert_eq!(choose(&laws, &refit, &all), Some(TrackLaw::Oscillation));
    }

    #[test]
    fn an_oscillation_is_not_followed_where_its_rate_changes_over_its_span() {
        let gamma0 = |value: f64, error: f64| {
            vec![Value {
                name: "gamma0",
                value,
                error,
                unit: "1/s^2",
            }]
        };
        let mut long = span(TrackLaw::Oscillation, 7.0, 0.1);
        // 4 % apart at 5.7 joint errors: the rule's first tier.
        long.halves = vec![gamma0(43.3, 0.3), gamma0(45.1, 0.1)];
        let laws = [long.clone(), span(TrackLaw::AngularOscillation, 5.0, 0.1)];
        let refit = |_: TrackLaw, _: usize, _: usize| None;
        let none = |_: usize, _: usize| false;
        assert_eq!(
            choose(&laws, &refit, &none),
            Some(TrackLaw::AngularOscillation)
        );
        // Halves alike: the longer span's.
        long.halves = vec![gamma0(44.9, 0.3), gamma0(45.1, 0.1)];
        let laws = [long, laws[1].clone()];
        assert_eq!(choose(&laws, &refit, &none), Some(TrackLaw::Oscillation));
    }

    #[test]
    fn of_laws_alike_in_fit_the_one_whose_rate_stays_over_its_span() {
        let rate = |name: &'static str, value: f64| {
            vec![Value {
                name,
                value,
                error: 0.0055,
                unit: "1/s^2",
            }]
        };
        // The 25° swing read by its rod (the swings suite): the angle's oscillation follows it
        // 15 % closer, but its rate rises 0.2 % (2.8 errors) as the swing dies down, in
        // residuals that follow one another (ρ 0.7: 107 samples worth 19); the pendulum's stays.
        let mut angle = span(TrackLaw::AngularOscillation, 5.3, 0.053);
        angle.halves = vec![rate("gamma0", 10.767), rate("gamma0", 10.789)];
        angle.follow = 0.7;
        let mut swing = span(TrackLaw::Swing, 5.3, 0.062);
        swing.halves = vec![rate("g_over_l", 10.998), rate("g_over_l", 10.997)];
        swing.follow = 0.65;
        let laws = [angle.clone(), swing.clone()];
        let own = |law: TrackLaw, _: usize, _: usize| {
            laws.iter().find(|l| l.law == law).map(|l| l.rms_px)
        };
        let none = |_: usize, _: usize| false;
        assert_eq!(choose(&laws, &own, &none), Some(TrackLaw::Swing));
        // With residuals that do not follow one another (107 worth 107), the closer fit.
        angle.follow = 0.0;
        swing.follow = 0.0;
        let laws = [angle, swing];
        let own = |law: TrackLaw, _: usize, _: usize| {
            laws.iter().find(|l| l.law == law).map(|l| l.rms_px)
        };
        assert_eq!(
            choose(&laws, &own, &none),
            Some(TrackLaw::AngularOscillation)
        );
    }
}
