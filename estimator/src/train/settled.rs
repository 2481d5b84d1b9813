//! Whether a run's answer has settled: the convergence stop's test (every parameter within the
//! model's band over the last epochs), and, for a run the epoch limit stopped, the answer of an
//! earlier checkpoint to set beside the kept one (`EarlierAnswer`, judged by the verdict's
//! `training` check).

use super::outcome::{EarlierAnswer, EpochRecord};
use super::refine;
use crate::config::RunConfig;
use crate::data::ClipData;
use crate::network::Network;
use crate::physics::Settles;
use tch::Tensor;

/// The window over which every parameter has stayed within the model's `converged_spread` of
/// its mean in `history` (the current curriculum stage began at epoch `stage_start`), if it
/// has: the answer is known, and more epochs would only polish the last digits (the kept
/// checkpoint is still the best validation epoch).
pub(super) fn converged(
    cfg: &RunConfig,
    history: &[EpochRecord],
    stage_start: usize,
) -> Option<usize> {
    let w = (cfg.patience / 2).max(5);
    let n = history.len();
    if n + 1 < stage_start + 2 * w {
        return None;
    }
    let window = &history[n - w..];
    let params = window[0].parameters.len();
    let specs = cfg.model.parameters();
    let settles = |i: usize| specs.get(i).map_or(Settles::Relative, |s| s.settles);
    (0..params)
        .all(|i| {
            let v = window.iter().map(|r| r.parameters[i]);
            let (lo, hi) = v
                .clone()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                    (a.min(x), b.max(x))
                });
            let mean = v.sum::<f64>() / w as f64;
            settles(i)
                .scale(mean)
                .is_none_or(|scale| hi - lo <= cfg.model.info().training.converged_spread * scale)
        })
        .then_some(w)
}

/// The answer of the checkpoint `vars` (of `epoch`), refined and read as the kept one is
/// (`refine::held`); the network is left in that state.
pub(super) fn answer_of(
    network: &Network,
    cfg: &RunConfig,
    data: &ClipData,
    epoch: usize,
    vars: &[Tensor],
) -> EarlierAnswer {
    network.restore(vars);
    let held = refine::held(network, cfg, data);
    let parameters = tch::no_grad(|| network.values(&held.z));
    EarlierAnswer { epoch, parameters }
}
