//! The block's parameters refitted on halves of the training clips (the encoder held), each
//! half with its own covariance: earlier and later clips (a recording's windows), and across
//! the motion's range (small and large swings; low and high levels, long clips cut in two).

use super::curvature::refit;
use super::groups::{renumber, time_blocks};
use super::{covariance, REFIT_ITERATIONS};
use crate::data::ClipData;
use crate::network::Network;
use crate::physics::Clips;
use crate::windows::Windows;
use serde::{Deserialize, Serialize};
use tch::{Kind, Tensor};

/// How the training clips were halved for a refit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
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

/// The block's parameters refitted on the first and on the second half of a recording's
/// windows, with their covariances.
pub(super) fn window_halves(network: &Network, w: &Windows) -> Option<Split> {
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
pub(super) fn split(
    network: &Network,
    data: &ClipData,
    z: &Tensor,
    groups: &[usize],
    by: SplitBy,
) -> Option<Split> {
    let p = Pieces::of(data, network.dt, z, groups, by);
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
    fn of(data: &ClipData, dt: f64, z: &Tensor, groups: &[usize], by: SplitBy) -> Pieces {
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
            let shift = Tensor::from_slice(&[0.0f32, (h as f64 * dt) as f32])
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
