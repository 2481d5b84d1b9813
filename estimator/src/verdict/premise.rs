//! The model's premise about the picture: where the model assumes every pixel is an affine
//! function of the quantity (an LED's brightness scales its light), the frames must lie on a
//! line through pixel space, and the latent must explain them as an affine function. A latent
//! that only a curved map turns into the law's motion (a draining tank's moving edge read as a
//! dimming light) fits the law for any first-order law: this is where it shows.

use super::{Check, Grade, Reason};
use crate::report::Report;
use physvid_shared::cli::approx;

pub struct Premise;

/// The share of what the latent explains of the picture that an affine function of it must
/// explain too (measured: LED scenes 1.000; a draining tank's frames read by the LED model
/// 0.46–0.55).
pub const AFFINE: f64 = 0.9;
pub const NOT_AFFINE: f64 = 0.75;

impl Check for Premise {
    fn name(&self) -> &'static str {
        "premise"
    }
    fn judge(&self, r: &Report) -> Vec<Reason> {
        let (Some(why), Some(f)) = (
            r.config.model.info().footage.affine_picture,
            &r.evidence.fold,
        ) else {
            return Vec::new();
        };
        let ratio = f.affine_share / f.explained_share.max(1e-12);
        if ratio >= AFFINE {
            return Vec::new();
        }
        let grade = if ratio < NOT_AFFINE {
            Grade::Unreliable
        } else {
            Grade::Doubtful
        };
        vec![Reason::new(
            self.name(),
            grade,
            format!(
                "{} assumes every pixel is an affine function of the quantity ({why}), but an \
                 affine function of the latent explains only {} % of what the latent explains \
                 of the frames: the video shows another kind of change (a moving edge, a level, \
                 a shape); check the model",
                r.config.model.name(),
                approx(100.0 * ratio)
            ),
        )
        .measured(ratio, AFFINE)]
    }
}
