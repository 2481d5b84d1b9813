//! `DataSpec` (a dataset as `gen` would make it, from the same arguments) and `Runner`, which
//! renders datasets into a scratch directory and runs estimations as `estimate` would, with one
//! progress bar over a table's runs.

use clap::{Parser, ValueEnum};
use estimator::cli::DeviceChoice;
use estimator::report::parameters::ParameterResult;
use estimator::report::Report;
use estimator::{estimation, EstimateArgs};
use generator::{generate_to_disk, GenArgs, SceneRef};
use indicatif::ProgressBar;
use std::path::{Path, PathBuf};

/// A dataset as `gen` would make it.
#[derive(Debug, Clone, PartialEq)]
pub struct DataSpec {
    pub scenario: &'static str,
    pub samples: usize,
    pub size: usize,
    /// Frames per clip and dt (the scene's default when `None`).
    pub frames: Option<usize>,
    pub dt: Option<f64>,
    pub setting: u8,
    pub seed: u64,
    pub noise: f64,
    /// Further `gen` arguments (`--set NAME=VALUE`, `--color`, `--perturb NAME:LEVEL`).
    pub extra: Vec<String>,
}

impl DataSpec {
    /// The paper's set (500 clips of 50×50), or a small one for `--quick`.
    pub fn new(scenario: &'static str, quick: bool) -> DataSpec {
        DataSpec {
            scenario,
            samples: if quick { 120 } else { 500 },
            size: if quick { 32 } else { 50 },
            frames: None,
            dt: None,
            setting: 1,
            seed: 0,
            noise: 0.0,
            extra: Vec::new(),
        }
    }

    /// The `gen` arguments that write this dataset (without `--out`).
    pub fn args(&self) -> Vec<String> {
        let mut a = vec![
            "--scenario".to_string(),
            self.scenario.into(),
            "--samples".into(),
            self.samples.to_string(),
            "--size".into(),
            self.size.to_string(),
        ];
        let mut add = |flag: &str, value: String| a.extend([flag.to_string(), value]);
        if SceneRef::by_name(self.scenario).is_some_and(|s| s.has_settings()) {
            add("--setting", self.setting.to_string());
        }
        if let Some(f) = self.frames {
            add("--frames", f.to_string());
        }
        if let Some(dt) = self.dt {
            add("--dt", dt.to_string());
        }
        if self.noise > 0.0 {
            add("--noise", self.noise.to_string());
        }
        add("--seed", self.seed.to_string());
        a.extend(self.extra.iter().map(|e| e.to_string()));
        a
    }

    /// The `gen` command that writes this dataset.
    pub fn command(&self) -> String {
        format!("gen {}", self.args().join(" "))
    }
}

/// Renders datasets and runs estimations for the tables, with one progress bar over the runs.
pub struct Runner {
    pub(crate) quick: bool,
    pub(crate) device: DeviceChoice,
    pub(crate) threads: Option<usize>,
    pub(crate) scratch: PathBuf,
    pub(crate) bar: ProgressBar,
    /// stderr is not a terminal (a log file, CI): one line per finished run instead of the bar.
    pub(crate) lines: bool,
    /// `--scratch` was given: keep every dataset there.
    pub(crate) keep: bool,
}

impl Runner {
    pub fn quick(&self) -> bool {
        self.quick
    }

    /// Starts a table of `runs` estimations.
    pub fn begin(&self, table: &str, runs: usize) {
        self.bar.set_length(runs as u64);
        self.bar.set_position(0);
        self.bar.set_prefix(table.to_string());
        self.bar.reset_elapsed();
    }

    /// Renders `spec` into the scratch directory (once; later calls reuse it).
    pub fn dataset(&self, spec: &DataSpec) -> anyhow::Result<PathBuf> {
        let dir = self.scratch.join(
            spec.command()
                .replace("gen ", "")
                .replace("--", "")
                .replace([' ', '='], "_"),
        );
        if !dir.join("meta.json").exists() {
            self.bar.set_message(spec.command());
            let mut args = spec.args();
            args.extend(["--out".into(), dir.display().to_string(), "--force".into()]);
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            generate_to_disk(&GenArgs::config_from(&args)?)?;
        }
        Ok(dir)
    }

    /// Deletes a dataset no later run needs (the coverage table renders twenty), unless the
    /// user asked to keep them with `--scratch`.
    pub fn discard(&self, dir: &Path) {
        if !self.keep {
            let _ = std::fs::remove_dir_all(dir);
        }
    }

    /// Trains on `data` as `estimate DATA FLAGS...` would (quietly, outputs discarded; every
    /// candidate with `--model auto`).
    pub fn estimate(&self, data: &Path, flags: &[&str]) -> anyhow::Result<Report> {
        self.bar
            .set_message(format!("estimate {}", flags.join(" ")));
        let out = self.scratch.join("run");
        let mut args: Vec<String> = vec!["estimate".into(), data.display().to_string()];
        args.extend(flags.iter().map(|f| f.to_string()));
        args.extend(["--quiet".into(), "--out".into(), out.display().to_string()]);
        let device = self
            .device
            .to_possible_value()
            .expect("no skipped variants");
        args.extend(["--device".into(), device.get_name().into()]);
        if let Some(t) = self.threads {
            args.extend(["--threads".into(), t.to_string()]);
        }
        let args = EstimateArgs::try_parse_from(&args)
            .map_err(|e| anyhow::anyhow!("internal flags {args:?}: {e}"))?
            .validate()?;
        let report = estimation(&args)?.report;
        self.bar.inc(1);
        if self.lines {
            eprintln!(
                "{} {}/{}: estimate {} ({:.1} s)",
                self.bar.prefix(),
                self.bar.position(),
                self.bar.length().unwrap_or(0),
                flags.join(" "),
                report.wall_time_s
            );
        }
        Ok(report)
    }
}

/// Looks a reported value up by name.
pub fn value<'a>(report: &'a Report, name: &str) -> Option<&'a ParameterResult> {
    report.parameters.iter().find(|p| p.name == name)
}
