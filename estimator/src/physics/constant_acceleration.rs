//! Constant acceleration z'' = a from rest (Delfys75): the sliding block (s'' = g·(sin α −
//! μ·cos α)) and free fall (h'' = g), two models that share `ConstantAccelerationBlock` and
//! differ in what their SI answers are.

use super::block::{frame_index, BlockOptions, Clips, PhysicsBlock};
use super::hooks::Implausible;
use super::info::{Calibrates, ModelInfo, ParamSpec, TruthKey};
use super::model::{Derived, Model};
use crate::calibration::{needs_reference, Calibration, CalibrationInput, DerivedValue, Readings};
use crate::physics::hooks::MotionHooks;
use physvid_shared::cli::approx;
use physvid_shared::systems;
use tch::nn;
use tch::Tensor;

/// Earth's gravity (m/s²), and how far from it a measured g may lie before it is doubtful
/// (a camera's perspective biases a fall by 10–15 %; a wrong frame rate by 4× or more).
const EARTH_G: f64 = 9.81;
const G_TOLERANCE: f64 = 0.3;

const PARAMETERS: [ParamSpec; 1] = [ParamSpec::new("acceleration_latent", 0.0, false)];

const UNTIMED: &str = "no clip start times (meta.json's clip_start_times): the block rolls out \
     from two frames, and for motion from rest that law is degenerate (a latent like √s is \
     linear in time and fits z'' = 0), so the acceleration may come out far too small";

/// A model of motion from rest with constant acceleration.
pub struct ConstantAcceleration {
    info: ModelInfo,
    /// Whether the acceleration is the incline's (μ follows from it), else gravity's.
    incline: bool,
}

/// The block sliding down an incline of Delfys75.
pub static SLIDING_BLOCK: ConstantAcceleration = ConstantAcceleration {
    info: ModelInfo {
        calibration: Calibrates::by(&[
            CalibrationInput::Reference,
            CalibrationInput::InclineDeg,
            CalibrationInput::G,
        ])
        .past_end(),
        ..ModelInfo::of(
            &systems::SLIDING_BLOCK,
            "s'' = g·(sin α − μ·cos α), constant (acceleration_latent)",
            &PARAMETERS,
            &[TruthKey::signed("acceleration"), TruthKey::signed("mu")],
        )
    },
    incline: true,
};

/// The ball falling away from the camera of Delfys75.
pub static FREE_FALL: ConstantAcceleration = ConstantAcceleration {
    info: ModelInfo {
        calibration: Calibrates::by(&[CalibrationInput::Reference]).past_end(),
        ..ModelInfo::of(
            &systems::FREE_FALL,
            "h'' = g (acceleration_latent)",
            &PARAMETERS,
            &[TruthKey::positive("g")],
        )
    },
    incline: false,
};

impl Model for ConstantAcceleration {
    fn info(&self) -> &ModelInfo {
        &self.info
    }
    fn build(&self, path: &nn::Path, init: &[f64], opts: BlockOptions) -> Box<dyn PhysicsBlock> {
        Box::new(
            ConstantAccelerationBlock::new(path, init, opts.dt, opts.timed).rising(opts.rising),
        )
    }
    /// The acceleration in SI needs the latent's scale (g for free fall); the block's μ also
    /// the incline's angle.
    fn derive(&self, params: &[f64], cal: &Calibration, readings: &Readings) -> Derived {
        let mut values = vec![DerivedValue::latent("acceleration_latent", params[0])];
        let mut warnings = Vec::new();
        let Some(alpha) = cal.latent_scale(&readings.values) else {
            let what = if self.incline {
                "the block's acceleration (and so μ)"
            } else {
                "the fall's acceleration g"
            };
            warnings.push(needs_reference(what));
            return (values, warnings);
        };
        let acc = params[0] / alpha;
        if !self.incline {
            values.insert(0, DerivedValue::si("g", "m/s^2", acc, Some("g")));
            return (values, warnings);
        }
        values.insert(
            0,
            DerivedValue::si("acceleration", "m/s^2", acc, Some("acceleration")),
        );
        match cal.incline_deg {
            Some(deg) => {
                let r = deg.to_radians();
                let mu = r.tan() - acc / (cal.g * r.cos());
                values.insert(0, DerivedValue::si("mu", "1", mu, Some("mu")));
            }
            None => warnings.push(
                "the friction coefficient needs the incline's angle: pass --incline-deg".into(),
            ),
        }
        (values, warnings)
    }
    fn motion_hooks(&self) -> Option<&dyn MotionHooks> {
        Some(self)
    }
}

