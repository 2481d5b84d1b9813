//! The verdict on an answer: `ok`, `doubtful` or `unreliable`, with the reasons in words a user
//! can act on, computed from the pipeline's `Run` (its evidence, fits and data facts; never
//! report.json's layout). Each check is one file implementing [`Check`], listed once in
//! [`CHECKS`]; the model choice adds its own reason (`choice::close`, named [`CHOICE`]).
//! README's "Reading the verdict" describes them, and docs/verdict.md justifies their
//! thresholds by measurement.

mod amplitude;
mod calibration;
mod consistency;
pub mod grade;
mod harmonic;
mod law;
mod motion;
mod plausible;
mod premise;
mod release;
pub(crate) mod routes;
mod sampling;
mod swing;
mod training;
mod uncertainty;

pub use grade::{Grade, Reason, Verdict};

use crate::analysis::Run;

/// The name of the reason a model choice adds to its chosen answer's verdict (a close call).
pub const CHOICE: &str = "choice";

/// The verdict on `run`'s answer, from every check of [`CHECKS`].
pub fn judge(run: &Run) -> Verdict {
    Verdict::of(CHECKS.iter().flat_map(|c| c.judge(run)).collect())
}

/// The checks that judge the answer's values themselves (how well they are determined, whether
/// such a system could have them), not how the latent learned them.
static ANSWER_CHECKS: &[&dyn Check] = &[&uncertainty::Determined, &plausible::Plausible];

/// `verdict` with the reasons of the checks that judge the answer's values (`ANSWER_CHECKS`)
/// judged again on `run`, whose values changed after the judgement (`guide::combine`: the
/// track's values in the latent's place); every other reason stands.
pub fn rejudge_answer(verdict: Verdict, run: &Run) -> Verdict {
    let names: Vec<&str> = ANSWER_CHECKS.iter().map(|c| c.name()).collect();
    let kept = verdict
        .reasons
        .into_iter()
        .filter(|r| !names.contains(&r.check));
    Verdict::of(
        kept.chain(ANSWER_CHECKS.iter().flat_map(|c| c.judge(run)))
            .collect(),
    )
}

/// One check of an answer.
pub trait Check: Sync {
    /// Its name in report.json's reasons.
    fn name(&self) -> &'static str;
    /// What it finds against `run`'s answer (nothing: no objection).
    fn judge(&self, run: &Run) -> Vec<Reason>;
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
    &plausible::Plausible,
    &calibration::References,
    &routes::Routes,
    &amplitude::Amplitude,
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique() {
        let mut names: Vec<_> = CHECKS.iter().map(|c| c.name()).chain([CHOICE]).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), CHECKS.len() + 1);
        assert!(Grade::Unreliable > Grade::Doubtful && Grade::Doubtful > Grade::Ok);
    }
}
