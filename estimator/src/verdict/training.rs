//! Training itself: a latent that collapsed, parameters that never left their start, a run
//! that never improved after its first epochs or was still improving when it was stopped, and
//! a loss that became NaN.

use super::{Check, Grade, Reason};
use crate::analysis::Run;
use crate::train::StopReason;

pub struct Training;

/// A kept checkpoint this early in a run of at least [`LONG_RUN`] epochs: the validation error
/// never improved after the first epochs (measured: good runs keep epoch 9 or later; a real
/// pendulum whose bob is mostly out of frame kept epoch 1).
pub const EARLY_BEST: usize = 2;
const LONG_RUN: usize = 10;

impl Check for Training {
    fn name(&self) -> &'static str {
        "training"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let mut out = Vec::new();
        let name = self.name();
        if r.latent_collapsed {
            out.push(Reason::new(
                name,
                Grade::Unreliable,
                "the latent collapsed towards a constant, which fits any parameters: the values \
                 are not determined by the video; train with --loss mse+kl, check the framing \
                 (--preview: crop, stride) or try another --seed",
            ));
        }
        let unmoved = !r.final_values.is_empty()
            && r.final_values
                .iter()
                .zip(&r.initial_values)
                .all(|(p, s)| (p - s).abs() <= 1e-9 * s.abs().max(1e-12));
        if unmoved {
            out.push(Reason::new(
                name,
                Grade::Unreliable,
                "training left every parameter at its start: nothing in the frames moved them, \
                 so the values are the start, not a measurement",
            ));
        }
        if r.best_epoch <= EARLY_BEST && r.epochs_run >= LONG_RUN {
            out.push(
                Reason::new(
                    name,
                    Grade::Doubtful,
                    format!(
                        "the validation error never improved after epoch {} of {}: the latent \
                         did not learn to follow the motion; check the framing (--preview) and \
                         that the object is in view most of the time",
                        r.best_epoch, r.epochs_run
                    ),
                )
                .measured(r.best_epoch as f64, EARLY_BEST as f64),
            );
        }
        match r.stop {
            StopReason::MaxEpochs => out.push(Reason::new(
                name,
                Grade::Doubtful,
                format!(
                    "the validation error was still improving after --epochs {}: the answer may \
                     not have converged; raise --epochs",
                    r.config.epochs
                ),
            )),
            StopReason::NonFiniteLoss { epoch } => out.push(Reason::new(
                name,
                Grade::Doubtful,
                format!(
                    "the loss became NaN or infinite in epoch {epoch} and training stopped there \
                     (the best earlier epoch is kept); lower --lr or --lr-phys"
                ),
            )),
            StopReason::LawNotFinite { epoch, ref detail } => out.push(Reason::new(
                name,
                Grade::Unreliable,
                format!(
                    "the law gave no finite value in epoch {epoch} and training stopped: {detail}"
                ),
            )),
            StopReason::EarlyStop { .. } | StopReason::Converged { .. } => {}
        }
        out
    }
}
