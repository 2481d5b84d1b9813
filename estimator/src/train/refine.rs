//! The final refinement of the physical parameters with the kept encoder held: on the training
//! clips, then, for a recording, on long windows of its encoded timeline (`windows.rs`), where
//! a light damping shows (appendix A.6's peak fit reads the same signal).

use crate::data::ClipData;
use crate::network::Network;
use crate::physics::Clips;
use crate::windows::Windows;

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
