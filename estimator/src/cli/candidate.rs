//! A model choice's command lines: whether a run chooses its model, what the choice reads of
//! the flags (`choice::ChoiceRequest`), and each candidate's own flags (the user's, with the
//! model set and what it does not read dropped). The choice itself (`choice`) never sees
//! these types.

use super::{EstimateArgs, ModelSpec};
use crate::calibration::CalibrationInput;
use crate::choice::{self, cut::CommonCut, ChoiceRequest};
use crate::error::{input_error, EstimateError};
use crate::physics::ModelRef;

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

    /// What the model choice reads of these flags.
    pub fn choice_request(&self) -> ChoiceRequest {
        ChoiceRequest {
            input: self.input().to_path_buf(),
            recording: self.recording.request(),
            positions: !self.model.reference_positions().is_empty(),
            incline: self.model.incline_deg.is_some(),
            files: self.model.candidate.clone(),
        }
    }

    /// The flags for trying `model` (on the `cut` shared by all, unless it is released from
    /// rest): the model set, the flags it does not read dropped (a calibration it has no use
    /// for, `--init` of parameters it lacks), one member and no progress bars.
    pub fn for_candidate(&self, model: ModelRef, cut: Option<&CommonCut>) -> EstimateArgs {
        let mut a = self.clone();
        if let Some(c) = cut.filter(|_| !model.released_from_rest()) {
            a.recording.frames_per_clip = Some(c.frames_per_clip);
            a.recording.stride = Some(c.stride);
        }
        let m = &mut a.model;
        m.model = Some(ModelSpec::Given(model));
        m.candidate.clear();
        for c in CalibrationInput::ALL {
            if !model.info().calibration.inputs.contains(&c) {
                m.drop_calibration(c);
            }
        }
        if let Some(init) = m.init.as_mut() {
            init.0
                .retain(|(name, _)| model.parameters().iter().any(|p| p.name == name));
        }
        a.trying = true;
        a.training.ensemble = 1;
        a.output.quiet = true;
        a
    }
}
