//! A batch's summary: one `RowResult` per row of the batch file (those of other shards marked
//! so), written as summary.json (what `--merge` reads), summary.csv (one line per row, one
//! group of columns per reported value) and summary.md (`formats.rs`).

mod formats;

use super::shard::Shard;
use serde::{Deserialize, Serialize};

/// What summary.json holds.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Summary {
    pub format: String,
    /// The batch file as given on the command line.
    pub batch_file: String,
    pub shard: Option<Shard>,
    /// Every row of the batch file, in order.
    pub rows: Vec<RowResult>,
}

/// Where a row stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RowStatus {
    Ok,
    /// An estimate graded `unreliable` (exit code 4): counted as failed.
    Unreliable,
    Failed,
    /// Not yet run (the batch is under way).
    Pending,
    /// Not run: the batch stopped before it (a full disk, an unwritable folder).
    Stopped,
    /// Run by another shard.
    OtherShard,
    /// In no merged summary.
    NotRun,
}

impl RowStatus {
    pub fn word(self) -> &'static str {
        match self {
            RowStatus::Ok => "ok",
            RowStatus::Unreliable => "unreliable",
            RowStatus::Failed => "failed",
            RowStatus::Pending => "pending",
            RowStatus::Stopped => "stopped",
            RowStatus::OtherShard => "other shard",
            RowStatus::NotRun => "not run",
        }
    }
}

/// One reported value of a row.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Estimate {
    pub name: String,
    pub value: f64,
    pub unit: String,
    pub truth: Option<f64>,
    pub relative_error: Option<f64>,
    #[serde(default)]
    pub standard_error: Option<f64>,
}

/// One row's outcome.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RowResult {
    /// From 1, in the batch file's order.
    pub row: usize,
    /// The row's directory name.
    pub name: String,
    /// The input as the batch file gives it.
    pub input: String,
    pub model: String,
    pub status: RowStatus,
    pub exit_code: Option<i32>,
    /// A failed row's one-line error.
    pub error: Option<String>,
    pub estimates: Vec<Estimate>,
    pub epochs: Option<usize>,
    pub wall_s: Option<f64>,
    pub warnings: Vec<String>,
    /// The verdict's grade (`ok`, `doubtful`, `unreliable`) and its reasons, one line each.
    #[serde(default)]
    pub verdict: Option<String>,
    #[serde(default)]
    pub reasons: Vec<String>,
    /// The row's directory, relative to the summary's.
    pub dir: String,
    /// The command that ran the row.
    pub command: String,
}

impl Summary {
    /// The rows this summary ran (or will run): those not of another shard.
    pub fn own_rows(&self) -> impl Iterator<Item = &RowResult> {
        self.rows
            .iter()
            .filter(|r| r.status != RowStatus::OtherShard)
    }

    /// Err(`RowsFailed`) when any own row failed or was not run; `summary_md` is named in it.
    pub fn outcome(&self, summary_md: std::path::PathBuf) -> Result<(), crate::EstimateError> {
        match self.failed() {
            0 => Ok(()),
            failed => Err(crate::EstimateError::RowsFailed {
                failed,
                total: self.own_rows().count(),
                summary: summary_md,
            }),
        }
    }

    pub fn failed(&self) -> usize {
        self.own_rows()
            .filter(|r| {
                matches!(
                    r.status,
                    RowStatus::Failed
                        | RowStatus::NotRun
                        | RowStatus::Unreliable
                        | RowStatus::Stopped
                )
            })
            .count()
    }

    /// Reported value names over all rows, in order of first appearance.
    fn value_names(&self) -> Vec<String> {
        let mut names: Vec<String> = Vec::new();
        for e in self.own_rows().flat_map(|r| &r.estimates) {
            if !names.contains(&e.name) {
                names.push(e.name.clone());
            }
        }
        names
    }
}
