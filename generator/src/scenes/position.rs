//! The position scene: a white disc that moves horizontally with z.

use super::{DiscPicture, PictureInfo};
use crate::render::Disc;

/// A white disc of radius max(0.1·size, 1) whose centre is x = size/2 + z·(size/2 − r − 1).
pub struct Position;

const INFO: PictureInfo = PictureInfo {
    name: "position",
    help: "damped oscillator: a white disc of radius 0.1·size moving horizontally, x = size/2 + z·(size/2 − r − 1)",
    mapping_text: "white anti-aliased disc of radius max(0.1*size, 1) on black; centre x = size/2 + z*(size/2 - radius - 1) pixels, y = size/2",
};

impl DiscPicture for Position {
    fn info(&self) -> &PictureInfo {
        &INFO
    }
    fn disc(&self, z: f64, size: usize) -> Disc {
        let s = size as f32;
        let r = (0.1 * s).max(1.0);
        Disc {
            cx: s / 2.0 + z as f32 * (s / 2.0 - r - 1.0),
            cy: s / 2.0,
            radius: r,
            grey: 1.0,
        }
    }
}
