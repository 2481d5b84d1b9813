//! The five Delfys75 systems (appendix A.6, Table 4) as synthetic scenes: their true parameters
//! per setting, the trajectory of the physical quantity each clip shows, the drawing, and the
//! calibration a user would measure to turn latent-unit answers into SI units.

use crate::config::ConfigError;
use crate::render::Canvas;
use physvid_shared::SampleTruth;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;

/// Standard gravity used by the scenes (m/s²).
pub const G: f64 = 9.81;

/// One of the Delfys75 systems.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum System {
    Pendulum,
    Torricelli,
    SlidingBlock,
    Led,
    FreeFall,
}

/// Parameters of a system by name (SI units), after `--setting` and `--set`.
pub type Params = BTreeMap<String, f64>;

fn params(pairs: &[(&str, f64)]) -> Params {
    pairs.iter().map(|(k, v)| (k.to_string(), *v)).collect()
}

fn invalid(value: impl ToString, expected: impl Into<String>) -> ConfigError {
    ConfigError {
        flag: "--set",
        value: value.to_string(),
        expected: expected.into(),
    }
}

impl System {
    /// The `estimate --model` name.
    pub fn model_name(self) -> &'static str {
        match self {
            System::Pendulum => "pendulum",
            System::Torricelli => "torricelli",
            System::SlidingBlock => "sliding-block",
            System::Led => "led",
            System::FreeFall => "free-fall",
        }
    }

    /// Whether the recording starts at the release from rest (sliding block, free fall): then
    /// each clip's start time since the release is written to meta.json, as a user reads it off
    /// the frame counter.
    pub fn released_from_rest(self) -> bool {
        matches!(self, System::SlidingBlock | System::FreeFall)
    }

    /// Table 4's values for `setting` 1, 2 or 3, plus the fixed quantities of the scene.
    pub fn setting(self, setting: u8) -> Params {
        let i = (setting.clamp(1, 3) - 1) as usize;
        match self {
            System::Pendulum => params(&[
                ("length", [0.45, 0.90, 1.50][i]),
                ("damping", 0.059),
                ("g", G),
                ("amplitude_min_deg", 10.0),
                ("amplitude_max_deg", 60.0),
            ]),
            System::Torricelli => params(&[
                ("k", [0.0095, 0.0128, 0.0162][i]),
                ("h_start", 0.07),
                ("h_end", 0.01),
            ]),
            System::SlidingBlock => params(&[
                ("incline_deg", [20.0, 25.0, 30.0][i]),
                ("mu", 0.21),
                ("g", G),
                ("travel", 0.726),
            ]),
            System::Led => params(&[("gamma", [2.3, 0.92, 0.46][i])]),
            System::FreeFall => {
                params(&[("radius", [0.0335, 0.06, 0.10][i]), ("h0", 0.20), ("g", G)])
            }
        }
    }

    /// Table 5's frames per clip and time step.
    pub fn default_frames_and_dt(self) -> (usize, f64) {
        match self {
            System::Pendulum => (20, 0.1),
            System::Torricelli => (20, 1.0),
            System::SlidingBlock => (10, 1.0 / 30.0),
            System::Led => (20, 1.0 / 60.0),
            System::FreeFall => (4, 1.0 / 30.0),
        }
    }

    /// The parameters `estimate` recovers (SI), as written in meta.json's model.
    pub fn estimated_parameters(self, p: &Params) -> Params {
        let keep: &[&str] = match self {
            System::Pendulum => &["length", "damping", "g"],
            System::Torricelli => &["k"],
            System::SlidingBlock => &["mu", "incline_deg", "g"],
            System::Led => &["gamma"],
            System::FreeFall => &["g"],
        };
        let mut out: Params = keep.iter().map(|&k| (k.to_string(), p[k])).collect();
        if self == System::SlidingBlock {
            out.insert("acceleration".into(), block_acceleration(p));
        }
        out
    }

    /// Checks the parameters against physics and the clip length.
    pub fn validate(self, p: &Params, frames: usize, dt: f64) -> Result<(), ConfigError> {
        let span = (frames - 1) as f64 * dt;
        for (k, v) in p {
            if !v.is_finite() {
                return Err(invalid(format!("{k}={v}"), "must be a finite number"));
            }
        }
        let positive = |k: &str| -> Result<(), ConfigError> {
            if p[k] > 0.0 {
                Ok(())
            } else {
                Err(invalid(format!("{k}={}", p[k]), "must be > 0"))
            }
        };
        match self {
            System::Pendulum => {
                positive("length")?;
                positive("g")?;
                let (lo, hi) = (p["amplitude_min_deg"], p["amplitude_max_deg"]);
                if !(0.0 < lo && lo <= hi && hi < 90.0) {
                    return Err(invalid(
                        format!("amplitude_min_deg={lo},amplitude_max_deg={hi}"),
                        "need 0 < amplitude_min_deg <= amplitude_max_deg < 90",
                    ));
                }
                if p["damping"] < 0.0 {
                    return Err(invalid(format!("damping={}", p["damping"]), "must be >= 0"));
                }
            }
            System::Torricelli => {
                positive("k")?;
                positive("h_end")?;
                if p["h_start"] <= p["h_end"] {
                    return Err(invalid(
                        format!("h_start={}", p["h_start"]),
                        "must be above h_end (the level falls)",
                    ));
                }
                let total = torricelli_duration(p);
                if span > total {
                    return Err(invalid(
                        format!("k={}", p["k"]),
                        format!(
                            "the tank drains from h_start to h_end in {total:.2} s, shorter than one clip ({span:.2} s); lower --frames or --dt"
                        ),
                    ));
                }
            }
            System::SlidingBlock => {
                positive("travel")?;
                positive("g")?;
                let alpha = p["incline_deg"];
                if !(0.0 < alpha && alpha < 90.0) {
                    return Err(invalid(
                        format!("incline_deg={alpha}"),
                        "must be in (0, 90)",
                    ));
                }
                if p["mu"] < 0.0 || block_acceleration(p) <= 0.0 {
                    return Err(invalid(
                        format!("mu={}", p["mu"]),
                        format!(
                            "the block only slides when 0 <= mu < tan(incline) = {:.3}",
                            alpha.to_radians().tan()
                        ),
                    ));
                }
                let total = block_duration(p);
                if span > total {
                    return Err(invalid(
                        format!("mu={}", p["mu"]),
                        format!("the block covers the incline in {total:.2} s, shorter than one clip ({span:.2} s); lower --frames or --dt"),
                    ));
                }
            }
            System::Led => positive("gamma")?,
            System::FreeFall => {
                positive("radius")?;
                positive("h0")?;
                positive("g")?;
            }
        }
        Ok(())
    }

    /// Draws one clip: its ground truth and the physical quantity at each frame (the angle in
    /// rad, the level or distance in m, the brightness relative to its start).
    pub fn sample(
        self,
        p: &Params,
        rng: &mut ChaCha8Rng,
        frames: usize,
        dt: f64,
    ) -> (SampleTruth, Vec<f64>) {
        let span = (frames - 1) as f64 * dt;
        let times = |t0: f64| (0..frames).map(move |k| t0 + k as f64 * dt);
        match self {
            System::Pendulum => {
                let amp = rng
                    .random_range(p["amplitude_min_deg"]..=p["amplitude_max_deg"])
                    .to_radians();
                let theta0 = amp * rng.random_range(-1.0..1.0);
                let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
                let w2 = p["g"] / p["length"];
                let omega0 = sign * (2.0 * w2 * (theta0.cos() - amp.cos())).max(0.0).sqrt();
                let z = pendulum_trajectory(w2, p["damping"], theta0, omega0, frames, dt);
                (
                    SampleTruth::from_pairs([
                        ("amplitude", amp),
                        ("theta0", theta0),
                        ("omega0", omega0),
                    ]),
                    z,
                )
            }
            System::Torricelli => {
                let t0 = rng.random_range(0.0..=(torricelli_duration(p) - span).max(0.0));
                let root = p["h_start"].sqrt();
                let z = times(t0)
                    .map(|t| (root - p["k"] * t / 2.0).powi(2))
                    .collect();
                (SampleTruth::from_pairs([("start_time", t0)]), z)
            }
            System::SlidingBlock => {
                let t0 = rng.random_range(0.0..=(block_duration(p) - span).max(0.0));
                let a = block_acceleration(p);
                let z = times(t0).map(|t| a * t * t / 2.0).collect();
                (SampleTruth::from_pairs([("start_time", t0)]), z)
            }
            System::Led => {
                let t0 = rng.random_range(0.0..=1.0 / p["gamma"]);
                let z = times(t0).map(|t| (-p["gamma"] * t).exp()).collect();
                (SampleTruth::from_pairs([("start_time", t0)]), z)
            }
            System::FreeFall => {
                let t0 = rng.random_range(0.0..=0.3);
                let z = times(t0).map(|t| p["h0"] + p["g"] * t * t / 2.0).collect();
                (SampleTruth::from_pairs([("start_time", t0)]), z)
            }
        }
    }

    /// Pixels per metre of the scene in a `size`-pixel frame (the focal length in pixels for
    /// free fall).
    pub fn pixels_per_metre(self, p: &Params, size: usize) -> f64 {
        let s = size as f64;
        match self {
            System::Pendulum => 0.5 * s / p["length"],
            System::Torricelli => 0.7 * s / p["h_start"],
            System::SlidingBlock => 0.8 * s / p["travel"],
            System::Led => 1.0,
            // The ball's apparent radius at h0 for the largest setting (10 cm) is 0.4·size.
            System::FreeFall => 0.4 * s * 0.20 / 0.10,
        }
    }

    /// Draws the scene for physical value `z` into `out` (zeroed by the caller).
    pub fn render(self, p: &Params, z: f64, size: usize, canvas: &mut Canvas, out: &mut [f32]) {
        let s = size as f32;
        let ppm = self.pixels_per_metre(p, size) as f32;
        out.fill(0.0);
        match self {
            System::Pendulum => {
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
            System::Torricelli => {
                let (x0, x1, bottom) = (0.3 * s, 0.7 * s, 0.9 * s);
                let wall = 0.03 * s;
                let top = 0.1 * s;
                let rect =
                    |xa: f32, xb: f32, ya: f32, yb: f32| [(xa, ya), (xb, ya), (xb, yb), (xa, yb)];
                canvas.draw_polygon(&rect(x0 - wall, x0, top, bottom + wall), 0.4, out);
                canvas.draw_polygon(&rect(x1, x1 + wall, top, bottom + wall), 0.4, out);
                canvas.draw_polygon(&rect(x0, x1, bottom, bottom + wall), 0.4, out);
                let level = bottom - z as f32 * ppm;
                canvas.draw_polygon(&rect(x0, x1, level, bottom), 0.9, out);
            }
            System::SlidingBlock => {
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
            System::Led => {
                let housing = canvas.circle_points(s / 2.0, s / 2.0, 0.3 * s);
                canvas.draw_polygon(&housing, 0.15, out);
                let led = canvas.circle_points(s / 2.0, s / 2.0, 0.2 * s);
                canvas.draw_polygon(&led, 0.15 + 0.85 * z as f32, out);
            }
            System::FreeFall => {
                let r = ppm * p["radius"] as f32 / z as f32;
                let ball = canvas.circle_points(s / 2.0, s / 2.0, r);
                canvas.draw_polygon(&ball, 1.0, out);
            }
        }
    }

    /// What the physical quantity z is, in words (for meta.json).
    pub fn mapping_text(self) -> &'static str {
        match self {
            System::Pendulum => "latent = angle theta (rad) of a bob on a string seen from the front; pivot at (size/2, 0.1*size), pixels_per_metre = 0.5*size/length",
            System::Torricelli => "latent = water level h (m) above the bottom of a tank; pixels_per_metre = 0.7*size/h_start",
            System::SlidingBlock => "latent = distance s (m) travelled down the incline from the top; pixels_per_metre = 0.8*size/travel along the incline",
            System::Led => "latent = brightness I/I(0) of an LED (grey 0.15 + 0.85*I) in a dim housing",
            System::FreeFall => "latent = distance h (m) of a ball from the camera; apparent radius = focal_px_per_m * radius / h",
        }
    }
}

