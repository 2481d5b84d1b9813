//! Delfys75 free fall: h'' = g, a ball falling away from the camera, seen at radius f·r0/h.

use super::delfys::{positive, times, DelfysSystem, SystemInfo, G};
use super::{params, Params};
use crate::error::ConfigError;
use crate::render::Canvas;
use physvid_shared::systems;
use physvid_shared::{Calibration, SampleTruth};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

pub struct FreeFall;

const INFO: SystemInfo = SystemInfo {
    system: &systems::FREE_FALL,
    help: "Delfys75: a ball falling away from the camera, h'' = g, seen at radius f·r0/h",
    mapping_text: "latent = distance h (m) of a ball from the camera; apparent radius = focal_px_per_m * radius / h",
    quantity: "distance from the camera h (m)",
};

impl DelfysSystem for FreeFall {
    fn info(&self) -> &SystemInfo {
        &INFO
    }
    fn setting(&self, i: usize) -> Params {
        params(&[("radius", [0.0335, 0.06, 0.10][i]), ("h0", 0.20), ("g", G)])
    }
    fn model_parameters(&self, p: &Params) -> Params {
        params(&[("g", p["g"])])
    }
    fn validate(&self, p: &Params, _span: f64, _dt: f64) -> Result<(), ConfigError> {
        positive(p, "radius")?;
        positive(p, "h0")?;
        positive(p, "g")
    }
    fn sample(
        &self,
        p: &Params,
        rng: &mut ChaCha8Rng,
        frames: usize,
        dt: f64,
    ) -> (SampleTruth, Vec<f64>) {
        let t0 = rng.random_range(0.0..=0.3);
        let z = times(t0, frames, dt)
            .map(|t| p["h0"] + p["g"] * t * t / 2.0)
            .collect();
        (SampleTruth::from_pairs([("start_time", t0)]), z)
    }
    /// The ball's apparent radius at h0 for the largest setting (10 cm) is 0.4·size.
    fn pixels_per_metre(&self, _p: &Params, size: usize) -> f64 {
        0.4 * size as f64 * 0.20 / 0.10
    }
    fn render(&self, p: &Params, z: f64, size: usize, canvas: &mut Canvas, out: &mut [f32]) {
        let s = size as f32;
        let r = self.pixels_per_metre(p, size) as f32 * p["radius"] as f32 / z as f32;
        let ball = canvas.circle_points(s / 2.0, s / 2.0, r);
        canvas.draw_polygon(&ball, 1.0, out);
    }
    fn calibrate(&self, p: &Params, pixels_per_metre: f64, c: &mut Calibration) {
        c.focal_px_per_m = Some(pixels_per_metre);
        c.radius = Some(p["radius"]);
        c.h0 = Some(p["h0"]);
        c.g = Some(p["g"]);
    }
}
