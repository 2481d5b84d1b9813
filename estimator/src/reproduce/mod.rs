//! `reproduce`: regenerates the paper's tables (and ours beyond them) from nothing: each table
//! renders its datasets with `gen`'s library into a scratch directory, trains with the same
//! arguments a user would give `estimate`, and writes `<out>/<table>.md` and `<table>.csv`.

pub mod coverage;
pub mod init;
pub mod losses;
pub mod noise;
pub mod table;
pub mod table3;
pub mod table6;

use crate::cli::EstimateArgs;
use crate::config::DeviceChoice;
use crate::error::input_error;
use crate::report::Report;
use crate::run::estimate;
use clap::{Parser, ValueEnum};
use generator::delfys::System;
use generator::{generate_to_disk, GenConfig, Scenario};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;
pub use table::{Cell, Table};

/// The tables `reproduce` makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum TableKind {
    /// Appendix Table 3: MSE+KL against MSE only, both integrators (intensity set).
    Table3,
    /// Appendix Table 6: the estimate as dt changes (intensity, Torricelli, pendulum).
    Table6,
    /// Robustness to the initial γ0, γ1 (three scenes × seven starts × five seeds).
    Init,
    /// MSE+KL rollout against the ICML 2026 peer's residual+floor loss (three scenes).
    Losses,
    /// Accuracy as Gaussian pixel noise rises (three scenes, ensembles of 3).
    Noise,
    /// Is the ensemble's spread honest? Truth within mean ± 2 std over 20 intensity sets.
    Coverage,
    /// Every table above, one after another.
    All,
}

impl TableKind {
    pub const EACH: [TableKind; 6] = [
        TableKind::Table3,
        TableKind::Table6,
        TableKind::Init,
        TableKind::Losses,
        TableKind::Noise,
        TableKind::Coverage,
    ];

    pub fn name(self) -> &'static str {
        match self {
            TableKind::Table3 => "table3",
            TableKind::Table6 => "table6",
            TableKind::Init => "init",
            TableKind::Losses => "losses",
            TableKind::Noise => "noise",
            TableKind::Coverage => "coverage",
            TableKind::All => "all",
        }
    }
}

/// Settings of one `reproduce` run.
#[derive(Debug, Clone, PartialEq)]
pub struct ReproduceConfig {
    pub table: TableKind,
    pub out: PathBuf,
    /// Small datasets and grids (under 3 minutes for everything): what the tests run.
    pub quick: bool,
    pub device: DeviceChoice,
    pub threads: Option<usize>,
    /// Where datasets are rendered (a fresh temporary directory when `None`; removed after).
    pub scratch: Option<PathBuf>,
    /// No progress bar.
    pub quiet: bool,
}

impl ReproduceConfig {
    pub fn validate(self) -> Result<ReproduceConfig, crate::EstimateError> {
        if self.threads == Some(0) {
            return Err(input_error("--threads 0: must be at least 1"));
        }
        if self.out.is_file() {
            return Err(input_error(format!(
                "--out {}: is a file; give a directory (created if missing)",
                self.out.display()
            )));
        }
        Ok(self)
    }
}

/// A dataset as `gen` would make it.
#[derive(Debug, Clone, PartialEq)]
pub struct DataSpec {
    pub scenario: Scenario,
    pub samples: usize,
    pub size: usize,
    /// Frames per clip and dt (the scene's default when `None`).
    pub frames: Option<usize>,
    pub dt: Option<f64>,
    pub setting: u8,
    pub seed: u64,
    pub noise: f64,
}

impl DataSpec {
    /// The paper's set (500 clips of 50×50), or a small one for `--quick`.
    pub fn new(scenario: Scenario, quick: bool) -> DataSpec {
        DataSpec {
            scenario,
            samples: if quick { 120 } else { 500 },
            size: if quick { 32 } else { 50 },
            frames: None,
            dt: None,
            setting: 1,
            seed: 0,
            noise: 0.0,
        }
    }

    fn gen_config(&self, out: PathBuf) -> GenConfig {
        let system = self.scenario.system();
        let (frames, dt) = system.map_or((20, 0.2), System::default_frames_and_dt);
        GenConfig {
            scenario: self.scenario,
            out,
            samples: self.samples,
            frames: self.frames.unwrap_or(frames),
            size: self.size,
            dt: self.dt.unwrap_or(dt),
            omega: 2.0,
            zeta: 0.04,
            seed: self.seed,
            noise: self.noise,
            force: true,
            params: system.map(|s| s.setting(self.setting)).unwrap_or_default(),
        }
    }

