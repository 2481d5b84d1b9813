//! The pendulum θ'' = −(g/L)·sin θ − ζ·θ' (Delfys75): the model and `PendulumBlock`, with the
//! angle read from the latent as θ = (z − c)/s. The KL term holds the latent's spread at 1,
//! which must not fix the angle's amplitude (the paper's block takes z as θ and finds L about
//! 20 % short on real swings); at finite amplitude L depends on s. Given reference frames of
//! known angle, s and c are fitted to them before every step; otherwise they are learned
//! (weakly pinned). The rollout is the RK4 trajectory (sub-steps ≤ 50 ms) through the initial
//! state that best fits the whole clip: a velocity from two encoded frames multiplies encoder
//! errors about five-fold over a period, and the fit buys them down with too much damping.

use super::block::{BlockOptions, Clips, Integrator, PhysicsBlock};
use super::model::{Derived, Model, ModelInfo, ParamSpec, TruthKey};
use super::ode::{ObservationMap, OdeSystem, ShootingBlock};
use crate::calibration::{Calibration, DerivedValue, Readings};
use crate::peaks::{self, PeakDecay};
use crate::spectral::spectral_start;
use tch::nn;
use tch::Tensor;

/// The pendulum of Delfys75 (appendix A.6).
pub struct Pendulum;

/// The calibrated answers need the latent affine to a few parts in 10⁴: patience 30.
const INFO: ModelInfo = ModelInfo {
    calibrates_in_training: true,
    calibration_flags: &["--reference", "--g"],
    truth: &[TruthKey::positive("length"), TruthKey::signed("damping")],
    max_dt: (
        10.0,
        "a pendulum of 100 m swings once in 20 s: frames further apart than half a swing cannot follow it",
    ),
    ..ModelInfo::new(
        "pendulum",
        "θ'' = −(g/L)·sin θ − ζ·θ', θ = (z − c)/s (g_over_l, damping, angle_scale, angle_offset)",
        &[
            ParamSpec::new("g_over_l", 10.0, true),
            ParamSpec::new("damping", 0.1, true),
            ParamSpec::map("angle_scale", 10.0, true),
            ParamSpec::map("angle_offset", 0.0, false),
        ],
        (20, 0.1),
    )
};

