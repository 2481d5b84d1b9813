//! Physics blocks with learnable parameters: `DampedOscillatorBlock` rolls the latent forward
//! with the exact two-step propagator of z'' + γ1 z' + γ0 z = 0, or the paper's Euler step.

use tch::nn;
use tch::{Kind, Tensor};

/// How the block advances the latent one frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Integrator {
    /// Exact propagator of the linear ODE: no discretisation bias at any dt.
    Exact,
    /// The paper's explicit Euler step with a backward-difference velocity (biased at large dt).
    Euler,
}

/// Where the oscillator's rollout starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RolloutStart {
    /// The state (z0, z1) whose rollout fits the whole clip in least squares: noise in the first
    /// two frames is not carried through the clip.
    Fit,
    /// The first two encoded frames (the paper's): pixel noise there biases the damping high.
    Frames,
}

/// The damped oscillator z'' + γ1·z' + γ0·z = 0 with learnable γ0 > 0 and γ1. γ0 is stored
/// as its logarithm so that Adam's steps are relative (one learning rate serves γ0 = 0.1 and
/// γ0 = 100 alike); γ1, which is small and may cross zero, is learned directly.
#[derive(Debug)]
pub struct DampedOscillatorBlock {
    log_gamma0: Tensor,
    gamma1: Tensor,
    integrator: Integrator,
    dt: f64,
    start: RolloutStart,
}

/// Parameter names in report order.
pub const OSCILLATOR_PARAMETERS: [&str; 2] = ["gamma0", "gamma1"];

impl DampedOscillatorBlock {
    /// Registers the parameters under `path`, starting at `init` = (γ0 > 0, γ1).
    pub fn new(
        path: &nn::Path,
        init: (f64, f64),
        integrator: Integrator,
        dt: f64,
        start: RolloutStart,
    ) -> Self {
        let log_gamma0 = path.var("log_gamma0", &[], nn::Init::Const(init.0.ln()));
        let gamma1 = path.var("gamma1", &[], nn::Init::Const(init.1));
        DampedOscillatorBlock {
            log_gamma0,
            gamma1,
            integrator,
            dt,
            start,
        }
    }

    /// Current (γ0, γ1).
    pub fn values(&self) -> [f64; 2] {
        [
            self.log_gamma0.double_value(&[]).exp(),
            self.gamma1.double_value(&[]),
        ]
    }

    /// The two-step coefficients (a, b) of z[t+1] = a·z[t] + b·z[t−1], differentiable in γ.
    pub fn coefficients(&self) -> (Tensor, Tensor) {
        let g0 = self.log_gamma0.exp();
        let g1 = &self.gamma1;
        let dt = self.dt;
        match self.integrator {
            Integrator::Euler => {
                // z[t+1] = z[t] + (z[t] − z[t−1]) − dt·(γ1·(z[t] − z[t−1]) + dt·γ0·z[t])
                let a = -(g1 * dt) - &g0 * (dt * dt) + 2.0;
                let b = g1 * dt - 1.0;
                (a, b)
            }
            Integrator::Exact => {
                // x = (γ0 − γ1²/4)·dt²; C = cos √x (under-damped), cosh √−x (over-damped),
                // with a series near critical damping where the square root's gradient blows up.
                let x = (&g0 - g1.square() * 0.25) * (dt * dt);
                let xv = x.double_value(&[]);
                let c = if xv > 1e-4 {
                    x.sqrt().cos()
                } else if xv < -1e-4 {
                    (-&x).sqrt().cosh()
                } else {
                    -&x * 0.5 + x.square() / 24.0 + 1.0
                };
                let a = (g1 * (-dt / 2.0)).exp() * c * 2.0;
                let b = -(g1 * (-dt)).exp();
                (a, b)
            }
        }
    }

