//! Training: `fit` probes each start for a few epochs with a `Trainer`, keeps the one with the
//! lowest validation error and trains it to the end; `outcome` holds what comes out.

pub mod outcome;
mod readings;
mod refine;
mod trainer;

pub use outcome::{EpochRecord, StopReason, TrainOutcome};
pub use trainer::Trainer;

use crate::config::RunConfig;
use crate::data::ClipData;
use crate::error::EstimateError;
use serde::Serialize;
use std::time::Instant;
use tch::Device;

/// How one start fared in the probe phase of [`fit`].
#[derive(Debug, Clone, Serialize)]
pub struct StartProbe {
    pub initial: Vec<f64>,
    /// Best validation metric within the probe epochs.
    pub probe_val_rel_mse: f64,
    pub chosen: bool,
}

/// Epochs each start trains before the best one (by validation metric) is kept.
pub const PROBE_EPOCHS: usize = 8;

/// Trains from each of `starts` for [`PROBE_EPOCHS`] epochs, keeps the start with the lowest
/// validation metric (a start that locked onto a harmonic of the motion fits far worse) and
/// trains it to the end. With one start this is plain training. `on_epoch` sees the kept
/// start's epochs.
pub fn fit(
    cfg: &RunConfig,
    data: &ClipData,
    device: Device,
    starts: &[Vec<f64>],
    on_epoch: &mut dyn FnMut(&EpochRecord),
) -> Result<(TrainOutcome, Vec<StartProbe>), EstimateError> {
    assert!(!starts.is_empty(), "at least one start");
    let mut probes = Vec::new();
    let mut chosen: Option<(usize, Trainer)> = None;
    let start = Instant::now();
    // One curriculum for every start, so that their probe scores compare.
    let horizon = starts
        .iter()
        .filter_map(|s| cfg.model.first_horizon(s, data.dt))
        .min();
    for (i, init) in starts.iter().enumerate() {
        let mut t = Trainer::new(cfg, data, device, init, horizon, start)?;
        if starts.len() > 1 {
            while t.stop.is_none() && t.history.len() < PROBE_EPOCHS {
                t.epoch(&mut |_| {});
            }
        }
        let score = t.best_score();
        probes.push(StartProbe {
            initial: init.clone(),
            probe_val_rel_mse: score,
            chosen: false,
        });
        if chosen
            .as_ref()
            .is_none_or(|(k, _)| score < probes[*k].probe_val_rel_mse)
        {
            chosen = Some((i, t));
        }
    }
    let (k, mut t) = chosen.expect("one start");
    probes[k].chosen = true;
    for rec in &t.history {
        on_epoch(rec);
    }
    while t.stop.is_none() {
        t.epoch(on_epoch);
    }
    Ok((t.finish(), probes))
}

/// Trains from `cfg.init` alone (see [`fit`]).
pub fn train(
    cfg: &RunConfig,
    data: &ClipData,
    device: Device,
    on_epoch: &mut dyn FnMut(&EpochRecord),
) -> Result<TrainOutcome, EstimateError> {
    fit(cfg, data, device, std::slice::from_ref(&cfg.init), on_epoch).map(|(o, _)| o)
}
