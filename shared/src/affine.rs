//! `AffineFit`: the least-squares line y = slope·x + intercept with its R², used for
//! calibrations (latent against a measured quantity) and for checking a latent against the truth.

use serde::{Deserialize, Serialize};

/// Least-squares fit y = slope·x + intercept, with R².
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AffineFit {
    pub slope: f64,
    pub intercept: f64,
    pub r2: f64,
}

impl AffineFit {
    /// The fit of `y` against `x` (pairs in order); `None` unless both vary.
    pub fn of(x: &[f64], y: &[f64]) -> Option<AffineFit> {
        if x.len() < 2 || y.len() != x.len() {
            return None;
        }
        let n = x.len() as f64;
        let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
        let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
        for (a, b) in x.iter().zip(y) {
            sxx += (a - mx).powi(2);
            sxy += (a - mx) * (b - my);
            syy += (b - my).powi(2);
        }
        (sxx > 0.0 && syy > 0.0).then(|| AffineFit {
            slope: sxy / sxx,
            intercept: my - sxy / sxx * mx,
            r2: sxy * sxy / (sxx * syy),
        })
    }
}

/// Least-squares similarity map of points in the plane, latent ≈ scale·R·truth + offset, with R
/// a rotation or a reflection (whichever fits better), and its R².
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SimilarityFit {
    pub scale: f64,
    /// Rotation angle (rad).
    pub angle: f64,
    /// Whether R is a reflection.
    pub reflected: bool,
    pub r2: f64,
}

impl SimilarityFit {
    /// The fit of `latent` against `truth` (pairs of points in order); `None` unless both vary.
    pub fn of(truth: &[[f64; 2]], latent: &[[f64; 2]]) -> Option<SimilarityFit> {
        if truth.len() < 2 || latent.len() != truth.len() {
            return None;
        }
        let n = truth.len() as f64;
        let mean = |p: &[[f64; 2]]| {
            let (x, y) = p.iter().fold((0.0, 0.0), |a, q| (a.0 + q[0], a.1 + q[1]));
            [x / n, y / n]
        };
        let (mt, ml) = (mean(truth), mean(latent));
        let centred = |p: &[[f64; 2]], m: [f64; 2]| -> Vec<[f64; 2]> {
            p.iter().map(|q| [q[0] - m[0], q[1] - m[1]]).collect()
        };
        let (t, l) = (centred(truth, mt), centred(latent, ml));
        let tt: f64 = t.iter().map(|q| q[0] * q[0] + q[1] * q[1]).sum();
        let ll: f64 = l.iter().map(|q| q[0] * q[0] + q[1] * q[1]).sum();
        if !(tt > 0.0 && ll > 0.0) {
            return None;
        }
        // As complex numbers, latent = a·truth (or a·conj(truth)): a = Σ conj(t)·l / Σ |t|².
        let fit = |flip: f64| {
            let (mut re, mut im) = (0.0, 0.0);
            for (p, q) in t.iter().zip(&l) {
                let (px, py) = (p[0], flip * p[1]);
                re += px * q[0] + py * q[1];
                im += px * q[1] - py * q[0];
            }
            let (ar, ai) = (re / tt, im / tt);
            let sse: f64 = t
                .iter()
                .zip(&l)
                .map(|(p, q)| {
                    let (px, py) = (p[0], flip * p[1]);
                    (q[0] - (ar * px - ai * py)).powi(2) + (q[1] - (ar * py + ai * px)).powi(2)
                })
                .sum();
            (ar, ai, sse)
        };
        let (rot, refl) = (fit(1.0), fit(-1.0));
        let ((ar, ai, sse), reflected) = if refl.2 < rot.2 {
            (refl, true)
        } else {
            (rot, false)
        };
        Some(SimilarityFit {
            scale: ar.hypot(ai),
            angle: ai.atan2(ar),
            reflected,
            r2: 1.0 - sse / ll,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn similarity_recovers_scale_rotation_and_reflection() {
        let truth = [[0.0, 0.0], [1.0, 0.0], [0.0, 2.0], [3.0, 1.0]];
        for reflect in [false, true] {
            let latent: Vec<[f64; 2]> = truth
                .iter()
                .map(|p| {
                    let y = if reflect { -p[1] } else { p[1] };
                    let (c, s) = (0.5f64.cos(), 0.5f64.sin());
                    [
                        2.5 * (c * p[0] - s * y) + 1.0,
                        2.5 * (s * p[0] + c * y) - 4.0,
                    ]
                })
                .collect();
            let f = SimilarityFit::of(&truth, &latent).unwrap();
            assert!(
                (f.scale - 2.5).abs() < 1e-12 && (f.r2 - 1.0).abs() < 1e-12,
                "{f:?}"
            );
            assert_eq!(f.reflected, reflect);
        }
    }

    #[test]
    fn exact_line_and_degenerate_inputs() {
        let f = AffineFit::of(&[0.0, 1.0, 2.0], &[1.0, 3.0, 5.0]).unwrap();
        assert!((f.slope - 2.0).abs() < 1e-12 && (f.intercept - 1.0).abs() < 1e-12);
        assert!((f.r2 - 1.0).abs() < 1e-12);
        assert!(AffineFit::of(&[1.0, 1.0], &[0.0, 1.0]).is_none());
        assert!(AffineFit::of(&[1.0], &[0.0]).is_none());
    }
}