    /// The `gen` command that writes this dataset.
    pub fn command(&self) -> String {
        let mut s = format!(
            "gen --scenario {} --samples {} --size {}",
            self.scenario.name(),
            self.samples,
            self.size
        );
        if self.scenario.system().is_some() {
            s += &format!(" --setting {}", self.setting);
        }
        if let Some(f) = self.frames {
            s += &format!(" --frames {f}");
        }
        if let Some(dt) = self.dt {
            s += &format!(" --dt {dt}");
        }
        if self.noise > 0.0 {
            s += &format!(" --noise {}", self.noise);
        }
        s + &format!(" --seed {}", self.seed)
    }
}

/// Renders datasets and runs estimations for the tables, with one progress bar over the runs.
pub struct Runner {
    quick: bool,
    device: DeviceChoice,
    threads: Option<usize>,
    scratch: PathBuf,
    bar: ProgressBar,
    /// stderr is not a terminal (a log file, CI): one line per finished run instead of the bar.
    lines: bool,
    /// `--scratch` was given: keep every dataset there.
    keep: bool,
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
                .replace(' ', "_"),
        );
        if !dir.join("meta.json").exists() {
            self.bar.set_message(spec.command());
            let cfg = spec.gen_config(dir.clone()).validate()?;
            generate_to_disk(&cfg)?;
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

    /// Trains on `data` as `estimate DATA FLAGS...` would (quietly, outputs discarded).
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
        let cfg = EstimateArgs::try_parse_from(&args)
            .map_err(|e| anyhow::anyhow!("internal flags {args:?}: {e}"))?
            .into_config()
            .validate()?;
        let report = estimate(&cfg)?.report;
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
pub fn value<'a>(report: &'a Report, name: &str) -> Option<&'a crate::report::ParameterResult> {
    report.parameters.iter().find(|p| p.name == name)
}

/// Makes the configured tables and writes them; prints where they are.
pub fn run(cfg: &ReproduceConfig) -> anyhow::Result<()> {
    std::fs::create_dir_all(&cfg.out).map_err(|source| crate::EstimateError::Write {
        path: cfg.out.clone(),
        source,
    })?;
    let temp;
    let scratch = match &cfg.scratch {
        Some(dir) => dir.clone(),
        None => {
            temp = tempfile::Builder::new().prefix("reproduce-").tempdir()?;
            temp.path().to_path_buf()
        }
    };
    std::fs::create_dir_all(&scratch)?;
    let terminal = std::io::stderr().is_terminal();
    let bar = if cfg.quiet || !terminal {
        // Hidden bars still count, so the line fallback reads its position from them.
        ProgressBar::hidden()
    } else {
        ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::stderr())
    };
    bar.set_style(
        ProgressStyle::with_template(
            "{prefix:>8} [{bar:30}] {pos}/{len} runs, {elapsed} (eta {eta})  {wide_msg}",
        )
        .expect("valid template")
        .progress_chars("=> "),
    );
    let runner = Runner {
        quick: cfg.quick,
        device: cfg.device,
        threads: cfg.threads,
        scratch,
        bar,
        lines: !cfg.quiet && !terminal,
        keep: cfg.scratch.is_some(),
    };
    let kinds: Vec<TableKind> = match cfg.table {
        TableKind::All => TableKind::EACH.to_vec(),
        k => vec![k],
    };
    let mut tables = Vec::new();
    for kind in kinds {
        let start = Instant::now();
        let mut table = match kind {
            TableKind::Table3 => table3::make(&runner)?,
            TableKind::Table6 => table6::make(&runner)?,
            TableKind::Init => init::make(&runner)?,
            TableKind::Losses => losses::make(&runner)?,
            TableKind::Noise => noise::make(&runner)?,
            TableKind::Coverage => coverage::make(&runner)?,
            TableKind::All => unreachable!("expanded above"),
        };
        table.wall_s = start.elapsed().as_secs_f64();
        table.command = format!(
            "reproduce {}{}",
            kind.name(),
            if cfg.quick { " --quick" } else { "" }
        );
        let files = table.write(&cfg.out)?;
        runner.bar.suspend(|| {
            eprintln!(
                "{}: {:.0} s → {}",
                kind.name(),
                table.wall_s,
                files
                    .iter()
                    .map(|f| f.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        });
        tables.push(table);
    }
    runner.bar.finish_and_clear();
    if cfg.table == TableKind::All {
        let mut s = String::from("# Reproduced tables\n\n");
        for t in &tables {
            s += &t.markdown();
            s += "\n";
        }
        let total: f64 = tables.iter().map(|t| t.wall_s).sum();
        s += &format!("All tables: {total:.0} s.\n");
        crate::report::write_atomic(&cfg.out.join("RESULTS.md"), s.as_bytes())?;
    }
    for t in &tables {
        println!("{}", t.markdown());
    }
    Ok(())
}
