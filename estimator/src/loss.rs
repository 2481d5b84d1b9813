//! Loss terms: the rollout MSE and `KlToStandardNormal`, which keeps the latent from collapsing.

use tch::{Kind, Tensor};

/// Which loss to train with (appendix Table 3 ablates the KL term).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, serde::Serialize)]
pub enum LossKind {
    /// MSE(encoded, rolled out) + KL(N(μ, σ²) ‖ N(0, 1)), weight 1 : 1 (the paper's).
    #[value(name = "mse+kl")]
    #[serde(rename = "mse+kl")]
    MseKl,
    /// MSE only: the latent collapses to a constant (the ablation).
    #[value(name = "mse")]
    #[serde(rename = "mse")]
    Mse,
}

/// KL(N(μ, σ²) ‖ N(0, 1)) = ½(σ² + μ² − 1 − ln σ²), with μ and σ² the mean and (biased)
/// variance of all latents of the batch over batch × time.
pub struct KlToStandardNormal;

impl KlToStandardNormal {
    pub fn of(z: &Tensor) -> Tensor {
        let mu = z.mean(Kind::Float);
        let var = z.var(false) + 1e-8;
        (&var + mu.square() - 1.0 - var.log()) * 0.5
    }
}

/// Loss of encoded latents `z` [B, T] against their rollout `z_hat` [B, T]; returns (total, mse).
pub fn loss(kind: LossKind, z: &Tensor, z_hat: &Tensor) -> (Tensor, Tensor) {
    let mse = z.mse_loss(z_hat, tch::Reduction::Mean);
    let total = match kind {
        LossKind::MseKl => &mse + KlToStandardNormal::of(z),
        LossKind::Mse => mse.shallow_clone(),
    };
    (total, mse)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kl_is_zero_for_standard_latents_and_positive_otherwise() {
        let z = Tensor::from_slice(&[-1.0f32, 1.0, -1.0, 1.0]).view([2, 2]);
        assert!(KlToStandardNormal::of(&z).double_value(&[]).abs() < 1e-6);
        let z = Tensor::from_slice(&[0.0f32, 0.01, 0.0, 0.01]).view([2, 2]);
        assert!(KlToStandardNormal::of(&z).double_value(&[]) > 1.0);
    }
}