impl Model for Pendulum {
    fn info(&self) -> &ModelInfo {
        &INFO
    }
    fn build(&self, path: &nn::Path, init: &[f64], opts: BlockOptions) -> Box<dyn PhysicsBlock> {
        Box::new(PendulumBlock::new(path, init, opts))
    }
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
    /// The small-angle frequency √(g/L), the fastest it swings.
    /// Half the frequency: g/L/4, the damping halved, the map kept.
    fn subharmonic(&self, params: &[f64]) -> Option<Vec<f64>> {
        let mut p = params.to_vec();
        p[0] /= 4.0;
        p[1] /= 2.0;
        Some(p)
    }
    fn oscillates(&self, _params: &[f64]) -> bool {
        true
    }
    fn rate(&self, params: &[f64]) -> Option<f64> {
        Some(params[0].max(0.0).sqrt())
    }
    /// The damping from the decay of the swing peaks (appendix A.6's procedure), around the
    /// angle offset.
    fn cross_check(&self, params: &[f64], latents: &[f64], dt: f64) -> Option<PeakDecay> {
        peaks::cross_check("damping", params[1], latents, dt, params[3])
    }
    /// One and a half swings at the start's g/L, at least four frames.
    fn first_horizon(&self, init: &[f64], dt: f64) -> Option<usize> {
        let frames_per_swing = std::f64::consts::TAU / (init[0].sqrt() * dt);
        Some((1.5 * frames_per_swing).ceil().max(4.0) as usize)
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
}

/// Longest RK4 sub-step (s): at ω ≤ 5 rad/s its relative phase error is below 1e-4.
const MAX_SUBSTEP: f64 = 0.05;
/// Levenberg–Marquardt iterations of the final refinement of g/L and ζ.
const REFINE_ITERATIONS: usize = 10;
/// Most RK4 sub-steps per frame (a dt of 50 s).
const MAX_SUBSTEPS: usize = 1000;

/// θ' = ω, ω' = −(g/L)·sin θ − ζ·ω, with parameters (g/L, ζ).
pub struct PendulumSystem;

impl OdeSystem for PendulumSystem {
    fn states(&self) -> usize {
        2
    }
    fn params(&self) -> usize {
        2
    }
    fn eval(
        &self,
        x: &[f64],
        p: &[f64],
        _t: f64,
        f: &mut [f64],
        jac: Option<(&mut [f64], &mut [f64])>,
    ) {
        let (sin, cos) = x[0].sin_cos();
        f[0] = x[1];
        f[1] = -p[0] * sin - p[1] * x[1];
        if let Some((jx, jp)) = jac {
            jx.copy_from_slice(&[0.0, 1.0, -p[0] * cos, -p[1]]);
            jp.copy_from_slice(&[0.0, 0.0, -sin, -x[1]]);
        }
    }
    /// θ0 from the first frame, ω0 from the first three (second-order one-sided difference).
    fn guess(&self, obs: &[f64], _observed: &[usize], dt: f64) -> Vec<f64> {
        let omega = if obs.len() >= 3 {
            (-3.0 * obs[0] + 4.0 * obs[1] - obs[2]) / (2.0 * dt)
        } else {
            (obs[1] - obs[0]) / dt
        };
        vec![obs[0], omega]
    }
}

/// The pendulum's block: RK4 shooting (`ode::ShootingBlock`) for the exact integrator, the
/// paper's Euler step from the first two frames otherwise, both reading θ = (z − c)/s.
pub struct PendulumBlock {
    shooting: ShootingBlock,
    integrator: Integrator,
    dt: f64,
}

impl PendulumBlock {
    /// `init` = [g/L, damping, angle scale s, angle offset c]; with `opts.calibrated`, s and c
    /// come from [`PhysicsBlock::calibrate`] instead of being learned.
    pub fn new(path: &nn::Path, init: &[f64], opts: BlockOptions) -> Self {
        let map = ObservationMap::new(&(path / "angle"), 1, init[2], init[3], opts.calibrated);
        let substeps = ((opts.dt / MAX_SUBSTEP).ceil() as usize).clamp(1, MAX_SUBSTEPS);
        let shooting = ShootingBlock::new(
            path,
            Box::new(PendulumSystem),
            &INFO.parameters[..2],
            &init[..2],
            map,
            vec![0],
            opts.dt,
            substeps,
        );
        PendulumBlock {
            shooting,
            integrator: opts.integrator,
            dt: opts.dt,
        }
    }

    /// The paper's step: θ[t+1] = θ[t] + Δ − dt·(ζ·Δ + dt·(g/L)·sin θ[t]), Δ = θ[t] − θ[t−1],
    /// from the first two frames, [B, T] in and out.
    fn euler(&self, theta: &Tensor, steps: i64) -> Tensor {
        let p = self.shooting.physical();
        let (w2, zeta) = (p.get(0), p.get(1));
        let mut out = vec![theta.select(1, 0), theta.select(1, 1)];
        for t in 2..steps as usize {
            let d = &out[t - 1] - &out[t - 2];
            let next = &out[t - 1] + &d - (&d * &zeta + out[t - 1].sin() * &w2 * self.dt) * self.dt;
            out.push(next);
        }
        out.truncate(steps as usize);
        Tensor::stack(&out, 1)
    }
}

impl PhysicsBlock for PendulumBlock {
    fn order(&self) -> i64 {
        2
    }

    fn rollout(&self, z: &Tensor, clips: Clips, steps: i64) -> Tensor {
        let theta = self
            .shooting
            .to_observed(&z.narrow(1, 0, steps).unsqueeze(-1));
        let out = match self.integrator {
            Integrator::Exact => self.shooting.observed_rollout(&theta, clips),
            Integrator::Euler => self.euler(&theta.squeeze_dim(-1), steps).unsqueeze(-1),
        };
        self.shooting.from_observed(&out).squeeze_dim(-1)
    }

    fn values(&self, _latents: &Tensor) -> Vec<f64> {
        self.shooting.values()
    }

    /// g/L and ζ solved on the training latents (exact integrator only).
    fn refine(&self, z: &Tensor, clips: Clips) -> bool {
        self.integrator == Integrator::Exact
            && self
                .shooting
                .refine(&z.unsqueeze(-1), clips, REFINE_ITERATIONS)
    }

