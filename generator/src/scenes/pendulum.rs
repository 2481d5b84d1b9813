//! Delfys75 pendulum: θ'' = −(g/L)·sin θ − ζ·θ' at finite angles (RK4, 64 sub-steps per frame),
//! a bob on a string seen from the front.

use super::delfys::{positive, set_error, DelfysSystem, SystemInfo, G};
use super::{params, Params, MIN_PHASE_SPAN};
use crate::error::{invalid, ConfigError};
use crate::render::Canvas;
use physvid_shared::cli::{approx, num};
use physvid_shared::{rk4, systems};
use physvid_shared::{Calibration, SampleTruth};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

pub struct Pendulum;

const INFO: SystemInfo = SystemInfo {
    system: &systems::PENDULUM,
    help: "Delfys75: a bob on a string, θ'' = −(g/L)·sin θ − ζ·θ' (finite angles)",
    mapping_text: "latent = angle theta (rad) of a bob on a string seen from the front; pivot at (size/2, 0.1*size), pixels_per_metre = 0.5*size/length",
    quantity: "angle theta (rad)",
};

impl DelfysSystem for Pendulum {
    fn info(&self) -> &SystemInfo {
        &INFO
    }
    fn setting(&self, i: usize) -> Params {
        params(&[
            ("length", [0.45, 0.90, 1.50][i]),
            ("damping", 0.059),
            ("g", G),
            ("amplitude_min_deg", 10.0),
            ("amplitude_max_deg", 60.0),
        ])
    }
    fn model_parameters(&self, p: &Params) -> Params {
        params(&[
            ("length", p["length"]),
            ("damping", p["damping"]),
            ("g", p["g"]),
        ])
    }
    fn validate(&self, p: &Params, span: f64, dt: f64) -> Result<(), ConfigError> {
        positive(p, "length")?;
        positive(p, "g")?;
        let (lo, hi) = (p["amplitude_min_deg"], p["amplitude_max_deg"]);
        if !(0.0 < lo && lo <= hi && hi < 90.0) {
            return Err(set_error(
                format!("amplitude_min_deg={lo},amplitude_max_deg={hi}"),
                "need 0 < amplitude_min_deg <= amplitude_max_deg < 90",
            ));
        }
        // The small-angle frequency is the fastest the pendulum swings.
        let omega = (p["g"] / p["length"]).sqrt();
        let swings = format!(
            "a pendulum of length {} m (g {}) swings at sqrt(g/length) = {} rad/s",
            num(p["length"]),
            p["g"],
            approx(omega)
        );
        if omega * dt >= std::f64::consts::PI {
            return Err(invalid(
                "--dt",
                num(dt),
                format!(
                    "{swings}: frames {dt} s apart sample it below its Nyquist rate; need dt < {} s, or a longer pendulum (--set length=...)",
                    approx(std::f64::consts::PI / omega)
                ),
            ));
        }
        if omega * span < MIN_PHASE_SPAN {
            return Err(invalid(
                "--dt",
                num(dt),
                format!(
                    "{swings}: a clip of {} s spans {} rad of it, too little to see it move; need at least {MIN_PHASE_SPAN} rad (a longer --dt or --frames)",
                    approx(span),
                    approx(omega * span)
                ),
            ));
        }
        if p["damping"] < 0.0 {
            return Err(set_error(
                format!("damping={}", p["damping"]),
                "must be >= 0",
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
    ) -> (SampleTruth, Vec<f64>) {
        let amp = rng
            .random_range(p["amplitude_min_deg"]..=p["amplitude_max_deg"])
            .to_radians();
        let theta0 = amp * rng.random_range(-1.0..1.0);
        let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
        let w2 = p["g"] / p["length"];
        let omega0 = sign * (2.0 * w2 * (theta0.cos() - amp.cos())).max(0.0).sqrt();
        let z = pendulum_trajectory(w2, p["damping"], theta0, omega0, frames, dt);
        let truth =
            SampleTruth::from_pairs([("amplitude", amp), ("theta0", theta0), ("omega0", omega0)]);
        (truth, z)
    }
    fn pixels_per_metre(&self, p: &Params, size: usize) -> f64 {
        0.5 * size as f64 / p["length"]
    }
    fn render(&self, p: &Params, z: f64, size: usize, canvas: &mut Canvas, out: &mut [f32]) {
        let s = size as f32;
        let ppm = self.pixels_per_metre(p, size) as f32;
        let (px, py) = (s / 2.0, 0.1 * s);
        let l = p["length"] as f32 * ppm;
        let (bx, by) = (px + l * (z as f32).sin(), py + l * (z as f32).cos());
        let half = 0.35f32.max(0.01 * s);
        let (nx, ny) = ((z as f32).cos() * half, -(z as f32).sin() * half);
        canvas.draw_polygon(
            &[
                (px - nx, py - ny),
                (px + nx, py + ny),
                (bx + nx, by + ny),
                (bx - nx, by - ny),
            ],
            0.5,
            out,
        );
        let bob = canvas.circle_points(bx, by, 0.06 * s);
        canvas.draw_polygon(&bob, 1.0, out);
    }
    fn calibrate(&self, p: &Params, pixels_per_metre: f64, c: &mut Calibration) {
        c.pixels_per_metre = Some(pixels_per_metre);
        c.g = Some(p["g"]);
    }
}

/// θ'' = −w2·sin θ − damping·θ', RK4 with 64 sub-steps per frame.
pub fn pendulum_trajectory(
    w2: f64,
    damping: f64,
    theta0: f64,
    omega0: f64,
    frames: usize,
    dt: f64,
) -> Vec<f64> {
    let law = |_t: f64, x: &[f64], d: &mut [f64]| {
        d[0] = x[1];
        d[1] = -w2 * x[0].sin() - damping * x[1];
    };
    rk4::trajectory(law, &[theta0, omega0], 0.0, dt, frames, 64)
        .chunks(2)
        .map(|x| x[0])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn pendulum_period_grows_with_amplitude() {
        // Small-angle period 2π/√(g/L); at 60° it is 7.3 % longer.
        let w2 = G / 0.9;
        let dt = 0.001;
        let period = |amp: f64| {
            let z = pendulum_trajectory(w2, 0.0, amp, 0.0, 6000, dt);
            // Released at rest at +amp: the first zero crossing is a quarter period later
            // (interpolated between samples).
            let k = (1..z.len()).find(|&k| z[k] <= 0.0).unwrap();
            let frac = z[k - 1] / (z[k - 1] - z[k]);
            4.0 * (k as f64 - 1.0 + frac) * dt
        };
        let t0 = 2.0 * PI / w2.sqrt();
        assert!((period(0.01) / t0 - 1.0).abs() < 2e-3);
        assert!((period(60f64.to_radians()) / t0 - 1.0732).abs() < 3e-3);
    }
}
