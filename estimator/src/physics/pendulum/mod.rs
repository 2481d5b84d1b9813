//! The pendulum θ'' = −(g/L)·sin θ − ζ·θ' (Delfys75): the model and `PendulumBlock`, with the
//! angle read from the latent as θ = (z − c)/s. The KL term holds the latent's spread at 1,
//! which must not fix the angle's amplitude (the paper's block takes z as θ and finds L about
//! 20 % short on real swings); at finite amplitude L depends on s. Given reference frames of
//! known angle, s and c are fitted to them before every step; otherwise they are learned
//! (weakly pinned). The rollout is the RK4 trajectory (sub-steps ≤ 50 ms) through the initial
//! state that best fits the whole clip: a velocity from two encoded frames multiplies encoder
//! errors about five-fold over a period, and the fit buys them down with too much damping.

mod block;

pub use block::{PendulumBlock, PendulumSystem};

use super::block::{BlockOptions, Integrator, PhysicsBlock};
use super::info::{Calibrates, Footage, ModelInfo, ParamSpec, TruthKey};
use super::model::{Derived, Model};
use crate::calibration::{Calibration, CalibrationInput, DerivedValue, Readings};
use crate::peaks::{self, PeakDecay};
use crate::physics::hooks::{MotionHooks, TrainingHooks};
use crate::physics::spectral::spectral_start;
use physvid_shared::systems;
use tch::nn;
use tch::Tensor;

/// The pendulum of Delfys75 (appendix A.6).
pub struct Pendulum;

/// The calibrated answers need the latent affine to a few parts in 10⁴: patience 30.
pub(super) const INFO: ModelInfo = {
    let info = ModelInfo::of(
        &systems::PENDULUM,
        "θ'' = −(g/L)·sin θ − ζ·θ', θ = (z − c)/s (g_over_l, damping, angle_scale, angle_offset)",
        &[
            ParamSpec::new("g_over_l", 10.0, true),
            ParamSpec::new("damping", 0.1, true),
            ParamSpec::map("angle_scale", 10.0, true),
            ParamSpec::map("angle_offset", 0.0, false),
        ],
        &[TruthKey::positive("length"), TruthKey::signed("damping")],
    );
    ModelInfo {
        footage: Footage {
            max_dt: (
                10.0,
                "a pendulum of 100 m swings once in 20 s: frames further apart than half a swing cannot follow it",
            ),
            swings: Some("its period gives g/L, the decay of its swings the damping"),
            ..info.footage
        },
        calibration: Calibrates {
            in_training: true,
            ..Calibrates::by(&[CalibrationInput::Reference, CalibrationInput::G])
        },
        ..info
    }
};

impl Model for Pendulum {
    fn info(&self) -> &ModelInfo {
        &INFO
    }
    fn build(&self, path: &nn::Path, init: &[f64], opts: BlockOptions) -> Box<dyn PhysicsBlock> {
        Box::new(PendulumBlock::new(path, init, opts))
    }
    fn derive(&self, params: &[f64], cal: &Calibration, _readings: &Readings) -> Derived {
        let mut warnings = Vec::new();
        if cal.reference.len() < 2 {
            warnings.push(
                "the pendulum's angle scale was learned, not calibrated: at finite amplitude \
                 the period depends on the amplitude, so L depends on that scale, which the \
                 video pins only weakly; give the angle in rad at two or more frames with \
                 --reference CLIP:FRAME=ANGLE,... to calibrate it"
                    .into(),
            );
        }
        let values = vec![
            DerivedValue::si("length", "m", cal.g / params[0], Some("length")),
            DerivedValue::si("damping", "1/s", params[1], Some("damping")),
            DerivedValue::si("g_over_l", "1/s^2", params[0], None),
            DerivedValue::latent("angle_scale", params[2]),
            DerivedValue::latent("angle_offset", params[3]),
        ];
        (values, warnings)
    }
    fn training_hooks(&self) -> Option<&dyn TrainingHooks> {
        Some(self)
    }
    fn motion_hooks(&self) -> Option<&dyn MotionHooks> {
        Some(self)
    }
}

impl TrainingHooks for Pendulum {
    /// The oscillator's two-step recurrence gives the small-angle g/L and damping. The most
    /// persistent mode of a real swing is often the second harmonic (a latent like |x|
    /// oscillates at 2ω, so g/L 4× too large): its sub-harmonic is probed too, and the
    /// validation error picks.
    fn extra_starts(
        &self,
        train: &Tensor,
        dt: f64,
        integrator: Integrator,
        init: &[f64],
    ) -> Vec<Vec<f64>> {
        let Some(g) = spectral_start(train, dt, integrator) else {
            return Vec::new();
        };
        let damping = g[1].max(1e-3);
        vec![
            vec![g[0], damping, init[2], init[3]],
            vec![g[0] / 4.0, damping / 2.0, init[2], init[3]],
        ]
    }
    /// Half the frequency: g/L/4, the damping halved, the map kept.
    fn subharmonic(&self, params: &[f64]) -> Option<Vec<f64>> {
        let mut p = params.to_vec();
        p[0] /= 4.0;
        p[1] /= 2.0;
        Some(p)
    }
    /// One and a half swings at the start's g/L, at least four frames.
    fn first_horizon(&self, init: &[f64], dt: f64) -> Option<usize> {
        let frames_per_swing = std::f64::consts::TAU / (init[0].sqrt() * dt);
        Some((1.5 * frames_per_swing).ceil().max(4.0) as usize)
    }
}

impl MotionHooks for Pendulum {
    fn oscillates(&self, _params: &[f64]) -> bool {
        true
    }
    /// The small-angle frequency √(g/L), the fastest it swings.
    fn rate(&self, params: &[f64]) -> Option<f64> {
        Some(params[0].max(0.0).sqrt())
    }
    /// The damping from the decay of the swing peaks (appendix A.6's procedure), around the
    /// angle offset.
    fn cross_check(&self, params: &[f64], latents: &[f64], dt: f64) -> Option<PeakDecay> {
        peaks::cross_check("damping", params[1], latents, dt, params[3])
    }
}
