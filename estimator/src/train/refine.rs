//! The final refinement of the physical parameters with the kept encoder held: on the training
//! clips, then, for a recording, on long windows of its encoded timeline (`windows.rs`), where
//! a light damping shows (appendix A.6's peak fit reads the same signal).

use crate::config::RunConfig;
use crate::data::ClipData;
use crate::loss::LossKind;
use crate::network::Network;
use crate::physics::Clips;
use crate::timeline::encode_recording;
use crate::windows::Windows;
use tch::Tensor;

/// The network's state held and refined: the recording's latent of every frame (for a
/// recording) and the validation clips' latents and rollouts.
pub struct Held {
    pub recording_latents: Option<Vec<f32>>,
    pub z: Tensor,
    pub z_hat: Tensor,
}

/// Holds the encoder in its present state: encodes the recording, refines the block's
/// parameters (the MSE+KL loss only: the refinement solves the rollout's fit with a latent the
/// KL term keeps spread, not the residual loss's objective, nor the MSE-only ablation's, whose
/// latent collapses), and rolls the validation clips out.
pub fn held(network: &Network, cfg: &RunConfig, data: &ClipData) -> Held {
    let recording_latents = data
        .recording
        .as_ref()
        .map(|(_, frames)| encode_recording(network, frames));
    if cfg.loss == LossKind::MseKl {
        refine(network, data, recording_latents.as_deref());
    }
    let val_ids: Vec<usize> = (data.n_train() as usize..data.shape[0]).collect();
    let clips = Clips {
        start: data.val_start.as_ref(),
        ids: Some(&val_ids),
    };
    let (z, z_hat) = tch::no_grad(|| network.forward(&data.val, clips, data.frames_per_clip));
    Held {
        recording_latents,
        z,
        z_hat,
    }
}

/// Refines the block's parameters on the training clips, then, given the latent of every
/// frame of a recording (`encode_recording`), on its windows.
pub fn refine(network: &Network, data: &ClipData, recording_latents: Option<&[f32]>) {
    let z = tch::no_grad(|| network.encoder.encode(&data.train));
    let ids: Vec<usize> = (0..data.n_train() as usize).collect();
    let clips = Clips {
        start: data.train_start.as_ref(),
        ids: Some(&ids),
    };
    if network.refine(&z, clips) {
        network.prepare();
    }
    let Some(windows) =
        recording_latents.and_then(|l| Windows::of(data, network.model.latent_dims(), l))
    else {
        return;
    };
    if network.refine(&windows.z, windows.clips()) {
        network.prepare();
    }
}