    /// The ODE residual z'' + γ1·z' + γ0·z at the inner frames of `z` [B, T ≥ 3], [B, T − 2],
    /// with central differences z' ≈ (z[t+1] − z[t−1])/2dt and z'' ≈ (z[t+1] − 2z[t] + z[t−1])/dt²
    /// (the ICML 2026 peer's loss; independent of the integrator).
    pub fn residual(&self, z: &Tensor) -> Tensor {
        let t = z.size()[1];
        let (prev, mid, next) = (
            z.narrow(1, 0, t - 2),
            z.narrow(1, 1, t - 2),
            z.narrow(1, 2, t - 2),
        );
        let dt = self.dt;
        let d1 = (&next - &prev) / (2.0 * dt);
        let d2 = (&next - &mid * 2.0 + &prev) / (dt * dt);
        d2 + d1 * &self.gamma1 + mid * self.log_gamma0.exp()
    }

    /// Autoregressive rollout over `steps` frames of `z` [B, steps]: z_hat[t] = p[t]·z0 + q[t]·z1,
    /// where p and q are the block's impulse responses and (z0, z1) the first two latents or
    /// the least-squares start (see [`RolloutStart`]).
    pub fn rollout(&self, z: &Tensor, steps: i64) -> Tensor {
        let (a, b) = self.coefficients();
        let (p, q) = impulse_responses(&a, &b, steps, z.device());
        let (z0, z1) = if self.start == RolloutStart::Fit {
            least_squares_start(z, &p, &q)
        } else {
            (z.select(1, 0), z.select(1, 1))
        };
        z0.unsqueeze(1) * p.unsqueeze(0) + z1.unsqueeze(1) * q.unsqueeze(0)
    }
}

/// The initial state (z0, z1) [B] whose rollout z0·p + z1·q fits each clip of `z` [B, T] best in
/// least squares (2×2 normal equations in closed form; differentiable in p, q and z).
fn least_squares_start(z: &Tensor, p: &Tensor, q: &Tensor) -> (Tensor, Tensor) {
    let (pp, qq, pq) = (
        (p * p).sum(Kind::Float),
        (q * q).sum(Kind::Float),
        (p * q).sum(Kind::Float),
    );
    let zp = z.matmul(p);
    let zq = z.matmul(q);
    let det = &pp * &qq - &pq * &pq;
    let z0 = (&zp * &qq - &zq * &pq) / &det;
    let z1 = (&zq * &pp - &zp * &pq) / &det;
    (z0, z1)
}

