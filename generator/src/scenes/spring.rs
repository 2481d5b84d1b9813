//! The two-body spring of appendix A.5 (PAIG's "2-digit spring" set): two digits (unit masses)
//! joined by a spring, F = k·(|d| − l)·d̂ pulling them together when stretched (l the rest
//! length; the appendix prints another form, PAIG's, Hofherr's and the official code use this
//! one), over a fixed cluttered backdrop. MNIST cannot be fetched here: the digits are DejaVu
//! Sans Bold glyphs ('5' and '0', MNIST's first two training digits), about 20 px high,
//! anti-aliased at their sub-pixel positions. Integrated by RK4 with 64 sub-steps per frame (PAIG
//! used semi-implicit Euler). The latent is both bodies' x, y in pixels.

use super::spring_picture::{backdrop, draw_digit};
use super::{params, Params, Scene};
use crate::error::{invalid, ConfigError};
use crate::render::Canvas;
use crate::sampling::sample_rng;
use physvid_shared::{rk4, systems};
use physvid_shared::{Calibration, PositionPoint, SampleTruth};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;

/// The scene.
pub struct Spring;

/// Half the digit box (22 px, as PAIG crops MNIST): how far a body's ink reaches.
pub const RADIUS: f64 = 11.0;
/// RK4 steps per frame.
const SUBSTEPS: usize = 64;
/// A centre closer than this to the border makes the sequence be drawn again (PAIG's rule).
const BORDER: f64 = 2.0;
/// Draws of a sequence before giving up (validation checks that some succeed).
const MAX_DRAWS: usize = 10_000;

/// Both bodies' positions at `frames` frames `dt` apart from state `s` (x1, y1, x2, y2, vx1,
/// vy1, vx2, vy2) (x1, y1, x2, y2 each).
pub fn spring_trajectory(s: [f64; 8], k: f64, l: f64, frames: usize, dt: f64) -> Vec<f64> {
    let law = |_t: f64, s: &[f64], d: &mut [f64]| {
        let (dx, dy) = (s[2] - s[0], s[3] - s[1]);
        let r = (dx * dx + dy * dy).sqrt().max(1e-9);
        let (fx, fy) = (k * (r - l) * dx / r, k * (r - l) * dy / r);
        d.copy_from_slice(&[s[4], s[5], s[6], s[7], fx, fy, -fx, -fy]);
    };
    rk4::trajectory(law, &s, 0.0, dt, frames, SUBSTEPS)
        .chunks(8)
        .flat_map(|s| s[..4].iter().copied())
        .collect()
}

/// One draw of PAIG's initial state: centre of mass uniform in [r + l/2, size − (r + l/2)] per
/// axis, separation l·u (u ~ U[0.5, 1.5)) at a random angle, each body moving at `speed` in its
/// own random direction.
fn initial_state(p: &Params, size: f64, rng: &mut ChaCha8Rng) -> [f64; 8] {
    let l = p["rest_length"];
    let margin = (RADIUS + l / 2.0).min(size / 2.0);
    let (cx, cy) = (
        rng.random_range(margin..=size - margin),
        rng.random_range(margin..=size - margin),
    );
    let sep = l * rng.random_range(0.5..1.5);
    let angle = rng.random_range(0.0..TAU);
    let (ox, oy) = (sep / 2.0 * angle.cos(), sep / 2.0 * angle.sin());
    let (a1, a2) = (rng.random_range(0.0..TAU), rng.random_range(0.0..TAU));
    let v = p["speed"];
    [
        cx - ox,
        cy - oy,
        cx + ox,
        cy + oy,
        v * a1.cos(),
        v * a1.sin(),
        v * a2.cos(),
        v * a2.sin(),
    ]
}

/// A sequence drawn again until both centres stay clear of the border; the draws it took.
fn draw_sequence(
    p: &Params,
    size: f64,
    rng: &mut ChaCha8Rng,
    frames: usize,
    dt: f64,
) -> Option<(usize, [f64; 8], Vec<f64>)> {
    for draw in 1..=MAX_DRAWS {
        let s = initial_state(p, size, rng);
        let z = spring_trajectory(s, p["k"], p["rest_length"], frames, dt);
        if z.iter().all(|&c| (BORDER..=size - BORDER).contains(&c)) {
            return Some((draw, s, z));
        }
    }
    None
}

