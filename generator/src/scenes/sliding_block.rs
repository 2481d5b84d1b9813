//! Delfys75 sliding block: s'' = g·(sin α − μ·cos α), a block released from rest on an incline.

use super::delfys::{
    fits_in_motion, positive, set_error, start_within, times, DelfysSystem, SystemInfo, G,
};
use super::{params, Params};
use crate::error::ConfigError;
use crate::render::Canvas;
use physvid_shared::cli::num;
use physvid_shared::systems;
use physvid_shared::{Calibration, SampleTruth};
use rand_chacha::ChaCha8Rng;

pub struct SlidingBlock;

const INFO: SystemInfo = SystemInfo {
    system: &systems::SLIDING_BLOCK,
    help: "Delfys75: a block sliding down an incline, s'' = g·(sin α − μ·cos α)",
    mapping_text: "latent = distance s (m) travelled down the incline from the top; pixels_per_metre = 0.8*size/travel along the incline",
    quantity: "distance along the incline s (m)",
};

/// a = g·(sin α − μ·cos α).
pub fn block_acceleration(p: &Params) -> f64 {
    let a = p["incline_deg"].to_radians();
    p["g"] * (a.sin() - p["mu"] * a.cos())
}

/// Seconds to cover the incline's travel from rest.
fn duration(p: &Params) -> f64 {
    (2.0 * p["travel"] / block_acceleration(p)).sqrt()
}

impl DelfysSystem for SlidingBlock {
    fn info(&self) -> &SystemInfo {
        &INFO
    }
    fn setting(&self, i: usize) -> Params {
        params(&[
            ("incline_deg", [20.0, 25.0, 30.0][i]),
            ("mu", 0.21),
            ("g", G),
            ("travel", 0.726),
        ])
    }
    fn model_parameters(&self, p: &Params) -> Params {
        params(&[
            ("mu", p["mu"]),
            ("incline_deg", p["incline_deg"]),
            ("g", p["g"]),
            ("acceleration", block_acceleration(p)),
        ])
    }
    fn validate(&self, p: &Params, span: f64, _dt: f64) -> Result<(), ConfigError> {
        positive(p, "travel")?;
        positive(p, "g")?;
        let alpha = p["incline_deg"];
        if !(0.0 < alpha && alpha < 90.0) {
            return Err(set_error(
                format!("incline_deg={alpha}"),
                "must be in (0, 90)",
            ));
        }
        if p["mu"] < 0.0 || block_acceleration(p) <= 0.0 {
            return Err(set_error(
                format!("mu={}", p["mu"]),
                format!(
                    "the block only slides when 0 <= mu < tan(incline) = {:.3}",
                    alpha.to_radians().tan()
                ),
            ));
        }
        let what = "the block covers the incline";
        let blame = format!(
            "travel={},mu={},incline_deg={alpha}",
            num(p["travel"]),
            p["mu"]
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
        let a = block_acceleration(p);
        let z = times(t0, frames, dt).map(|t| a * t * t / 2.0).collect();
        (SampleTruth::from_pairs([("start_time", t0)]), z)
    }
    fn pixels_per_metre(&self, p: &Params, size: usize) -> f64 {
        0.8 * size as f64 / p["travel"]
    }
    fn render(&self, p: &Params, z: f64, size: usize, canvas: &mut Canvas, out: &mut [f32]) {
        let s = size as f32;
        let ppm = self.pixels_per_metre(p, size) as f32;
        let a = (p["incline_deg"] as f32).to_radians();
        let (ux, uy) = (a.cos(), a.sin());
        let (nx, ny) = (a.sin(), -a.cos()); // normal, pointing up-right of the slope
        let (ox, oy) = (0.1 * s, 0.5 * s - 0.4 * s * uy);
        let len = 0.9 * s;
        let th = 0.03 * s;
        canvas.draw_polygon(
            &[
                (ox, oy),
                (ox + ux * len, oy + uy * len),
                (ox + ux * len - nx * th, oy + uy * len - ny * th),
                (ox - nx * th, oy - ny * th),
            ],
            0.4,
            out,
        );
        let side = 0.1 * s;
        let c = z as f32 * ppm + 0.02 * s;
        let (bx, by) = (ox + ux * c, oy + uy * c);
        canvas.draw_polygon(
            &[
                (bx, by),
                (bx + ux * side, by + uy * side),
                (bx + ux * side + nx * side, by + uy * side + ny * side),
                (bx + nx * side, by + ny * side),
            ],
            1.0,
            out,
        );
    }
    fn calibrate(&self, p: &Params, pixels_per_metre: f64, c: &mut Calibration) {
        c.pixels_per_metre = Some(pixels_per_metre);
        c.incline_deg = Some(p["incline_deg"]);
        c.g = Some(p["g"]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_follow_table_4_and_validate() {
        let mut p = SlidingBlock.setting(0);
        assert!(SlidingBlock.validate(&p, 9.0 / 30.0, 1.0 / 30.0).is_ok());
        p.insert("mu".into(), 0.5);
        let e = SlidingBlock
            .validate(&p, 9.0 / 30.0, 1.0 / 30.0)
            .unwrap_err();
        assert!(e.expected.contains("tan"), "{e}");
    }
}
