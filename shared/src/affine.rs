//! `AffineFit`: the least-squares line y = slope·x + intercept with its R², used for
//! calibrations (latent against a measured quantity) and for checking a latent against the truth.

use serde::Serialize;

/// Least-squares fit y = slope·x + intercept, with R².
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_line_and_degenerate_inputs() {
        let f = AffineFit::of(&[0.0, 1.0, 2.0], &[1.0, 3.0, 5.0]).unwrap();
        assert!((f.slope - 2.0).abs() < 1e-12 && (f.intercept - 1.0).abs() < 1e-12);
        assert!((f.r2 - 1.0).abs() < 1e-12);
        assert!(AffineFit::of(&[1.0, 1.0], &[0.0, 1.0]).is_none());
        assert!(AffineFit::of(&[1.0], &[0.0]).is_none());
    }
}
