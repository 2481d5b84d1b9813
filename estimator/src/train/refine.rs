//! The final refinement of the physical parameters with the kept encoder held: on the training
//! clips, then, for a recording, on long windows of its encoded timeline. A clip spans a
//! swing or two, over which a light damping changes the amplitude by a percent or two, the
//! size of the encoder's own errors; the whole recording carries ten times that signal (what
//! appendix A.6's peak fit reads), so the damping is solved where it shows.

use crate::data::ClipData;
use crate::network::Network;
use crate::physics::Clips;
use tch::Tensor;

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
    let (Some((summary, _)), Some(latents)) = (data.recording.as_ref(), recording_latents) else {
        return;
    };
    let dims = data.model.latent_dims().max(1);
    let windows = recording_windows(latents.len() / dims, summary.stride, MAX_WINDOW);
    let Some(first) = windows.first() else {
        return;
    };
    let frames_per_window = first.len();
    let flat: Vec<f32> = windows
        .iter()
        .flat_map(|w| w.iter().flat_map(|&f| &latents[f * dims..(f + 1) * dims]))
        .copied()
        .collect();
    let shape = if dims == 1 {
        vec![windows.len() as i64, frames_per_window as i64]
    } else {
        vec![windows.len() as i64, frames_per_window as i64, dims as i64]
    };
    let device = data.train.device();
    let z = Tensor::from_slice(&flat)
        .view(shape.as_slice())
        .to_device(device);
    let starts = data.train_start.as_ref().map(|_| {
        let t: Vec<f32> = windows
            .iter()
            .map(|w| (w[0] as f64 / summary.fps) as f32)
            .collect();
        Tensor::from_slice(&t).to_device(device)
    });
    let clips = Clips {
        start: starts.as_ref(),
        ids: None,
    };
    if network.refine(&z, clips) {
        network.prepare();
    }
}

/// Samples per window at most (at 10 samples/s, over 3 min).
const MAX_WINDOW: usize = 2000;

/// Fewer samples per phase than this make no windows (two default clips: nothing to gain).
const MIN_WINDOW: usize = 40;

/// The recording frames of long windows over `frames` kept frames, sampled every `stride`
/// frames like the clips: for each of the `stride` phases, the sampled frames cut into equal
/// windows of at most `longest` samples (the remainder left out), so that every frame is used.
/// None when a phase has fewer than [`MIN_WINDOW`] samples.
pub fn recording_windows(frames: usize, stride: usize, longest: usize) -> Vec<Vec<usize>> {
    let stride = stride.max(1);
    // Samples of the shortest phase.
    let samples = frames / stride;
    if samples < MIN_WINDOW {
        return Vec::new();
    }
    let longest = longest.max(MIN_WINDOW);
    let count = samples.div_ceil(longest);
    let len = samples / count;
    (0..stride)
        .flat_map(|phase| {
            (0..count).map(move |w| {
                (0..len)
                    .map(|k| phase + (w * len + k) * stride)
                    .collect::<Vec<_>>()
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_use_every_phase_and_stay_in_range() {
        let w = recording_windows(1299, 6, MAX_WINDOW);
        // 216 samples per phase: one window each.
        assert_eq!(w.len(), 6);
        assert!(w.iter().all(|v| v.len() == 216));
        assert!(w.iter().flatten().all(|&f| f < 1299));
        assert_eq!(w[5][0], 5);
        assert_eq!(w[0][1] - w[0][0], 6);
        // Capped: 2000 samples in windows of at most 60 → 34 windows of 58.
        let w = recording_windows(2000, 1, 60);
        assert_eq!(w.len(), 34);
        assert!(w.iter().all(|v| v.len() == 58));
        assert!(recording_windows(100, 3, MAX_WINDOW).is_empty());
    }
}
