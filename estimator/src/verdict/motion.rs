//! The latent follows what moves: the principal components of the frames (what changes in the
//! picture) must be largely a function of the latent. A latent that explains almost none of
//! them follows a detail (a leaf among branches, one pixel's flicker) rather than the motion
//! the law describes, and the law fitted to it says nothing about the scene.

use super::{Check, Grade, Reason};
use crate::report::Report;
use physvid_shared::cli::approx;

pub struct FollowsMotion;

/// Shares of the frames' leading components the latent must explain (measured: `gen`'s scenes
/// 0.99–1.00, the shared pendulum and jar recordings 0.75 and 0.99, a rod-and-bob behind moving
/// clutter 0.87 with its true angle; a tree's branches swaying in the wind 0.008).
pub const UNRELIABLE_BELOW: f64 = 0.05;
pub const DOUBTFUL_BELOW: f64 = 0.15;

impl Check for FollowsMotion {
    fn name(&self) -> &'static str {
        "motion"
    }
    fn judge(&self, r: &Report) -> Vec<Reason> {
        let Some(f) = &r.evidence.fold else {
            return Vec::new();
        };
        let e = f.explained_share;
        let Some(grade) = Grade::below(e, UNRELIABLE_BELOW, DOUBTFUL_BELOW) else {
            return Vec::new();
        };
        vec![Reason::new(
            self.name(),
            grade,
            format!(
                "the latent explains only {} % of what changes in the frames (their leading \
                 principal components): it follows a detail, not the scene's main motion \
                 (several things moving, a background that changes, or nothing of this law); \
                 crop to the object (--crop) and check the model",
                approx(100.0 * e.max(0.0))
            ),
        )
        .measured(e, DOUBTFUL_BELOW)]
    }
}
