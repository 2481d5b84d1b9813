//! Whether a run's flags choose its model (`--model auto`, or none on a recording); what each
//! candidate is asked is derived from the typed request (`choice::candidate_request`), never
//! from these flags.

use super::{EstimateArgs, ModelSpec};
use crate::choice;
use crate::error::{input_error, EstimateError};

impl EstimateArgs {
    /// Whether this run chooses its model: `--model auto`, or no `--model` on an input that
    /// does not name one (a recording or a bare `.npy`; a data set's meta.json names its
    /// model). `--candidate` without a choice is refused.
    pub fn chooses_model(&self) -> Result<bool, EstimateError> {
        let wanted = match self.model.model {
            Some(ModelSpec::Auto) => true,
            Some(ModelSpec::Given(_)) => false,
            None => choice::chosen_without_model(self.input()),
        };
        if !wanted && !self.model.candidate.is_empty() {
            return Err(input_error(
                "--candidate: tried only when the model is chosen (--model auto, or no --model on a recording); drop it or pass --model auto",
            ));
        }
        Ok(wanted)
    }
}
