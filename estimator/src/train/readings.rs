//! The latent at the calibration's reference frames, read through the physics: the clip's
//! rollout at the frame, shifted by the clip's mean residual (per coordinate), that is the
//! latent there as the whole clip sees it, not one frame's encoding; past the clip's last frame
//! (a reference after the part kept) the rollout carried on.

use crate::calibration::{Calibration, Readings};
use crate::data::ClipData;
use crate::network::Network;
use crate::physics::Clips;
use tch::{Device, Kind};

/// The latent (all its numbers) at frame `frame` of clip `clip` (past its last frame on the
/// rollout, where the law runs on: a reference after the part kept).
fn latent_at(network: &Network, data: &ClipData, clip: usize, frame: usize) -> Vec<f64> {
    let (x, i) = data.clip(clip);
    let start = data.clip_start(clip);
    let ids = [clip];
    let clips = Clips {
        start: start.as_ref(),
        ids: Some(&ids),
    };
    let steps = data.frames_per_clip.max(frame as i64 + 1);
    let (z, z_hat) = network.forward(&x.narrow(0, i, 1), clips, steps);
    let seen = z_hat.narrow(1, 0, data.frames_per_clip);
    let shift = (&z - &seen).mean_dim(1, false, Kind::Float);
    let at = z_hat.select(1, frame as i64) + shift;
    Vec::<f64>::try_from(
        &at.to_device(Device::Cpu)
            .to_kind(Kind::Double)
            .contiguous()
            .view([-1]),
    )
    .expect("a float tensor")
}

/// The readings at every reference frame of `cal`.
pub fn read(network: &Network, data: &ClipData, cal: &Calibration) -> Readings {
    tch::no_grad(|| Readings {
        values: cal
            .reference
            .iter()
            .map(|&(clip, frame, _)| latent_at(network, data, clip, frame)[0])
            .collect(),
        positions: cal
            .positions
            .iter()
            .map(|(clip, frame, _)| latent_at(network, data, *clip, *frame))
            .collect(),
    })
}
