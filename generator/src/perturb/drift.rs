//! Brightness drift: the light on the whole scene rises and falls slowly (an auto-exposure, a
//! cloud), over an ambient floor so that a black background shows it too.

use super::light::AMBIENT;
use super::{Clip, Perturbation};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

pub struct Drift;

impl Perturbation for Drift {
    fn name(&self) -> &'static str {
        "drift"
    }
    fn help(&self) -> &'static str {
        "the whole scene's light swinging by ±0.06·level once every 2–6 clip spans, over an ambient floor of 0.2"
    }
    fn apply(&self, level: u8, clip: &mut Clip, rng: &mut ChaCha8Rng, _fixed: &mut ChaCha8Rng) {
        let period = rng.random_range(2.0f64..6.0) * clip.span();
        let phase = rng.random_range(0.0..std::f64::consts::TAU);
        let len = clip.frame_len();
        let dt = clip.dt;
        for (k, frame) in clip.frames.chunks_mut(len).enumerate() {
            let g = 1.0
                + 0.06
                    * level as f64
                    * (std::f64::consts::TAU * k as f64 * dt / period + phase).sin();
            for v in frame.iter_mut() {
                *v = (AMBIENT + (1.0 - AMBIENT) * *v) * g as f32;
            }
        }
    }
}
