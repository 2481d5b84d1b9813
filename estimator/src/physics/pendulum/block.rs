//! `PendulumBlock`: the pendulum's law as an `OdeSystem` (`PendulumSystem`) on the shooting
//! machinery, with the angle read from the latent as θ = (z − c)/s, RK4 sub-steps of at most
//! 50 ms, the final solve on the held encoder, and the paper's Euler step for comparison.

use crate::physics::block::{BlockOptions, Clips, Integrator, PhysicsBlock};
use crate::physics::ode::{ObservationMap, OdeSystem, ShootingBlock};
use tch::nn;
use tch::Tensor;

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
            &super::INFO.law.parameters[..2],
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
            rising: false,
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
            rising: false,
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
