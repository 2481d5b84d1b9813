//! Identifiability: a value whose standard error is as large as itself is not determined by the
//! data; one whose error is a large fraction of it is barely determined; a value whose error
//! could not be computed (too few independent clips, a direction the data do not fix) is not
//! known to be determined.

use super::{Check, Grade, Reason};
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
        // A value whose sign the law leaves free (an offset, a temperature, a friction
        // coefficient) may be zero: its error is not judged against its own size.
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
        for p in answers.filter(|p| !signed(&p.name)) {
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
