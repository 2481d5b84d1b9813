//! The pendulum θ'' = −(g/L)·sin θ − ζ·θ' (Delfys75): the model and `PendulumBlock`, with the
//! angle read from the latent as θ = (z − c)/s. The KL term holds the latent's spread at 1,
//! which must not fix the angle's amplitude (the paper's block takes z as θ and finds L about
//! 20 % short on real swings); at finite amplitude L depends on s. Given reference frames of
//! known angle, s and c are fitted to them before every step; otherwise they are learned
//! (weakly pinned). The rollout is the RK4 trajectory (sub-steps ≤ 50 ms) through the initial
//! state that best fits the whole clip: a velocity from two encoded frames multiplies encoder
//! errors about five-fold over a period, and the fit buys them down with too much damping.

use super::block::{BlockOptions, Integrator, PhysicsBlock};
use super::model::{Derived, Model, ModelInfo, ParamSpec};
use crate::calibration::{Calibration, DerivedValue};
use crate::spectral::spectral_start;
use tch::nn;
use tch::{Kind, Tensor};

/// The pendulum of Delfys75 (appendix A.6).
pub struct Pendulum;

/// The calibrated answers need the latent affine to a few parts in 10⁴: patience 30.
const INFO: ModelInfo = ModelInfo {
    calibrates_in_training: true,
    ..ModelInfo::new(
        "pendulum",
        "θ'' = −(g/L)·sin θ − ζ·θ', θ = (z − c)/s (g_over_l, damping, angle_scale, angle_offset)",
        &[
            ParamSpec::new("g_over_l", 10.0, true),
            ParamSpec::new("damping", 0.1, false),
            ParamSpec::new("angle_scale", 10.0, true),
            ParamSpec::new("angle_offset", 0.0, false),
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
        let damping = g[1].max(0.0);
        vec![
            vec![g[0], damping, init[2], init[3]],
            vec![g[0] / 4.0, damping / 2.0, init[2], init[3]],
        ]
    }
    fn derive(&self, params: &[f64], cal: &Calibration, _reference: &[f64]) -> Derived {
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
            DerivedValue::si("length", cal.g / params[0], Some("length")),
            DerivedValue::si("damping", params[1], Some("damping")),
            DerivedValue::si("g_over_l", params[0], None),
            DerivedValue::latent("angle_scale", params[2]),
            DerivedValue::latent("angle_offset", params[3]),
        ];
        (values, warnings)
    }
}

/// Longest RK4 sub-step (s): at ω ≤ 5 rad/s its relative phase error is below 1e-4.
const MAX_SUBSTEP: f64 = 0.05;
const NEWTON_STEPS: usize = 3;
const GAUSS_NEWTON_STEPS: usize = 2;

pub struct PendulumBlock {
    log_w2: Tensor,
    damping: Tensor,
    /// The angle's scale s: learned (as its logarithm's exponential) or calibrated (a buffer).
    angle: AngleMap,
    offset: Tensor,
    integrator: Integrator,
    dt: f64,
    substeps: usize,
}

impl PendulumBlock {
    /// `init` = [g/L, damping, angle scale s, angle offset c]; with `opts.calibrated`, s and c
    /// come from [`PhysicsBlock::calibrate`] instead of being learned.
    pub fn new(path: &nn::Path, init: &[f64], opts: BlockOptions) -> Self {
        let BlockOptions { integrator, dt, .. } = opts;
        let (angle, offset) = if opts.calibrated {
            let buffer = |name: &str, v: f64| {
                let mut t = path.zeros_no_train(name, &[]);
                let _ = tch::no_grad(|| t.fill_(v));
                t
            };
            (
                AngleMap::Calibrated(buffer("angle_scale", init[2])),
                buffer("angle_offset", init[3]),
            )
        } else {
            (
                AngleMap::Learned(path.var("log_angle_scale", &[], nn::Init::Const(init[2].ln()))),
                path.var("angle_offset", &[], nn::Init::Const(init[3])),
            )
        };
        PendulumBlock {
            log_w2: path.var("log_g_over_l", &[], nn::Init::Const(init[0].ln())),
            damping: path.var("damping", &[], nn::Init::Const(init[1])),
            angle,
            offset,
            integrator,
            dt,
            substeps: (dt / MAX_SUBSTEP).ceil().max(1.0) as usize,
        }
    }

