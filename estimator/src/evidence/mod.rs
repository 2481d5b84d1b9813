//! What the verdict weighs, gathered once training has ended with the network at its final
//! state (and left there): the final fit's curvature (a covariance of the block's parameters,
//! `curvature.rs`), the parameters refitted on each half of the training clips, whether the
//! latent folds the picture (`fold.rs`), and how well the law explains the latent's motion on
//! the validation clips.

pub mod curvature;
pub mod fold;
mod groups;
mod halves;

use crate::data::ClipData;
use crate::network::Network;
use crate::physics::Clips;
use crate::windows::Windows;
use curvature::{jacobian, sandwich, step, Variables};
use fold::{Components, Fold};
use groups::{clip_groups, distinct_rows, time_blocks};
use halves::{split, window_halves};
pub use halves::{Split, SplitBy};
use serde::Serialize;
use tch::{Kind, Tensor};

/// Iterations of the generic refit on each half (blocks without a final solve of their own).
pub(crate) const REFIT_ITERATIONS: usize = 30;

/// At most this many frames are encoded for the fold test.
const FOLD_FRAMES: i64 = 4096;

/// The evidence about a trained network.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Evidence {
    /// Covariance of the block's parameters (in the model's order, row-major), from the
    /// curvature of the fit on the training clips with the encoder held.
    #[serde(skip)]
    pub covariance: Option<Vec<f64>>,
    /// Groups of training clips the covariance treats as independent draws (each clip of a
    /// data set; clips of a recording that share frames are one group).
    pub clusters: usize,
    /// The block's parameters refitted on halves of the training clips (the encoder held):
    /// earlier and later clips, and clips low and high in the latent's range or with small
    /// and large motions within them.
    pub splits: Vec<Split>,
    /// The most folded principal component of the frames (one-number latents).
    pub fold: Option<Fold>,
    /// The same of the object's track where it guides the run and gives the answer
    /// (`guide::followed`): how much of the picture the answer's own coordinate explains.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub track_fold: Option<Fold>,
    /// A recording's frames' leading components, from its kept frame `first` on (what the
    /// latent's fold was measured on), for the track's.
    #[serde(skip)]
    pub picture: Option<Picture>,
    /// How the rollout explains the latent on the validation clips.
    pub law: Option<LawFit>,
}

/// A recording's frames' leading components (`fold::Components`), in time order from its kept
/// frame `first` on.
#[derive(Debug, Clone)]
pub struct Picture {
    pub first: usize,
    pub components: Components,
}

/// How well the law explains the latent's motion within clips.
#[derive(Debug, Clone, Serialize)]
pub struct LawFit {
    /// The rollout's squared residuals over the latent's squared deviations from each clip's
    /// own mean: the share of the motion within clips the law leaves unexplained.
    pub unexplained_within: f64,
    /// Lag-one autocorrelation of the residuals within clips (about 0 for noise, near 1 for a
    /// misfit that is smooth in time).
    pub residual_autocorrelation: f64,
    /// The latent's variance within clips over its whole variance.
    pub latent_within_share: f64,
    /// The range of the latent over the validation clips.
    pub latent_range: (f64, f64),
    /// Frames each clip's rollout starts from (the states fitted per clip, besides the law).
    pub start_frames: i64,
    /// The share of the clips in which a one-number latent turns back (`turns_back`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turning_share: Option<f64>,
}

/// A clip's latent turns back when a frame inside it lies beyond both of its ends by this share
/// of the clip's range (a swing's crest or trough; a monotone motion's noise stays far below).
pub const TURN: f64 = 0.1;

/// Whether the latent of one clip `z` turns back (see [`TURN`]).
pub fn turns_back(z: &[f64]) -> bool {
    if z.len() < 3 {
        return false;
    }
    let (first, last) = (z[0], z[z.len() - 1]);
    let range = z.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
        - z.iter().fold(f64::INFINITY, |a, &b| a.min(b));
    let beyond = z[1..z.len() - 1]
        .iter()
        .map(|&v| (v - first).min(v - last).max((first - v).min(last - v)))
        .fold(0.0, f64::max);
    range > 0.0 && beyond > TURN * range
}

