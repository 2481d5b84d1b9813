//! Training: `fit` probes each start for a few epochs with a `Trainer`, keeps the one with the
//! lowest validation error and trains it to the end; `outcome` holds what comes out.

mod jitter;
pub mod outcome;
mod readings;
mod refine;
mod settled;
mod trainer;

pub use outcome::{EarlierAnswer, EpochRecord, StopReason, TrainOutcome};
pub use trainer::Trainer;

use crate::config::RunConfig;
use crate::data::ClipData;
use crate::error::EstimateError;
use crate::evidence::fold::MAYBE_FOLDED;
use serde::Serialize;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;
use tch::Device;

/// How one start fared in the probe phase of [`fit`].
#[derive(Debug, Clone, Serialize)]
pub struct StartProbe {
    pub initial: Vec<f64>,
    /// Best validation metric within the probe epochs (for the half-frequency start: of its
    /// whole training).
    pub probe_val_rel_mse: f64,
    pub chosen: bool,
    /// Why the start was tried, where it was not one of the starts given to [`fit`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// Epochs each start trains before the best one (by validation metric) is kept.
pub const PROBE_EPOCHS: usize = 8;

/// A caller's way to stop a training between epochs: a flag it may set from anywhere (another
/// thread, a signal handler); none for a run only the process's end stops (the CLI's).
#[derive(Debug, Clone, Copy, Default)]
pub struct Cancel<'a>(pub Option<&'a AtomicBool>);

impl Cancel<'_> {
    /// [`EstimateError::Cancelled`] once the flag is set.
    pub fn check(self) -> Result<(), EstimateError> {
        match self.0 {
            Some(flag) if flag.load(Ordering::Relaxed) => Err(EstimateError::Cancelled),
            _ => Ok(()),
        }
    }
}

