//! `reproduce`: regenerates the paper's tables (and ours beyond them) from nothing. A driver
//! outside the libraries: each table renders its datasets with `gen`'s library into a scratch
//! directory, trains with the same arguments a user would give `estimate`, and writes
//! `<out>/<table>.md` and `<table>.csv`. One file per table.

mod coverage;
mod init;
mod losses;
mod model_choice;
mod noise;
mod options;
mod others;
mod real;
mod recordings;
mod robustness;
mod runner;
mod shard;
mod spring;
mod table;
mod table3;
mod table6;
mod verdict;
mod worker;

use clap::Parser;
use estimator::cli::{parse_shard, DeviceChoice, Shard};
use estimator::error::{exit_with, input_error};
use estimator::EstimateError;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use physvid_shared::interrupt::{Kind, Registered};
use physvid_shared::write_atomic;
use runner::Runner;
use shard::{Sharded, Sharding};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// The tables `reproduce` makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum TableKind {
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
    /// Appendix A.5's two-body spring: k and the rest length from two starts, without
    /// clutter, in colour, on 30-frame clips.
    Spring,
    /// The verdict on default runs of every scene (its false alarms) and on constructed
    /// failures (a harmonic, frames out of order, a still scene, the wrong law, short clips).
    Verdict,
    /// Perturbed scenes (texture, distractors, shake, drift, light, occluder, noise; levels
    /// 1–5) on the oscillator's scenes and the pendulum: error and verdict.
    Robustness,
    /// The model chosen by the evidence (--model auto) on every built-in system of one latent
    /// number, clean and under footage of others: the share chosen right, the confusion.
    ModelChoice,
    /// The verdict on the shared real recordings (--recordings) with their README's readings:
    /// every candidate's answer right or wrong, the detection and false-alarm rates.
    Real,
    /// The verdict on footage rendered by others (`scripts/others_suite.py`: a rod and bob
    /// under clutter, shake, light, occlusion, noise; levels 1–5), no model given: right or
    /// wrong, the detection and false-alarm rates.
    Others,
    /// Every table above, one after another.
    All,
}

impl TableKind {
    const EACH: [TableKind; 12] = [
        TableKind::Table3,
        TableKind::Table6,
        TableKind::Init,
        TableKind::Losses,
        TableKind::Noise,
        TableKind::Coverage,
        TableKind::Spring,
        TableKind::Verdict,
        TableKind::Robustness,
        TableKind::ModelChoice,
        TableKind::Real,
        TableKind::Others,
    ];

    fn name(self) -> &'static str {
        match self {
            TableKind::Table3 => "table3",
            TableKind::Table6 => "table6",
            TableKind::Init => "init",
            TableKind::Losses => "losses",
            TableKind::Noise => "noise",
            TableKind::Coverage => "coverage",
            TableKind::Spring => "spring",
            TableKind::Verdict => "verdict",
            TableKind::Robustness => "robustness",
            TableKind::ModelChoice => "model-choice",
            TableKind::Real => "real",
            TableKind::Others => "others",
            TableKind::All => "all",
        }
    }

    fn make(self, r: &Runner) -> anyhow::Result<table::Table> {
        match self {
            TableKind::Table3 => table3::make(r),
            TableKind::Table6 => table6::make(r),
            TableKind::Init => init::make(r),
            TableKind::Losses => losses::make(r),
            TableKind::Noise => noise::make(r),
            TableKind::Coverage => coverage::make(r),
            TableKind::Spring => spring::make(r),
            TableKind::Verdict => verdict::make(r),
            TableKind::Robustness => robustness::make(r),
            TableKind::ModelChoice => model_choice::make(r),
            TableKind::Real => real::make(r),
            TableKind::Others => others::make(r),
            TableKind::All => unreachable!("expanded before"),
        }
    }
}

/// Regenerate the paper's tables, and ours beyond them, with one command each.
///
/// Each table renders its synthetic datasets with gen's library (seeded: seed 0 unless the table
/// varies it) into a temporary directory, trains with `estimate`'s own options (every row
/// names them as flags), and writes OUT/TABLE.md and OUT/TABLE.csv, the paper's values and the ground
/// truth in their own columns. `all` also writes OUT/RESULTS.md. Deterministic on CPU. Full
/// set: about 2 hours on 2 cores without model-choice (each table's own time is printed under
/// it; docs/status.md lists them); --quick: about 2.5 minutes.
#[derive(Debug, Parser)]
#[command(name = "reproduce", version)]
struct Cli {
    /// Which table.
    #[arg(value_enum)]
    table: TableKind,
    /// Directory for the tables (created; files are replaced).
    #[arg(long, default_value = "docs/results", value_name = "DIR")]
    out: PathBuf,
    /// Small datasets and grids: every table in about 2.5 minutes (what the tests run).
    #[arg(long)]
    quick: bool,
    /// Where to train.
    #[arg(long, value_enum, default_value_t = DeviceChoice::Auto)]
    device: DeviceChoice,
    /// CPU threads for libtorch in each estimation, 1 to 256 (default: all cores; with
    /// --jobs N, the cores / N for each of the N).
    #[arg(long, value_parser = physvid_shared::cli::thread_count)]
    threads: Option<usize>,
    /// Estimations run side by side, each in a process of its own, 1 to 256 (default 1: one
    /// at a time; the verdict table always one at a time). The numbers are those of a run
    /// one at a time with the same --threads.
    #[arg(long, default_value_t = 1, value_parser = physvid_shared::cli::thread_count)]
    jobs: usize,
    /// Render datasets here and keep them (default: a temporary directory, removed after the
    /// run, or when Ctrl-C, SIGTERM or SIGHUP stops it).
    #[arg(long, value_name = "DIR")]
    scratch: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
    /// The shared real recordings the `real` table reads (its README's files; those absent are
    /// left out and named).
    #[arg(long, default_value = "../shared/real-videos", value_name = "DIR")]
    recordings: PathBuf,
    /// For a cluster's job array: run only this shard's estimations of each table (those whose
    /// index i in the table's job list has i mod N = I − 1; a table of estimations that follow
    /// one another, verdict, real and others, whole in shard 1) and record them in
    /// OUT/TABLE.shard-I-of-N.cbor instead of writing the table.
    #[arg(long, value_parser = parse_shard, value_name = "I/N", conflicts_with = "merge")]
    shard: Option<Shard>,
    /// Make the tables from the records of every shard, found in these folders (their --out),
    /// running nothing: the same tables as one run makes, wall times aside.
    #[arg(long, num_args = 1.., value_name = "DIR")]
    merge: Vec<PathBuf>,
}

