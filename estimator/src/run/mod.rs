//! `run`: probes the input, resolves the configuration, loads the data, picks the device,
//! trains (the ensemble's members too), and hands the report to `output` and the terminal.

use crate::analysis::ensemble::summarise;
use crate::analysis::{Run, RunInfo};
use crate::config::{Request, RunConfig};
use crate::data::{load_clips, probe, ClipData};
use crate::device::{cpu_threads, select_device};
use crate::error::EstimateError;
use crate::guide;
use crate::output::{check_out, clear_earlier, write_outputs};
use crate::physics::Settles;
use crate::progress::Progress;
use crate::report::Report;
use crate::track::TrackRoute;
use crate::train::{fit, fit_best, Cancel, EpochRecord, StopReason};
use crate::verdict::{self, Grade};
pub use choose::{choose, chooses};
use physvid_shared::term;
use std::sync::atomic::AtomicBool;
use std::time::Instant;
use tch::Device;

mod choose;

/// A caller's function told each epoch, with the model's parameter names.
pub type EpochFn<'a> = dyn Fn(&EpochRecord, &[&str]) + Sync + 'a;

/// How a caller follows and stops a run: each epoch of the training kept, and a flag that stops
/// it between epochs with [`EstimateError::Cancelled`]. The default is the command line's: the
/// terminal's progress (a bar, lines, nothing with `quiet`) and no flag (Ctrl-C ends the
/// process, `shared::interrupt`).
#[derive(Clone, Copy, Default)]
pub struct Watch<'a> {
    /// Each epoch of a training kept (every candidate's in a model choice), with the model's
    /// parameter names, instead of the terminal's progress.
    pub epoch: Option<&'a EpochFn<'a>>,
    pub cancel: Option<&'a AtomicBool>,
}

/// An estimation's report with the clips it was trained on.
pub struct Estimation {
    pub report: Report,
    pub data: ClipData,
}

/// Runs one estimation as `req` asks, writes its outputs and prints the table.
pub fn run(req: &Request) -> anyhow::Result<()> {
    check_out(&req.out, Some(req.input()), req.force)?;
    let Estimation { mut report, data } = match estimation(req) {
        Ok(e) => e,
        Err(e) => {
            // No estimate: an earlier run's report must not stand in --out as this run's.
            if matches!(
                e.downcast_ref::<EstimateError>(),
                Some(EstimateError::NoEstimate(_))
            ) {
                clear_earlier(&req.out, req.force)?;
            }
            return Err(e);
        }
    };
    report.command = Some(shell_words::join(
        std::env::args_os().map(|a| a.to_string_lossy().into_owned()),
    ));
    let cfg = &report.run.config;
    write_outputs(&cfg.out, cfg.force, &data, &report)?;
    if let Some(c) = &report.model_choice {
        term::print(&c.text())?;
    }
    term::print(&report.table())?;
    if let Some(e) = &report.run.ensemble {
        term::print(&e.table())?;
    }
    if let Some(t) = &report.run.track {
        term::print(&t.line())?;
    }
    for w in &report.run.warnings {
        term::eprint_line(&format!("warning: {w}"));
    }
    term::print(&report.verdict.text())?;
    if !cfg.quiet {
        term::eprint_line(&format!(
            "report: {}  (report.json, metrics.csv and the plots beside it)",
            cfg.out.join("report.html").display()
        ));
    }
    if report.verdict.grade == Grade::Unreliable {
        return Err(EstimateError::Unreliable(cfg.out.join("report.json")).into());
    }
    Ok(())
}

/// The object's track (`guide`), then the model's choice where the request makes one
/// ([`chooses`]) or one estimation; writes nothing.
pub fn estimation(req: &Request) -> anyhow::Result<Estimation> {
    estimation_watched(req, Watch::default())
}

/// [`estimation`], followed and stopped as `watch` says.
pub fn estimation_watched(req: &Request, watch: Watch) -> anyhow::Result<Estimation> {
    cpu_threads(req.training.threads);
    let mut warnings = Vec::new();
    let route = guide::second_route(req, &mut warnings)?;
    // The frame the page will show is known now: made while the latent trains.
    if let Some(at) = route.as_ref().and_then(TrackRoute::shown_at) {
        physvid_shared::video::still_ahead(req.input(), at);
    }
    let guided = route
        .as_ref()
        .and_then(|r| guide::request(req, r, chooses(req)));
    let req = guided.as_ref().map_or(req, |(g, _)| g);
    let steadied = route.as_ref().and_then(|r| guide::steadied(req, r));
    let req = steadied.as_ref().map_or(req, |(g, _)| g);
    let mut est = if chooses(req) {
        choose(req, watch)?
    } else {
        estimate(req, watch)?
    };
    warnings.extend(guided.map(|(_, why)| why));
    warnings.extend(steadied.map(|(_, why)| why));
    guide::settle(&mut est.report, route, warnings);
    Ok(est)
}

