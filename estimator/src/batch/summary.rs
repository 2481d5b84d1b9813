//! A batch's summary: one `RowResult` per row of the batch file (those of other shards marked
//! so), written as summary.json (what `--merge` reads), summary.csv (one line per row, one
//! group of columns per reported value) and summary.md.

use super::shard::Shard;
use crate::html::sig;
use crate::report::text::significant;
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
    /// Not yet run (the batch is under way or was stopped).
    Pending,
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
                    RowStatus::Failed | RowStatus::NotRun | RowStatus::Unreliable
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

    /// summary.csv: row, name, input, model, status, verdict, epochs, wall_s; for each reported
    /// value NAME, NAME_se, NAME_unit, NAME_truth, NAME_rel_error; the verdict's reasons and
    /// the warnings (each joined by " | "); error.
    pub fn csv(&self) -> String {
        let names = self.value_names();
        let mut w = csv::Writer::from_writer(Vec::new());
        let mut header: Vec<String> = [
            "row", "name", "input", "model", "status", "verdict", "epochs", "wall_s",
        ]
        .map(String::from)
        .to_vec();
        for n in &names {
            header.extend([
                n.clone(),
                format!("{n}_se"),
                format!("{n}_unit"),
                format!("{n}_truth"),
                format!("{n}_rel_error"),
            ]);
        }
        header.extend(["reasons".into(), "warnings".into(), "error".into()]);
        w.write_record(&header).expect("in memory");
        let opt = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v}"));
        for r in self.own_rows() {
            let mut rec = vec![
                r.row.to_string(),
                r.name.clone(),
                r.input.clone(),
                r.model.clone(),
                r.status.word().to_string(),
                r.verdict.clone().unwrap_or_default(),
                r.epochs.map_or(String::new(), |e| e.to_string()),
                r.wall_s.map_or(String::new(), |w| format!("{w:.2}")),
            ];
            for n in &names {
                match r.estimates.iter().find(|e| &e.name == n) {
                    Some(e) => rec.extend([
                        format!("{}", e.value),
                        opt(e.standard_error),
                        e.unit.clone(),
                        opt(e.truth),
                        opt(e.relative_error),
                    ]),
                    None => rec.extend(std::iter::repeat_n(String::new(), 5)),
                }
            }
            rec.push(r.reasons.join(" | "));
            rec.push(r.warnings.join(" | "));
            rec.push(r.error.clone().unwrap_or_default());
            w.write_record(&rec).expect("in memory");
        }
        String::from_utf8(w.into_inner().expect("in memory")).expect("UTF-8 fields")
    }

    /// summary.md: a Markdown table, each row's name linked to its report.html.
    pub fn markdown(&self) -> String {
        let mut s = format!(
            "# Batch {}\n\n{} of {} rows failed{}.\n\n\
             | row | name | model | status | verdict | estimates | epochs | wall (s) | reasons, warnings, error |\n\
             |---:|---|---|---|---|---|---:|---:|---|\n",
            self.batch_file,
            self.failed(),
            self.own_rows().count(),
            self.shard.map_or(String::new(), |s| format!(
                " (shard {}/{})",
                s.index, s.count
            ))
        );
        let cell = |t: &str| t.replace('|', "\\|").replace('\n', " ");
        for r in self.own_rows() {
            let name = if matches!(r.status, RowStatus::Ok | RowStatus::Unreliable) {
                format!("[{}]({}/report.html)", r.name, r.dir)
            } else {
                r.name.clone()
            };
            let estimates: Vec<String> = r.estimates.iter().map(Estimate::text).collect();
            let mut notes = r.reasons.clone();
            notes.extend(r.warnings.iter().cloned());
            notes.extend(r.error.iter().map(|e| format!("**error**: {e}")));
            s += &format!(
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                r.row,
                cell(&name),
                r.model,
                r.status.word(),
                r.verdict.as_deref().unwrap_or(""),
                cell(&estimates.join("<br>")),
                r.epochs.map_or(String::new(), |e| e.to_string()),
                r.wall_s.map_or(String::new(), |w| format!("{w:.1}")),
                cell(&notes.join("<br>"))
            );
        }
        s
    }
}

impl Estimate {
    /// `g = 9.87 m/s^2 (truth 9.81, +0.61 %)`.
    pub fn text(&self) -> String {
        let mut s = format!("{} = {}", self.name, sig(self.value));
        if let Some(se) = self.standard_error {
            s += &format!(" ± {}", significant(se));
        }
        s += &format!(" {}", self.unit);
        if let Some(t) = self.truth {
            s += &format!(" (truth {}", sig(t));
            if let Some(e) = self.relative_error {
                s += &format!(", {:+.2} %", e * 100.0);
            }
            s += ")";
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(n: usize, status: RowStatus, estimates: Vec<Estimate>) -> RowResult {
        RowResult {
            row: n,
            name: format!("0{n}-x"),
            input: "x.mp4".into(),
            model: "free-fall".into(),
            status,
            exit_code: Some(0),
            error: (status == RowStatus::Failed).then(|| "no such file, x".into()),
            estimates,
            epochs: Some(12),
            wall_s: Some(1.5),
            warnings: vec![],
            verdict: Some("ok".into()),
            reasons: vec![],
            dir: format!("0{n}-x"),
            command: String::new(),
        }
    }

    #[test]
    fn csv_has_a_column_group_per_value_and_every_own_row() {
        let g = Estimate {
            name: "g".into(),
            value: 9.87,
            unit: "m/s^2".into(),
            truth: Some(9.81),
            relative_error: Some(0.006),
            standard_error: Some(0.0123),
        };
        let s = Summary {
            format: "x".into(),
            batch_file: "runs.csv".into(),
            shard: None,
            rows: vec![
                row(1, RowStatus::Ok, vec![g.clone()]),
                row(2, RowStatus::Failed, vec![]),
                row(3, RowStatus::OtherShard, vec![]),
            ],
        };
        let csv = s.csv();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 3, "{csv}");
        assert!(lines[0].contains("g,g_se,g_unit,g_truth,g_rel_error,reasons,warnings,error"));
        assert!(lines[2].ends_with("no such file, x\""), "{csv}");
        assert_eq!(s.failed(), 1);
        assert!(s.markdown().contains("[01-x](01-x/report.html)"));
        assert_eq!(
            g.text(),
            "g = 9.87000 ± 0.012 m/s^2 (truth 9.81000, +0.60 %)"
        );
    }
}
