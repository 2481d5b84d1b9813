//! The release of a motion from rest: a constant acceleration's span that reaches back over
//! the object at rest before its vertex (held, then let go) rather than over its rise to it (a
//! toss's apex) is read as still until a release, then accelerating (`laws::released`). Near
//! its vertex a parabola is flat within the noise, so the span grown where the law explains the
//! track takes in a few frames of rest; a parabola through them, its velocity free, puts its
//! vertex early and its acceleration low (uniform carts pulled from rest,
//! `scripts/carts_suite.py`: vertex 0.05–0.09 s early, acceleration 5.9–10.5 % low), and a
//! latent released at that vertex and calibrated by readings in the motion is low by as much
//! again. Read from rest, those still samples pin where the object was let go.

use super::laws::{released, TrackLaw};
use super::segment::{Samples, Span};

/// `span` of `law` on `s`, read from rest (`released`) where the samples before its vertex are
/// explained at least as well by resting at their mean place as by the parabola, and the
/// reading from rest explains the span at least as well; else `span` itself (any other law, no
/// vertex inside the span, or no fit).
pub fn from_release(s: &Samples, law: TrackLaw, span: Span) -> Span {
    if law != TrackLaw::ConstantAcceleration {
        return span;
    }
    let Some(vertex) = span.fitted.value("vertex").map(|v| v.value) else {
        return span;
    };
    let (first, last) = (span.first, span.last);
    let Some(k) = (first..last).find(|&i| s.t[i] >= vertex) else {
        return span;
    };
    let len = last - first;
    let r = &span.fitted.residuals;
    if k == first || r.len() != 2 * len {
        return span;
    }
    // The parabola's residuals there (x's then y's, or along and across a bent path's
    // acceleration: two channels either way), and the spread about their mean place.
    let parabola: f64 = (0..k - first)
        .map(|i| r[i] * r[i] + r[len + i] * r[len + i])
        .sum();
    let before = &s.xy[first..k];
    let m = before.len() as f64;
    let (mx, my) = before
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 / m, b + p.1 / m));
    let rest: f64 = before
        .iter()
        .map(|p| (p.0 - mx).powi(2) + (p.1 - my).powi(2))
        .sum();
    if rest > parabola {
        return span;
    }
    // Read from rest over the whole span, where that explains it at least as well as the
    // parabola with its free velocity does.
    match released(&s.t[first..last], &s.xy[first..last], vertex) {
        Some(fitted) if fitted.rms() <= span.fitted.rms() => Span {
            first,
            last,
            holds: s.explained(law, first, last, &fitted),
            fitted,
            from_rest: true,
        },
        _ => span,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::segment::{longest, noise};

    /// A cart at rest at x = 90 px until 0.5 s, then pulled along x at 240 px/s², seen at 30
    /// fps for 2.6 s with a ±0.4 px wobble; or a ball tossed up through its apex at 0.5 s.
    fn track(tossed: bool) -> (Vec<f64>, Vec<(f64, f64)>) {
        let t: Vec<f64> = (0..78).map(|i| i as f64 / 30.0).collect();
        let xy = t
            .iter()
            .enumerate()
            .map(|(i, &s)| {
                let d = s - 0.5;
                let u = if tossed || d > 0.0 {
                    120.0 * d * d
                } else {
                    0.0
                };
                let wobble = if i % 2 == 0 { 0.4 } else { -0.4 };
                (90.0 + u + wobble, 200.0 + 0.3 * wobble)
            })
            .collect();
        (t, xy)
    }

    fn span_of(t: &[f64], xy: &[(f64, f64)]) -> (Span, Span) {
        let u: Vec<f64> = xy.iter().map(|p| p.0).collect();
        let s = Samples { t, u: &u, xy };
        let law = TrackLaw::ConstantAcceleration;
        let grown = longest(&s, law, 10, noise(&u).unwrap(), &[]).unwrap();
        (grown.clone(), from_release(&s, law, grown))
    }

    #[test]
    fn a_span_that_reaches_back_over_the_rest_is_read_from_it() {
        let (t, xy) = track(false);
        let (grown, kept) = span_of(&t, &xy);
        // The law explains a few frames of rest before the release within the noise, and
        // the parabola through them puts its vertex early…
        assert!(t[grown.first] < 0.45, "{}", t[grown.first]);
        let v = |s: &Span, name: &str| s.fitted.value(name).unwrap().value;
        assert!(v(&grown, "vertex") < 0.495, "{}", v(&grown, "vertex"));
        // …read from rest, the same span gives the release where it was.
        assert_eq!((kept.first, kept.last), (grown.first, grown.last));
        assert!(
            (v(&kept, "vertex") - 0.5).abs() < 0.003,
            "{}",
            v(&kept, "vertex")
        );
        assert!((v(&kept, "acceleration") / 240.0 - 1.0).abs() < 0.005);
        assert!(kept.fitted.rms() < grown.fitted.rms());
        assert!(kept.holds && kept.from_rest);
        // Its halves are read from rest too: the earlier, its rest and the start of the
        // motion, gives the same acceleration as the later.
        let u: Vec<f64> = xy.iter().map(|p| p.0).collect();
        let s = Samples {
            t: &t,
            u: &u,
            xy: &xy,
        };
        let h = crate::track::segment::halves(&s, TrackLaw::ConstantAcceleration, &kept);
        let a = |i: usize| {
            h[i].iter()
                .find(|v| v.name == "acceleration")
                .unwrap()
                .value
        };
        assert!((a(0) / a(1) - 1.0).abs() < 0.02, "{} {}", a(0), a(1));
    }

    #[test]
    fn a_toss_keeps_its_rise_to_the_apex() {
        let (t, xy) = track(true);
        let (grown, kept) = span_of(&t, &xy);
        assert_eq!(grown.first, 0);
        assert_eq!((kept.first, kept.last), (grown.first, grown.last));
    }
}
