//! Where a law holds: the track's own noise (what a smooth motion leaves of each point), and
//! for a law the longest span it explains within that noise, grown from the window it explains
//! best. The free motion is where the law holds: a hand holding or letting go, an impact, a
//! bounce or an exit from the frame end it, whatever the picture does around it.

use super::laws::{released, Fitted, TrackLaw, Value};

/// A span's residuals may be this many times the track's noise (root mean square)…
pub(super) const SPREADS: f64 = 3.0;
/// …and no point added to it this many times.
const POINT_SPREADS: f64 = 6.0;

/// A law holds on a span where it explains at least this share of the motion's variance.
pub const EXPLAINED: f64 = 0.99;

/// A track's noise is at least this (pixels): a blob's centroid or a match's peak is not known
/// better than a tenth of a pixel (where the threshold cuts the object's edge, the parabola
/// through the correlation's peak), and a smoother track is one whose bias of a few hundredths
/// of a pixel, as a drifting light or a textured wall gives, would end a law's span. Set on the
/// others' rod and bob (docs/status.md: the track right on 22 of 36 renders held out one at a
/// time, 17 at 0.02 px); no shared recording's span changes.
pub const LEAST_NOISE: f64 = 0.1;

/// The noise of a sampled motion: each point's distance from the cubic through its six
/// neighbours' window (the Savitzky–Golay smoother's residual, 7 points), as a robust spread
/// (1.4826 × the median absolute residual), scaled to a point's own noise (the residual's
/// variance is 2/3 of it). `None` for fewer than 9 points.
pub fn noise(u: &[f64]) -> Option<f64> {
    const C: [f64; 7] = [-2.0, 3.0, 6.0, 7.0, 6.0, 3.0, -2.0];
    if u.len() < 9 {
        return None;
    }
    let mut r: Vec<f64> = u
        .windows(7)
        .map(|w| (w[3] - w.iter().zip(C).map(|(a, c)| a * c).sum::<f64>() / 21.0).abs())
        .collect();
    let mid = r.len() / 2;
    let med = *r.select_nth_unstable_by(mid, f64::total_cmp).1;
    Some((1.4826 * med / (2.0f64 / 3.0).sqrt()).max(LEAST_NOISE))
}

/// A span of the track (indices `first..last`, the end excluded) and the law fitted there.
#[derive(Debug, Clone)]
pub struct Span {
    pub first: usize,
    pub last: usize,
    pub fitted: Fitted,
    /// Whether the law explains the span: its residuals leave at most `1 − EXPLAINED` of the
    /// motion's variance there.
    pub holds: bool,
    /// Whether it is read from rest (`release`): its halves are too.
    pub from_rest: bool,
}

/// The samples of a track that a law is fitted to.
pub struct Samples<'a> {
    pub t: &'a [f64],
    pub u: &'a [f64],
    pub xy: &'a [(f64, f64)],
}

impl Samples<'_> {
    /// The variance of what `law` is fitted to over `a..b` (the acceleration's: x's and y's,
    /// averaged as its residuals are; the swing's: the path's, along its arc).
    fn variance(&self, law: TrackLaw, a: usize, b: usize) -> f64 {
        fn var(v: impl Iterator<Item = f64> + Clone) -> f64 {
            let n = v.clone().count() as f64;
            let m = v.clone().sum::<f64>() / n;
            v.map(|x| (x - m) * (x - m)).sum::<f64>() / n
        }
        match law {
            TrackLaw::Oscillation | TrackLaw::Decay | TrackLaw::Drain => {
                var(self.u[a..b].iter().copied())
            }
            // The arc's: the path's whole spread (x's and y's).
            TrackLaw::Swing | TrackLaw::AngularOscillation => {
                let xy = &self.xy[a..b];
                var(xy.iter().map(|p| p.0)) + var(xy.iter().map(|p| p.1))
            }
            TrackLaw::ConstantAcceleration => {
                let xy = &self.xy[a..b];
                0.5 * (var(xy.iter().map(|p| p.0)) + var(xy.iter().map(|p| p.1)))
            }
        }
    }

    pub fn fit(&self, law: TrackLaw, a: usize, b: usize, near: Option<&Fitted>) -> Option<Fitted> {
        law.fit(&self.t[a..b], &self.u[a..b], &self.xy[a..b], near)
    }

    /// Whether `fitted` (of `law` on `a..b`) explains the span: its residuals leave at most
    /// `1 − EXPLAINED` of the motion's variance there.
    pub fn explained(&self, law: TrackLaw, a: usize, b: usize, fitted: &Fitted) -> bool {
        let spread = self.variance(law, a, b);
        spread > 0.0 && fitted.rms().powi(2) <= (1.0 - EXPLAINED) * spread
    }
}

