//! `--ensemble K`: K independently seeded trainings on the same clips (seeds --seed … --seed+K−1,
//! one after another, each using every core), and the spread of each reported value across
//! them: mean, sample standard deviation and range.

use super::parameters::ParameterResult;
use serde::{Deserialize, Serialize};

/// One reported value across the ensemble.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct EnsembleValue {
    pub name: String,
    pub units: String,
    pub unit: String,
    pub mean: f64,
    /// Sample standard deviation (n − 1).
    pub std: f64,
    pub min: f64,
    pub max: f64,
    /// Each member's value, in seed order.
    pub values: Vec<f64>,
    pub truth: Option<f64>,
    /// Whether the truth lies within mean ± 2·std.
    pub truth_within_2std: Option<bool>,
}

/// The ensemble's summary, in report.json as `ensemble`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Ensemble {
    pub members: usize,
    pub seeds: Vec<u64>,
    pub values: Vec<EnsembleValue>,
}

/// Summarises the members' reported values (`members[i]` from seed `seeds[i]`); values are
/// matched by name, in the first member's order.
pub fn summarise(seeds: Vec<u64>, members: &[Vec<ParameterResult>]) -> Ensemble {
    let values = members
        .first()
        .map(|first| {
            first
                .iter()
                .map(|p| {
                    let values: Vec<f64> = members
                        .iter()
                        .filter_map(|m| m.iter().find(|q| q.name == p.name).map(|q| q.estimate))
                        .collect();
                    let n = values.len() as f64;
                    let mean = values.iter().sum::<f64>() / n;
                    let var =
                        values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
                    let std = var.sqrt();
                    EnsembleValue {
                        name: p.name.clone(),
                        units: p.units.clone(),
                        unit: p.unit.clone(),
                        mean,
                        std,
                        min: values.iter().copied().fold(f64::INFINITY, f64::min),
                        max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                        truth: p.truth,
                        truth_within_2std: p.truth.map(|t| (t - mean).abs() <= 2.0 * std),
                        values,
                    }
                })
                .collect()
        })
        .unwrap_or_default();
    Ensemble {
        members: members.len(),
        seeds,
        values,
    }
}

impl Ensemble {
    /// The closing table: mean ± std and range of each value.
    pub fn table(&self) -> String {
        let mut s = format!(
            "ensemble of {} (seeds {}–{})\n{:<20} {:>12} {:>12} {:>25} {:>7} {:>12}\n",
            self.members,
            self.seeds.first().unwrap_or(&0),
            self.seeds.last().unwrap_or(&0),
            "parameter",
            "mean",
            "std",
            "range",
            "unit",
            "truth"
        );
        for v in &self.values {
            s += &format!(
                "{:<20} {:>12.6} {:>12.6} {:>25} {:>7} {:>12}\n",
                v.name,
                v.mean,
                v.std,
                format!("[{:.6}, {:.6}]", v.min, v.max),
                v.unit,
                v.truth.map_or("-".into(), |t| format!("{t:.6}"))
            );
        }
        s.trim_end().to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(name: &str, estimate: f64) -> ParameterResult {
        ParameterResult {
            truth: Some(4.0),
            ..ParameterResult::si(name, estimate, "m/s^2", None)
        }
    }

    #[test]
    fn spread_is_the_sample_standard_deviation() {
        let e = summarise(
            vec![0, 1, 2],
            &[vec![p("g", 3.9)], vec![p("g", 4.0)], vec![p("g", 4.1)]],
        );
        let v = &e.values[0];
        assert!((v.mean - 4.0).abs() < 1e-12);
        assert!((v.std - 0.1).abs() < 1e-12);
        assert_eq!((v.min, v.max), (3.9, 4.1));
        assert_eq!(v.truth_within_2std, Some(true));
        assert!(e.table().contains("ensemble of 3"));
    }
}
