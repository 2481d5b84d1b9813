//! Moving distractors: discs of random grey drifting across the frame in front of the scene
//! (wrapping around its edges), as many as the level.

use super::{Clip, Perturbation};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

pub struct Distractors;

impl Perturbation for Distractors {
    fn name(&self) -> &'static str {
        "distractors"
    }
    fn help(&self) -> &'static str {
        "level discs (radius 0.05–0.1 of the frame, grey 0.2–0.9) drifting in front of the scene, each up to half the frame per clip"
    }
    fn apply(&self, level: u8, clip: &mut Clip, rng: &mut ChaCha8Rng, _fixed: &mut ChaCha8Rng) {
        let s = clip.size as f32;
        let span = clip.span() as f32;
        let discs: Vec<[f32; 6]> = (0..level)
            .map(|_| {
                [
                    rng.random_range(0.0..s),
                    rng.random_range(0.0..s),
                    rng.random_range(-0.5f32..0.5) * s / span,
                    rng.random_range(-0.5f32..0.5) * s / span,
                    rng.random_range(0.05f32..0.1) * s,
                    rng.random_range(0.2f32..0.9),
                ]
            })
            .collect();
        let px = clip.size * clip.size;
        let len = clip.frame_len();
        let dt = clip.dt as f32;
        for (k, frame) in clip.frames.chunks_mut(len).enumerate() {
            let t = k as f32 * dt;
            for &[x, y, vx, vy, r, grey] in &discs {
                let cx = (x + vx * t).rem_euclid(s);
                let cy = (y + vy * t).rem_euclid(s);
                let points = clip.canvas.circle_points(cx, cy, r);
                for plane in frame.chunks_mut(px) {
                    clip.canvas.draw_polygon(&points, grey, plane);
                }
            }
        }
    }
}
