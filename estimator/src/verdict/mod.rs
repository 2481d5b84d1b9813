//! The verdict on an answer: `ok`, `doubtful` or `unreliable`, with the reasons in words a user
//! can act on, computed from evidence about the run (`evidence/`) and the report. Each check is
//! one file implementing [`Check`], listed once in [`CHECKS`]; README's "Reading the verdict"
//! describes them, and their thresholds are justified there by measurement.

mod calibration;
mod consistency;
mod harmonic;
mod law;
mod motion;
mod physics;
mod premise;
mod sampling;
mod training;
mod uncertainty;

use crate::report::Report;
use serde::Serialize;

/// How far an answer can be trusted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Grade {
    /// Nothing the checks can see speaks against it.
    Ok,
    /// Something speaks against it: read the reasons before using it.
    Doubtful,
    /// It is most likely wrong (or not determined by the data): do not use it as it stands.
    Unreliable,
}

impl Grade {
    pub fn name(self) -> &'static str {
        match self {
            Grade::Ok => "ok",
            Grade::Doubtful => "doubtful",
            Grade::Unreliable => "unreliable",
        }
    }
}

/// One finding of one check.
#[derive(Debug, Clone, Serialize)]
pub struct Reason {
    /// The check's name.
    pub check: &'static str,
    pub grade: Grade,
    /// What was found and what to do about it.
    pub detail: String,
    /// The figure the check measured, and the limit it was held against, where there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub value: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit: Option<f64>,
}

impl Reason {
    pub fn new(check: &'static str, grade: Grade, detail: impl Into<String>) -> Reason {
        Reason {
            check,
            grade,
            detail: detail.into(),
            value: None,
            limit: None,
        }
    }

    /// The figure measured and the limit it crossed.
    pub fn measured(mut self, value: f64, limit: f64) -> Reason {
        self.value = Some(value);
        self.limit = Some(limit);
        self
    }
}

/// The verdict: the worst grade among the reasons (`ok` without any).
#[derive(Debug, Clone, Serialize)]
pub struct Verdict {
    pub grade: Grade,
    pub reasons: Vec<Reason>,
}

impl Verdict {
    /// The verdict of `report`'s answer, from every check of [`CHECKS`].
    pub fn of(report: &Report) -> Verdict {
        let mut reasons: Vec<Reason> = CHECKS.iter().flat_map(|c| c.judge(report)).collect();
        reasons.sort_by_key(|r| std::cmp::Reverse(r.grade));
        Verdict {
            grade: reasons.iter().map(|r| r.grade).max().unwrap_or(Grade::Ok),
            reasons,
        }
    }

    /// The verdict as lines for the terminal.
    pub fn text(&self) -> String {
        let mut s = format!("verdict: {}", self.grade.name());
        if self.reasons.is_empty() {
            s += " (no check found anything against this answer)";
        }
        for r in &self.reasons {
            s += &format!("\n  - {} [{}]: {}", r.check, r.grade.name(), r.detail);
        }
        s
    }
}

/// One check of an answer.
pub trait Check: Sync {
    /// Its name in report.json's reasons.
    fn name(&self) -> &'static str;
    /// What it finds against `report`'s answer (nothing: no objection).
    fn judge(&self, report: &Report) -> Vec<Reason>;
}

/// Every check, in the order their reasons are listed at equal grade.
pub static CHECKS: &[&dyn Check] = &[
    &training::Training,
    &sampling::Sampling,
    &harmonic::Harmonic,
    &motion::FollowsMotion,
    &law::LawFits,
    &premise::Premise,
    &uncertainty::Determined,
    &consistency::Halves,
    &physics::Plausible,
    &calibration::References,
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique() {
        let mut names: Vec<_> = CHECKS.iter().map(|c| c.name()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), CHECKS.len());
        assert!(Grade::Unreliable > Grade::Doubtful && Grade::Doubtful > Grade::Ok);
    }
}
