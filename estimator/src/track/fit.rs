//! Each law of `laws` fitted where it holds (`segment`) on a track's positions: the picture's
//! pixels, or the plane of the motion's where one is given (`plane`).

use super::laws::TrackLaw;
use super::segment::{self, longest, noise, Samples};
use super::LawSpan;

/// The window a law starts from: an oscillation's or a swing's an eighth of the track (at
/// least 12 samples), an acceleration's 10 samples.
fn least_window(law: TrackLaw, n: usize) -> usize {
    match law {
        TrackLaw::Oscillation | TrackLaw::Swing => (n / 8).max(12),
        TrackLaw::ConstantAcceleration => 10,
    }
}

/// Each law fitted where it holds on positions `xy` at times `t`, and what it was read along.
pub(super) struct Fitted {
    pub along: Vec<f64>,
    pub axis: (f64, f64),
    pub noise: f64,
    pub laws: Vec<LawSpan>,
}

/// The laws of positions `xy` (pixels of the picture, or of the plane of the motion) at times
/// `t`: the path's principal axis, the noise along it, and each law's span.
pub(super) fn fit(t: &[f64], xy: &[(f64, f64)]) -> Fitted {
    let (x, y): (Vec<f64>, Vec<f64>) = xy.iter().copied().unzip();
    let (along, axis) = principal_axis(&x, &y);
    let sigma = noise(&along).unwrap_or(segment::LEAST_NOISE);
    let samples = Samples { t, u: &along, xy };
    let laws = TrackLaw::ALL
        .iter()
        .filter_map(|&law| {
            let s = longest(&samples, law, least_window(law, t.len()), sigma)?;
            Some(LawSpan {
                halves: segment::halves(&samples, law, &s),
                law,
                holds: s.holds,
                first_s: t[s.first],
                last_s: t[s.last - 1],
                samples: s.last - s.first,
                rms_px: s.fitted.rms(),
                si: Vec::new(),
                periods: s.fitted.periods,
                values: s.fitted.values,
                curve: s.fitted.curve,
                first: s.first,
            })
        })
        .collect();
    Fitted {
        along,
        axis,
        noise: sigma,
        laws,
    }
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
}
