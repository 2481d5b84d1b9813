//! What the verdict weighs, gathered once training has ended with the network at its final
//! state (and left there): the final fit's curvature (a covariance of the block's parameters,
//! `curvature.rs`), the parameters refitted on each half of the training clips, whether the
//! latent folds the picture (`fold.rs`), and how well the law explains the latent's motion on
//! the validation clips.

pub mod curvature;
pub mod fold;

use crate::data::ClipData;
use crate::network::Network;
use crate::physics::Clips;
use crate::windows::Windows;
use curvature::{jacobian, refit, sandwich, step, Variables};
use fold::Fold;
use serde::Serialize;
use tch::{Kind, Tensor};

/// Iterations of the generic refit on each half (blocks without a final solve of their own).
const REFIT_ITERATIONS: usize = 30;

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
    /// How the rollout explains the latent on the validation clips.
    pub law: Option<LawFit>,
}

/// How the training clips were halved for a refit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SplitBy {
    /// The first and the second half in the data's order (a recording's earlier and later
    /// part).
    Order,
    /// Clips whose mean latent is in the lower and in the upper half (a level, a distance);
    /// long clips are cut in two first (see `Pieces`).
    Level,
    /// Clips whose latent moves least and most within them (small and large swings).
    Motion,
}

impl SplitBy {
    /// The two halves in words.
    pub fn halves(self) -> [&'static str; 2] {
        match self {
            SplitBy::Order => ["the first half of the clips", "the second half"],
            SplitBy::Level => ["the clips low in the latent's range", "those high in it"],
            SplitBy::Motion => ["the clips that move least", "those that move most"],
        }
    }
}

/// One refit on each half.
#[derive(Debug, Clone, Serialize)]
pub struct Split {
    pub by: SplitBy,
    /// The block's parameters on each half.
    pub values: [Vec<f64>; 2],
    /// Their covariances from each half's curvature.
    #[serde(skip)]
    pub covariances: [Option<Vec<f64>>; 2],
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
}

