//! The damped oscillator's disc scenes (appendix A.1): z(t) = A·e^(−ζt)·cos(ωt + φ) with
//! A ~ U[0.5, 1) and φ ~ U[0, 2π), shown as the grey level, position or size of a disc
//! (`DiscPicture`, one file each). `DiscScene` adds what they share: the dynamics, the
//! validation of ω and ζ, and meta.json's model.

use super::{params, Params, Scene, MIN_PHASE_SPAN};
use crate::error::{invalid, ConfigError};
use crate::render::{Canvas, Disc};
use crate::sampling::{draw_initial_condition, AMPLITUDE_MAX, SAMPLING_TEXT};
use physvid_shared::cli::{approx, num};
use physvid_shared::systems;
use physvid_shared::{Calibration, DampedOscillator, SampleTruth};
use rand_chacha::ChaCha8Rng;

/// The largest ζ·dt rendered: beyond it the amplitude falls more than e²-fold per frame.
pub const MAX_DECAY_PER_FRAME: f64 = 2.0;

/// The facts about a disc picture, one record per picture (its file's `INFO`).
#[derive(Debug, Clone, Copy)]
pub struct PictureInfo {
    /// The scenario name.
    pub name: &'static str,
    pub help: &'static str,
    /// How z shows, in words (meta.json's latent_mapping).
    pub mapping_text: &'static str,
}

/// How a disc shows z (|z| ≤ 1 keeps it inside the frame and its grey level in [0, 1]).
pub trait DiscPicture: Sync {
    fn info(&self) -> &PictureInfo;
    /// The disc that shows `z` in a `size`×`size` frame (the moving part of the picture).
    fn disc(&self, z: f64, size: usize) -> Disc;
    /// Draws the frame for `z` into `out` (size² values): the disc on black, unless the
    /// picture draws more than its disc.
    fn draw(&self, z: f64, size: usize, canvas: &mut Canvas, out: &mut [f32]) {
        canvas.render_frame(&self.disc(z, size), out);
    }
}

/// A damped-oscillator scene drawn by picture `P`.
pub struct DiscScene<P>(pub P);

fn oscillator(p: &Params) -> DampedOscillator {
    DampedOscillator {
        omega: p["omega"],
        zeta: p["zeta"],
    }
}

impl<P: DiscPicture> Scene for DiscScene<P> {
    fn name(&self) -> &'static str {
        self.0.info().name
    }
    fn help(&self) -> &'static str {
        self.0.info().help
    }
    fn model_name(&self) -> &'static str {
        systems::DAMPED_OSCILLATOR.model
    }
    fn default_clip(&self) -> (usize, f64) {
        systems::DAMPED_OSCILLATOR.clip
    }
    fn params(&self, _setting: u8) -> Params {
        params(&[("omega", 2.0), ("zeta", 0.04)])
    }
    fn accepts_set(&self) -> bool {
        false
    }

    fn validate(
        &self,
        p: &Params,
        frames: usize,
        dt: f64,
        _size: usize,
    ) -> Result<(), ConfigError> {
        let (omega, zeta) = (p["omega"], p["zeta"]);
        if !(omega.is_finite() && omega > 0.0) {
            return Err(invalid(
                "--omega",
                omega,
                "must be a finite number > 0 (rad/s)",
            ));
        }
        if omega * dt >= std::f64::consts::PI {
            return Err(invalid(
                "--omega",
                omega,
                format!(
                    "with --dt {dt} the frames sample the oscillation below its Nyquist rate (omega*dt = {:.3} >= pi); need omega < {:.4}",
                    omega * dt,
                    std::f64::consts::PI / dt
                ),
            ));
        }
        let phase_span = omega * (frames - 1) as f64 * dt;
        if phase_span < MIN_PHASE_SPAN {
            return Err(invalid(
                "--dt",
                num(dt),
                format!(
                    "a clip of {frames} frames spans {} rad of the oscillation (omega*(frames-1)*dt), too little to see it move; need at least {MIN_PHASE_SPAN} rad",
                    approx(phase_span)
                ),
            ));
        }
        if !zeta.is_finite() {
            return Err(invalid("--zeta", zeta, "must be a finite number (1/s)"));
        }
        if zeta * dt > MAX_DECAY_PER_FRAME {
            return Err(invalid(
                "--zeta",
                num(zeta),
                format!(
                    "with --dt {dt} the amplitude falls e^{}-fold from one frame to the next and the clip is still after its first frames; need zeta*dt <= {MAX_DECAY_PER_FRAME} (zeta <= {})",
                    approx(zeta * dt),
                    approx(MAX_DECAY_PER_FRAME / dt)
                ),
            ));
        }
        let t_end = (frames - 1) as f64 * dt;
        let growth = (-zeta * t_end).exp().max(1.0);
        if AMPLITUDE_MAX * growth > 1.0 {
            return Err(invalid(
                "--zeta",
                zeta,
                format!(
                    "a negative decay rate makes the amplitude grow {growth:.3}x by the last frame, pushing the object out of the frame; need zeta >= 0 for {frames} frames at dt {dt}"
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
        _size: usize,
    ) -> (SampleTruth, Vec<f64>) {
        let model = oscillator(p);
        let (amplitude, phase) = draw_initial_condition(rng);
        let latents = (0..frames)
            .map(|k| model.latent(amplitude, phase, k as f64 * dt))
            .collect();
        let truth = SampleTruth::from_pairs([("amplitude", amplitude), ("phase", phase)]);
        (truth, latents)
    }

    fn render(&self, _p: &Params, z: &[f64], size: usize, canvas: &mut Canvas, out: &mut [f32]) {
        self.0.draw(z[0], size, canvas, out);
    }

    fn mapping_text(&self) -> &'static str {
        self.0.info().mapping_text
    }
    fn sampling_text(&self) -> &'static str {
        SAMPLING_TEXT
    }

    fn model_parameters(&self, p: &Params) -> Params {
        let m = oscillator(p);
        params(&[
            ("omega", m.omega),
            ("zeta", m.zeta),
            ("gamma0", m.gamma0()),
            ("gamma1", m.gamma1()),
        ])
    }

    fn calibration(&self, _p: &Params, _size: usize, _latents: &[Vec<f64>]) -> Calibration {
        Calibration::default()
    }
    fn fps(&self, _dt: f64) -> Option<f64> {
        None
    }
    fn released_from_rest(&self) -> bool {
        false
    }
    fn picture(&self) -> Option<&dyn DiscPicture> {
        Some(&self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{intensity::Intensity, position::Position, rod::Rod, scale::Scale};
    use super::DiscPicture;

    #[test]
    fn discs_stay_inside_the_frame_and_in_range_for_unit_latents() {
        let pictures: [&dyn DiscPicture; 4] = [&Intensity, &Position, &Scale, &Rod];
        for size in [8usize, 50, 128] {
            for pic in pictures {
                for z in [-1.0, -0.3, 0.0, 0.7, 1.0] {
                    let d = pic.disc(z, size);
                    let s = size as f32;
                    let name = pic.info().name;
                    assert!(
                        d.cx - d.radius >= 0.0 && d.cx + d.radius <= s,
                        "{name} {size} {z}"
                    );
                    assert!(d.cy - d.radius >= 0.0 && d.cy + d.radius <= s);
                    assert!(d.radius > 0.0 && (0.0..=1.0).contains(&d.grey));
                }
            }
        }
    }
}
