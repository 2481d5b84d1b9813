//! `estimate --batch FILE`: every row of a CSV file run as its own `estimate` process (a row
//! that crashes cannot take the others with it; each row's command is one a user can type),
//! one after another with all cores, each into its own directory under --out; the summary
//! (summary.json, .csv, .md and index.html) is rewritten after every row, so a stopped batch
//! still lists every row. `--merge` joins the summaries of a batch's shards (`merge.rs`).

mod file;
mod index;
mod merge;
pub mod shard;
pub mod summary;

pub use file::{command_line_flags, read_batch_file, BatchRow, BATCH_ONLY};
pub use merge::merge;

use crate::error::EstimateError;
use crate::output::OUTPUTS;
use crate::EstimateArgs;
use physvid_shared::outdir::{OutputDir, Wait};
use physvid_shared::{interrupt, term};
use std::ffi::OsString;
use std::path::Path;
use std::process::Command;
use std::time::Instant;
use summary::{Estimate, RowResult, RowStatus, Summary};

/// summary.json's `format`.
pub const SUMMARY_FORMAT: &str = "physvid-batch-summary";

/// The files a batch (or a merge) writes into its --out, besides a folder per row.
pub const SUMMARY_FILES: [&str; 4] = ["summary.json", "summary.csv", "summary.md", "index.html"];

/// `out` opened for a batch's or a merge's summaries: refused while another batch writes
/// there (two would interleave their rows and summaries).
pub fn open_out(out: &Path, force: bool) -> Result<OutputDir, EstimateError> {
    Ok(OutputDir::open(
        "--out",
        out,
        "estimate",
        &SUMMARY_FILES,
        force,
        Wait::Refuse,
    )?)
}

/// Runs the batch `args.batch.batch` with `exe` (this program) for every row of its shard;
/// `base` are the command line's flags that apply to every row. Err when the file is bad
/// (exit 2) or any row failed (exit 1).
pub fn run(args: &EstimateArgs, base: &[OsString], exe: &Path) -> anyhow::Result<()> {
    let file = args.batch.batch.as_deref().expect("a batch");
    let shard = args.batch.shard;
    let rows = read_batch_file(file)?;
    let out = &args.output.out;
    let mut dir = open_out(out, args.output.force)?;
    let mut summary = Summary {
        format: SUMMARY_FORMAT.into(),
        batch_file: file.display().to_string(),
        shard,
        rows: rows.iter().map(|r| pending(r, shard)).collect(),
    };
    let mine: Vec<&BatchRow> = rows
        .iter()
        .filter(|r| shard.is_none_or(|s| s.holds(r.number)))
        .collect();
    let ran = (|| {
        write_summary(&mut dir, &summary)?;
        for (k, row) in mine.iter().enumerate() {
            if !args.output.quiet {
                term::eprint_line(&format!(
                    "batch: row {} ({} of {}): {}",
                    row.number,
                    k + 1,
                    mine.len(),
                    row.input_text
                ));
            }
            let result = run_row(row, base, exe, &mut dir, args.output.force)?;
            if !args.output.quiet {
                term::eprint_line(&match &result.error {
                    None => format!("  ok in {:.1} s", result.wall_s.unwrap_or(0.0)),
                    Some(e) => format!("  failed: {e}"),
                });
            }
            summary.rows[row.number - 1] = result;
            write_summary(&mut dir, &summary)?;
        }
        Ok::<(), EstimateError>(())
    })();
    if let Err(e) = ran {
        // The batch stops (a full disk, an unwritable folder): its summary must not say the
        // rest are still to come.
        stopped(&mut dir, &mut summary, &e);
        return Err(e.into());
    }
    dir.finish();
    term::print(summary.markdown().trim_end())?;
    Ok(summary.outcome(out.join("summary.md"))?)
}

/// The summary of a batch that stopped on `why`: its pending rows marked so, written if the
/// folder still takes it, else the stale summaries removed.
fn stopped(dir: &mut OutputDir, summary: &mut Summary, why: &EstimateError) {
    for r in &mut summary.rows {
        if r.status == RowStatus::Pending {
            r.status = RowStatus::Stopped;
            r.error = Some(format!("the batch stopped before this row: {why:#}"));
        }
    }
    if write_summary(dir, summary).is_err() {
        let _ = dir.remove_own(&SUMMARY_FILES);
    }
}

/// Writes summary.json, summary.csv, summary.md and index.html into `dir`.
pub fn write_summary(dir: &mut OutputDir, summary: &Summary) -> Result<(), EstimateError> {
    let json = serde_json::to_vec_pretty(summary).expect("summary serialises");
    dir.write("summary.json", &json)?;
    dir.write("summary.csv", summary.csv().as_bytes())?;
    dir.write("summary.md", summary.markdown().as_bytes())?;
    dir.write("index.html", index::index_page(summary).as_bytes())?;
    Ok(())
}

/// A row before it runs.
fn pending(row: &BatchRow, shard: Option<shard::Shard>) -> RowResult {
    let own = shard.is_none_or(|s| s.holds(row.number));
    RowResult {
        row: row.number,
        name: row.dir.clone(),
        input: row.input_text.clone(),
        model: flag_value(&row.flags, "--model").unwrap_or_default(),
        status: if own {
            RowStatus::Pending
        } else {
            RowStatus::OtherShard
        },
        exit_code: None,
        error: row.problem.clone().filter(|_| own),
        estimates: Vec::new(),
        epochs: None,
        wall_s: None,
        warnings: Vec::new(),
        verdict: None,
        reasons: Vec::new(),
        dir: row.dir.clone(),
        command: String::new(),
    }
}