impl LawFit {
    /// From encoded latents `z` and their rollout `z_hat`, [N, T] or [N, T, D], rolled out
    /// from `start_frames` of each clip.
    pub fn of(z: &Tensor, z_hat: &Tensor, start_frames: i64) -> Option<LawFit> {
        let z = z.to_kind(Kind::Double);
        let r = &z - z_hat.to_kind(Kind::Double);
        let mean = z.mean_dim(1, true, Kind::Double);
        let within = (&z - &mean).square().sum(Kind::Double).double_value(&[]);
        let total = (&z - z.mean_dim([0, 1].as_slice(), true, Kind::Double))
            .square()
            .sum(Kind::Double)
            .double_value(&[]);
        let ssr = r.square().sum(Kind::Double).double_value(&[]);
        let t = r.size()[1];
        if t < 3 || within <= 0.0 || total <= 0.0 {
            return None;
        }
        let lagged = (r.narrow(1, 1, t - 1) * r.narrow(1, 0, t - 1))
            .sum(Kind::Double)
            .double_value(&[]);
        // One-number latents only; none rather than a share of nothing where the copy fails.
        let turning_share = (z.dim() == 2)
            .then(|| Vec::<f64>::try_from(&z.contiguous().view([-1])).ok())
            .flatten()
            .map(|zs| {
                let clips = zs.chunks(t as usize);
                let n = clips.len().max(1);
                clips.filter(|c| turns_back(c)).count() as f64 / n as f64
            });
        Some(LawFit {
            turning_share,
            latent_range: (z.min().double_value(&[]), z.max().double_value(&[])),
            unexplained_within: ssr / within,
            residual_autocorrelation: if ssr > 0.0 { lagged / ssr } else { 0.0 },
            latent_within_share: within / total,
            start_frames,
        })
    }
}

/// Gathers the evidence; `val` holds the encoded validation latents and their rollout,
/// `recording_latents` the latent of every frame of a recording.
pub fn gather(
    network: &Network,
    data: &ClipData,
    val: (&Tensor, &Tensor),
    recording_latents: Option<&[f32]>,
) -> Evidence {
    let z = tch::no_grad(|| network.encoder.encode(&data.train));
    let n = data.n_train() as usize;
    let t = data.frames_per_clip as usize;
    let ids: Vec<usize> = (0..n).collect();
    let clips = Clips {
        start: data.train_start.as_ref(),
        ids: Some(&ids),
    };
    let groups = clip_groups(data);
    // Across the range of the motion: small and large swings of an oscillation, low and high
    // levels of a decay, a drain or a fall.
    let range_split = if network.model.oscillates(&network.values(&z)) {
        SplitBy::Motion
    } else {
        SplitBy::Level
    };
    // A recording's answer was solved on long windows of its timeline: its error and its
    // earlier and later halves come from them; a data set's from its clips.
    let windows = recording_latents.and_then(|l| Windows::of(data, network.model.latent_dims(), l));
    let (covariance, clusters, order) = match &windows {
        Some(w) => {
            let g = time_blocks(w);
            let clusters = g.iter().copied().max().map_or(0, |m| m + 1);
            let cov = covariance(network, &w.z, w.clips(), &g);
            (cov, clusters, window_halves(network, w))
        }
        None => {
            let per_sample: Vec<usize> = groups.iter().flat_map(|&g| [g].repeat(t)).collect();
            let clusters = groups.iter().copied().max().map_or(0, |g| g + 1);
            let cov = covariance(network, &z, clips, &per_sample);
            (
                cov,
                clusters,
                split(network, data, &z, &groups, SplitBy::Order),
            )
        }
    };
    let (fold, picture) = frames_fold(network, data, recording_latents).unzip();
    let picture = picture.flatten();
    Evidence {
        covariance,
        clusters,
        splits: order
            .into_iter()
            .chain(split(network, data, &z, &groups, range_split))
            .collect(),
        fold,
        track_fold: None,
        picture,
        law: LawFit::of(val.0, val.1, network.start_frames()),
    }
}

