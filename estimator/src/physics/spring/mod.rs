//! The two-body spring of appendix A.5: unit masses joined by F = k·(|d| − l)·d̂ (d from body
//! one to body two; it pulls them together when stretched), on a vector latent: both bodies'
//! (x, y), four numbers per frame, integrated by the shooting machinery (RK4 through each clip's
//! least-squares positions and velocities).
//!
//! What the law leaves free, and what pins the latent: it is invariant under similarities of
//! the plane (translation, rotation, reflection, uniform scale) and under swapping the bodies,
//! so the latent is the true positions up to a similarity: k (1/time², per unit mass) is
//! scale-free and comes out as learned; the rest length l comes out in latent units, and in
//! pixels once reference frames give the bodies' positions (the similarity's scale). Anything
//! else fails the law: an anisotropic or bent map changes |d| unevenly; a harmonic of the motion
//! or a collapsed body (one body's latent constant) leaves the force unbalanced (body two's
//! acceleration must mirror body one's); a latent in which only the relative coordinate moves is
//! the one freedom left, the centre of mass, which the law lets drift uniformly: it carries no
//! parameter, and `latent_vs_truth` (a similarity fit of the true positions) shows whether the
//! encoder kept it. The KL term, per coordinate, keeps every coordinate from collapsing.

mod system;

use super::block::{BlockOptions, Clips, Integrator, PhysicsBlock};
use super::info::{Calibrates, Footage, Law, ModelInfo, ParamSpec, Training, TruthKey};
use super::model::{Derived, Model};
use super::ode::{ObservationMap, ShootingBlock};
use crate::calibration::{
    position_scale, Calibration, CalibrationInput, DerivedValue, Readings, POSITION_FIT_R2,
};
use crate::encoder::EncoderKind;
use crate::physics::hooks::{MotionHooks, TrainingHooks};
use crate::physics::spectral::spectral_start;
use physvid_shared::systems;
use system::{SpringSystem, SUBSTEPS_PER_FRAME};
use tch::nn;
use tch::Tensor;

/// The two-body spring.
pub struct Spring;

const INFO: ModelInfo = {
    let info = ModelInfo::of(
        &systems::SPRING,
        "two bodies, x_i'' = ±k·(|d| − l)·d̂, latent (x1, y1, x2, y2) (k, rest_length)",
        &[
            ParamSpec::new("k", 1.0, true),
            ParamSpec::new("rest_length", 1.0, true),
        ],
        &[TruthKey::positive("k"), TruthKey::positive("rest_length")],
    );
    ModelInfo {
        law: Law {
            latent_dims: 4,
            ..info.law
        },
        footage: Footage {
            min_frame: (44, "two 22-px digits side by side"),
            ..info.footage
        },
        calibration: Calibrates::by(&[CalibrationInput::Reference]),
        training: Training {
            encoder: EncoderKind::Keypoints,
            has_euler: false,
            ..Training::DEFAULT
        },
    }
};

/// Levenberg–Marquardt iterations of the final refinement of k and l.
const REFINE_ITERATIONS: usize = 10;
/// Clips the final scan of k looks at.
const SCAN_CLIPS: i64 = 64;
/// Values of k the final scan tries.
const SCAN_POINTS: usize = 24;

/// A log grid of k from 1/1000 of the largest to the largest the frames resolve: the relative
/// coordinate turns √(2k)·dt per frame, below π·0.9.
fn k_grid(dt: f64) -> Vec<f64> {
    let top = (0.9 * std::f64::consts::PI / dt).powi(2) / 2.0;
    (0..SCAN_POINTS)
        .map(|i| top * 1e-3f64.powf(1.0 - i as f64 / (SCAN_POINTS - 1) as f64))
        .collect()
}

/// The spring's block: shooting over both bodies, the latent read as positions directly.
pub struct SpringBlock {
    shooting: ShootingBlock,
    /// Seconds between frames.
    dt: f64,
}

impl PhysicsBlock for SpringBlock {
    fn order(&self) -> i64 {
        2
    }
    fn rollout(&self, z: &Tensor, clips: Clips, steps: i64) -> Tensor {
        self.shooting
            .observed_rollout(&z.narrow(1, 0, steps), clips)
    }
    fn values(&self, _latents: &Tensor) -> Vec<f64> {
        self.shooting.values()
    }
    /// A scan of k over a log grid up to the frames' Nyquist limit first (on up to
    /// `SCAN_CLIPS` clips): the misfit has a minimum per basin of frequency, and training
    /// from a k several times off can settle in the wrong one while the encoder is right.
    fn refine(&self, z: &Tensor, clips: Clips) -> bool {
        let current = self.shooting.values();
        let n = z.size()[0].min(SCAN_CLIPS);
        let sub_start = clips.start.map(|s| s.narrow(0, 0, n));
        let subset = Clips {
            start: sub_start.as_ref(),
            ids: None,
        };
        let candidates: Vec<Vec<f64>> = k_grid(self.dt)
            .into_iter()
            .map(|k| vec![k, current[1]])
            .collect();
        let scanned = self.shooting.scan(&z.narrow(0, 0, n), subset, &candidates);
        self.shooting.refine(z, clips, REFINE_ITERATIONS) || scanned
    }
}

