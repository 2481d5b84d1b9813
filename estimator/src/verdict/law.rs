//! The law fits: the rollout must explain the latent's motion within clips. A latent that
//! follows something the law does not describe (frames out of order, flicker, a static scene's
//! noise, a different law) leaves residuals as large as the motion itself, or a misfit that is
//! smooth in time rather than noise. Where the object's track corroborates the rate
//! (`routes::corroborates`), a doubtful fit is the encoder's noise, not the law's: a note.

use super::{routes, Check, Grade, Reason};
use crate::analysis::Run;
use physvid_shared::cli::approx;

pub struct LawFits;

/// The share of the latent's motion within clips the law may leave unexplained before the fit
/// is doubtful (right answers on `gen`'s clean scenes leave under [`CLEAN_UNEXPLAINED`], the
/// real pendulum 4.7 %; perturbed scenes whose damping came out 11–13 % off left 6.6–7.2 %),
/// and before it is unreliable.
pub const DOUBTFUL_UNEXPLAINED: f64 = 0.05;
/// What right answers on `gen`'s clean scenes leave: the law follows such a latent as well as
/// it follows anything.
pub const CLEAN_UNEXPLAINED: f64 = 0.01;
pub const UNRELIABLE_UNEXPLAINED: f64 = 0.5;
/// A misfit at least this large that is also smooth in time (residual autocorrelation above
/// [`STRUCTURED`]) says the law's shape is wrong rather than the frames noisy.
pub const STRUCTURED_UNEXPLAINED: f64 = 0.02;
pub const STRUCTURED: f64 = 0.7;

impl Check for LawFits {
    fn name(&self) -> &'static str {
        "law"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let Some(law) = &r.evidence.law else {
            return Vec::new();
        };
        let u = law.unexplained_within;
        let pct = approx(100.0 * u);
        if u >= UNRELIABLE_UNEXPLAINED {
            return vec![Reason::new(
                self.name(),
                Grade::Unreliable,
                format!(
                    "the law explains little of the latent's motion within clips ({pct} % left \
                     unexplained on the validation clips): the latent does not follow a motion \
                     of this law (frames out of order, flicker, a scene that does not move, or \
                     another model)"
                ),
            )
            .measured(u, UNRELIABLE_UNEXPLAINED)];
        }
        let doubt = if u >= DOUBTFUL_UNEXPLAINED {
            Reason::new(
                self.name(),
                Grade::Doubtful,
                format!(
                    "the law leaves {pct} % of the latent's motion within clips unexplained on \
                     the validation clips: noisy frames, a distracting motion, or another model"
                ),
            )
            .measured(u, DOUBTFUL_UNEXPLAINED)
        } else if u >= STRUCTURED_UNEXPLAINED && law.residual_autocorrelation >= STRUCTURED {
            Reason::new(
                self.name(),
                Grade::Doubtful,
                format!(
                    "the rollout misses the latent by a smooth curve, not noise ({pct} % of the \
                     motion within clips, residual autocorrelation {}): the law's shape does \
                     not match the motion; check the model",
                    approx(law.residual_autocorrelation)
                ),
            )
            .measured(law.residual_autocorrelation, STRUCTURED)
        } else {
            return Vec::new();
        };
        vec![doubt.unless(routes::corroborated(r))]
    }
}