    /// One frame of RK4 from (θ, ω) [B] each.
    fn step(&self, th: &Tensor, om: &Tensor, w2: &Tensor, zeta: &Tensor) -> (Tensor, Tensor) {
        let h = self.dt / self.substeps as f64;
        let f = |t: &Tensor, o: &Tensor| (o.shallow_clone(), -(t.sin() * w2) - o * zeta);
        let (mut th, mut om) = (th.shallow_clone(), om.shallow_clone());
        for _ in 0..self.substeps {
            let (a1, b1) = f(&th, &om);
            let (a2, b2) = f(&(&th + &a1 * (h / 2.0)), &(&om + &b1 * (h / 2.0)));
            let (a3, b3) = f(&(&th + &a2 * (h / 2.0)), &(&om + &b2 * (h / 2.0)));
            let (a4, b4) = f(&(&th + &a3 * h), &(&om + &b3 * h));
            th = &th + (a1 + a2 * 2.0 + a3 * 2.0 + a4) * (h / 6.0);
            om = &om + (b1 + b2 * 2.0 + b3 * 2.0 + b4) * (h / 6.0);
        }
        (th, om)
    }

    /// θ at frames 0..steps from (θ0, ω0) [B]: [B, steps].
    fn trajectory(
        &self,
        th0: &Tensor,
        om0: &Tensor,
        w2: &Tensor,
        zeta: &Tensor,
        steps: i64,
    ) -> Tensor {
        let mut out = vec![th0.shallow_clone()];
        let (mut th, mut om) = (th0.shallow_clone(), om0.shallow_clone());
        for _ in 1..steps {
            (th, om) = self.step(&th, &om, w2, zeta);
            out.push(th.shallow_clone());
        }
        Tensor::stack(&out, 1)
    }

    /// The initial state (θ0, ω0) [B] whose trajectory best fits `theta` [B, T] (least squares
    /// over every frame), and the trajectory's sensitivities to it [B, T] each, all without
    /// autograd: Newton shooting through the first two frames, then Gauss–Newton.
    fn fit_initial_state(&self, theta: &Tensor, w2: &Tensor, zeta: &Tensor) -> [Tensor; 4] {
        tch::no_grad(|| {
            let steps = theta.size()[1];
            let (w2, zeta) = (w2.detach(), zeta.detach());
            let theta = theta.detach();
            let (th0, th1) = (theta.select(1, 0), theta.select(1, 1));
            let delta = 1e-3;
            let mut om = (&th1 - &th0) / self.dt;
            for _ in 0..NEWTON_STEPS {
                let (a, _) = self.step(&th0, &om, &w2, &zeta);
                let (b, _) = self.step(&th0, &(&om + delta), &w2, &zeta);
                let slope = ((&b - &a) / delta).clamp_min(1e-3 * self.dt);
                om = &om - (a - &th1) / slope;
            }
            let mut th = th0;
            let b = th.size()[0];
            let (mut j0, mut j1) = (Tensor::zeros_like(&theta), Tensor::zeros_like(&theta));
            for _ in 0..GAUSS_NEWTON_STEPS {
                // The base trajectory and the two perturbed ones in one batch.
                let all = self.trajectory(
                    &Tensor::cat(&[&th, &(&th + delta), &th], 0),
                    &Tensor::cat(&[&om, &om, &(&om + delta)], 0),
                    &w2,
                    &zeta,
                    steps,
                );
                let base = all.narrow(0, 0, b);
                j0 = (all.narrow(0, b, b) - &base) / delta;
                j1 = (all.narrow(0, 2 * b, b) - &base) / delta;
                let (d_th, d_om) = gauss_newton_step(&j0, &j1, &(base - &theta));
                th = &th + d_th;
                om = &om + d_om;
            }
            [th, om, j0, j1]
        })
    }
}

/// How the block reads the angle's scale.
enum AngleMap {
    /// log s, trained with the other parameters.
    Learned(Tensor),
    /// s (signed), fitted to reference frames.
    Calibrated(Tensor),
}

impl AngleMap {
    fn scale(&self) -> Tensor {
        match self {
            AngleMap::Learned(log_s) => log_s.exp(),
            AngleMap::Calibrated(s) => s.shallow_clone(),
        }
    }
}

