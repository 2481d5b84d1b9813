//! `run`: loads the data, picks the device, trains, writes the report and plots, prints the table.

use crate::calibration::resolve;
use crate::config::{DeviceChoice, EstimateConfig, ModelKind};
use crate::data::{load_clips, ClipData};
use crate::ensemble::summarise;
use crate::error::input_error;
use crate::error::EstimateError;
use crate::loss::LossKind;
use crate::progress::Progress;
use crate::report::{write_outputs, Report, RunInfo};
use crate::spectral::spectral_start;
use crate::train::fit;
use std::time::Instant;
use tch::Device;

/// Resolves `--device`.
pub fn select_device(choice: DeviceChoice) -> Result<Device, EstimateError> {
    match choice {
        DeviceChoice::Cpu => Ok(Device::Cpu),
        DeviceChoice::Auto => Ok(Device::cuda_if_available()),
        DeviceChoice::Cuda if tch::Cuda::is_available() => Ok(Device::Cuda(0)),
        DeviceChoice::Cuda => Err(EstimateError::NoCuda),
    }
}

/// An estimation's report with the clips it was trained on.
pub struct Estimation {
    pub report: Report,
    pub data: ClipData,
}

/// Runs one estimation as configured and writes report.json, metrics.csv and the plots.
pub fn run(cfg: &EstimateConfig) -> anyhow::Result<()> {
    let Estimation { report, data } = estimate(cfg)?;
    let cfg = &report.config;
    write_outputs(cfg, &data, &report)?;
    println!("{}", report.table());
    if let Some(e) = &report.ensemble {
        println!("{}", e.table());
    }
    for w in &report.warnings {
        eprintln!("warning: {w}");
    }
    if !cfg.quiet {
        eprintln!(
            "report: {}  (metrics.csv, parameters.png, latents.png beside it)",
            cfg.out.join("report.json").display()
        );
    }
    Ok(())
}

/// Loads the data and trains (and the ensemble's further members); writes nothing.
pub fn estimate(cfg: &EstimateConfig) -> anyhow::Result<Estimation> {
    let start = Instant::now();
    let threads = cfg
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    tch::set_num_threads(threads as i32);
    let device = select_device(cfg.device)?;
    let data = load_clips(cfg, device)?;
    // From here on the model's defaults (encoder, patience) are explicit, so the report shows them.
    let cfg = &cfg.for_model(data.model);
    let init = cfg.initial_values(data.model)?;
    if cfg.loss == LossKind::ResidualFloor && data.model != ModelKind::DampedOscillator {
        return Err(input_error(format!(
            "--loss residual+floor: implemented for damped-oscillator only, not {}; use --loss mse+kl",
            data.model.name()
        ))
        .into());
    }
    let names = data.model.parameter_names();
    // Two starts: the given (or default) values and one read off the frames' principal
    // components; the better after a short probe is trained to the end.
    let mut starts = vec![init.clone()];
    if !cfg.single_start {
        // The oscillator's two-step recurrence also gives the pendulum's small-angle g/L and
        // damping; the other systems do not oscillate.
        match data.model {
            ModelKind::DampedOscillator => {
                starts.extend(spectral_start(&data.train, data.dt, cfg.integrator))
            }
            ModelKind::Pendulum => {
                // The most persistent mode of a real swing is often the second harmonic (a
                // latent like |x| oscillates at 2ω, so g/L 4× too large): its sub-harmonic is
                // probed too, and the validation error picks.
                if let Some(g) = spectral_start(&data.train, data.dt, cfg.integrator) {
                    let damping = g[1].max(0.0);
                    starts.push(vec![g[0], damping, init[2], init[3]]);
                    starts.push(vec![g[0] / 4.0, damping / 2.0, init[2], init[3]]);
                }
            }
            _ => {}
        }
    }
    let calibration = resolve(cfg, data.meta.as_ref());
    let reference = &calibration.reference;
    let [n, t, ..] = data.shape;
    if let Some(&(c, f, _)) = reference.iter().find(|&&(c, f, _)| c >= n || f >= t) {
        let origin = if calibration.source == "flags" {
            "--reference"
        } else {
            "meta.json reference point"
        };
        return Err(input_error(format!(
            "{origin} {c}:{f}: the data has clips 0..{n} and frames 0..{t}"
        ))
        .into());
    }
    let progress = Progress::new(cfg.epochs, cfg.quiet);
    let (outcome, probes) = fit(cfg, &data, device, &starts, reference, &mut |rec| {
        progress.epoch(rec, names)
    })?;
    progress.finish();
    let chosen = probes
        .iter()
        .find(|p| p.chosen)
        .map_or(&starts[0], |p| &p.initial)
        .clone();
    // Further members of an ensemble: the same clips and starts, seeds --seed+1 … --seed+K−1.
    let mut members = Vec::new();
    for i in 1..cfg.ensemble {
        let member = EstimateConfig {
            seed: cfg.seed + i as u64,
            ..cfg.clone()
        };
        if !cfg.quiet {
            eprintln!(
                "ensemble member {}/{} (seed {})",
                i + 1,
                cfg.ensemble,
                member.seed
            );
        }
        let (o, _) = fit(&member, &data, device, &starts, reference, &mut |_| {})?;
        let info = RunInfo {
            device,
            threads,
            wall: start.elapsed(),
        };
        members.push(Report::new(&member, &data, info, &chosen, o, calibration.clone()).parameters);
    }
    let info = RunInfo {
        device,
        threads,
        wall: start.elapsed(),
    };
    let mut report =
        Report::new(cfg, &data, info, &chosen, outcome, calibration).with_starts(probes);
    if cfg.ensemble > 1 {
        members.insert(0, report.parameters.clone());
        let seeds = (0..cfg.ensemble as u64).map(|i| cfg.seed + i).collect();
        report.ensemble = Some(summarise(seeds, &members));
    }
    Ok(Estimation { report, data })
}