fn flag_value(flags: &[OsString], flag: &str) -> Option<String> {
    let i = flags.iter().rposition(|f| f == flag)?;
    flags.get(i + 1).map(|v| v.to_string_lossy().into_owned())
}

/// Runs one row as its own process and reads its report.json.
fn run_row(
    row: &BatchRow,
    base: &[OsString],
    exe: &Path,
    out: &mut OutputDir,
    force: bool,
) -> Result<RowResult, EstimateError> {
    let mut result = pending(row, None);
    let dir = out.path().join(&row.dir);
    let mut argv: Vec<OsString> = vec![row.input.clone().into()];
    argv.extend(file::merged_flags(base, &row.flags));
    argv.extend(["--out".into(), dir.clone().into(), "--quiet".into()]);
    let words: Vec<String> = std::iter::once(exe.as_os_str())
        .chain(argv.iter().map(OsString::as_os_str))
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    result.command = shell_words::join(words);
    if let Some(problem) = &row.problem {
        result.status = RowStatus::Failed;
        result.error = Some(problem.clone());
        return Ok(result);
    }
    // The row's folder, inside --out (a link planted there is refused), without a stale
    // report from an earlier batch that could pass for this row's.
    let cleared = out
        .subfolder(&row.dir)
        .map_err(EstimateError::from)
        .and_then(|d| {
            let mut own = OutputDir::open("--out", &d, "estimate", &OUTPUTS, force, Wait::Turns)?;
            own.remove_own(&OUTPUTS)?;
            own.finish();
            Ok(())
        });
    if let Err(e) = cleared {
        if !e.is_bad_input() {
            return Err(e);
        }
        result.status = RowStatus::Failed;
        result.error = Some(term::one_line(&format!("{e:#}")).into_owned());
        return Ok(result);
    }
    let start = Instant::now();
    let mut command = Command::new(exe);
    command.args(&argv);
    physvid_shared::child::die_with_parent(&mut command);
    command
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped());
    let output = interrupt::run_child(&mut command);
    result.wall_s = Some(start.elapsed().as_secs_f64());
    let output = match output {
        Ok(o) => o,
        Err(e) => {
            result.status = RowStatus::Failed;
            result.error = Some(format!("cannot start {} ({e})", exe.display()));
            return Ok(result);
        }
    };
    result.exit_code = output.status.code();
    let report = std::fs::read(dir.join("report.json")).ok();
    // Exit code 4: an estimate graded unreliable; its report is complete.
    let unreliable = output.status.code() == Some(4);
    match (output.status.success() || unreliable, report) {
        (true, Some(bytes)) => {
            read_report(&mut result, &bytes, &row.truth);
            if unreliable && result.status == RowStatus::Ok {
                result.status = RowStatus::Unreliable;
            }
        }
        (success, _) => {
            let stderr = String::from_utf8_lossy(&output.stderr);
            let last = stderr
                .lines()
                .rev()
                .find(|l| l.contains("error: "))
                .or_else(|| stderr.lines().rev().find(|l| !l.trim().is_empty()));
            result.status = RowStatus::Failed;
            result.error = Some(match (last, output.status.code()) {
                (Some(l), _) => l
                    .split_once("error: ")
                    .map_or(l, |(_, msg)| msg)
                    .trim()
                    .to_string(),
                (None, Some(c)) if !success => format!("exit code {c}"),
                (None, Some(_)) => "no report.json was written".to_string(),
                (None, None) => "killed by a signal".to_string(),
            });
        }
    }
    Ok(result)
}

/// Fills an ok row from its report.json, with the batch file's known values as truth.
fn read_report(result: &mut RowResult, bytes: &[u8], truth: &[(String, f64)]) {
    let Ok(report) = serde_json::from_slice::<serde_json::Value>(bytes) else {
        result.status = RowStatus::Failed;
        result.error = Some("report.json is not JSON".into());
        return;
    };
    result.status = RowStatus::Ok;
    result.model = report["model"].as_str().unwrap_or_default().to_string();
    result.epochs = report["epochs_run"].as_u64().map(|e| e as usize);
    result.warnings = report["warnings"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|w| w.as_str().map(String::from))
        .collect();
    result.verdict = report["verdict"]["grade"].as_str().map(String::from);
    result.reasons = report["verdict"]["reasons"]
        .as_array()
        .into_iter()
        .flatten()
        .map(|r| {
            format!(
                "{} ({}): {}",
                r["check"].as_str().unwrap_or_default(),
                r["grade"].as_str().unwrap_or_default(),
                r["detail"].as_str().unwrap_or_default()
            )
        })
        .collect();
    for p in report["parameters"].as_array().into_iter().flatten() {
        let name = p["name"].as_str().unwrap_or_default().to_string();
        let value = p["estimate"].as_f64().unwrap_or(f64::NAN);
        let given = truth.iter().find(|(n, _)| *n == name).map(|(_, v)| *v);
        let t = given.or(p["truth"].as_f64());
        result.estimates.push(Estimate {
            unit: p["unit"].as_str().unwrap_or_default().to_string(),
            truth: t,
            relative_error: t.filter(|t| *t != 0.0).map(|t| (value - t) / t),
            standard_error: p["standard_error"].as_f64(),
            name,
            value,
        });
    }
    for (n, _) in truth {
        if !result.estimates.iter().any(|e| &e.name == n) {
            let names: Vec<&str> = result.estimates.iter().map(|e| e.name.as_str()).collect();
            result.warnings.push(format!(
                "truth names '{n}', which this model does not report (it reports {})",
                names.join(", ")
            ));
        }
    }
}
