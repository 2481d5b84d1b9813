//! Identifiability: a value whose standard error is as large as itself is not determined by the
//! data; one whose error is a large fraction of it is barely determined; a value whose error
//! could not be computed (too few independent clips, a direction the data do not fix) is not
//! known to be determined.

use super::{Check, Grade, Reason};
use crate::analysis::parameters::ParameterResult;
use crate::analysis::Run;
use crate::physics::Settles;
use physvid_shared::cli::approx;

pub struct Determined;

/// Relative standard errors above this are doubtful (a one-σ range from half to one and a half
/// times the value); above [`UNDETERMINED`], unreliable.
pub const DOUBTFUL_RELATIVE: f64 = 0.5;
pub const UNDETERMINED: f64 = 1.0;

impl Check for Determined {
    fn name(&self) -> &'static str {
        "uncertainty"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let mut out = Vec::new();
        let any_error = r.parameters.iter().any(|p| p.standard_error.is_some());
        if !any_error && !r.parameters.is_empty() {
            out.push(Reason::new(
                self.name(),
                Grade::Doubtful,
                format!(
                    "no standard error could be computed ({} independent group(s) of clips, or a \
                     direction of the parameters the data do not fix): more clips, or a longer \
                     recording, would show whether the answer is determined",
                    r.evidence.clusters
                ),
            ));
            return out;
        }
        // The answers are the SI values where there are any; otherwise the latent-unit ones,
        // but not the latent-to-quantity map (a pendulum's angle scale) or the latent's offsets
        // (a tank's base): those are means, not answers, and how well the data fix them shows
        // in the answers that depend on them.
        let means: Vec<&str> = r
            .config
            .model
            .parameters()
            .iter()
            .filter(|p| p.settles != Settles::Relative)
            .map(|p| p.name)
            .collect();
        let any_si = r.parameters.iter().any(|p| p.units == "SI");
        let answers = r.parameters.iter().filter(|p| {
            if any_si {
                p.units == "SI"
            } else {
                !means.contains(&p.name.as_str())
            }
        });
        let model = r.config.model;
        // A value whose sign the law leaves free (a damping, an offset, a temperature, a
        // friction coefficient) may be zero: its error is judged against its own size only
        // where it is at least as large (`unsigned_reason`).
        let signed = |name: &str| {
            model
                .parameters()
                .iter()
                .find(|p| p.name == name)
                .map(|p| !p.bounds.is_positive())
                .or_else(|| {
                    model
                        .info()
                        .law
                        .truth
                        .iter()
                        .find(|t| t.name == name)
                        .map(|t| !t.positive)
                })
                .unwrap_or(false)
        };
        let (signed_answers, answers): (Vec<_>, Vec<_>) = answers.partition(|p| signed(&p.name));
        out.extend(
            signed_answers
                .into_iter()
                .filter_map(|p| self.unsigned_reason(p)),
        );
        for p in answers {
            let Some(se) = p.standard_error else { continue };
            let rel = se / p.estimate.abs().max(1e-300);
            let grade = if rel >= UNDETERMINED {
                Grade::Unreliable
            } else if rel >= DOUBTFUL_RELATIVE {
                Grade::Doubtful
            } else {
                continue;
            };
            let what = if grade == Grade::Unreliable {
                "is not determined by the data"
            } else {
                "is barely determined by the data"
            };
            out.push(
                Reason::new(
                    self.name(),
                    grade,
                    format!(
                        "{} = {} ± {} {what} (the error is {} % of the value): longer clips, \
                         more of the motion, or a calibration would pin it",
                        p.name,
                        approx(p.estimate),
                        approx(se),
                        approx(100.0 * rel)
                    ),
                )
                .measured(rel, DOUBTFUL_RELATIVE),
            );
        }
        out
    }
}

impl Determined {
    /// A value whose sign the law leaves free, with an error at least as large as itself: the
    /// data fix neither its size nor its sign. Doubtful, not unreliable: none at all may be the
    /// truth (an undamped swing), and the other values stand on their own. Measured on the
    /// others' suite (`scripts/others_suite.py`, seeds 7 and 11: 45 right answers): every right
    /// damping's error under three quarters of it; four dampings 33–94 % off under moving
    /// clutter (seed 7) at 1.0–3.8 times their value.
    fn unsigned_reason(&self, p: &ParameterResult) -> Option<Reason> {
        let se = p.standard_error?;
        let rel = se / p.estimate.abs().max(1e-300);
        (rel >= UNDETERMINED).then(|| {
            Reason::new(
                self.name(),
                Grade::Doubtful,
                format!(
                    "{} = {} ± {}: its error is as large as itself, so the data fix neither its \
                     size nor its sign (none at all is within it); longer clips or more of the \
                     motion would pin it",
                    p.name,
                    approx(p.estimate),
                    approx(se)
                ),
            )
            .measured(rel, UNDETERMINED)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn damping(estimate: f64, standard_error: Option<f64>) -> ParameterResult {
        ParameterResult::si("gamma1", estimate, "1/s", standard_error)
    }

    #[test]
    fn a_free_signed_value_is_doubtful_only_where_its_error_reaches_its_size() {
        // Under moving clutter: γ1 = 0.0048 ± 0.018 (the truth 0.08).
        let r = Determined
            .unsigned_reason(&damping(0.00484, Some(0.018)))
            .expect("undetermined");
        assert_eq!(r.grade, Grade::Doubtful);
        assert!(
            r.detail.contains("neither its size nor its sign"),
            "{}",
            r.detail
        );
        // The widest right damping measured, 0.0744 ± 0.0369 (half of itself), and one of
        // the opposite sign as well determined: nothing said.
        assert!(Determined
            .unsigned_reason(&damping(0.0744, Some(0.0369)))
            .is_none());
        assert!(Determined
            .unsigned_reason(&damping(-0.0744, Some(0.0369)))
            .is_none());
        // No error: nothing to weigh (the missing error is its own reason above).
        assert!(Determined.unsigned_reason(&damping(0.001, None)).is_none());
    }
}
