//! The model's premise about the picture, read from how much of what the latent explains of the
//! frames an affine function of it explains too. Where the model assumes every pixel is an
//! affine function of the quantity (an LED's brightness scales its light), nearly all of it
//! must be: a latent that only a curved map turns into the law's motion (a draining tank's
//! moving edge read as a dimming light) fits the law for any first-order law. Where the
//! quantity moves an edge across the picture (a tank's water line), an affine function cannot
//! draw it: frames that only brighten or dim as a whole are a light, not a level, whatever
//! first-order law the latent was bent to follow.

use super::{Check, Grade, Reason};
use crate::analysis::Run;
use crate::physics::Picture;
use physvid_shared::cli::approx;

pub struct Premise;

/// The share of what the latent explains of the picture that an affine function of it must
/// explain too where the picture is affine in the quantity (measured: LED scenes 1.000; a
/// draining tank's frames read by the LED model 0.46–0.55).
pub const AFFINE: f64 = 0.9;
pub const NOT_AFFINE: f64 = 0.75;

/// The share it may not reach where the quantity moves an edge (measured: `gen`'s tank scenes
/// 0.56–0.67 at every setting and level, the shared jar 0.43; an LED's frames read by the
/// tank's law 1.00).
pub const EDGE_DOUBTFUL: f64 = 0.85;
pub const EDGE_UNRELIABLE: f64 = 0.95;

impl Check for Premise {
    fn name(&self) -> &'static str {
        "premise"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let (Some(premise), Some(f)) = (r.config.model.info().footage.picture, &r.evidence.fold)
        else {
            return Vec::new();
        };
        let ratio = f.affine_share / f.explained_share.max(1e-12);
        let model = r.config.model.name();
        let pct = approx(100.0 * ratio);
        let (grade, detail, limit) = match premise {
            Picture::Affine(why) => {
                if ratio >= AFFINE {
                    return Vec::new();
                }
                let grade = if ratio < NOT_AFFINE {
                    Grade::Unreliable
                } else {
                    Grade::Doubtful
                };
                let detail = format!(
                    "{model} assumes every pixel is an affine function of the quantity ({why}), \
                     but an affine function of the latent explains only {pct} % of what the \
                     latent explains of the frames: the video shows another kind of change (a \
                     moving edge, a level, a shape); check the model"
                );
                (grade, detail, AFFINE)
            }
            Picture::MovingEdge(why) => {
                if ratio < EDGE_DOUBTFUL {
                    return Vec::new();
                }
                let grade = if ratio >= EDGE_UNRELIABLE {
                    Grade::Unreliable
                } else {
                    Grade::Doubtful
                };
                let detail = format!(
                    "{model} reads a quantity that moves an edge across the picture ({why}), \
                     but an affine function of the latent explains {pct} % of what the latent \
                     explains of the frames: they brighten or dim as a whole, as a light does, \
                     and the latent was bent to follow this law; check the model (a decay: \
                     --model led)"
                );
                (grade, detail, EDGE_DOUBTFUL)
            }
        };
        vec![Reason::new(self.name(), grade, detail).measured(ratio, limit)]
    }
}
