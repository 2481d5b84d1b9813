//! A textured static background: smooth random blotches (a coarse grid of random values,
//! interpolated), the same for every clip, behind the scene's objects.

use super::{Clip, Perturbation};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

pub struct Texture;

/// The texture's standard deviation per level.
const AMPLITUDE: f32 = 0.04;

impl Perturbation for Texture {
    fn name(&self) -> &'static str {
        "texture"
    }
    fn help(&self) -> &'static str {
        "a static smooth random texture behind the objects (standard deviation 0.04·level, blotches of a sixth of the frame)"
    }
    fn apply(&self, level: u8, clip: &mut Clip, _rng: &mut ChaCha8Rng, fixed: &mut ChaCha8Rng) {
        let size = clip.size;
        let cells = 6usize;
        let grid: Vec<f32> = (0..(cells + 1) * (cells + 1))
            .map(|_| fixed.random_range(-1.7f32..1.7))
            .collect();
        let amp = AMPLITUDE * level as f32;
        let tex: Vec<f32> = (0..size * size)
            .map(|i| {
                let (x, y) = ((i % size) as f32, (i / size) as f32);
                let gx = x / size as f32 * cells as f32;
                let gy = y / size as f32 * cells as f32;
                let (x0, y0) = (gx.floor() as usize, gy.floor() as usize);
                let (fx, fy) = (gx - x0 as f32, gy - y0 as f32);
                let g = |a: usize, b: usize| grid[b.min(cells) * (cells + 1) + a.min(cells)];
                // Smoothstep between the grid's values.
                let (sx, sy) = (fx * fx * (3.0 - 2.0 * fx), fy * fy * (3.0 - 2.0 * fy));
                let top = g(x0, y0) * (1.0 - sx) + g(x0 + 1, y0) * sx;
                let bottom = g(x0, y0 + 1) * (1.0 - sx) + g(x0 + 1, y0 + 1) * sx;
                amp * (top * (1.0 - sy) + bottom * sy)
            })
            .collect();
        let px = size * size;
        let backgrounds: Vec<f32> = (0..clip.channels).map(|c| clip.background(c)).collect();
        let len = clip.frame_len();
        for frame in clip.frames.chunks_mut(len) {
            for (c, plane) in frame.chunks_mut(px).enumerate() {
                let bg = backgrounds[c];
                for (v, t) in plane.iter_mut().zip(&tex) {
                    // Behind the objects: where the frame shows the background.
                    let behind = (1.0 - (*v - bg).abs() / 0.05).clamp(0.0, 1.0);
                    *v += behind * t;
                }
            }
        }
    }
}
