//! Sensor noise: independent Gaussian noise on every pixel, clipped to [0, 1].

use super::{Clip, Perturbation};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

pub struct Noise;

impl Perturbation for Noise {
    fn name(&self) -> &'static str {
        "noise"
    }
    fn help(&self) -> &'static str {
        "Gaussian noise of standard deviation 0.02·level on every pixel, clipped to [0, 1]"
    }
    fn apply(&self, level: u8, clip: &mut Clip, rng: &mut ChaCha8Rng, _fixed: &mut ChaCha8Rng) {
        let sigma = 0.02 * level as f32;
        for v in clip.frames.iter_mut() {
            let n: f32 = StandardNormal.sample(rng);
            *v += sigma * n;
        }
    }
}
