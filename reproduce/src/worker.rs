//! One estimation as the tables read it ([`Run`]), and the process that runs one on its own for
//! `--jobs N`: libtorch's seed is process-wide, so estimations side by side in one process
//! would draw from one generator and lose their determinism. The parent writes a table row's
//! typed `Request` (`options::request`) beside the report's path in JSON and starts this same
//! binary with [`WORKER`] set to that path; the worker reads the request, runs it, and writes
//! the report there in CBOR (its floats as they are: JSON would write a NaN as null, and read it back as no
//! number), which the parent reads back.

use estimator::analysis::ensemble::Ensemble;
use estimator::analysis::parameters::ParameterResult;
use estimator::analysis::truth::LatentVsTruth;
use estimator::choice::candidate::ModelChoice;
use estimator::report::Report;
use estimator::train::outcome::EpochRecord;
use estimator::verdict::Verdict;
use estimator::{estimation, Request};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::process::{Command, ExitCode, Stdio};

/// Set to the report's path in a worker's environment; its request lies beside it
/// ([`request_path`]).
pub const WORKER: &str = "PHYSVID_REPRODUCE_WORKER";

/// Where a worker writing `report` finds its request.
fn request_path(report: &Path) -> std::path::PathBuf {
    report.with_extension("request.json")
}

/// What the tables read of one estimation: report.json's fields of the same names.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Run {
    /// The model of the answer (the chosen one's, where a choice was made).
    pub model: String,
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
    /// The object's track, as far as the tables read it (absent: no track).
    #[serde(default)]
    pub track: Option<Track>,
}

/// Of report.json's `track`: each law's values (in its own units and in SI) and the law chosen.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct Track {
    #[serde(default)]
    pub laws: Vec<TrackLaw>,
    #[serde(default)]
    pub chosen: Option<String>,
}

/// One law on the track: its name, its values and its values in SI (by a stick or on a plane).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct TrackLaw {
    pub law: String,
    #[serde(default)]
    pub values: Vec<SiValue>,
    #[serde(default)]
    pub si: Vec<SiValue>,
}

/// A value and its unit.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SiValue {
    pub name: String,
    pub value: f64,
    pub unit: String,
}

impl Track {
    /// The chosen law.
    pub fn chosen_law(&self) -> Option<&TrackLaw> {
        self.laws
            .iter()
            .find(|l| Some(&l.law) == self.chosen.as_ref())
    }

    /// The chosen law's values in SI.
    pub fn si(&self) -> &[SiValue] {
        self.chosen_law().map_or(&[], |l| &l.si)
    }

    /// A value of the chosen law by name, in its own units.
    pub fn value(&self, name: &str) -> Option<f64> {
        let law = self.chosen_law()?;
        law.values.iter().find(|v| v.name == name).map(|v| v.value)
    }
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

/// A worker's whole life: the estimation of the request beside `report`, its report written
/// to `report`.
pub fn main(report: &Path) -> ExitCode {
    let result = (|| -> anyhow::Result<()> {
        let path = request_path(report);
        let text = std::fs::read_to_string(&path)?;
        let req: Request = serde_json::from_str(&text)
            .map_err(|e| anyhow::anyhow!("{}: not a request: {e}", path.display()))?;
        let r = estimation(&req)?.report;
        physvid_shared::write_atomic(report, &encoded(&r)?)?;
        Ok(())
    })();
    estimator::error::exit_with("reproduce (worker)", result)
}

/// Runs `req` in a worker process, handed over in JSON, and reads its run back from `report`;
/// `what` names it in an error.
pub fn estimate_apart(req: &Request, report: &Path, what: &str) -> anyhow::Result<Run> {
    let request = request_path(report);
    physvid_shared::write_atomic(&request, serde_json::to_string(req)?.as_bytes())?;
    let exe = std::env::current_exe()?;
    let mut command = Command::new(exe);
    command.env(WORKER, report);
    physvid_shared::child::die_with_parent(&mut command);
    command
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let out = physvid_shared::interrupt::run_child(&mut command);
    let _ = std::fs::remove_file(&request);
    let out = out?;
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        anyhow::bail!("{what} failed ({}): {}", out.status, stderr.trim());
    }
    let bytes = std::fs::read(report)?;
    let run = ciborium::from_reader(bytes.as_slice())
        .map_err(|e| anyhow::anyhow!("{}: not a report: {e}", report.display()))?;
    let _ = std::fs::remove_file(report);
    Ok(run)
}
