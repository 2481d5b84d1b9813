//! Each law of `laws` fitted where it holds (`segment`) on a track's positions: the picture's
//! pixels, or the plane of the motion's where one is given (`plane`).

use super::laws::TrackLaw;
use super::segment::{self, longest, noise, Samples};
use super::LawSpan;
use rayon::prelude::*;

/// The window a law starts from: an oscillation's or a swing's an eighth of the track (at
/// least 12 samples), an acceleration's 10 samples.
fn least_window(law: TrackLaw, n: usize) -> usize {
    match law {
        TrackLaw::Oscillation
        | TrackLaw::Swing
        | TrackLaw::AngularOscillation
        | TrackLaw::Decay
        | TrackLaw::Drain => (n / 8).max(12),
        TrackLaw::ConstantAcceleration => 10,
    }
}

/// Each law fitted where it holds on positions `xy` at times `t`, and what it was read along.
pub(super) struct Fitted {
    pub along: Vec<f64>,
    pub axis: (f64, f64),
    pub noise: f64,
    pub laws: Vec<LawSpan>,
    /// The law chosen among them (`choose`).
    pub chosen: Option<TrackLaw>,
}

/// The laws of positions `xy` (pixels of the picture, or of the plane of the motion) at times
/// `t`: the path's principal axis, the noise along it, and each law's span.
pub(super) fn fit(t: &[f64], xy: &[(f64, f64)]) -> Fitted {
    let (x, y): (Vec<f64>, Vec<f64>) = xy.iter().copied().unzip();
    let (along, axis) = principal_axis(&x, &y);
    spans(t, along, axis, xy, &TrackLaw::ALL)
}

/// The laws of an observable that is not a position (`TrackLaw::OF_LEVELS`: a brightness, in
/// grey levels) with values `u` at times `t`, its place in the picture `at`.
pub(super) fn levels(t: &[f64], u: Vec<f64>, at: (f64, f64)) -> Fitted {
    let xy = vec![at; t.len()];
    spans(t, u, (1.0, 0.0), &xy, &TrackLaw::OF_LEVELS)
}

/// Each of `laws` fitted where it holds on `along` (with positions `xy`) at times `t`, and the
/// one chosen.
fn spans(
    t: &[f64],
    along: Vec<f64>,
    axis: (f64, f64),
    xy: &[(f64, f64)],
    laws: &[TrackLaw],
) -> Fitted {
    let sigma = noise(&along).unwrap_or(segment::LEAST_NOISE);
    let samples = Samples { t, u: &along, xy };
    // Each law on a thread of the pool (in the order of `laws`).
    let laws = laws
        .par_iter()
        .filter_map(|&law| span(&samples, law, sigma, &[]))
        .collect::<Vec<_>>();
    let refit = |law: TrackLaw, a: usize, b: usize| samples.fit(law, a, b, None).map(|f| f.rms());
    let uniform = |a: usize, b: usize| super::uniform::uniform(&samples, a, b, sigma);
    Fitted {
        chosen: super::choose::choose(&laws, &refit, &uniform),
        along,
        axis,
        noise: sigma,
        laws,
    }
}

/// The span where `law` holds on `samples` (noise `sigma`), grown from the window it explains
/// best, of those that hold one of the samples `through` where any are named.
fn span(samples: &Samples, law: TrackLaw, sigma: f64, through: &[usize]) -> Option<LawSpan> {
    let t = samples.t;
    let s = longest(samples, law, least_window(law, t.len()), sigma, through)?;
    let s = super::release::from_release(samples, law, s);
    Some(LawSpan {
        halves: segment::halves(samples, law, &s),
        law,
        holds: s.holds,
        first_s: t[s.first],
        last_s: t[s.last - 1],
        samples: s.last - s.first,
        rms_px: s.fitted.rms(),
        follow: super::laws::lag_one(&s.fitted.residuals),
        si: Vec::new(),
        periods: s.fitted.periods,
        values: s.fitted.values,
        curve: s.fitted.curve,
        first: s.first,
        from_rest: s.from_rest,
    })
}

/// `law`'s span on the positions `xy` (and `along` them, with `noise`) at times `t`, grown from
/// a window that holds one of the samples `through` (where a user read the motion).
pub(super) fn through(
    t: &[f64],
    along: &[f64],
    xy: &[(f64, f64)],
    law: TrackLaw,
    noise: f64,
    through: &[usize],
) -> Option<LawSpan> {
    let samples = Samples { t, u: along, xy };
    span(&samples, law, noise, through)
}