/// Trains from each of `starts` for [`PROBE_EPOCHS`] epochs, keeps the start with the lowest
/// validation metric (a start that locked onto a harmonic of the motion fits far worse) and
/// trains it to the end. With one start this is plain training. `on_epoch` sees the kept
/// start's epochs; `cancel` is asked before each epoch.
pub fn fit(
    cfg: &RunConfig,
    data: &ClipData,
    device: Device,
    starts: &[Vec<f64>],
    on_epoch: &mut dyn FnMut(&EpochRecord),
    cancel: Cancel,
) -> Result<(TrainOutcome, Vec<StartProbe>), EstimateError> {
    assert!(!starts.is_empty(), "at least one start");
    let mut probes = Vec::new();
    let mut chosen: Option<(usize, Trainer)> = None;
    let start = Instant::now();
    // One curriculum for every start, so that their probe scores compare.
    let horizon = starts
        .iter()
        .filter_map(|s| cfg.model.first_horizon(s, cfg.dt))
        .min();
    for (i, init) in starts.iter().enumerate() {
        let mut t = Trainer::new(cfg, data, device, init, horizon, start)?;
        if starts.len() > 1 {
            while t.stop.is_none() && t.history.len() < PROBE_EPOCHS {
                cancel.check()?;
                t.epoch(&mut |_| {});
            }
        }
        let score = t.best_score();
        probes.push(StartProbe {
            initial: init.clone(),
            probe_val_rel_mse: score,
            chosen: false,
            note: None,
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
        cancel.check()?;
        t.epoch(on_epoch);
    }
    Ok((t.finish(), probes))
}

/// How much worse (validation error) a solution whose latent does not fold the picture may fit
/// than a folded one and still be preferred: a latent that follows the motion one to one is the
/// fundamental, and the law fits it about as well as it fits the harmonic (measured on a
/// rod-and-bob: 0.04 against 0.06).
const UNFOLDED_PREFERENCE: f64 = 2.0;

/// [`fit`], then, when the answer oscillates and its latent folds the picture (an even function
/// of the motion swings at twice its frequency: `evidence::fold`), a start at half its
/// frequency trained to the end too; the answer kept is the unfolded one unless the folded one
/// fits `UNFOLDED_PREFERENCE` times better. (Training the other probed starts to the end
/// whenever an answer followed little of the picture was tried and dropped: among moving
/// distractors the validation error then preferred a distractor's straight path, γ0 0.3
/// instead of 4.) `--single-start` trains the one start alone. `announce` is told before the
/// further training.
pub fn fit_best(
    cfg: &RunConfig,
    data: &ClipData,
    device: Device,
    starts: &[Vec<f64>],
    on_epoch: &mut dyn FnMut(&EpochRecord),
    announce: &mut dyn FnMut(&str),
    cancel: Cancel,
) -> Result<(TrainOutcome, Vec<StartProbe>), EstimateError> {
    let (first, mut probes) = fit(cfg, data, device, starts, on_epoch, cancel)?;
    let folded = |o: &TrainOutcome| o.evidence.fold.as_ref().map_or(0.0, |f| f.folded_share);
    let mut others: Vec<(Vec<f64>, String)> = Vec::new();
    if !cfg.single_start
        && folded(&first) >= MAYBE_FOLDED
        && cfg.model.oscillates(&first.parameters)
    {
        if let Some(half) = cfg
            .model
            .subharmonic(&first.parameters)
            .filter(|h| inside_bounds(cfg, h))
        {
            others.push((
                half,
                format!(
                    "half the frequency of the first answer, whose latent folded {:.0} % of the \
                     picture",
                    100.0 * folded(&first)
                ),
            ));
        }
    }
    if others.is_empty() {
        return Ok((first, probes));
    }
    announce(&format!(
        "the latent folds the picture ({:.0} % of it), as a harmonic of the motion would: \
         training again from half the frequency",
        100.0 * folded(&first)
    ));
    // The first answer's probe stays chosen unless another wins.
    let mut best = first;
    let mut best_probe = probes.iter().position(|p| p.chosen);
    for (init, note) in others {
        let (o, _) = fit(
            cfg,
            data,
            device,
            std::slice::from_ref(&init),
            &mut |_| {},
            cancel,
        )?;
        let k = probes.len();
        probes.push(StartProbe {
            initial: init,
            probe_val_rel_mse: o.best_val_rel_mse,
            chosen: false,
            note: Some(format!(
                "{note} (its latent folds {:.0} %)",
                100.0 * folded(&o)
            )),
        });
        if better(&o, &best) {
            best = o;
            best_probe = Some(k);
        }
    }
    probes.iter_mut().for_each(|p| p.chosen = false);
    if let Some(k) = best_probe {
        probes[k].chosen = true;
    }
    Ok((best, probes))
}

/// Whether `a` is a better answer than `b`: a latent that folds the picture less unless it fits
/// far worse, else the lower validation error.
fn better(a: &TrainOutcome, b: &TrainOutcome) -> bool {
    if a.best_epoch == 0 || !a.best_val_rel_mse.is_finite() {
        return false;
    }
    let fold = |o: &TrainOutcome| o.evidence.fold.as_ref().map_or(0.0, |f| f.folded_share);
    let (fa, fb) = (fold(a) >= MAYBE_FOLDED, fold(b) >= MAYBE_FOLDED);
    match (fa, fb) {
        (false, true) => a.best_val_rel_mse <= UNFOLDED_PREFERENCE * b.best_val_rel_mse,
        (true, false) => a.best_val_rel_mse * UNFOLDED_PREFERENCE < b.best_val_rel_mse,
        _ => a.best_val_rel_mse < b.best_val_rel_mse,
    }
}

/// Whether `values` lie strictly inside every parameter's bounds.
fn inside_bounds(cfg: &RunConfig, values: &[f64]) -> bool {
    cfg.model
        .parameters()
        .iter()
        .zip(values)
        .all(|(p, v)| p.bounds.contains(*v))
}

/// Trains from `cfg.init` alone (see [`fit`]).
pub fn train(
    cfg: &RunConfig,
    data: &ClipData,
    device: Device,
    on_epoch: &mut dyn FnMut(&EpochRecord),
) -> Result<TrainOutcome, EstimateError> {
    let starts = std::slice::from_ref(&cfg.init);
    fit(cfg, data, device, starts, on_epoch, Cancel::default()).map(|(o, _)| o)
}
