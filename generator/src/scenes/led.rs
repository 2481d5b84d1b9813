//! Delfys75 LED: I' = −γ·I, a dimming LED in a dim housing.

use super::delfys::{positive, times, DelfysSystem, SystemInfo};
use super::{params, Params};
use crate::error::ConfigError;
use crate::render::Canvas;
use physvid_shared::systems;
use physvid_shared::{Calibration, SampleTruth};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

pub struct Led;

const INFO: SystemInfo = SystemInfo {
    system: &systems::LED,
    help: "Delfys75: a dimming LED, I' = −γ·I",
    mapping_text: "latent = brightness I/I(0) of an LED (grey 0.15 + 0.85*I) in a dim housing",
    quantity: "brightness I/I(0)",
};

impl DelfysSystem for Led {
    fn info(&self) -> &SystemInfo {
        &INFO
    }
    fn setting(&self, i: usize) -> Params {
        params(&[("gamma", [2.3, 0.92, 0.46][i])])
    }
    fn model_parameters(&self, p: &Params) -> Params {
        params(&[("gamma", p["gamma"])])
    }
    fn validate(&self, p: &Params, _span: f64, _dt: f64) -> Result<(), ConfigError> {
        positive(p, "gamma")
    }
    fn sample(
        &self,
        p: &Params,
        rng: &mut ChaCha8Rng,
        frames: usize,
        dt: f64,
    ) -> (SampleTruth, Vec<f64>) {
        let t0 = rng.random_range(0.0..=1.0 / p["gamma"]);
        let z = times(t0, frames, dt)
            .map(|t| (-p["gamma"] * t).exp())
            .collect();
        (SampleTruth::from_pairs([("start_time", t0)]), z)
    }
    fn pixels_per_metre(&self, _p: &Params, _size: usize) -> f64 {
        1.0
    }
    fn render(&self, _p: &Params, z: f64, size: usize, canvas: &mut Canvas, out: &mut [f32]) {
        let s = size as f32;
        let housing = canvas.circle_points(s / 2.0, s / 2.0, 0.3 * s);
        canvas.draw_polygon(&housing, 0.15, out);
        let led = canvas.circle_points(s / 2.0, s / 2.0, 0.2 * s);
        canvas.draw_polygon(&led, 0.15 + 0.85 * z as f32, out);
    }
    fn calibrate(&self, _p: &Params, _pixels_per_metre: f64, _c: &mut Calibration) {}
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_follow_table_4() {
        assert_eq!(Led.setting(1)["gamma"], 0.92);
        assert_eq!(super::super::torricelli::Torricelli.setting(2)["k"], 0.0162);
    }
}