/// The positions along the path's principal direction (from its mean), and that direction.
fn principal_axis(x: &[f64], y: &[f64]) -> (Vec<f64>, (f64, f64)) {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        sxx += (a - mx) * (a - mx);
        syy += (b - my) * (b - my);
        sxy += (a - mx) * (b - my);
    }
    let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let d = (angle.cos(), angle.sin());
    let along = x
        .iter()
        .zip(y)
        .map(|(a, b)| (a - mx) * d.0 + (b - my) * d.1)
        .collect();
    (along, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_axis_of_a_slanted_line_is_its_direction() {
        let x: Vec<f64> = (0..10).map(|i| i as f64).collect();
        let y: Vec<f64> = x.iter().map(|v| 2.0 * v + 1.0).collect();
        let (along, d) = principal_axis(&x, &y);
        assert!((d.1 / d.0 - 2.0).abs() < 1e-9);
        assert!((along[9] - along[0] - 9.0 * 5f64.sqrt()).abs() < 1e-9);
    }

    /// A bob on a 26-px rod from a pivot at (32, 14), its angle `theta(t)` at 20 fps for 7.85 s,
    /// rounded to a hundredth of a pixel.
    fn bob(theta: impl Fn(f64) -> f64) -> (Vec<f64>, Vec<(f64, f64)>) {
        let t: Vec<f64> = (0..157).map(|i| i as f64 / 20.0).collect();
        let round = |v: f64| (v * 100.0).round() / 100.0;
        let xy = t
            .iter()
            .map(|&s| {
                let a = theta(s);
                (round(32.0 + 26.0 * a.sin()), round(14.0 + 26.0 * a.cos()))
            })
            .collect();
        (t, xy)
    }

    /// The others' suite's law: θ'' + 0.08 θ' + 4.0016 θ = 0 from 60°. Read along the
    /// sideways position the sine bends it (γ1 low by a fifth); as the pendulum's sine it
    /// holds on a late part alone; the angle's oscillation follows it throughout.
    #[test]
    fn a_wide_swing_whose_angle_oscillates_is_read_by_its_angle() {
        let (g0, g1) = (4.0016f64, 0.08f64);
        let (z, w) = (g1 / 2.0, (g0 - g1 * g1 / 4.0).sqrt());
        let a0 = 60f64.to_radians();
        let (t, xy) = bob(|s| a0 * (-z * s).exp() * ((w * s).cos() + z / w * (w * s).sin()));
        let f = fit(&t, &xy);
        assert_eq!(f.chosen, Some(TrackLaw::AngularOscillation));
        let l = f.laws.iter().find(|l| Some(l.law) == f.chosen).unwrap();
        assert_eq!(l.samples, t.len());
        let v = |name: &str| l.values.iter().find(|v| v.name == name).unwrap().value;
        assert!((v("gamma0") / g0 - 1.0).abs() < 1e-3, "{}", v("gamma0"));
        assert!((v("gamma1") / g1 - 1.0).abs() < 0.02, "{}", v("gamma1"));
        assert!((v("amplitude") - 60.0).abs() < 0.5, "{}", v("amplitude"));
    }

    /// A pendulum from 80°, θ'' = −4 sin θ − 0.05 θ' (RK4, fine steps): its sine is read.
    #[test]
    fn a_pendulum_from_80_degrees_is_read_as_a_swing() {
        let f = |a: f64, v: f64| (v, -4.0 * a.sin() - 0.05 * v);
        let (mut a, mut v, h) = (80f64.to_radians(), 0.0, 1e-3);
        let mut path = vec![a];
        for _ in 1..157 {
            for _ in 0..50 {
                let k1 = f(a, v);
                let k2 = f(a + 0.5 * h * k1.0, v + 0.5 * h * k1.1);
                let k3 = f(a + 0.5 * h * k2.0, v + 0.5 * h * k2.1);
                let k4 = f(a + h * k3.0, v + h * k3.1);
                a += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
                v += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
            }
            path.push(a);
        }
        let (t, xy) = bob(|s| path[(s * 20.0).round() as usize]);
        let fitted = fit(&t, &xy);
        assert_eq!(fitted.chosen, Some(TrackLaw::Swing));
    }
}
