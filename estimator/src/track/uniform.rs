//! Uniform motion, what needs no force: a constant acceleration is a law of the track only
//! where a straight line at constant speed does not explain its span as well (a person walking
//! behind the object, a drift of the picture).

use super::laws::linear;
use super::segment::{Samples, SPREADS};

/// Whether a uniform motion (p0 + v t in x and y: what needs no force) explains the picture
/// positions of `a..b` within `noise` as a law's span must ([`SPREADS`]): a constant
/// acceleration there is then no law's (a person walking behind, a drift).
pub(super) fn uniform(s: &Samples, a: usize, b: usize, noise: f64) -> bool {
    let t = &s.t[a..b];
    let line = [vec![1.0; t.len()], t.to_vec()];
    let xy = &s.xy[a..b];
    let ss = |u: Vec<f64>| linear(&line, &u).map(|(_, r)| r.iter().map(|e| e * e).sum::<f64>());
    match (
        ss(xy.iter().map(|p| p.0).collect()),
        ss(xy.iter().map(|p| p.1).collect()),
    ) {
        // The acceleration's residuals are x's and y's alike: their mean square.
        (Some(x), Some(y)) => ((x + y) / (2 * t.len()) as f64).sqrt() <= SPREADS * noise,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_walk_is_uniform_and_a_fall_is_not() {
        let t: Vec<f64> = (0..60).map(|i| i as f64 / 30.0).collect();
        // 12 px/s across, wobbling by a tenth of a pixel; its noise 0.1 px.
        let walk: Vec<(f64, f64)> = t
            .iter()
            .enumerate()
            .map(|(i, s)| (12.0 * s + 0.1 * (i % 2) as f64, 150.0))
            .collect();
        let u = vec![0.0; t.len()];
        let s = Samples {
            t: &t,
            u: &u,
            xy: &walk,
        };
        assert!(uniform(&s, 0, 60, 0.1));
        // Falling from rest at 2 px/s² leaves 0.21 px rms of the line over 2 s (x's and y's):
        // uniform within three noises; at 20 px/s², 2.1 px, it is not.
        for (a, seen) in [(2.0, true), (20.0, false)] {
            let fall: Vec<(f64, f64)> = t.iter().map(|s| (40.0, 0.5 * a * s * s)).collect();
            let s = Samples {
                t: &t,
                u: &u,
                xy: &fall,
            };
            assert_eq!(uniform(&s, 0, 60, 0.1), seen, "{a}");
        }
    }
}
