//! Harmonics: a latent that is an even function of the motion (a bob's height, |x|) swings at
//! twice the motion's frequency, and the law fits it there as well as the motion at its own.
//! Such a latent folds a coordinate of the picture (see `evidence::fold`): one side of the
//! swing and the other give the same latent, so the picture's coordinate is not a function of
//! the latent while the latent is one of it. Where the object's track corroborates the rate
//! (`routes::corroborates`), the rates are not the fold's four times the motion's: a fold at the
//! doubtful tier is then a note.

use super::{routes, Check, Grade, Reason};
use crate::analysis::Run;
use physvid_shared::cli::approx;

pub struct Harmonic;

use crate::evidence::fold::{FOLDED, MAYBE_FOLDED};

impl Check for Harmonic {
    fn name(&self) -> &'static str {
        "harmonic"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let Some(f) = &r.evidence.fold else {
            return Vec::new();
        };
        if f.folded_share < MAYBE_FOLDED {
            return Vec::new();
        }
        let grade = if f.folded_share >= FOLDED {
            Grade::Unreliable
        } else {
            Grade::Doubtful
        };
        let oscillates = r.config.model.rate(&r.final_values).is_some();
        let consequence = if oscillates {
            "it follows an even function of the motion (a height, a distance from the middle), \
             which swings at twice the motion's frequency, so the rates come out about four \
             times too large (γ0, g/L); the fundamental is near a quarter of them: crop to the \
             object's path (--crop) or start there (--init ... --single-start)"
        } else {
            "it does not follow the motion one to one (an even function of it?): crop to the \
             object's path (--crop) and check the model"
        };
        let reason = Reason::new(
            self.name(),
            grade,
            format!(
                "the latent folds the picture: frames on either side of the motion give the same \
                 latent ({} % of the frames' leading components differ between them by an \
                 amount the latent itself fixes); {consequence}",
                approx(100.0 * f.folded_share),
            ),
        )
        .measured(f.folded_share, FOLDED);
        match grade {
            Grade::Doubtful => vec![reason.unless(routes::corroborated(r))],
            _ => vec![reason],
        }
    }
}
