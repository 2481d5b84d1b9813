//! The rod scene: a dark rod and bob on a light background, swinging about a pivot near the
//! top with angle θ = 60°·z (the ICML 2026 peer's robustness set-up, drawn our own way). At
//! such swings the bob's height is an even function of z that oscillates at twice its
//! frequency: the case where an encoder can learn the second harmonic.

use super::{DiscPicture, PictureInfo};
use crate::render::{Canvas, Disc};

/// A rod of length 0.42·size from the pivot (size/2, 0.15·size) to a bob of radius 0.08·size,
/// at angle 60°·z from the vertical; ink 0.1 on a background of 0.8.
pub struct Rod;

/// The angle at z = ±1 (rad).
pub const MAX_ANGLE: f64 = std::f64::consts::FRAC_PI_3;
const BACKGROUND: f32 = 0.8;
const INK: f32 = 0.1;

const INFO: PictureInfo = PictureInfo {
    name: "rod",
    help: "damped oscillator: a dark rod and bob on a light background swinging to θ = 60°·z (its height swings at 2ω)",
    mapping_text: "grey 0.8 background; rod of width 0.04*size and length 0.42*size from the pivot (size/2, 0.15*size) to a bob of radius 0.08*size, both grey 0.1, at angle 60 deg * z from the vertical",
};

impl DiscPicture for Rod {
    fn info(&self) -> &PictureInfo {
        &INFO
    }
    /// The bob.
    fn disc(&self, z: f64, size: usize) -> Disc {
        let s = size as f64;
        let (px, py, len) = (s / 2.0, 0.15 * s, 0.42 * s);
        let a = MAX_ANGLE * z;
        Disc {
            cx: (px + len * a.sin()) as f32,
            cy: (py + len * a.cos()) as f32,
            radius: (0.08 * s).max(1.0) as f32,
            grey: INK,
        }
    }
    fn draw(&self, z: f64, size: usize, canvas: &mut Canvas, out: &mut [f32]) {
        out.fill(BACKGROUND);
        let s = size as f32;
        let bob = self.disc(z, size);
        let (px, py) = (s / 2.0, 0.15 * s);
        // The rod: a thin rectangle from the pivot to the bob's centre.
        let (dx, dy) = (bob.cx - px, bob.cy - py);
        let len = (dx * dx + dy * dy).sqrt().max(1e-6);
        let half = (0.02 * s).max(0.5);
        let (nx, ny) = (-dy / len * half, dx / len * half);
        let rod = [
            (px + nx, py + ny),
            (bob.cx + nx, bob.cy + ny),
            (bob.cx - nx, bob.cy - ny),
            (px - nx, py - ny),
        ];
        canvas.draw_polygon(&rod, INK, out);
        let circle = canvas.circle_points(bob.cx, bob.cy, bob.radius);
        canvas.draw_polygon(&circle, bob.grey, out);
    }
}
