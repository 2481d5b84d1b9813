//! The two-step recurrence z[t+1] = a·z[t] + b·z[t−1] of the linear second-order blocks: its
//! impulse responses in closed form, and the clip's least-squares initial state. Everything
//! stays on the device (no host sync).

use tch::{Kind, Tensor};

/// Beyond this |cos θ| the closed form is ill-conditioned (near-double roots) and the
/// recurrence is unrolled instead.
const CLOSED_FORM_LIMIT: f64 = 1.0 - 1e-3;

/// Below this |cos θ| (and with b < 0) the roots are safely complex: parameters cannot move
/// from here past [`CLOSED_FORM_LIMIT`] within an epoch, so the closed form alone is taken.
const SAFELY_COMPLEX: f64 = 1.0 - 1e-2;

/// Whether (a, b) are safely in the oscillating regime (read on the host, once per epoch).
pub fn safely_complex(a: f64, b: f64) -> bool {
    b < 0.0 && (a / (2.0 * (-b).sqrt())).abs() < SAFELY_COMPLEX
}

/// The responses p, q [steps] of z[t+1] = a·z[t] + b·z[t−1] to (z0, z1) = (1, 0) and (0, 1).
/// With ρ = √(−b) and cos θ = a/(2ρ) they have the closed forms
/// q[t] = ρ^(t−1)·sin(tθ)/sin θ and p[t] = −ρ^t·sin((t−1)θ)/sin θ when the roots are complex
/// (the oscillating case): a few tensor operations instead of a loop. For real or nearly double
/// roots (sin θ → 0) the unrolled recurrence is taken. Both are computed and one is selected on
/// the device, with the closed form's inputs clamped into its domain so that the branch not
/// taken never feeds a NaN into the gradient. With `complex_only` (see [`safely_complex`]) the
/// selection is skipped: the result is the same, at a third of the cost.
pub fn impulse_responses(
    a: &Tensor,
    b: &Tensor,
    steps: i64,
    device: tch::Device,
    complex_only: bool,
) -> (Tensor, Tensor) {
    let opts = (Kind::Float, device);
    let t = Tensor::arange(steps, opts);
    let rho = (-b).clamp_min(1e-30).sqrt();
    let c_raw = a / (&rho * 2.0);
    let closed = b.lt(0.0).logical_and(&c_raw.abs().lt(CLOSED_FORM_LIMIT));
    let c = c_raw.clamp(-CLOSED_FORM_LIMIT, CLOSED_FORM_LIMIT);
    let log_rho = rho.log();
    let theta = c.acos();
    let (s_t, s_tm1, s_1) = (
        (&t * &theta).sin(),
        ((&t - 1.0) * &theta).sin(),
        theta.sin(),
    );
    let q_closed = ((&t - 1.0) * &log_rho).exp() * s_t / &s_1;
    let p_closed = -(&t * &log_rho).exp() * s_tm1 / &s_1;
    if complex_only {
        return (p_closed, q_closed);
    }
    let (p_rec, q_rec) = unrolled(a, b, steps, device);
    (
        p_closed.where_self(&closed, &p_rec),
        q_closed.where_self(&closed, &q_rec),
    )
}

/// The impulse responses by unrolling the recurrence.
fn unrolled(a: &Tensor, b: &Tensor, steps: i64, device: tch::Device) -> (Tensor, Tensor) {
    let opts = (Kind::Float, device);
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

/// The initial state (z0, z1) [B] whose rollout z0·p + z1·q fits each clip of `z` [B, T] best in
/// least squares (2×2 normal equations in closed form; differentiable in p, q and z). The
/// determinant (≥ 0 by Cauchy–Schwarz) is clamped away from zero, as the pendulum's is.
pub fn least_squares_start(z: &Tensor, p: &Tensor, q: &Tensor) -> (Tensor, Tensor) {
    let (pp, qq, pq) = (
        (p * p).sum(Kind::Float),
        (q * q).sum(Kind::Float),
        (p * q).sum(Kind::Float),
    );
    let zp = z.matmul(p);
    let zq = z.matmul(q);
    let det = (&pp * &qq - &pq * &pq).clamp_min(1e-12);
    let z0 = (&zp * &qq - &zq * &pq) / &det;
    let z1 = (&zq * &pp - &zp * &pq) / &det;
    (z0, z1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_form_impulse_responses_match_the_recurrence() {
        // Complex roots, real positive roots, real negative roots, b ≥ 0.
        for (a, b) in [
            (1.8f64, -0.95f64),
            (1.5, -0.5),
            (-1.5, -0.5),
            (0.3, -0.9),
            (0.5, 0.2),
        ] {
            let (p, q) = impulse_responses(
                &Tensor::from(a as f32),
                &Tensor::from(b as f32),
                12,
                tch::Device::Cpu,
                false,
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
    fn gradients_are_finite_on_both_branches() {
        for (a, b) in [(1.8f32, -0.95f32), (1.5, -0.5), (2.0, -1.0)] {
            let a = Tensor::from(a).set_requires_grad(true);
            let b = Tensor::from(b).set_requires_grad(true);
            let (p, q) = impulse_responses(&a, &b, 10, tch::Device::Cpu, false);
            (p.sum(Kind::Float) + q.sum(Kind::Float)).backward();
            assert!(a.grad().double_value(&[]).is_finite());
            assert!(b.grad().double_value(&[]).is_finite());
        }
    }
}
