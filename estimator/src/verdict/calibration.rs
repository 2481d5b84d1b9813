//! The calibration holds: bodies' positions at reference frames (the spring's, a model file's
//! bodies) must be a similarity of the latent there (a rotation, a reflection, a scale and a
//! shift of the plane). When they are not, the encoder did not find both bodies, or the
//! references are wrong, and every value converted with the fitted scale is suspect.

use super::{Check, Grade, Reason};
use crate::analysis::Run;
use crate::calibration::{position_scale, POSITION_FIT_R2};
use physvid_shared::cli::approx;

pub struct References;

impl Check for References {
    fn name(&self) -> &'static str {
        "calibration"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let Some((_, r2)) = position_scale(&r.calibration, &r.outcome.readings.positions) else {
            return Vec::new();
        };
        if r2 >= POSITION_FIT_R2 {
            return Vec::new();
        }
        vec![Reason::new(
            self.name(),
            Grade::Doubtful,
            format!(
                "the bodies' positions at the reference frames fit the latent only with R² {} \
                 (a similarity of the plane should fit exactly): the values in pixels are \
                 suspect; check the references, or whether the encoder found both bodies \
                 (latents.png)",
                approx(r2)
            ),
        )
        .measured(r2, POSITION_FIT_R2)]
    }
}
