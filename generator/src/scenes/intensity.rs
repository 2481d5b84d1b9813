//! The intensity scene: a fixed disc whose grey level follows z.

use super::{DiscPicture, PictureInfo};
use crate::render::Disc;

/// A fixed disc of radius 0.3·size whose grey level is 0.5 + 0.5·z.
pub struct Intensity;

const INFO: PictureInfo = PictureInfo {
    name: "intensity",
    help: "damped oscillator: a fixed disc of radius 0.3·size whose grey level is 0.5 + 0.5·z",
    mapping_text:
        "fixed anti-aliased disc of radius 0.3*size at the centre on black; grey level 0.5 + 0.5*z",
};

impl DiscPicture for Intensity {
    fn info(&self) -> &PictureInfo {
        &INFO
    }
    fn disc(&self, z: f64, size: usize) -> Disc {
        let s = size as f32;
        Disc {
            cx: s / 2.0,
            cy: s / 2.0,
            radius: 0.3 * s,
            grey: 0.5 + 0.5 * z as f32,
        }
    }
}
