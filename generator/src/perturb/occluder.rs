//! An occluder: a static grey bar in front of the scene, from a fifth of the frame's height
//! down, at a place drawn once for the run.

use super::{Clip, Perturbation};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

pub struct Occluder;

impl Perturbation for Occluder {
    fn name(&self) -> &'static str {
        "occluder"
    }
    fn help(&self) -> &'static str {
        "a static grey bar (0.5) in front of the scene, 0.05·level of the frame wide, from a fifth of its height down"
    }
    fn apply(&self, level: u8, clip: &mut Clip, _rng: &mut ChaCha8Rng, fixed: &mut ChaCha8Rng) {
        let s = clip.size as f32;
        let width = 0.05 * level as f32 * s;
        let x0 = fixed.random_range(0.35f32..0.65) * s - width / 2.0;
        let bar = [
            (x0, 0.2 * s),
            (x0 + width, 0.2 * s),
            (x0 + width, s),
            (x0, s),
        ];
        let px = clip.size * clip.size;
        let len = clip.frame_len();
        for frame in clip.frames.chunks_mut(len) {
            for plane in frame.chunks_mut(px) {
                clip.canvas.draw_polygon(&bar, 0.5, plane);
            }
        }
    }
}