/// The values of `law` refitted on the earlier and the later half of `span` (each started from
/// the whole span's fit; from rest, from the whole's release, where it is: `release`): whether
/// the law holds alike over it, measured with no encoder. Empty where a half gives no fit.
pub fn halves(s: &Samples, law: TrackLaw, span: &Span) -> Vec<Vec<Value>> {
    let middle = (span.first + span.last) / 2;
    let parts = [(span.first, middle), (middle, span.last)];
    let fits: Option<Vec<Vec<Value>>> = parts
        .iter()
        .map(|&(a, b)| {
            let fitted = if span.from_rest {
                let vertex = span.fitted.value("vertex")?.value;
                released(&s.t[a..b], &s.xy[a..b], vertex)
            } else {
                s.fit(law, a, b, Some(&span.fitted))
            };
            Some(fitted?.values)
        })
        .collect();
    fits.unwrap_or_default()
}

/// The longest span where `law` explains `s` within `noise`: the window of `least` samples whose
/// motion it explains best, grown at either end (by halves, eighths, then single samples) while the
/// span's residuals stay within [`SPREADS`] noise and each sample added within
/// [`POINT_SPREADS`]; where samples are named `through` (a user's readings), of the windows
/// that hold one of them. `None` where the track is shorter than `least` or the law fits no
/// window.
pub fn longest(
    s: &Samples,
    law: TrackLaw,
    least: usize,
    noise: f64,
    through: &[usize],
) -> Option<Span> {
    let n = s.t.len();
    if n < least || least < 2 {
        return None;
    }
    let starts: Vec<usize> = if through.is_empty() {
        let step = (least / 3).max(1);
        let mut every = (0..=n - least).step_by(step).collect::<Vec<_>>();
        every.push(n - least);
        every
    } else {
        (0..=n - least)
            .filter(|i| through.iter().any(|j| (*i..i + least).contains(j)))
            .collect()
    };
    // The seed: the window whose motion the law explains best (least residual for its spread;
    // a still stretch explains nothing).
    let (mut first, mut last) = starts
        .iter()
        .filter_map(|&i| {
            let f = s.fit(law, i, i + least, None)?;
            let spread = s.variance(law, i, i + least);
            (spread > 0.0).then(|| (f.rms().powi(2) / spread, i))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, i)| (i, i + least))?;
    let mut fitted = s.fit(law, first, last, None)?;
    // The law's own accuracy on this track: its best window's residual (widened for the
    // freedom it used there), where that is above the noise (a centroid's smooth bias, a
    // swing's arc read along a line).
    let k = law.freedom() as f64
        / if law == TrackLaw::ConstantAcceleration {
            2.0
        } else {
            1.0
        };
    let level = fitted.rms() * (least as f64 / (least as f64 - k).max(1.0)).sqrt();
    let noise = noise.max(level);
    'grow: loop {
        for before in [true, false] {
            let len = last - first;
            for by in [len / 2, len / 8, 1] {
                let by = by.max(1);
                let (a, b) = if before {
                    (first.saturating_sub(by), last)
                } else {
                    (first, (last + by).min(n))
                };
                if (a, b) == (first, last) {
                    continue;
                }
                let Some(f) = s.fit(law, a, b, Some(&fitted)) else {
                    continue;
                };
                if explains(&f, law, (a, b), (first, last), noise) {
                    first = a;
                    last = b;
                    fitted = f;
                    continue 'grow;
                }
            }
        }
        break;
    }
    Some(Span {
        first,
        last,
        holds: s.explained(law, first, last, &fitted),
        fitted,
        from_rest: false,
    })
}

