//! Camera shake: every frame moved by its own random offset (a hand-held camera), sub-pixel,
//! the edges repeated.

use super::{Clip, Perturbation};
use physvid_shared::video::shifted;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

pub struct Shake;

impl Perturbation for Shake {
    fn name(&self) -> &'static str {
        "shake"
    }
    fn help(&self) -> &'static str {
        "every frame moved by a random offset of standard deviation 0.01·level of the frame in x and y"
    }
    fn apply(&self, level: u8, clip: &mut Clip, rng: &mut ChaCha8Rng, _fixed: &mut ChaCha8Rng) {
        let sigma = 0.01 * level as f32 * clip.size as f32;
        let px = clip.size * clip.size;
        let len = clip.frame_len();
        let size = clip.size;
        for frame in clip.frames.chunks_mut(len) {
            let dx: f32 = StandardNormal.sample(rng);
            let dy: f32 = StandardNormal.sample(rng);
            for plane in frame.chunks_mut(px) {
                let moved = shifted(plane, (size, size), sigma * dx, sigma * dy);
                plane.copy_from_slice(&moved);
            }
        }
    }
}
