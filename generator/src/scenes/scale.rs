//! The scale scene: a white disc at the centre whose radius follows z.

use super::{DiscPicture, PictureInfo};
use crate::render::Disc;

/// A white disc at the centre of radius size·(0.25 + 0.15·z).
pub struct Scale;

const INFO: PictureInfo = PictureInfo {
    name: "scale",
    help: "damped oscillator: a white disc at the centre whose radius is size·(0.25 + 0.15·z)",
    mapping_text:
        "white anti-aliased disc at the centre on black; radius = size*(0.25 + 0.15*z) pixels",
};

impl DiscPicture for Scale {
    fn info(&self) -> &PictureInfo {
        &INFO
    }
    fn disc(&self, z: f64, size: usize) -> Disc {
        let s = size as f32;
        Disc {
            cx: s / 2.0,
            cy: s / 2.0,
            radius: s * (0.25 + 0.15 * z as f32),
            grey: 1.0,
        }
    }
}
