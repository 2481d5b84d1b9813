//! Physics: values the model forbids or that no such system has (a growing amplitude where the
//! system dissipates, a negative friction coefficient, a fall slower than a feather's), as each
//! model states them (`Model::implausible`).

use super::{Check, Grade, Reason};
use crate::analysis::Run;

pub struct Plausible;

impl Check for Plausible {
    fn name(&self) -> &'static str {
        "physics"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let values: Vec<(&str, f64, f64)> = r
            .parameters
            .iter()
            .map(|p| (p.name.as_str(), p.estimate, p.standard_error.unwrap_or(0.0)))
            .collect();
        r.config
            .model
            .implausible(&values)
            .into_iter()
            .map(|i| {
                let grade = if i.forbidden {
                    Grade::Unreliable
                } else {
                    Grade::Doubtful
                };
                Reason::new(self.name(), grade, i.detail)
            })
            .collect()
    }
}