/// The responses p, q [steps] of z[t+1] = a·z[t] + b·z[t−1] to (z0, z1) = (1, 0) and (0, 1).
/// With ρ = √(−b) and cos θ = a/(2ρ) they have the closed forms
/// q[t] = ρ^(t−1)·sin(tθ)/sin θ and p[t] = −ρ^t·sin((t−1)θ)/sin θ when the roots are complex
/// (the oscillating case): a few tensor operations instead of a loop. For real or nearly double
/// roots (sin θ → 0) the recurrence is unrolled instead.
fn impulse_responses(a: &Tensor, b: &Tensor, steps: i64, device: tch::Device) -> (Tensor, Tensor) {
    let opts = (Kind::Float, device);
    let (av, bv) = (a.double_value(&[]), b.double_value(&[]));
    let cos_theta = if bv < 0.0 {
        av / (2.0 * (-bv).sqrt())
    } else {
        f64::NAN
    };
    if cos_theta.abs() < 1.0 - 1e-3 {
        let t = Tensor::arange(steps, opts);
        let rho = (-b).sqrt();
        let c = a / (&rho * 2.0);
        let log_rho = rho.log();
        let theta = c.acos();
        let (s_t, s_tm1, s_1) = (
            (&t * &theta).sin(),
            ((&t - 1.0) * &theta).sin(),
            theta.sin(),
        );
        let q = ((&t - 1.0) * &log_rho).exp() * s_t / &s_1;
        let p = -(&t * &log_rho).exp() * s_tm1 / &s_1;
        return (p, q);
    }
    let (one, zero) = (Tensor::ones([], opts), Tensor::zeros([], opts));
    let mut p = vec![one.shallow_clone(), zero.shallow_clone()];
    let mut q = vec![zero, one];
    for t in 2..steps as usize {
        p.push(a * &p[t - 1] + b * &p[t - 2]);
        q.push(a * &q[t - 1] + b * &q[t - 2]);
    }
    p.truncate(steps as usize);
    q.truncate(steps as usize);
    (Tensor::stack(&p, 0), Tensor::stack(&q, 0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use physvid_shared::DampedOscillator;

    fn block(
        init: (f64, f64),
        integrator: Integrator,
        dt: f64,
    ) -> (nn::VarStore, DampedOscillatorBlock) {
        let vs = nn::VarStore::new(tch::Device::Cpu);
        let b = DampedOscillatorBlock::new(&vs.root(), init, integrator, dt, RolloutStart::Frames);
        (vs, b)
    }

    #[test]
    fn exact_rollout_reproduces_the_closed_form() {
        let o = DampedOscillator::PAPER;
        let dt = 0.2;
        let (_vs, b) = block((o.gamma0(), o.gamma1()), Integrator::Exact, dt);
        let truth: Vec<f32> = (0..20)
            .map(|k| o.latent(0.8, 0.4, k as f64 * dt) as f32)
            .collect();
        let z = Tensor::from_slice(&truth).view([1, 20]);
        let r = b.rollout(&z, 20);
        let err = (r - z).abs().max().double_value(&[]);
        assert!(err < 1e-5, "{err}");
    }

    #[test]
    fn closed_form_impulse_responses_match_the_recurrence() {
        // Complex roots, real positive roots, real negative roots.
        for (a, b) in [(1.8f64, -0.95f64), (1.5, -0.5), (-1.5, -0.5), (0.3, -0.9)] {
            let (p, q) = impulse_responses(
                &Tensor::from(a as f32),
                &Tensor::from(b as f32),
                12,
                tch::Device::Cpu,
            );
            let (mut pr, mut qr) = (vec![1.0, 0.0], vec![0.0, 1.0]);
            for t in 2..12 {
                pr.push(a * pr[t - 1] + b * pr[t - 2]);
                qr.push(a * qr[t - 1] + b * qr[t - 2]);
            }
            for t in 0..12 {
                let (pv, qv) = (p.double_value(&[t as i64]), q.double_value(&[t as i64]));
                assert!(
                    (pv - pr[t]).abs() < 1e-4 * (1.0 + pr[t].abs()),
                    "a {a} b {b} t {t}: p {pv} vs {}",
                    pr[t]
                );
                assert!(
                    (qv - qr[t]).abs() < 1e-4 * (1.0 + qr[t].abs()),
                    "a {a} b {b} t {t}: q {qv} vs {}",
                    qr[t]
                );
            }
        }
    }

    #[test]
    fn euler_coefficients_match_the_papers_step() {
        let (_vs, b) = block((4.0, 0.08), Integrator::Euler, 0.2);
        let (a, bb) = b.coefficients();
        assert!((a.double_value(&[]) - (2.0 - 0.2 * 0.08 - 0.04 * 4.0)).abs() < 1e-6);
        assert!((bb.double_value(&[]) - (0.2 * 0.08 - 1.0)).abs() < 1e-6);
    }

    #[test]
    fn gradients_are_finite_through_critical_damping() {
        for (g0, g1) in [(4.0, 4.0), (4.0, 4.0001), (3.0, 4.0), (1.0, 0.1)] {
            let (_vs, b) = block((g0, g1), Integrator::Exact, 0.2);
            let z = Tensor::from_slice(&[1.0f32, 0.9]).view([1, 2]);
            let r = b.rollout(&z, 10).sum(Kind::Float);
            r.backward();
            let g = b.log_gamma0.grad().double_value(&[]);
            assert!(g.is_finite(), "{g0} {g1}: {g}");
        }
        // Over-damped propagator is exact: z = e^(−t) + e^(−3t) solves z'' + 4z' + 3z = 0.
        let (_vs, b) = block((3.0, 4.0), Integrator::Exact, 0.1);
        let zt: Vec<f32> = (0..8)
            .map(|k| {
                let t = k as f64 * 0.1;
                ((-t).exp() + (-3.0 * t).exp()) as f32
            })
            .collect();
        let z = Tensor::from_slice(&zt).view([1, 8]);
        let err = (b.rollout(&z, 8) - &z).abs().max().double_value(&[]);
        assert!(err < 1e-5, "{err}");
    }
}