/// a = g·(sin α − μ·cos α).
pub fn block_acceleration(p: &Params) -> f64 {
    let a = p["incline_deg"].to_radians();
    p["g"] * (a.sin() - p["mu"] * a.cos())
}

fn block_duration(p: &Params) -> f64 {
    (2.0 * p["travel"] / block_acceleration(p)).sqrt()
}

fn torricelli_duration(p: &Params) -> f64 {
    2.0 * (p["h_start"].sqrt() - p["h_end"].sqrt()) / p["k"]
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
    let f = |th: f64, om: f64| (om, -w2 * th.sin() - damping * om);
    let (mut th, mut om) = (theta0, omega0);
    let h = dt / 64.0;
    let mut out = Vec::with_capacity(frames);
    for _ in 0..frames {
        out.push(th);
        for _ in 0..64 {
            let k1 = f(th, om);
            let k2 = f(th + h / 2.0 * k1.0, om + h / 2.0 * k1.1);
            let k3 = f(th + h / 2.0 * k2.0, om + h / 2.0 * k2.1);
            let k4 = f(th + h * k3.0, om + h * k3.1);
            th += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            om += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        }
    }
    out
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

    #[test]
    fn settings_follow_table_4_and_validate() {
        assert_eq!(System::Torricelli.setting(3)["k"], 0.0162);
        assert_eq!(System::Led.setting(2)["gamma"], 0.92);
        let mut p = System::SlidingBlock.setting(1);
        assert!(System::SlidingBlock.validate(&p, 10, 1.0 / 30.0).is_ok());
        p.insert("mu".into(), 0.5);
        let e = System::SlidingBlock
            .validate(&p, 10, 1.0 / 30.0)
            .unwrap_err();
        assert!(e.expected.contains("tan"), "{e}");
    }
}