/// The Gauss–Newton step (Δθ0, Δω0) [B] that best cancels the residual r [B, T] given the
/// trajectory's sensitivities j0 = ∂θ/∂θ0 and j1 = ∂θ/∂ω0 [B, T].
fn gauss_newton_step(j0: &Tensor, j1: &Tensor, r: &Tensor) -> (Tensor, Tensor) {
    let dot = |a: &Tensor, b: &Tensor| (a * b).sum_dim_intlist(1, false, Kind::Float);
    let (a, b, c) = (dot(j0, j0), dot(j0, j1), dot(j1, j1));
    let (g0, g1) = (dot(j0, r), dot(j1, r));
    let det = (&a * &c - &b * &b).clamp_min(1e-12);
    let d_th = -(&c * &g0 - &b * &g1) / &det;
    let d_om = -(&a * &g1 - &b * &g0) / det;
    (d_th, d_om)
}

impl PhysicsBlock for PendulumBlock {
    fn order(&self) -> i64 {
        2
    }

    fn rollout(&self, z: &Tensor, _start: Option<&Tensor>, steps: i64) -> Tensor {
        let scale = self.angle.scale();
        let w2 = self.log_w2.exp();
        let theta = (z.narrow(1, 0, steps) - &self.offset) / &scale;
        let out = match self.integrator {
            Integrator::Exact => {
                // The trajectory through the best-fitting initial state: fitted without
                // autograd, then one differentiable Gauss–Newton step from it, taken to first
                // order (θ + j0·Δθ0 + j1·Δω0), which carries the exact first-order gradient
                // (implicit function theorem) for one differentiable trajectory.
                let [th0, om0, j0, j1] = self.fit_initial_state(&theta, &w2, &self.damping);
                let base = self.trajectory(&th0, &om0, &w2, &self.damping, steps);
                let (d_th, d_om) = gauss_newton_step(&j0, &j1, &(&base - &theta));
                base + j0 * d_th.unsqueeze(1) + j1 * d_om.unsqueeze(1)
            }
            Integrator::Euler => {
                // The paper's step: θ[t+1] = θ[t] + Δ − dt·(ζ·Δ + dt·(g/L)·sin θ[t]), Δ = θ[t] − θ[t−1].
                let mut out = vec![theta.select(1, 0), theta.select(1, 1)];
                for t in 2..steps as usize {
                    let d = &out[t - 1] - &out[t - 2];
                    let next = &out[t - 1] + &d
                        - (&d * &self.damping + out[t - 1].sin() * &w2 * self.dt) * self.dt;
                    out.push(next);
                }
                out.truncate(steps as usize);
                Tensor::stack(&out, 1)
            }
        };
        out * scale + &self.offset
    }

    fn values(&self, _latents: &Tensor) -> Vec<f64> {
        vec![
            self.log_w2.double_value(&[]).exp(),
            self.damping.double_value(&[]),
            self.angle.scale().double_value(&[]),
            self.offset.double_value(&[]),
        ]
    }

    fn calibrate(&self, latents: &Tensor, values: &Tensor) {
        let AngleMap::Calibrated(scale) = &self.angle else {
            return;
        };
        // z = s·θ + c by least squares over the reference frames.
        tch::no_grad(|| {
            let (z, th) = (latents.detach().view([-1]), values.view([-1]));
            let (zm, tm) = (z.mean(Kind::Float), th.mean(Kind::Float));
            let s = ((&z - &zm) * (&th - &tm)).sum(Kind::Float)
                / (&th - &tm).square().sum(Kind::Float).clamp_min(1e-12);
            let s = s.sign() * s.abs().clamp_min(1e-6);
            let c = zm - &s * tm;
            scale.shallow_clone().copy_(&s);
            self.offset.shallow_clone().copy_(&c);
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rollout_matches_a_fine_reference_at_large_angles() {
        let vs = nn::VarStore::new(tch::Device::Cpu);
        let (w2, zeta, dt) = (9.81 / 0.45, 0.059, 0.1);
        let opts = BlockOptions {
            integrator: Integrator::Exact,
            dt,
            timed: false,
            calibrated: false,
            start: super::super::block::RolloutStart::Fit,
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
        let r = b.rollout(&zt, None, 12);
        let err = (r - &zt).abs().max().double_value(&[]) / 2.0;
        assert!(err < 2e-3, "max angle error {err} rad");
    }
}
