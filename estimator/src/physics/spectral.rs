//! A start for the physics parameters estimated from the frames themselves, before any
//! training: project the clips onto their leading principal components, fit a linear
//! second-order recurrence to those signals (dynamic mode decomposition with one delay), and
//! take the most persistent oscillating mode as the fundamental.
//!
//! A moving or growing object is not a linear function of z, so each component carries the
//! fundamental and its harmonics (2ω, 3ω, …); the recurrence separates them into modes, and the
//! one that decays slowest is the motion itself (a harmonic k·ω decays k times faster, and
//! spurious modes of the fit decay within a few frames). A start there keeps training away from the
//! harmonics (latents like |z| or z², at 2ω) that a start far off can lock onto.

use super::block::Integrator;
use crate::pca::{principal_directions, project};
use tch::{Device, Kind, Tensor};

/// Principal components fed to the recurrence.
const COMPONENTS: i64 = 16;

/// (γ0, γ1) for `integrator` from standardised training clips [N, T, D], or `None` when no
/// persistent oscillating mode is found.
pub fn spectral_start(train: &Tensor, dt: f64, integrator: Integrator) -> Option<Vec<f64>> {
    tch::no_grad(|| spectral_mode(train, dt)).and_then(|(modulus, angle)| {
        // The two-step coefficients of the mode: a = 2|λ|cos θ, b = −|λ|².
        let (a, b) = (2.0 * modulus * angle.cos(), -modulus * modulus);
        let g = match integrator {
            Integrator::Exact => {
                let g1 = -2.0 * modulus.ln() / dt;
                let wd = angle / dt;
                vec![wd * wd + g1 * g1 / 4.0, g1]
            }
            Integrator::Euler => {
                // a = 2 − dt·γ1 − dt²·γ0, b = dt·γ1 − 1.
                let g1 = (1.0 + b) / dt;
                vec![(2.0 - a - dt * g1) / (dt * dt), g1]
            }
        };
        (g[0] > 0.0 && g.iter().all(|x| x.is_finite())).then_some(g)
    })
}

/// (|λ|, arg λ) of the oscillating mode with the largest modulus (the slowest decay).
fn spectral_mode(train: &Tensor, dt: f64) -> Option<(f64, f64)> {
    let (n, t, d) = train.size3().ok()?;
    if t < 4 {
        return None;
    }
    let frames = train.reshape([n * t, d]);
    let (v, _) = principal_directions(&frames, COMPONENTS)?;
    let k = v.size()[1];
    let y = project(&frames, &v).view([n, t, k]);
    // Regress y[t+1] on [y[t], y[t−1], 1] over every window of every clip.
    let next = y.narrow(1, 2, t - 2).reshape([-1, k]);
    let now = y.narrow(1, 1, t - 2).reshape([-1, k]);
    let prev = y.narrow(1, 0, t - 2).reshape([-1, k]);
    let ones = Tensor::ones([next.size()[0], 1], (Kind::Double, y.device()));
    let x = Tensor::cat(&[&now, &prev, &ones], 1);
    let ridge = Tensor::eye(2 * k + 1, (Kind::Double, y.device())) * 1e-9;
    let coef = Tensor::linalg_solve(&(x.tr().matmul(&x) + ridge), &x.tr().matmul(&next), true);
    // Companion matrix [[A1, A2], [I, 0]] with y[t+1] = A1·y[t] + A2·y[t−1].
    let a1 = coef.narrow(0, 0, k).tr();
    let a2 = coef.narrow(0, k, k).tr();
    let top = Tensor::cat(&[a1, a2], 1);
    let bottom = Tensor::cat(
        &[
            Tensor::eye(k, (Kind::Double, y.device())),
            Tensor::zeros([k, k], (Kind::Double, y.device())),
        ],
        1,
    );
    let companion = Tensor::cat(&[top, bottom], 0).to_device(Device::Cpu);
    let eig = companion.linalg_eigvals().view_as_real().contiguous();
    let parts = Vec::<f64>::try_from(&eig.view([-1])).ok()?;
    parts
        .chunks(2)
        .map(|c| (c[0].hypot(c[1]), c[1].atan2(c[0]).abs()))
        .filter(|&(m, ang)| ang > 1e-3 && ang < std::f64::consts::PI - 1e-3 && m < 1.5)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .filter(|_| dt > 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use physvid_shared::DampedOscillator;

    #[test]
    fn recovers_the_frequency_of_a_pattern_modulated_by_z() {
        // Frames = pattern · z(t) + noise-free background: the first component is exact.
        let o = DampedOscillator::PAPER;
        let (n, t, d) = (40usize, 20usize, 30usize);
        let pattern: Vec<f32> = (0..d).map(|i| (i as f32 * 0.37).sin()).collect();
        let mut data = Vec::with_capacity(n * t * d);
        for k in 0..n {
            for s in 0..t {
                let z = o.latent(0.5 + k as f64 / 80.0, k as f64 * 0.7, s as f64 * 0.2) as f32;
                data.extend(pattern.iter().map(|p| 1.0 + p * z));
            }
        }
        let x = Tensor::from_slice(&data).view([n as i64, t as i64, d as i64]);
        let g = spectral_start(&x, 0.2, Integrator::Exact).unwrap();
        assert!(
            (g[0] - 4.0016).abs() < 1e-3 && (g[1] - 0.08).abs() < 1e-3,
            "{g:?}"
        );
        let e = spectral_start(&x, 0.2, Integrator::Euler).unwrap();
        assert!((e[0] - 3.917).abs() < 0.01, "{e:?}");
    }
}