impl Model for Spring {
    fn info(&self) -> &ModelInfo {
        &INFO
    }
    fn build(&self, path: &nn::Path, init: &[f64], opts: BlockOptions) -> Box<dyn PhysicsBlock> {
        Box::new(SpringBlock {
            shooting: ShootingBlock::new(
                path,
                Box::new(SpringSystem),
                INFO.law.parameters,
                init,
                ObservationMap::Identity,
                vec![0, 1, 2, 3],
                opts.dt,
                SUBSTEPS_PER_FRAME,
            ),
            dt: opts.dt,
        })
    }
    /// k as learned; l in latent units, and in pixels with the similarity's scale from frames
    /// of known body positions.
    fn derive(&self, params: &[f64], cal: &Calibration, readings: &Readings) -> Derived {
        let mut values = vec![
            DerivedValue::si("k", "1/s^2", params[0], Some("k")),
            DerivedValue::latent("rest_length_latent", params[1]),
        ];
        let mut warnings = Vec::new();
        match position_scale(cal, &readings.positions) {
            Some((scale, r2)) => {
                values.insert(
                    1,
                    DerivedValue::si("rest_length", "px", params[1] / scale, Some("rest_length")),
                );
                if r2 < POSITION_FIT_R2 {
                    warnings.push(format!(
                        "the reference frames' body positions fit the latent only with R² \
                         {r2:.3} (a similarity should fit exactly): the rest length in pixels is \
                         suspect; check --reference, or that the encoder found both bodies"
                    ));
                }
            }
            None => warnings.push(
                "the rest length is reported in latent units only: give both bodies' positions \
                 at two or more frames (meta.json's reference_positions, or --reference \
                 CLIP:FRAME=X1/Y1/X2/Y2,...) to get it in pixels"
                    .into(),
            ),
        }
        (values, warnings)
    }
    fn training_hooks(&self) -> Option<&dyn TrainingHooks> {
        Some(self)
    }
    fn motion_hooks(&self) -> Option<&dyn MotionHooks> {
        Some(self)
    }
}

impl TrainingHooks for Spring {
    /// The relative coordinate d = body two − body one only: the KL term on d rules out the
    /// rigid pair (|d| = l fixed, both bodies riding on the centre of mass), which satisfies
    /// the law for every k and which KL on the raw coordinates would let through; the centre of
    /// mass carries no parameter, and pulling its spread to 1 would only distort the latent.
    fn kl_coordinates(&self, z: &Tensor) -> Tensor {
        z.narrow(-1, 2, 2) - z.narrow(-1, 0, 2)
    }
    /// The relative coordinate oscillates at √(2k): k from the frames' most persistent mode.
    fn extra_starts(
        &self,
        train: &Tensor,
        dt: f64,
        integrator: Integrator,
        init: &[f64],
    ) -> Vec<Vec<f64>> {
        spectral_start(train, dt, integrator)
            .map(|g| vec![g[0] / 2.0, init[1]])
            .into_iter()
            .collect()
    }
    /// One and a half periods of the relative coordinate at the start's k, at least 4 frames.
    fn first_horizon(&self, init: &[f64], dt: f64) -> Option<usize> {
        let period = std::f64::consts::TAU / ((2.0 * init[0]).sqrt() * dt);
        Some((1.5 * period).ceil().max(4.0) as usize)
    }
}

impl MotionHooks for Spring {
    /// The relative vector's oscillation √(2k) (two unit masses).
    fn oscillates(&self, _params: &[f64]) -> bool {
        true
    }
    fn rate(&self, params: &[f64]) -> Option<f64> {
        Some((2.0 * params[0]).max(0.0).sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use generator::scenes::spring::spring_trajectory;
    use std::f64::consts::TAU;

    /// Clips of the true trajectories (latent = pixels/32 − 1) of `n` PAIG-like draws.
    fn true_latents(n: usize, t: usize) -> Tensor {
        let mut state = 12345u64;
        let mut u01 = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut all = Vec::new();
        for _ in 0..n {
            let c = [23.0 + 18.0 * u01(), 23.0 + 18.0 * u01()];
            let (a, h) = (TAU * u01(), 12.0 * (0.5 + u01()));
            let mut s = [
                c[0] - h * a.cos(),
                c[1] - h * a.sin(),
                c[0] + h * a.cos(),
                c[1] + h * a.sin(),
                0.0,
                0.0,
                0.0,
                0.0,
            ];
            for v in &mut s[4..] {
                *v = 8.0 * (2.0 * u01() - 1.0);
            }
            let track = spring_trajectory(s, 2.0, 24.0, t, 0.3);
            all.extend(track.iter().map(|v| (v / 32.0 - 1.0) as f32));
        }
        Tensor::from_slice(&all).view([n as i64, t as i64, 4])
    }

    #[test]
    fn the_final_solve_finds_k_and_l_on_true_latents_from_far_starts() {
        // From k = 1 by descent; from k = 10 (an aliased basin: a local descent stays near
        // 9.9) only with the scan over k first. Truth k = 2, l = 24/32 = 0.75.
        let z = true_latents(48, 12);
        let ids: Vec<usize> = (0..48).collect();
        let clips = Clips {
            start: None,
            ids: Some(&ids),
        };
        for init in [[1.0, 0.6], [10.0, 0.9]] {
            let vs = nn::VarStore::new(tch::Device::Cpu);
            let opts = BlockOptions {
                integrator: Integrator::Exact,
                dt: 0.3,
                timed: false,
                rising: false,
                calibrated: false,
                start: crate::physics::RolloutStart::Fit,
            };
            let block = Spring.build(&vs.root(), &init, opts);
            assert!(block.refine(&z, clips));
            let v = block.values(&z);
            assert!((v[0] / 2.0 - 1.0).abs() < 1e-3, "from {init:?}: k {}", v[0]);
            assert!(
                (v[1] / 0.75 - 1.0).abs() < 1e-3,
                "from {init:?}: l {}",
                v[1]
            );
        }
    }
}
