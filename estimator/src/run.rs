//! `run`: loads the data, picks the device, trains, writes the report and plots, prints the table.

use crate::config::{DeviceChoice, EstimateConfig};
use crate::data::load_clips;
use crate::error::EstimateError;
use crate::progress::Progress;
use crate::report::{write_outputs, Report};
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

/// Runs one estimation as configured.
pub fn run(cfg: &EstimateConfig) -> anyhow::Result<()> {
    let start = Instant::now();
    let threads = cfg
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    tch::set_num_threads(threads as i32);
    let device = select_device(cfg.device)?;
    let data = load_clips(cfg, device)?;
    let init = cfg.initial_values(data.model)?;
    let names = data.model.parameter_names();
    // Two starts: the given (or default) values and one read off the frames' principal
    // components; the better after a short probe is trained to the end.
    let mut starts = vec![init];
    if !cfg.single_start {
        starts.extend(spectral_start(&data.train, data.dt, cfg.integrator));
    }
    let progress = Progress::new(cfg.epochs, cfg.quiet);
    let (outcome, probes) = fit(cfg, &data, device, &starts, &mut |rec| {
        progress.epoch(rec, names)
    })?;
    progress.finish();
    let chosen = probes
        .iter()
        .find(|p| p.chosen)
        .map_or(&starts[0], |p| &p.initial)
        .clone();
    let report = Report::new(
        cfg,
        &data,
        device,
        threads,
        &chosen,
        outcome,
        start.elapsed(),
    )
    .with_starts(probes);
    write_outputs(cfg, &data, &report)?;
    println!("{}", report.table());
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