impl Cli {
    fn validate(self) -> Result<Cli, EstimateError> {
        physvid_shared::atomic::check_writable_dir("--out", &self.out).map_err(input_error)?;
        if let Some(scratch) = &self.scratch {
            physvid_shared::atomic::check_writable_dir("--scratch", scratch)
                .map_err(input_error)?;
        }
        Ok(self)
    }
}

fn main() -> ExitCode {
    if let Some(report) = std::env::var_os(worker::WORKER) {
        return worker::main(std::path::Path::new(&report));
    }
    physvid_shared::interrupt::install("reproduce");
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return physvid_shared::cli::exit_on_clap_error(e),
    };
    let result = cli
        .validate()
        .map_err(anyhow::Error::from)
        .and_then(|cfg| run(&cfg));
    exit_with("reproduce", result)
}

/// Makes the configured tables and writes them; prints where they are.
fn run(cfg: &Cli) -> anyhow::Result<()> {
    std::fs::create_dir_all(&cfg.out).map_err(|source| EstimateError::Write {
        path: cfg.out.clone(),
        source,
    })?;
    let (temp, _registered);
    let scratch = match &cfg.scratch {
        Some(dir) => dir.clone(),
        None => {
            // A signal removes the scratch directory this run made (gigabytes for `all`); a
            // --scratch the user named is kept, as after a run that ends.
            temp = tempfile::Builder::new().prefix("reproduce-").tempdir()?;
            _registered = Registered::new(Kind::Scratch, temp.path());
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
        jobs: cfg.jobs,
        job_threads: cfg.threads.unwrap_or_else(|| {
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            (cores / cfg.jobs).max(1)
        }),
        scratch,
        recordings: cfg.recordings.clone(),
        bar,
        lines: !cfg.quiet && !terminal,
        keep: cfg.scratch.is_some(),
        sharding: match (cfg.shard, cfg.merge.is_empty()) {
            (Some(s), _) => Some(shard::State::new(Sharding::Shard(s), cfg.quick)),
            (None, false) => Some(shard::State::new(
                Sharding::Merge(cfg.merge.clone()),
                cfg.quick,
            )),
            (None, true) => None,
        },
    };
    let kinds: Vec<TableKind> = match cfg.table {
        TableKind::All => TableKind::EACH.to_vec(),
        k => vec![k],
    };
    let mut tables = Vec::new();
    for kind in kinds {
        let start = Instant::now();
        let made = kind.make(&runner);
        if let (Some(s), Some(shard)) = (runner.sharding.as_ref(), cfg.shard) {
            match made {
                Err(e) if e.downcast_ref::<Sharded>().is_none() => return Err(e),
                _ => {}
            }
            let (path, n) = s.write(&cfg.out)?;
            runner.bar.suspend(|| {
                eprintln!(
                    "{}: shard {}/{}: {n} estimations, {:.0} s → {}",
                    kind.name(),
                    shard.index,
                    shard.count,
                    start.elapsed().as_secs_f64(),
                    path.display()
                )
            });
            continue;
        }
        let mut table = made?;
        table.wall_s = start.elapsed().as_secs_f64();
        // The flags its numbers depend on (threads per estimation) and how it ran (jobs).
        table.command = format!("reproduce {}", kind.name());
        if cfg.quick {
            table.command += " --quick";
        }
        if cfg.jobs > 1 {
            table.command += &format!(" --jobs {}", cfg.jobs);
        }
        if let Some(t) = cfg.threads {
            table.command += &format!(" --threads {t}");
        }
        if !cfg.merge.is_empty() {
            table.command +=
                " (run in shards, --shard I/N, and merged: the wall time is the merge's)";
        }
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
    if cfg.table == TableKind::All && cfg.shard.is_none() {
        let mut s = String::from("# Reproduced tables\n\n");
        for t in &tables {
            s += &t.markdown();
            s += "\n";
        }
        let total: f64 = tables.iter().map(|t| t.wall_s).sum();
        s += &format!("All tables: {total:.0} s.\n");
        write_atomic(&cfg.out.join("RESULTS.md"), s.as_bytes())?;
    }
    for t in &tables {
        physvid_shared::term::print(&t.markdown())?;
    }
    Ok(())
}