impl MotionHooks for ConstantAcceleration {
    /// A negative friction coefficient (the block slides faster than without friction), a
    /// fall upwards, or a g far from Earth's.
    fn implausible(&self, values: &[(&str, f64, f64)]) -> Vec<Implausible> {
        let mut out = Vec::new();
        for &(name, v, se) in values {
            match name {
                "mu" if v + 2.0 * se < 0.0 => out.push(Implausible {
                    forbidden: true,
                    detail: format!(
                        "mu = {} ± {} is negative: the block would slide faster than without \
                         friction; check --incline-deg, the reference values and the release \
                         (the report's recording.descent; --start/--end)",
                        approx(v),
                        approx(se)
                    ),
                }),
                "g" if v - 2.0 * se <= 0.0 => out.push(Implausible {
                    forbidden: true,
                    detail: format!(
                        "g = {} ± {} m/s^2 is not positive: the latent does not follow the fall; \
                         check the framing (--preview) and the reference values",
                        approx(v),
                        approx(se)
                    ),
                }),
                "g" if ((v / EARTH_G) - 1.0).abs() > G_TOLERANCE + 2.0 * se / EARTH_G => {
                    out.push(Implausible {
                        forbidden: false,
                        detail: format!(
                            "g = {} ± {} m/s^2 is far from Earth's 9.81: check the frame rate \
                             (--fps for slow motion), the reference values and the release \
                             (the report's recording.descent; --start/--end)",
                            approx(v),
                            approx(se)
                        ),
                    })
                }
                _ => {}
            }
        }
        out
    }
    fn data_warnings(&self, timed: bool) -> Vec<String> {
        if timed {
            Vec::new()
        } else {
            vec![UNTIMED.into()]
        }
    }
}

/// z'' = a (constant). Motion from rest makes the law alone degenerate: any latent
/// z = β·s + γ·√s + c is a parabola in time, so the encoder may bend the latent (γ ≠ 0,
/// z'' = 0 at the extreme) and the calibrated acceleration comes out wrong. Known start times
/// since the release pin it: the velocity at a clip's first frame is then a·t0, so the block
/// rolls out from one frame, z\[k\] = z0 + a·t0·k·dt + a·(k·dt)²/2, which only the latent affine
/// in s fits (times before the release, t0 + k·dt < 0, count as at rest; for a toss, `rising`,
/// they are its rise, the same parabola on the vertex's other side). Without start times
/// it rolls out from two frames, z\[k\] = z0 + k·(z1 − z0) + a·dt²·k(k−1)/2 (the paper's Euler
/// step gives the same sequence).
/// Parameter: acceleration a in latent units/s² (a/α in SI for z = α·s + c).
pub struct ConstantAccelerationBlock {
    /// a·dt², the change of velocity per frame (so one learning rate suits any dt).
    per_frame: Tensor,
    dt: f64,
    timed: bool,
    rising: bool,
}

impl ConstantAccelerationBlock {
    pub fn new(path: &nn::Path, init: &[f64], dt: f64, timed: bool) -> Self {
        ConstantAccelerationBlock {
            per_frame: path.var("accel_per_frame", &[], nn::Init::Const(init[0] * dt * dt)),
            dt,
            timed,
            rising: false,
        }
    }

    /// The block whose times before the release are a toss's rise (`rising`), not rest.
    pub fn rising(self, rising: bool) -> Self {
        ConstantAccelerationBlock { rising, ..self }
    }
}

