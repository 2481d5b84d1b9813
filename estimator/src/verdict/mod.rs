//! The verdict on an answer: `ok`, `doubtful` or `unreliable`, with the reasons in words a user
//! can act on, computed from evidence about the run (`evidence/`) and the report. Each check is
//! one file implementing [`Check`], listed once in [`CHECKS`]; README's "Reading the verdict"
//! describes them, and their thresholds are justified there by measurement.

mod calibration;
mod choice;
mod consistency;
pub mod grade;
mod harmonic;
mod law;
mod motion;
mod physics;
mod premise;
mod release;
mod sampling;
mod swing;
mod training;
mod uncertainty;

pub use grade::{Grade, Reason, Verdict};

use crate::report::Report;

/// The verdict on `report`'s answer, from every check of [`CHECKS`].
pub fn judge(report: &Report) -> Verdict {
    let mut reasons: Vec<Reason> = CHECKS.iter().flat_map(|c| c.judge(report)).collect();
    reasons.sort_by_key(|r| std::cmp::Reverse(r.grade));
    Verdict {
        grade: reasons.iter().map(|r| r.grade).max().unwrap_or(Grade::Ok),
        reasons,
    }
}

/// `report` with its verdict.
pub fn judged(mut report: Report) -> Report {
    report.verdict = judge(&report);
    report
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
    &swing::Swings,
    &harmonic::Harmonic,
    &motion::FollowsMotion,
    &law::LawFits,
    &premise::Premise,
    &release::Release,
    &uncertainty::Determined,
    &consistency::Halves,
    &physics::Plausible,
    &calibration::References,
    &choice::Choice,
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
