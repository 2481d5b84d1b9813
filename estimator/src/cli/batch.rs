//! The batch flags: `--batch FILE` (many recordings or data sets in one command), `--shard I/N`
//! (a job array's share of the rows) and `--merge DIR...` (the shards' summaries joined). The
//! driver is `batch::run`.

pub use crate::batch::shard::{parse_shard, Shard};
use std::path::PathBuf;

/// Many inputs in one command, and the shards of a large batch joined.
#[derive(Debug, Clone, clap::Args)]
#[command(next_help_heading = "Batch")]
pub struct BatchArgs {
    /// Run every row of a CSV file, one after another with all cores, each into its own
    /// directory under --out, and write summary.csv, summary.md, summary.json and index.html
    /// there. Columns: `input` (required; relative paths are taken from the CSV's folder), `name`
    /// (the row's directory, default its input's name), `truth` (known values, NAME=VALUE;...,
    /// compared in the summary), and any flag of this command without its dashes (`model`,
    /// `start`, `end`, `crop`, `fps`, `reference`, `epochs`, ...; an empty cell keeps the
    /// command line's value, `true` sets a switch). Flags given on the command line apply to
    /// every row. Exit code 1 when any row failed (the others still run).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["input", "merge"])]
    pub batch: Option<PathBuf>,
    /// With --batch: run only rows I, I+N, I+2N, ... (1 ≤ I ≤ N), e.g. `--shard
    /// $SLURM_ARRAY_TASK_ID/N` in a job array of N tasks numbered from 1, each with its own --out;
    /// then join them with --merge.
    #[arg(long, value_name = "I/N", value_parser = parse_shard)]
    pub shard: Option<Shard>,
    /// Join the summaries of batch output directories (the shards of one batch file) into
    /// --out: summary.csv, summary.md, summary.json and index.html linking every row's report.
    /// Rows that no directory ran are listed as not run (exit code 1).
    #[arg(long, value_name = "DIR", num_args = 1.., conflicts_with = "input")]
    pub merge: Vec<PathBuf>,
}

impl BatchArgs {
    /// `--shard` only with `--batch`.
    pub fn validate(&self) -> Result<(), crate::EstimateError> {
        if self.shard.is_some() && self.batch.is_none() {
            return Err(crate::error::input_error(
                "--shard splits a --batch file's rows: give --batch FILE with it",
            ));
        }
        Ok(())
    }
}
