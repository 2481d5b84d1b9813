//! report.json as data: `Report`, the pipeline's `Run` beside its verdict and the model
//! choice, with what names the tool that wrote it. Built last, from what the layers below
//! returned; `text.rs` prints it, `output.rs` writes it.

pub mod text;

use crate::analysis::Run;
use crate::choice::rank::ModelChoice;
use crate::verdict::Verdict;
use serde::Serialize;

/// libtorch's version, read from the linked installation at build time.
pub const LIBTORCH_VERSION: &str = env!("PHYSVID_LIBTORCH_VERSION");

/// Everything `report.json` holds.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    pub tool: String,
    /// The command line that produced the report (set by `run`; absent for library callers).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub command: Option<String>,
    pub version: String,
    pub libtorch_version: String,
    /// The fit and what was derived from it (its fields stand at the top level of the file).
    #[serde(flatten)]
    pub run: Run,
    /// The candidates tried when the model was chosen (`--model auto`), ranked.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_choice: Option<ModelChoice>,
    /// `ok`, `doubtful` or `unreliable`, with the reasons (`verdict::judge`).
    pub verdict: Verdict,
}

impl Report {
    /// The report of `run` judged `verdict`.
    pub fn new(run: Run, verdict: Verdict) -> Report {
        Report {
            tool: "estimate".into(),
            command: None,
            version: env!("CARGO_PKG_VERSION").into(),
            libtorch_version: LIBTORCH_VERSION.into(),
            run,
            model_choice: None,
            verdict,
        }
    }
}