impl PhysicsBlock for ConstantAccelerationBlock {
    fn order(&self) -> i64 {
        if self.timed {
            1
        } else {
            2
        }
    }
    fn rollout(&self, z: &Tensor, clips: Clips, steps: i64) -> Tensor {
        let k = frame_index(steps, z);
        let z0 = z.narrow(1, 0, 1);
        match clips.start.filter(|_| self.timed) {
            Some(t0) => {
                // From rest: frames before the release (t0 < 0, a recording's rest kept before
                // its descent) stay where they are; a toss's rise is the parabola's other side.
                let since = (t0 / self.dt).unsqueeze(1);
                let moved = if self.rising {
                    (&since + &k).square() - since.square()
                } else {
                    (&since + &k).clamp_min(0.0).square() - since.clamp_min(0.0).square()
                };
                &z0 + &self.per_frame * moved * 0.5
            }
            None => {
                let z1 = z.narrow(1, 1, 1);
                &z0 + (&z1 - &z0) * &k + &self.per_frame * (&k * (&k - 1.0) * 0.5)
            }
        }
    }
    fn values(&self, _latents: &Tensor) -> Vec<f64> {
        vec![self.per_frame.double_value(&[]) / (self.dt * self.dt)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timed_constant_acceleration_rolls_out_from_one_frame() {
        let vs = nn::VarStore::new(tch::Device::Cpu);
        let (a, dt) = (1.42, 1.0 / 30.0);
        let b = ConstantAccelerationBlock::new(&vs.root(), &[a], dt, true);
        assert_eq!(b.order(), 1);
        // s = a·t²/2 from the release; clips start 0.1 s and 0.5 s after it.
        let starts = [0.1, 0.5];
        let z: Vec<f32> = starts
            .iter()
            .flat_map(|t0| (0..6).map(move |k| (a * (t0 + k as f64 * dt).powi(2) / 2.0) as f32))
            .collect();
        let z = Tensor::from_slice(&z).view([2, 6]);
        let t0 = Tensor::from_slice(&[0.1f32, 0.5]);
        let err = (b.rollout(
            &z,
            Clips {
                start: Some(&t0),
                ids: None,
            },
            6,
        ) - &z)
            .abs()
            .max()
            .double_value(&[]);
        assert!(err < 1e-6, "{err}");
        // The bent latent √s is linear in time: the untimed block fits it with a = 0, the
        // timed one cannot.
        let bent = z.sqrt();
        let flat = ConstantAccelerationBlock::new(&vs.root(), &[0.0], dt, false);
        let err = (flat.rollout(&bent, Clips::default(), 6) - &bent)
            .abs()
            .max()
            .double_value(&[]);
        assert!(err < 1e-6, "{err}");
        let timed_zero = ConstantAccelerationBlock::new(&vs.root(), &[0.0], dt, true);
        let err = (timed_zero.rollout(
            &bent,
            Clips {
                start: Some(&t0),
                ids: None,
            },
            6,
        ) - &bent)
            .abs()
            .max()
            .double_value(&[]);
        assert!(err > 1e-2, "{err}");
    }

    /// A clip across a toss's apex (from 0.1 s before it): the rising block rolls the
    /// parabola through the vertex, the block from rest holds it still until the release.
    #[test]
    fn a_toss_rises_to_its_vertex_on_the_same_parabola() {
        let vs = nn::VarStore::new(tch::Device::Cpu);
        let (a, dt, t0) = (9.8, 1.0 / 30.0, -0.1);
        let z: Vec<f32> = (0..8)
            .map(|k| (a * (t0 + k as f64 * dt).powi(2) / 2.0) as f32)
            .collect();
        let z = Tensor::from_slice(&z).view([1, 8]);
        let start = Tensor::from_slice(&[t0 as f32]);
        let clips = Clips {
            start: Some(&start),
            ids: None,
        };
        let off = |b: ConstantAccelerationBlock| {
            (b.rollout(&z, clips, 8) - &z).abs().max().double_value(&[])
        };
        let block = || ConstantAccelerationBlock::new(&vs.root(), &[a], dt, true);
        let err = off(block().rising(true));
        assert!(err < 1e-5, "{err}");
        assert!(off(block()) > 1e-2);
    }
}