impl LawFit {
    /// From encoded latents `z` and their rollout `z_hat`, [N, T] or [N, T, D].
    pub fn of(z: &Tensor, z_hat: &Tensor) -> Option<LawFit> {
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
        Some(LawFit {
            latent_range: (z.min().double_value(&[]), z.max().double_value(&[])),
            unexplained_within: ssr / within,
            residual_autocorrelation: if ssr > 0.0 { lagged / ssr } else { 0.0 },
            latent_within_share: within / total,
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
    let range_split = if data.model.oscillates(&network.values(&z)) {
        SplitBy::Motion
    } else {
        SplitBy::Level
    };
    // A recording's answer was solved on long windows of its timeline: its error and its
    // earlier and later halves come from them; a data set's from its clips.
    let windows = recording_latents.and_then(|l| Windows::of(data, l));
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
    Evidence {
        covariance,
        clusters,
        splits: order
            .into_iter()
            .chain(split(network, data, &z, &groups, range_split))
            .collect(),
        fold: frames_fold(network, data, recording_latents),
        law: LawFit::of(val.0, val.1),
    }
}

/// Samples of a window per time block: residuals of nearby frames are correlated (the
/// encoder's errors are smooth in time), so blocks of this many samples, across all the
/// stride's phases, are the independent draws of a recording's covariance.
fn time_blocks(w: &Windows) -> Vec<usize> {
    let len = w.frames[0].len();
    let block = ((len / 8).max(5) * w.stride).max(1);
    let keys: Vec<usize> = w.frames.iter().flatten().map(|&f| f / block).collect();
    renumber(&keys)
}

/// The block's parameters refitted on the first and on the second half of a recording's
/// windows, with their covariances.
fn window_halves(network: &Network, w: &Windows) -> Option<Split> {
    let saved = network.snapshot();
    let fit = |h: &Windows| {
        if !network.refine_held(&h.z, h.clips()) {
            refit(network, &h.z, h.clips(), REFIT_ITERATIONS);
        }
        network.prepare();
        let values = network.values(&h.z);
        let cov = covariance(network, &h.z, h.clips(), &time_blocks(h));
        network.restore(&saved);
        (values, cov)
    };
    let (a, ca) = fit(&w.half(false));
    let (b, cb) = fit(&w.half(true));
    [&a, &b]
        .iter()
        .all(|v| v.iter().all(|x| x.is_finite()))
        .then_some(Split {
            by: SplitBy::Order,
            values: [a, b],
            covariances: [ca, cb],
        })
}

/// The group of each training clip: clips that share frames (a recording's, or windows cut
/// from one sequence into a data set) are not independent draws, so clips whose first frames
/// lie within a quarter of a clip's span of the sequence are one group (neighbouring groups
/// still share frames; a recording of one or two clips' length would otherwise give one
/// group and no error at all); clips that share none are each their own group.
fn clip_groups(data: &ClipData) -> Vec<usize> {
    let n = data.n_train() as usize;
    let t = data.frames_per_clip as usize;
    // Each clip's sequence and the position of its first frame in it.
    let places: Vec<(usize, usize)> = match &data.recording {
        Some((summary, _)) => summary
            .clip_starts
            .iter()
            .take(n)
            .map(|&s| (0, s / summary.stride.max(1)))
            .collect(),
        None => {
            let offsets = window_offsets(&data.train);
            let mut places = Vec::with_capacity(n);
            for i in 0..n {
                let place = match (i.checked_sub(1), places.last()) {
                    (Some(prev), Some(&(seq, pos))) => match offsets[prev] {
                        Some(h) => (seq, pos + h),
                        None => (seq + 1, 0),
                    },
                    _ => (0, 0),
                };
                places.push(place);
            }
            places
        }
    };
    let block = (t / 4).max(1);
    let keys: Vec<(usize, usize)> = places.iter().map(|&(s, p)| (s, p / block)).collect();
    let mut distinct = keys.clone();
    distinct.sort_unstable();
    distinct.dedup();
    keys.iter()
        .map(|k| distinct.binary_search(k).unwrap_or(0))
        .collect()
}

/// The distinct rows of `frames` [M, D] in their order (windows cut from one sequence repeat
/// its frames, and a repeated frame would be its own nearest neighbour), told apart by two
/// fixed projections.
fn distinct_rows(frames: &Tensor) -> Tensor {
    let d = frames.size()[1];
    let keys = tch::no_grad(|| {
        let w = Tensor::arange(d, (Kind::Double, frames.device()));
        let p = Tensor::stack(&[(&w * 0.7548776662).sin(), (&w * 0.5698402910).cos()], 1);
        frames
            .to_kind(Kind::Double)
            .matmul(&p)
            .to_device(tch::Device::Cpu)
    });
    let keys = Vec::<Vec<f64>>::try_from(&keys).unwrap_or_default();
    let mut seen = std::collections::HashSet::new();
    let keep: Vec<i64> = keys
        .iter()
        .enumerate()
        .filter(|(_, k)| seen.insert((k[0].to_bits(), k[1].to_bits())))
        .map(|(i, _)| i as i64)
        .collect();
    if keep.len() == keys.len() {
        return frames.shallow_clone();
    }
    frames.index_select(0, &Tensor::from_slice(&keep).to_device(frames.device()))
}

/// For each clip but the last, the frame of it that the next clip starts with (the hop between
/// windows cut from one sequence), if any frame is identical to the next clip's first.
fn window_offsets(clips: &Tensor) -> Vec<Option<usize>> {
    let (n, t, _) = clips.size3().unwrap_or((0, 0, 0));
    if n < 2 {
        return Vec::new();
    }
    let mut out = Vec::with_capacity(n as usize - 1);
    for s in (0..n - 1).step_by(64) {
        let len = (n - 1 - s).min(64);
        let next = clips.narrow(0, s + 1, len).narrow(1, 0, 1);
        let same = tch::no_grad(|| {
            (clips.narrow(0, s, len) - next)
                .abs()
                .amax([2].as_slice(), false)
                .eq(0.0)
                .to_device(tch::Device::Cpu)
        });
        let rows = Vec::<Vec<bool>>::try_from(&same).unwrap_or_default();
        out.extend(
            rows.into_iter()
                .map(|r| r.iter().skip(1).position(|&b| b).map(|p| p + 1)),
        );
    }
    let _ = t;
    out
}

/// The covariance of the block's parameters (values) from the sandwich of its variables, the
/// latents `z` [N, T(, D)] grouped per sample (clip and frame) by `groups`.
fn covariance(network: &Network, z: &Tensor, clips: Clips, groups: &[usize]) -> Option<Vec<f64>> {
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

/// The training clips in the order that halves them `by` (1-D latents only for the level and
/// motion splits).
fn split_order(z: &Tensor, by: SplitBy) -> Option<Vec<i64>> {
    let n = z.size()[0];
    let key = match by {
        SplitBy::Order => return Some((0..n).collect()),
        _ if z.dim() != 2 => return None,
        SplitBy::Level => z.mean_dim(1, false, Kind::Double),
        SplitBy::Motion => z.to_kind(Kind::Double).std_dim(1, false, false),
    };
    let key = Vec::<f64>::try_from(&key.to_device(tch::Device::Cpu)).ok()?;
    let mut order: Vec<i64> = (0..n).collect();
    order.sort_by(|&a, &b| key[a as usize].total_cmp(&key[b as usize]));
    Some(order)
}

/// The block's parameters refitted on each half of the training clips ordered `by` (the
/// block's own final solve, or Levenberg–Marquardt on its variables) with each half's
/// covariance, the network put back afterwards.
fn split(
    network: &Network,
    data: &ClipData,
    z: &Tensor,
    groups: &[usize],
    by: SplitBy,
) -> Option<Split> {
    let p = Pieces::of(data, z, groups, by);
    let n = p.z.size()[0];
    if n < 4 {
        return None;
    }
    let order = split_order(&p.z, by)?;
    let saved = network.snapshot();
    let half = (n / 2) as usize;
    let fit = |rows: &[i64]| {
        let index = Tensor::from_slice(rows).to_device(z.device());
        let zh = p.z.index_select(0, &index);
        let ids: Vec<usize> = rows.iter().map(|&i| p.ids[i as usize]).collect();
        let start = p.start.as_ref().map(|t| t.index_select(0, &index));
        let clips = Clips {
            start: start.as_ref(),
            ids: Some(&ids),
        };
        if !network.refine_held(&zh, clips) {
            refit(network, &zh, clips, REFIT_ITERATIONS);
        }
        network.prepare();
        let values = network.values(&zh);
        let steps = zh.size()[1] as usize;
        let half_groups: Vec<usize> = rows
            .iter()
            .flat_map(|&i| [p.groups[i as usize]].repeat(steps))
            .collect();
        let covariance = covariance(network, &zh, clips, &renumber(&half_groups));
        network.restore(&saved);
        (values, covariance)
    };
    let (a, ca) = fit(&order[..half]);
    let (b, cb) = fit(&order[half..]);
    [&a, &b]
        .iter()
        .all(|v| v.iter().all(|x| x.is_finite()))
        .then_some(Split {
            by,
            values: [a, b],
            covariances: [ca, cb],
        })
}

/// Identifiers of the pieces of clips (the shooting blocks keep a warm start per identifier:
/// these must not be a clip's).
const PIECE_IDS: usize = 1 << 40;

/// The training clips as a split sees them. Across levels, clips of at least
/// [`MIN_PIECE`]·2 frames are cut into their two halves: a long clip spans much of a drain's
/// range, and halves of the data by whole clips would overlap in level so much that a law
/// with the wrong shape (an exponential decay fitted to a draining tank) fits both alike.
struct Pieces {
    z: Tensor,
    start: Option<Tensor>,
    ids: Vec<usize>,
    groups: Vec<usize>,
}

/// The shortest piece a clip is cut into.
const MIN_PIECE: i64 = 4;

impl Pieces {
    fn of(data: &ClipData, z: &Tensor, groups: &[usize], by: SplitBy) -> Pieces {
        let (n, t) = (z.size()[0], z.size()[1]);
        if by != SplitBy::Level || t < 2 * MIN_PIECE || z.dim() != 2 {
            return Pieces {
                z: z.shallow_clone(),
                start: data.train_start.as_ref().map(|s| s.shallow_clone()),
                ids: (0..n as usize).collect(),
                groups: groups.to_vec(),
            };
        }
        let h = t / 2;
        let pieces = z.narrow(1, 0, 2 * h).reshape([2 * n, h]);
        let start = data.train_start.as_ref().map(|s| {
            let shift = Tensor::from_slice(&[0.0f32, (h as f64 * data.dt) as f32])
                .to_device(s.device())
                .unsqueeze(0);
            (s.unsqueeze(1) + shift).reshape([2 * n])
        });
        Pieces {
            z: pieces,
            start,
            ids: (0..2 * n as usize).map(|i| PIECE_IDS + i).collect(),
            groups: (0..2 * n as usize).map(|i| groups[i / 2]).collect(),
        }
    }
}

/// Group numbers renumbered 0, 1, 2, … in order of first appearance.
fn renumber(groups: &[usize]) -> Vec<usize> {
    let mut seen: Vec<usize> = Vec::new();
    groups
        .iter()
        .map(|g| match seen.iter().position(|s| s == g) {
            Some(i) => i,
            None => {
                seen.push(*g);
                seen.len() - 1
            }
        })
        .collect()
}

/// The fold of the latent against the frames' principal components: a recording's every frame
/// with its latent, or up to [`FOLD_FRAMES`] frames spread over a data set's clips.
fn frames_fold(
    network: &Network,
    data: &ClipData,
    recording_latents: Option<&[f32]>,
) -> Option<Fold> {
    if data.model.latent_dims() != 1 {
        return None;
    }
    let (frames, z) = match (&data.recording, recording_latents) {
        (Some((_, frames)), Some(latents)) => {
            let f = frames.squeeze_dim(0);
            (f, latents.iter().map(|&v| v as f64).collect::<Vec<_>>())
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
            (f, z)
        }
    };
    fold::fold(&frames, &z)
}
