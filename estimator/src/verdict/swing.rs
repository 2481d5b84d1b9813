//! A law of swings must see the motion swing: the pendulum's and the oscillator's parameters
//! are read from the motion turning back (its period, the decay of its swings). On a motion
//! that only falls or only rises within every clip (a draining tank, a dimming light), an
//! overdamped swing or the slow arc of a long one fits any smooth relaxation, often better than
//! the true law; the answer (a pendulum of 95 m damped past its swing) says nothing.

use super::{Check, Grade, Reason};
use crate::analysis::Run;
use physvid_shared::cli::approx;

pub struct Swings;

/// Shares of clips whose latent must turn back (by [`TURN`](crate::evidence::TURN) of its
/// range within the clip). Measured on the true latents of `gen`'s sets (200 clips each): the oscillating scenes
/// (intensity, position, scale, the pendulum's three settings) 0.88–1.00, every monotone scene
/// (tank, LED, fall, slide; three settings each) 0.
pub const UNRELIABLE_BELOW: f64 = 0.1;
pub const DOUBTFUL_BELOW: f64 = 0.3;

impl Check for Swings {
    fn name(&self) -> &'static str {
        "swing"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let model = r.config.model;
        let (Some(what), Some(share)) = (
            model.info().footage.swings,
            r.evidence.law.as_ref().and_then(|l| l.turning_share),
        ) else {
            return Vec::new();
        };
        let Some(grade) = Grade::below(share, UNRELIABLE_BELOW, DOUBTFUL_BELOW) else {
            return Vec::new();
        };
        vec![Reason::new(
            self.name(),
            grade,
            format!(
                "{} reads its answer from the motion swinging back ({what}), but the latent \
                 turns back in only {} % of the validation clips: the clips show a relaxation \
                 or a drift, which any damped swing fits; another model (a decay, a drain), or \
                 clips long enough to show a swing (--stride, --frames-per-clip)",
                model.name(),
                approx(100.0 * share)
            ),
        )
        .measured(share, DOUBTFUL_BELOW)]
    }
}
