//! One estimation as the tables read it ([`Run`]), and the process that runs one on its own for
//! `--jobs N`: libtorch's seed is process-wide, so estimations side by side in one process
//! would draw from one generator and lose their determinism. The parent starts this same
//! binary with [`WORKER`] set to a file; it parses `estimate`'s arguments, runs them, and
//! writes the report there in CBOR (its floats as they are: JSON would write a NaN as null,
//! and read it back as no number), which the parent reads back.

use clap::Parser;
use estimator::choice::candidate::ModelChoice;
use estimator::report::ensemble::Ensemble;
use estimator::report::parameters::ParameterResult;
use estimator::report::truth::LatentVsTruth;
use estimator::report::Report;
use estimator::train::outcome::EpochRecord;
use estimator::verdict::Verdict;
use estimator::{estimation, EstimateArgs};
use serde::Deserialize;
use std::path::Path;
use std::process::{Command, ExitCode, Stdio};

/// Set to the report's path in a worker's environment; its arguments are `estimate`'s.
pub const WORKER: &str = "PHYSVID_REPRODUCE_WORKER";

/// What the tables read of one estimation: report.json's fields of the same names.
#[derive(Debug, Clone, Deserialize)]
pub struct Run {
    pub parameters: Vec<ParameterResult>,
    pub verdict: Verdict,
    pub model_choice: Option<ModelChoice>,
    pub latent_vs_truth: Option<LatentVsTruth>,
    pub ensemble: Option<Ensemble>,
    pub history: Vec<EpochRecord>,
    pub initial_values: Vec<f64>,
    pub final_values: Vec<f64>,
    pub epochs_run: usize,
    pub wall_time_s: f64,
}

impl Run {
    /// `report` as the tables read it (through its CBOR, as a worker's comes back).
    pub fn of(report: &Report) -> anyhow::Result<Run> {
        Ok(ciborium::from_reader(encoded(report)?.as_slice())?)
    }

    /// A value by name.
    pub fn value(&self, name: &str) -> Option<&ParameterResult> {
        self.parameters.iter().find(|p| p.name == name)
    }
}

/// `report` in CBOR.
fn encoded(report: &Report) -> anyhow::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    ciborium::into_writer(report, &mut bytes)?;
    Ok(bytes)
}

/// Parses `args` (`estimate`'s, the program's name first) and runs them in this process.
pub fn estimate_here(args: &[String]) -> anyhow::Result<Report> {
    let args = EstimateArgs::try_parse_from(args)
        .map_err(|e| anyhow::anyhow!("internal flags {args:?}: {e}"))?
        .validate()?;
    Ok(estimation(&args)?.report)
}

/// A worker's whole life: the estimation of its arguments, its report written to `report`.
pub fn main(report: &Path) -> ExitCode {
    // The program's path, then "estimate" as the program's name of `estimate`'s arguments.
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = estimate_here(&args).and_then(|r| {
        physvid_shared::write_atomic(report, &encoded(&r)?)?;
        Ok(())
    });
    estimator::error::exit_with("reproduce (worker)", result)
}

/// Runs `args` (`estimate`'s, without the program's name) in a worker process and reads its
/// run back from `report`.
pub fn estimate_apart(args: &[String], report: &Path) -> anyhow::Result<Run> {
    let exe = std::env::current_exe()?;
    let mut command = Command::new(exe);
    command.arg("estimate").args(args).env(WORKER, report);
    physvid_shared::child::die_with_parent(&mut command);
    command
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let out = physvid_shared::interrupt::run_child(&mut command)?;
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        anyhow::bail!(
            "estimate {} failed ({}): {}",
            args.join(" "),
            out.status,
            stderr.trim()
        );
    }
    let bytes = std::fs::read(report)?;
    let run = ciborium::from_reader(bytes.as_slice())
        .map_err(|e| anyhow::anyhow!("{}: not a report: {e}", report.display()))?;
    let _ = std::fs::remove_file(report);
    Ok(run)
}
