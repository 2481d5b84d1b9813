//! Delfys75 Torricelli tank: h' = −k·√h, a tank whose water level falls.

use super::delfys::{
    fits_in_motion, positive, set_error, start_within, times, DelfysSystem, SystemInfo,
};
use super::{params, Params};
use crate::error::ConfigError;
use crate::render::Canvas;
use physvid_shared::cli::num;
use physvid_shared::systems;
use physvid_shared::{Calibration, SampleTruth};
use rand_chacha::ChaCha8Rng;

pub struct Torricelli;

const INFO: SystemInfo = SystemInfo {
    system: &systems::TORRICELLI,
    help: "Delfys75: a draining tank, h' = −k·√h",
    mapping_text:
        "latent = water level h (m) above the bottom of a tank; pixels_per_metre = 0.7*size/h_start",
    quantity: "water level h (m)",
};

/// Seconds for the level to fall from h_start to h_end.
fn duration(p: &Params) -> f64 {
    2.0 * (p["h_start"].sqrt() - p["h_end"].sqrt()) / p["k"]
}

impl DelfysSystem for Torricelli {
    fn info(&self) -> &SystemInfo {
        &INFO
    }
    fn setting(&self, i: usize) -> Params {
        params(&[
            ("k", [0.0095, 0.0128, 0.0162][i]),
            ("h_start", 0.07),
            ("h_end", 0.01),
        ])
    }
    fn model_parameters(&self, p: &Params) -> Params {
        params(&[("k", p["k"])])
    }
    fn validate(&self, p: &Params, span: f64, _dt: f64) -> Result<(), ConfigError> {
        positive(p, "k")?;
        positive(p, "h_end")?;
        if p["h_start"] <= p["h_end"] {
            return Err(set_error(
                format!("h_start={}", p["h_start"]),
                "must be above h_end (the level falls)",
            ));
        }
        let what = "the tank drains from h_start to h_end";
        let blame = format!(
            "k={},h_start={},h_end={}",
            num(p["k"]),
            num(p["h_start"]),
            num(p["h_end"])
        );
        fits_in_motion(blame, what, duration(p), span)
    }
    fn sample(
        &self,
        p: &Params,
        rng: &mut ChaCha8Rng,
        frames: usize,
        dt: f64,
    ) -> (SampleTruth, Vec<f64>) {
        let t0 = start_within(rng, duration(p), frames, dt);
        let root = p["h_start"].sqrt();
        let z = times(t0, frames, dt)
            .map(|t| (root - p["k"] * t / 2.0).powi(2))
            .collect();
        (SampleTruth::from_pairs([("start_time", t0)]), z)
    }
    fn pixels_per_metre(&self, p: &Params, size: usize) -> f64 {
        0.7 * size as f64 / p["h_start"]
    }
    fn render(&self, p: &Params, z: f64, size: usize, canvas: &mut Canvas, out: &mut [f32]) {
        let s = size as f32;
        let ppm = self.pixels_per_metre(p, size) as f32;
        let (x0, x1, bottom) = (0.3 * s, 0.7 * s, 0.9 * s);
        let wall = 0.03 * s;
        let top = 0.1 * s;
        let rect = |xa: f32, xb: f32, ya: f32, yb: f32| [(xa, ya), (xb, ya), (xb, yb), (xa, yb)];
        canvas.draw_polygon(&rect(x0 - wall, x0, top, bottom + wall), 0.4, out);
        canvas.draw_polygon(&rect(x1, x1 + wall, top, bottom + wall), 0.4, out);
        canvas.draw_polygon(&rect(x0, x1, bottom, bottom + wall), 0.4, out);
        let level = bottom - z as f32 * ppm;
        canvas.draw_polygon(&rect(x0, x1, level, bottom), 0.9, out);
    }
    fn calibrate(&self, _p: &Params, pixels_per_metre: f64, c: &mut Calibration) {
        c.pixels_per_metre = Some(pixels_per_metre);
    }
}