/// The covariance of the block's parameters (values) from the sandwich of its variables, the
/// latents `z` [N, T(, D)] grouped per sample (clip and frame) by `groups`.
pub(crate) fn covariance(
    network: &Network,
    z: &Tensor,
    clips: Clips,
    groups: &[usize],
) -> Option<Vec<f64>> {
    let vars = Variables::of(network);
    let m = vars.len();
    if m == 0 || groups.is_empty() {
        return None;
    }
    let (r, jac) = jacobian(network, &vars, z, clips)?;
    let per_sample = (r.len() / groups.len()).max(1);
    let rows: Vec<usize> = (0..r.len())
        .map(|i| groups[(i / per_sample).min(groups.len() - 1)])
        .collect();
    let raw = sandwich(&r, &jac, &rows, m)?;
    // The values' Jacobian in the variables, by central differences.
    let x0 = vars.get();
    let values_at = |x: &[f64]| {
        vars.set(x);
        network.prepare();
        network.values(z)
    };
    let v0 = network.values(z);
    let p = v0.len();
    let mut jv = vec![0.0; p * m];
    for j in 0..m {
        let h = step(x0[j]);
        let mut x = x0.clone();
        x[j] += h;
        let plus = values_at(&x);
        x[j] = x0[j] - h;
        let minus = values_at(&x);
        for i in 0..p {
            jv[i * m + j] = (plus[i] - minus[i]) / (2.0 * h);
        }
    }
    values_at(&x0);
    // Jv·C·Jvᵀ.
    let mut cov = vec![0.0; p * p];
    for a in 0..p {
        for b in 0..p {
            let mut s = 0.0;
            for i in 0..m {
                for j in 0..m {
                    s += jv[a * m + i] * raw[i * m + j] * jv[b * m + j];
                }
            }
            cov[a * p + b] = s;
        }
    }
    cov.iter().all(|v| v.is_finite()).then_some(cov)
}

/// The fold of the latent against the frames' principal components: a recording's every frame
/// with its latent (for a toss, `Descent::rising`, those from its release on: its path's one
/// branch, where the height along its acceleration the latent reads is one to one with the
/// picture; up to the apex the other branch gives each height again, further across), or up
/// to [`FOLD_FRAMES`] frames spread over a data set's clips.
fn frames_fold(
    network: &Network,
    data: &ClipData,
    recording_latents: Option<&[f32]>,
) -> Option<(Fold, Option<Picture>)> {
    if network.model.latent_dims() != 1 {
        return None;
    }
    let (frames, z, first) = match (&data.recording, recording_latents) {
        (Some((summary, frames)), Some(latents)) => {
            let from = match summary.descent {
                Some(d) if d.rising => {
                    (summary.release.ceil().max(0.0) as usize).min(latents.len())
                }
                _ => 0,
            };
            let f = frames.squeeze_dim(0);
            (
                f.narrow(0, from as i64, f.size()[0] - from as i64),
                latents[from..]
                    .iter()
                    .map(|&v| v as f64)
                    .collect::<Vec<_>>(),
                Some(from),
            )
        }
        _ => {
            let all = Tensor::cat(&[&data.train, &data.val], 0);
            let d = all.size()[2];
            let flat = distinct_rows(&all.view([-1, d]));
            let m = flat.size()[0];
            let take = FOLD_FRAMES.min(m);
            let idx = Tensor::arange(take, (Kind::Int64, tch::Device::Cpu))
                .multiply_scalar(m as f64 / take as f64)
                .to_kind(Kind::Int64)
                .to_device(flat.device());
            let f = flat.index_select(0, &idx);
            let z = tch::no_grad(|| network.encoder.encode(&f.unsqueeze(0)));
            let z = Vec::<f64>::try_from(&z.to_kind(Kind::Double).contiguous().view([-1])).ok()?;
            (f, z, None)
        }
    };
    if z.len() < 20 || frames.size()[0] as usize != z.len() {
        return None;
    }
    let components = Components::of(&frames, first.is_some())?;
    let fold = components.fold(&z)?;
    let picture = first.map(|first| Picture { first, components });
    Some((fold, picture))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_clip_turns_back_at_a_crest_inside_it_not_on_a_noisy_ramp_or_at_its_end() {
        let wave = |phase: f64, noise: f64| -> Vec<f64> {
            (0..20)
                .map(|k| {
                    let t = k as f64 / 19.0;
                    (3.0 * t + phase).cos() + noise * if k % 2 == 0 { 1.0 } else { -1.0 }
                })
                .collect()
        };
        // A crest inside the clip (at a third of it), with a little noise.
        assert!(turns_back(&wave(-1.0, 0.01)));
        // A falling half-swing: its crest is the first frame.
        assert!(!turns_back(&wave(0.0, 0.0)));
        // A ramp whose noise is 5 % of its range.
        let ramp: Vec<f64> = (0..20)
            .map(|k| k as f64 / 19.0 + 0.05 * if k % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        assert!(!turns_back(&ramp));
        assert!(!turns_back(&[1.0; 5]) && !turns_back(&[]));
    }
}