impl Scene for Spring {
    fn name(&self) -> &'static str {
        "spring"
    }
    fn help(&self) -> &'static str {
        "appendix A.5: two digits joined by a spring, F = k·(|d| − l)·d̂, over a cluttered backdrop"
    }
    fn model_name(&self) -> &'static str {
        systems::SPRING.model
    }
    /// PAIG's training clips: 12 frames of 0.3 time units.
    fn default_clip(&self) -> (usize, f64) {
        systems::SPRING.clip
    }
    fn params(&self, _setting: u8) -> Params {
        params(&[
            ("k", 2.0),
            ("rest_length", 24.0),
            ("speed", 8.0),
            ("clutter", 1.0),
        ])
    }
    fn accepts_set(&self) -> bool {
        true
    }
    fn latent_dims(&self) -> usize {
        4
    }
    fn channels(&self, color: bool) -> usize {
        if color {
            3
        } else {
            1
        }
    }
    fn default_size(&self) -> usize {
        64
    }

    fn validate(&self, p: &Params, frames: usize, dt: f64, size: usize) -> Result<(), ConfigError> {
        for (k, v) in p {
            if !v.is_finite() {
                return Err(invalid(
                    "--set",
                    format!("{k}={v}"),
                    "must be a finite number",
                ));
            }
        }
        for k in ["k", "rest_length"] {
            if p[k] <= 0.0 {
                return Err(invalid("--set", format!("{k}={}", p[k]), "must be > 0"));
            }
        }
        if p["speed"] < 0.0 {
            return Err(invalid(
                "--set",
                format!("speed={}", p["speed"]),
                "must be >= 0",
            ));
        }
        if p["clutter"] != 0.0 && p["clutter"] != 1.0 {
            return Err(invalid(
                "--set",
                format!("clutter={}", p["clutter"]),
                "must be 1 (the cluttered backdrop) or 0 (black)",
            ));
        }
        let digit = 2.0 * RADIUS;
        if (size as f64) < 2.0 * digit {
            return Err(invalid(
                "--size",
                size,
                format!(
                    "frames too small for two {digit}-px digits; need at least {}",
                    2.0 * digit
                ),
            ));
        }
        let omega = (2.0 * p["k"]).sqrt();
        if omega * dt >= std::f64::consts::PI {
            return Err(invalid(
                "--dt",
                dt,
                format!(
                    "the frames sample the spring's oscillation (sqrt(2k) = {omega:.3}) below its Nyquist rate; need dt < {:.4}",
                    std::f64::consts::PI / omega
                ),
            ));
        }
        if p["rest_length"] / 2.0 + digit > size as f64 - 2.0 * BORDER {
            return Err(invalid(
                "--set",
                format!("rest_length={}", p["rest_length"]),
                format!("two digits that far apart cannot fit in a {size}×{size} frame"),
            ));
        }
        let mut rng = sample_rng(0, 0);
        if draw_sequence(p, size as f64, &mut rng, frames, dt).is_none() {
            return Err(invalid(
                "--frames",
                frames,
                format!(
                    "the bodies do not stay in the {size}×{size} frame for {frames} frames in {MAX_DRAWS} draws; lower --frames, --dt or speed"
                ),
            ));
        }
        Ok(())
    }

    fn sample(
        &self,
        p: &Params,
        rng: &mut ChaCha8Rng,
        frames: usize,
        dt: f64,
        size: usize,
    ) -> (SampleTruth, Vec<f64>) {
        let (draws, s, z) = draw_sequence(p, size as f64, rng, frames, dt)
            .expect("validation checks that sequences stay in frame");
        let truth = SampleTruth::from_pairs([
            ("draws", draws as f64),
            ("x1", s[0]),
            ("y1", s[1]),
            ("x2", s[2]),
            ("y2", s[3]),
            ("vx1", s[4]),
            ("vy1", s[5]),
            ("vx2", s[6]),
            ("vy2", s[7]),
        ]);
        (truth, z)
    }

    fn render(&self, p: &Params, z: &[f64], size: usize, _canvas: &mut Canvas, out: &mut [f32]) {
        let pixels = size * size;
        let channels = out.len() / pixels;
        let mut ink = [vec![0.0f32; pixels], vec![0.0f32; pixels]];
        for (b, cov) in ink.iter_mut().enumerate() {
            draw_digit(b, z[2 * b], z[2 * b + 1], size, cov);
        }
        let clutter = p["clutter"] != 0.0;
        for ch in 0..channels {
            for i in 0..pixels {
                let (x, y) = ((i % size) as f64 + 0.5, (i / size) as f64 + 0.5);
                let mut v = if clutter {
                    backdrop(x / size as f64, y / size as f64, ch) as f32
                } else {
                    0.0
                };
                // Grey: both digits drawn white, "over" what lies below; colour: digit one in
                // red, digit two in green (PAIG's channels).
                for (b, cov) in ink.iter().enumerate() {
                    if channels == 1 || ch == b {
                        v += cov[i] * (1.0 - v);
                    }
                }
                out[ch * pixels + i] = v;
            }
        }
    }

    fn mapping_text(&self) -> &'static str {
        "latent = (x1, y1, x2, y2): the centres (pixels, y down) of digit '5' (body one) and digit '0' (body two), each about 20 px high, drawn white over a fixed backdrop darkened to at most 0.2 (colour: digit one in red, digit two in green)"
    }
    fn sampling_text(&self) -> &'static str {
        "per clip, from ChaCha8 stream i (seeded with --seed) for sample i: centre of mass uniform in [11 + l/2, size - 11 - l/2] per axis, separation l*U[0.5, 1.5) at a uniform angle, each body moving at speed in a uniform direction; drawn again (counted in draws) until both centres stay at least 2 px from the border over the clip; then the pixel noise"
    }
    fn model_parameters(&self, p: &Params) -> Params {
        params(&[("k", p["k"]), ("rest_length", p["rest_length"])])
    }

    /// Both bodies' positions (pixels) at the first frame of five clips spread over the set.
    fn calibration(&self, _p: &Params, _size: usize, latents: &[Vec<f64>]) -> Calibration {
        let n = latents.len();
        let mut clips: Vec<usize> = (0..5).map(|i| i * n.saturating_sub(1) / 4).collect();
        clips.dedup();
        Calibration {
            quantity: Some("body positions x1, y1, x2, y2 (pixels, y down)".into()),
            reference_positions: clips
                .into_iter()
                .map(|clip| PositionPoint {
                    clip,
                    frame: 0,
                    positions: latents[clip][..4].to_vec(),
                })
                .collect(),
            ..Default::default()
        }
    }
    fn fps(&self, _dt: f64) -> Option<f64> {
        None
    }
    fn released_from_rest(&self) -> bool {
        false
    }
}