/// Loads the data and trains (and the ensemble's further members); writes nothing.
pub fn estimate(req: &Request, watch: Watch) -> anyhow::Result<Estimation> {
    let start = Instant::now();
    let (cfg, data, device) = loaded(req)?;
    let cfg = &cfg;
    let model = cfg.model;
    // The given (or default) start and those read off the frames; the best after a short
    // probe is trained to the end.
    let mut starts = vec![cfg.init.clone()];
    if !cfg.single_start {
        starts.extend(model.extra_starts(&data.train, cfg.dt, cfg.integrator, &cfg.init));
        if model.calibrates_in_training() && cfg.calibration.reference.len() >= 2 {
            // The map is fitted to the reference frames at every step: starts that differ only
            // in it are one start.
            let physical = |s: &[f64]| -> Vec<u64> {
                s.iter()
                    .zip(model.parameters())
                    .filter(|(_, p)| p.settles != Settles::Map)
                    .map(|(v, _)| v.to_bits())
                    .collect()
            };
            let mut seen = Vec::new();
            starts.retain(|s| {
                let key = physical(s);
                let new = !seen.contains(&key);
                seen.push(key);
                new
            });
        }
    }
    let names = model.parameter_names();
    let progress = Progress::new(cfg.epochs, cfg.quiet || watch.epoch.is_some());
    let quiet = cfg.quiet;
    let (outcome, probes) = fit_best(
        cfg,
        &data,
        device,
        &starts,
        &mut |rec| match watch.epoch {
            Some(f) => f(rec, &names),
            None => progress.epoch(rec, &names),
        },
        &mut |msg| {
            if !quiet {
                term::eprint(msg);
            }
        },
        Cancel(watch.cancel),
    )?;
    progress.finish();
    let chosen = probes
        .iter()
        .find(|p| p.chosen)
        .map_or(&starts[0], |p| &p.initial)
        .clone();
    let info = |start: Instant| RunInfo {
        device,
        threads: cfg.threads,
        wall: start.elapsed(),
    };
    // Further members of an ensemble: the same clips and starts (the start that won alone
    // where one trained to the end after the probe won), seeds --seed+1 … --seed+K−1.
    let member_starts = match probes.iter().find(|p| p.chosen && p.note.is_some()) {
        Some(p) => vec![p.initial.clone()],
        None => starts.clone(),
    };
    let run = Run::new(cfg, &data, info(start), &chosen, outcome).with_starts(probes);
    if let Some(why) = failure(&run) {
        return Err(EstimateError::NoEstimate(why).into());
    }
    let verdict = verdict::judge(&run);
    let mut report = Report::new(run, verdict);
    let (mut members, mut failed) = (Vec::new(), Vec::new());
    for i in 1..cfg.ensemble {
        let member = cfg.with_seed(cfg.seed + i as u64);
        if !cfg.quiet {
            eprintln!(
                "ensemble member {}/{} (seed {})",
                i + 1,
                cfg.ensemble,
                member.seed
            );
        }
        let cancel = Cancel(watch.cancel);
        let (o, _) = fit(&member, &data, device, &member_starts, &mut |_| {}, cancel)?;
        let r = Run::new(&member, &data, info(start), &chosen, o);
        match failure(&r) {
            Some(why) => failed.push(format!("seed {}: {why}", member.seed)),
            None => members.push((member.seed, r.parameters)),
        }
    }
    if cfg.ensemble > 1 {
        members.insert(0, (cfg.seed, report.run.parameters.clone()));
        if !failed.is_empty() {
            report.run.warnings.push(format!(
                "ensemble: {} of {} members gave no estimate and are left out of the spread ({})",
                failed.len(),
                cfg.ensemble,
                failed.join("; ")
            ));
        }
        if members.len() >= 2 {
            let (seeds, params): (Vec<u64>, Vec<_>) = members.into_iter().unzip();
            report.run.ensemble = Some(summarise(seeds, &params));
        } else {
            report.run.warnings.push(
                "ensemble: fewer than two members gave an estimate: no spread is reported"
                    .to_string(),
            );
        }
    }
    Ok(Estimation { report, data })
}

/// The configuration `req` resolves to, the clips it loads (with what the device and the
/// frames add to their warnings) and the device they are on.
fn loaded(req: &Request) -> anyhow::Result<(RunConfig, ClipData, Device)> {
    cpu_threads(req.training.threads);
    let (device, device_warning) = select_device(req.training.device)?;
    let cfg = RunConfig::resolve(req, probe(&req.load)?)?;
    let mut data = load_clips(&cfg.request, &cfg.plan, cfg.model, device)?;
    data.warnings.extend(device_warning);
    let cfg = cfg.with_frames(&data)?;
    data.warnings.extend(cfg.encoder_note.clone());
    data.warnings.extend(cfg.reference_notes.iter().cloned());
    Ok((cfg, data, device))
}

/// Why a run gave no estimate, if it did not: no epoch with a finite validation error (the
/// kept values would be the starting ones), or an estimate (learned or derived in SI) that is
/// not finite.
fn failure(run: &Run) -> Option<String> {
    let outcome = &run.outcome;
    if outcome.best_epoch == 0 {
        let when = match &outcome.stop {
            StopReason::NonFiniteLoss { epoch } => {
                format!("the loss was not finite at epoch {epoch}")
            }
            StopReason::LawNotFinite { detail, .. } => {
                return Some(format!(
                    "the law gives no finite value: {detail}; check the model's expressions \
                     (a division by zero, a root or logarithm of a negative number, an \
                     overflowing exponential) against the latent's range"
                ))
            }
            _ => "no epoch had a finite validation error".to_string(),
        };
        return Some(format!(
            "training diverged ({when}); lower --lr / --lr-phys, start elsewhere with --init, or check dt"
        ));
    }
    if outcome.parameters.iter().any(|p| !p.is_finite()) {
        return Some("a parameter came out infinite or NaN; start elsewhere with --init".into());
    }
    run.parameters
        .iter()
        .find(|p| !p.estimate.is_finite())
        .map(|p| {
            format!(
                "{} came out {} (the data cannot give it at this dt and calibration)",
                p.name, p.estimate
            )
        })
}
