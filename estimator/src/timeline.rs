//! `Timeline`: the encoded latent of every frame of a recording, with the physics rollouts of
//! clips that tile it back to back (what `timeline.png` draws).

use crate::data::summary::RecordingSummary;
use crate::data::ClipData;
use crate::network::{to_rows, Network};
use crate::physics::Clips;
use tch::{Device, Tensor};

/// The encoded latent over a whole recording with the physics rollouts of back-to-back clips.
#[derive(Debug, Clone)]
pub struct Timeline {
    /// Seconds between recording frames (1 / fps).
    pub frame_dt: f64,
    /// Time of the first kept frame on the recording's own timeline (`--start`, else 0).
    pub start_s: f64,
    /// Recording frames between clip frames.
    pub stride: usize,
    /// Latent of every frame.
    pub latents: Vec<f32>,
    /// (first recording frame, latent rollout at its clip frames) for clips that tile the
    /// recording.
    pub rollouts: Vec<(usize, Vec<f32>)>,
}

impl Timeline {
    /// `timeline.csv`: the time of every kept recording frame (s, on the recording's own
    /// timeline) and its latent coordinates, for analysis elsewhere.
    pub fn csv(&self, dims: usize) -> String {
        let dims = dims.max(1);
        let head: Vec<String> = (0..dims)
            .map(|d| {
                if dims == 1 {
                    "z".into()
                } else {
                    format!("z{d}")
                }
            })
            .collect();
        let mut s = format!("time_s,{}\n", head.join(","));
        for (k, row) in self.latents.chunks(dims).enumerate() {
            let row: Vec<String> = row.iter().map(|v| v.to_string()).collect();
            s += &format!("{},{}\n", self.time(k), row.join(","));
        }
        s
    }

    /// Time of kept frame `k` on the recording's own timeline (s).
    pub fn time(&self, k: usize) -> f64 {
        self.start_s + k as f64 * self.frame_dt
    }
}

/// The latent of every frame of a recording ([1, F, D] standardised frames), encoded in pieces.
pub fn encode_recording(model: &Network, frames: &Tensor) -> Vec<f32> {
    tch::no_grad(|| {
        let f = frames.size()[1];
        let mut latents = Vec::with_capacity(f as usize);
        for s in (0..f).step_by(512) {
            let z = model.encoder.encode(&frames.narrow(1, s, (f - s).min(512)));
            latents.extend(
                Vec::<f32>::try_from(&z.view([-1]).to_device(Device::Cpu)).unwrap_or_default(),
            );
        }
        latents
    })
}

/// The latent over a recording (`latents`, from [`encode_recording`]) and the rollouts of clips
/// that tile it, one clip span apart.
pub fn timeline(
    model: &Network,
    data: &ClipData,
    summary: &RecordingSummary,
    frames: &Tensor,
    latents: Vec<f32>,
) -> Timeline {
    tch::no_grad(|| {
        let t = data.frames_per_clip as usize;
        let span = (t - 1) * summary.stride;
        let mut rollouts = Vec::new();
        let mut next = 0;
        for &start in &summary.clip_starts {
            if start < next {
                continue;
            }
            next = start + span;
            let idx: Vec<i64> = (0..t)
                .map(|k| (start + k * summary.stride) as i64)
                .collect();
            let idx = Tensor::from_slice(&idx).to_device(frames.device());
            let x = frames.index_select(1, &idx);
            let t0 = data.train_start.as_ref().map(|_| {
                Tensor::from_slice(&[summary.since_release(start) as f32])
                    .to_device(frames.device())
            });
            let clips = Clips {
                start: t0.as_ref(),
                ids: None,
            };
            let (_, z_hat) = model.forward(&x, clips, data.frames_per_clip);
            rollouts.push((start, to_rows(&z_hat).remove(0)));
        }
        Timeline {
            frame_dt: 1.0 / summary.fps,
            start_s: summary.start.unwrap_or(0.0),
            stride: summary.stride,
            latents,
            rollouts,
        }
    })
}
