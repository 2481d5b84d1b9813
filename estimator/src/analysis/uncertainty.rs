//! The reported values' standard errors and their refits on each half of the data: the block's
//! covariance (`evidence::curvature`) carried through the model's `derive` by the delta method
//! (central differences), and the halves' block parameters derived the same way. The latent's
//! readings at reference frames are held: their own error is not in these figures.

use crate::calibration::{Calibration, DerivedValue, Readings};
use crate::evidence::{Split, SplitBy};
use crate::physics::ModelRef;
use serde::{Deserialize, Serialize};

/// Standard errors of the values `derive` gives for `params`, in its order (`None` where the
/// covariance is unknown or not finite, or where the value does not depend on the block's
/// parameters, such as a latent map settled by the final solve).
pub fn standard_errors(
    model: ModelRef,
    params: &[f64],
    covariance: Option<&[f64]>,
    cal: &Calibration,
    readings: &Readings,
) -> Vec<Option<f64>> {
    let values = |p: &[f64]| -> Vec<f64> {
        model
            .derive(p, cal, readings)
            .0
            .iter()
            .map(|v| v.estimate)
            .collect()
    };
    let base = values(params);
    let m = params.len();
    let Some(cov) = covariance.filter(|c| c.len() == m * m) else {
        return vec![None; base.len()];
    };
    // d(value)/d(parameter) by central differences, a step of a small fraction of the
    // parameter's own standard error (or of its size).
    let mut jac = vec![0.0; base.len() * m];
    for j in 0..m {
        let se = cov[j * m + j].max(0.0).sqrt();
        let h = (1e-3 * se).max(1e-9 * params[j].abs()).max(1e-15);
        let mut p = params.to_vec();
        p[j] = params[j] + h;
        let plus = values(&p);
        p[j] = params[j] - h;
        let minus = values(&p);
        if plus.len() != base.len() || minus.len() != base.len() {
            return vec![None; base.len()];
        }
        for i in 0..base.len() {
            jac[i * m + j] = (plus[i] - minus[i]) / (2.0 * h);
        }
    }
    (0..base.len())
        .map(|i| {
            let row = &jac[i * m..(i + 1) * m];
            let var: f64 = (0..m)
                .flat_map(|a| (0..m).map(move |b| (a, b)))
                .map(|(a, b)| row[a] * cov[a * m + b] * row[b])
                .sum();
            (var.is_finite() && var > 0.0).then(|| var.sqrt())
        })
        .collect()
}

/// The refits on each half of every split, derived like the answer: per reported value (in the
/// order of `names`), one [`SplitValue`] per split that gives it.
pub fn splits(
    model: ModelRef,
    splits: &[Split],
    names: &[String],
    cal: &Calibration,
    readings: &Readings,
) -> Vec<Vec<SplitValue>> {
    let derived: Vec<[Derivation; 2]> = splits
        .iter()
        .map(|s| {
            [0, 1].map(|h| {
                let p = &s.values[h];
                (
                    model.derive(p, cal, readings).0,
                    standard_errors(model, p, s.covariances[h].as_deref(), cal, readings),
                )
            })
        })
        .collect();
    names
        .iter()
        .map(|n| {
            splits
                .iter()
                .zip(&derived)
                .filter_map(|(s, d)| {
                    let pick = |(rows, errors): &Derivation| {
                        let i = rows.iter().position(|v| &v.name == n)?;
                        Some((rows[i].estimate, errors[i]))
                    };
                    let (a, ea) = pick(&d[0])?;
                    let (b, eb) = pick(&d[1])?;
                    Some(SplitValue {
                        by: s.by,
                        values: [a, b],
                        errors: [ea, eb],
                    })
                })
                .collect()
        })
        .collect()
}

/// The values `derive` gives for one half's parameters, with their standard errors.
type Derivation = (Vec<DerivedValue>, Vec<Option<f64>>);

/// One reported value refitted on the two halves of a split.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SplitValue {
    pub by: SplitBy,
    pub values: [f64; 2],
    pub errors: [Option<f64>; 2],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_follow_the_derivation() {
        // The oscillator reports its parameters as they are: the errors are the covariance's
        // diagonal.
        let osc = ModelRef::by_name("damped-oscillator").unwrap();
        let cov = [4e-6, 1e-7, 1e-7, 9e-8];
        let se = standard_errors(
            osc,
            &[4.0, 0.08],
            Some(&cov),
            &Calibration::default(),
            &Readings::default(),
        );
        assert!((se[0].unwrap() - 2e-3).abs() < 1e-9, "{se:?}");
        assert!((se[1].unwrap() - 3e-4).abs() < 1e-9, "{se:?}");
        // The pendulum's length L = g/(g/L): its relative error is that of g/L.
        let pendulum = ModelRef::by_name("pendulum").unwrap();
        let n = pendulum.parameters().len();
        let mut cov = vec![0.0; n * n];
        cov[0] = (0.01f64 * 20.0).powi(2);
        let params: Vec<f64> = pendulum
            .default_init()
            .iter()
            .enumerate()
            .map(|(i, v)| if i == 0 { 20.0 } else { *v })
            .collect();
        let cal = Calibration {
            g: 9.81,
            ..Default::default()
        };
        let rows = pendulum.derive(&params, &cal, &Readings::default()).0;
        let se = standard_errors(pendulum, &params, Some(&cov), &cal, &Readings::default());
        let l = rows.iter().position(|r| r.name == "length").unwrap();
        let rel = se[l].unwrap() / rows[l].estimate;
        assert!((rel - 0.01).abs() < 1e-6, "{rel}");
    }
}