    fn calibrate(&self, latents: &Tensor, values: &Tensor) {
        self.shooting.calibrate(latents, values);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::RolloutStart;
    use tch::Kind;

    #[test]
    fn rollout_matches_a_fine_reference_at_large_angles() {
        let vs = nn::VarStore::new(tch::Device::Cpu);
        let (w2, zeta, dt) = (9.81 / 0.45, 0.059, 0.1);
        let opts = BlockOptions {
            integrator: Integrator::Exact,
            dt,
            timed: false,
            calibrated: false,
            start: RolloutStart::Fit,
        };
        let b = PendulumBlock::new(&vs.root(), &[w2, zeta, 2.0, 0.3], opts);
        // Reference: gen's own trajectory (RK4, 64 sub-steps per frame) from a 60° release.
        let truth = generator::scenes::pendulum::pendulum_trajectory(
            w2,
            zeta,
            60f64.to_radians(),
            0.0,
            12,
            dt,
        );
        let z: Vec<f32> = truth.iter().map(|t| (2.0 * t + 0.3) as f32).collect();
        let zt = Tensor::from_slice(&z).view([1, 12]);
        let r = b.rollout(&zt, Clips::default(), 12);
        let err = (r - &zt).abs().max().double_value(&[]) / 2.0;
        assert!(err < 2e-3, "max angle error {err} rad");
    }

    #[test]
    fn gradients_match_finite_differences() {
        // Latents near (not on) a trajectory of the block's parameters, so the fit's correction
        // is exercised too (the surrogate is the first-order derivative: exact as the residual
        // vanishes).
        let (dt, steps) = (0.1, 15);
        let truth =
            generator::scenes::pendulum::pendulum_trajectory(10.0, 0.1, 0.8, 0.3, steps, dt);
        let z: Vec<f64> = truth
            .iter()
            .enumerate()
            .map(|(k, t)| 1.5 * t + 0.2 + 1e-3 * ((k * 7 % 5) as f64 - 2.0))
            .collect();
        let opts = BlockOptions {
            integrator: Integrator::Exact,
            dt,
            timed: false,
            calibrated: false,
            start: RolloutStart::Fit,
        };
        let loss = |init: &[f64], z: &[f64], grad: bool| {
            let vs = nn::VarStore::new(tch::Device::Cpu);
            let b = PendulumBlock::new(&vs.root(), init, opts);
            let zt = Tensor::from_slice(z)
                .to_kind(Kind::Float)
                .view([1, steps as i64]);
            let zt = if grad { zt.set_requires_grad(true) } else { zt };
            let w = Tensor::from_slice(
                &(0..steps)
                    .map(|k| (k as f32 * 0.37).sin())
                    .collect::<Vec<_>>(),
            );
            let l = (b.rollout(&zt, Clips::default(), steps as i64).squeeze() * w).sum(Kind::Float);
            if grad {
                l.backward();
                let mut g: Vec<f64> = vs
                    .variables()
                    .into_iter()
                    .collect::<std::collections::BTreeMap<_, _>>()
                    .into_values()
                    .map(|t| t.grad().double_value(&[]))
                    .collect();
                g.extend(
                    Vec::<f64>::try_from(&zt.grad().to_kind(Kind::Double).view([-1])).unwrap(),
                );
                (l.double_value(&[]), g)
            } else {
                (l.double_value(&[]), Vec::new())
            }
        };
        let init = [10.0, 0.1, 1.5, 0.2];
        let (_, g) = loss(&init, &z, true);
        // Variables sorted by name: angle.log_scale, angle.offset, log_damping, log_g_over_l.
        let eps = 1e-3;
        let log_moves: [(usize, usize); 4] = [(3, 0), (2, 1), (0, 2), (1, 3)];
        for (grad_index, param) in log_moves {
            let (mut a, mut b) = (init, init);
            if param == 3 {
                a[3] += eps;
                b[3] -= eps;
            } else {
                a[param] *= (eps).exp();
                b[param] *= (-eps).exp();
            }
            let fd = (loss(&a, &z, false).0 - loss(&b, &z, false).0) / (2.0 * eps);
            let an = g[grad_index];
            assert!(
                (fd - an).abs() < 1e-2 * (1.0 + an.abs()),
                "param {param}: fd {fd} vs {an}"
            );
        }
        for k in [0usize, 6, 14] {
            let (mut a, mut b) = (z.clone(), z.clone());
            a[k] += eps;
            b[k] -= eps;
            let fd = (loss(&init, &a, false).0 - loss(&init, &b, false).0) / (2.0 * eps);
            let an = g[4 + k];
            assert!(
                (fd - an).abs() < 1e-2 * (1.0 + an.abs()),
                "latent {k}: fd {fd} vs {an}"
            );
        }
    }
}
