//! A moving light with shadow: the scene lit from a direction that turns during the clip (a
//! brightness gradient across the frame, an ambient floor so that a black background shows
//! the light too), and each object's shadow cast on the background away from the light.

use super::{Clip, Perturbation};
use physvid_shared::video::shifted;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

pub struct Light;

/// The light's ambient floor: the scene is shown as AMBIENT + (1 − AMBIENT)·picture, lit.
pub const AMBIENT: f32 = 0.2;

impl Perturbation for Light {
    fn name(&self) -> &'static str {
        "light"
    }
    fn help(&self) -> &'static str {
        "a light turning once every 1.5–4 clip spans: a gradient of ±0.06·level across the frame over an ambient floor of 0.2, and shadows 0.03·level of the frame long, 0.08·level dark"
    }
    fn apply(&self, level: u8, clip: &mut Clip, rng: &mut ChaCha8Rng, _fixed: &mut ChaCha8Rng) {
        let l = level as f32;
        let period = rng.random_range(1.5f64..4.0) * clip.span();
        let phase = rng.random_range(0.0..std::f64::consts::TAU);
        let size = clip.size;
        let s = size as f32;
        let px = size * size;
        let len = clip.frame_len();
        let backgrounds: Vec<f32> = (0..clip.channels).map(|c| clip.background(c)).collect();
        let dt = clip.dt;
        for (k, frame) in clip.frames.chunks_mut(len).enumerate() {
            let a = phase + std::f64::consts::TAU * k as f64 * dt / period;
            let (ux, uy) = (a.cos() as f32, a.sin() as f32);
            for (c, plane) in frame.chunks_mut(px).enumerate() {
                let bg = backgrounds[c];
                let object: Vec<f32> = plane
                    .iter()
                    .map(|v| ((v - bg).abs() / 0.1).clamp(0.0, 1.0))
                    .collect();
                let reach = 0.03 * l * s;
                let shadow = shifted(&object, (size, size), -ux * reach, -uy * reach);
                for (i, v) in plane.iter_mut().enumerate() {
                    let (x, y) = ((i % size) as f32 - s / 2.0, (i / size) as f32 - s / 2.0);
                    let gain = 1.0 + 0.06 * l * (x * ux + y * uy) / (s / 2.0);
                    let dark = 1.0 - 0.08 * l * shadow[i] * (1.0 - object[i]);
                    *v = (AMBIENT + (1.0 - AMBIENT) * *v) * gain * dark;
                }
            }
        }
    }
}
