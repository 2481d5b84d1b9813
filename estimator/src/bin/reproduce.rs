//! `reproduce`: command-line entry point; regenerates the paper's tables (and ours) from nothing.

use clap::Parser;
use estimator::config::DeviceChoice;
use estimator::error::exit_with;
use estimator::reproduce::{run, ReproduceConfig, TableKind};
use std::path::PathBuf;
use std::process::ExitCode;

/// Regenerate the paper's tables, and ours beyond them, with one command each.
///
/// Each table renders its synthetic datasets with gen's library (seeded: seed 0 unless the table
/// varies it) into a temporary directory, trains with `estimate`'s own arguments (every row
/// names them), and writes OUT/TABLE.md and OUT/TABLE.csv, the paper's values and the ground
/// truth in their own columns. `all` also writes OUT/RESULTS.md. Deterministic on CPU. Full
/// set: about 56 minutes on 2 cores; --quick: about 2.
#[derive(Debug, Parser)]
#[command(name = "reproduce", version)]
struct Cli {
    /// Which table.
    #[arg(value_enum)]
    table: TableKind,
    /// Directory for the tables (created; files are replaced).
    #[arg(long, default_value = "results", value_name = "DIR")]
    out: PathBuf,
    /// Small datasets and grids: every table in about 2 minutes (what the tests run).
    #[arg(long)]
    quick: bool,
    /// Where to train.
    #[arg(long, value_enum, default_value_t = DeviceChoice::Auto)]
    device: DeviceChoice,
    /// CPU threads for libtorch (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Render datasets here and keep them (default: a temporary directory, removed after).
    #[arg(long, value_name = "DIR")]
    scratch: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return physvid_shared::cli::exit_on_clap_error(e),
    };
    let cfg = ReproduceConfig {
        table: cli.table,
        out: cli.out,
        quick: cli.quick,
        device: cli.device,
        threads: cli.threads,
        scratch: cli.scratch,
        quiet: cli.quiet,
    };
    let result = cfg
        .validate()
        .map_err(anyhow::Error::from)
        .and_then(|cfg| run(&cfg));
    exit_with("reproduce", result)
}