/// Whether `f`, fitted on `a..b`, explains it within the noise, the samples outside `was`
/// each within [`POINT_SPREADS`].
fn explains(
    f: &Fitted,
    law: TrackLaw,
    (a, b): (usize, usize),
    was: (usize, usize),
    noise: f64,
) -> bool {
    if f.rms() > SPREADS * noise {
        return false;
    }
    let len = b - a;
    // The acceleration's residuals are x's then y's.
    let channels = match law {
        TrackLaw::Oscillation
        | TrackLaw::Swing
        | TrackLaw::AngularOscillation
        | TrackLaw::Decay
        | TrackLaw::Drain => 1,
        TrackLaw::ConstantAcceleration => 2,
    };
    (0..channels).all(|c| {
        let r = &f.residuals[c * len..(c + 1) * len];
        (a..b)
            .filter(|i| !(was.0..was.1).contains(i))
            .all(|i| r[i - a].abs() <= POINT_SPREADS * noise)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The noise of `u` (a motion along a line at times `t`) and the oscillation's longest span
    /// on it, from a 40-sample window.
    fn oscillating(t: &[f64], u: &[f64]) -> (f64, Span) {
        let xy: Vec<(f64, f64)> = u.iter().map(|&v| (0.0, v)).collect();
        let s = Samples { t, u, xy: &xy };
        let sigma = noise(u).unwrap();
        (
            sigma,
            longest(&s, TrackLaw::Oscillation, 40, sigma, &[]).unwrap(),
        )
    }

    /// A mass held still by a hand that shakes it, then let go to oscillate.
    #[test]
    fn the_span_starts_where_the_hand_lets_go() {
        let t: Vec<f64> = (0..300).map(|i| i as f64 / 30.0).collect();
        let (w, z) = (6.0, 0.02);
        let u: Vec<f64> = t
            .iter()
            .map(|&s| {
                let ripple = 0.03 * (91.7 * s).sin();
                if s < 3.0 {
                    30.0 + 4.0 * (s * 2.3).sin().powi(3) + ripple
                } else {
                    let s = s - 3.0;
                    30.0 * (-z * s).exp() * (w * s).cos() + ripple
                }
            })
            .collect();
        let (_, span) = oscillating(&t, &u);
        assert!(span.holds);
        assert!((88..=92).contains(&span.first), "{}", span.first);
        assert_eq!(span.last, 300);
        let g0 = span.fitted.value("gamma0").unwrap().value;
        assert!((g0 / (w * w + z * z) - 1.0).abs() < 1e-3, "{g0}");
    }

    /// The halves of a span give the law's rate alike where it holds alike, and apart where the
    /// rate drifts (a spring whose period lengthens by 3 % over the span).
    #[test]
    fn halves_refit_the_rate_on_either_half() {
        let t: Vec<f64> = (0..240).map(|i| i as f64 / 30.0).collect();
        let rates = |drift: f64| {
            let u: Vec<f64> = t
                .iter()
                .map(|&s| 30.0 * (6.0 * s * (1.0 - drift * s / 8.0)).cos())
                .collect();
            let xy: Vec<(f64, f64)> = u.iter().map(|&v| (0.0, v)).collect();
            let s = Samples {
                t: &t,
                u: &u,
                xy: &xy,
            };
            let span = Span {
                first: 0,
                last: 240,
                fitted: s.fit(TrackLaw::Oscillation, 0, 240, None).unwrap(),
                holds: true,
                from_rest: false,
            };
            let h = halves(&s, TrackLaw::Oscillation, &span);
            let g0 = |v: &[Value]| v.iter().find(|v| v.name == "gamma0").unwrap().value;
            (g0(&h[0]), g0(&h[1]))
        };
        let (a, b) = rates(0.0);
        assert!(
            (a / 36.0 - 1.0).abs() < 1e-6 && (b / 36.0 - 1.0).abs() < 1e-6,
            "{a} {b}"
        );
        let (a, b) = rates(0.015);
        assert!(b < a * 0.98, "a slowing spring: {a} then {b}");
    }

    /// A bias of a few hundredths of a pixel that drifts slowly (a light, a texture under the
    /// object's edge) on an otherwise exact track: under the noise's floor, so the law holds
    /// over the whole track.
    #[test]
    fn a_slow_bias_under_a_tenth_of_a_pixel_does_not_end_the_law() {
        let t: Vec<f64> = (0..300).map(|i| i as f64 / 20.0).collect();
        let u: Vec<f64> = t
            .iter()
            .map(|&s| 20.0 * (-0.04 * s).exp() * (2.0 * s).cos() + 0.15 * (0.7 * s).sin())
            .collect();
        let (sigma, span) = oscillating(&t, &u);
        assert_eq!(sigma, LEAST_NOISE);
        assert!(span.holds);
        assert_eq!((span.first, span.last), (0, 300));
        let g0 = span.fitted.value("gamma0").unwrap().value;
        assert!((g0 / (4.0 + 0.04 * 0.04) - 1.0).abs() < 2e-3, "{g0}");
    }

    #[test]
    fn the_noise_of_a_smooth_motion_is_its_added_noise() {
        // A slow sine with an alternating ±0.5 px: the smoother leaves it all.
        let u: Vec<f64> = (0..200)
            .map(|i| 10.0 * (i as f64 * 0.05).sin() + if i % 2 == 0 { 0.5 } else { -0.5 })
            .collect();
        let n = noise(&u).unwrap();
        // The residual of ±0.5 through the smoother is 0.5·(1 + 14/21)... scaled: within 2×.
        assert!(n > 0.4 && n < 1.5, "{n}");
    }
}
