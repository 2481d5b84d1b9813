//! A batch summary as text: summary.csv (one line per row, one group of columns per reported
//! value) and summary.md (a table, each row linked to its report), with text from files and
//! messages escaped for each format.

use super::{Estimate, RowStatus, Summary};
use crate::digits::{sig, significant};
use physvid_shared::escape::{csv_text, md_text};

impl Summary {
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
        // Text from files and messages is written so that a spreadsheet shows it as text.
        let text = |t: &str| csv_text(t).into_owned();
        let header: Vec<String> = header.iter().map(|h| text(h)).collect();
        w.write_record(&header).expect("in memory");
        let opt = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v}"));
        for r in self.own_rows() {
            let mut rec = vec![
                r.row.to_string(),
                text(&r.name),
                text(&r.input),
                text(&r.model),
                r.status.word().to_string(),
                text(r.verdict.as_deref().unwrap_or_default()),
                r.epochs.map_or(String::new(), |e| e.to_string()),
                r.wall_s.map_or(String::new(), |w| format!("{w:.2}")),
            ];
            for n in &names {
                match r.estimates.iter().find(|e| &e.name == n) {
                    Some(e) => rec.extend([
                        format!("{}", e.value),
                        opt(e.standard_error),
                        text(&e.unit),
                        opt(e.truth),
                        opt(e.relative_error),
                    ]),
                    None => rec.extend(std::iter::repeat_n(String::new(), 5)),
                }
            }
            rec.push(text(&r.reasons.join(" | ")));
            rec.push(text(&r.warnings.join(" | ")));
            rec.push(text(r.error.as_deref().unwrap_or_default()));
            w.write_record(&rec).expect("in memory");
        }
        String::from_utf8(w.into_inner().expect("in memory")).expect("UTF-8 fields")
    }

    /// summary.md: a Markdown table, each row's name linked to its report.html. Text from files
    /// and messages is escaped (`md_text`): it cannot open HTML, a link or a column.
    pub fn markdown(&self) -> String {
        let mut s = format!(
            "# Batch {}\n\n{} of {} rows failed{}.\n\n\
             | row | name | model | status | verdict | estimates | epochs | wall (s) | reasons, warnings, error |\n\
             |---:|---|---|---|---|---|---:|---:|---|\n",
            md_text(&self.batch_file),
            self.failed(),
            self.own_rows().count(),
            self.shard.map_or(String::new(), |s| format!(
                " (shard {}/{})",
                s.index, s.count
            ))
        );
        for r in self.own_rows() {
            let name = if matches!(r.status, RowStatus::Ok | RowStatus::Unreliable) {
                // The folder is the row's sanitised name (letters, digits, `._-`), or a merge's
                // relative path to it: `<…>` keeps any other character out of the link.
                format!(
                    "[{}](<{}/report.html>)",
                    md_text(&r.name),
                    r.dir.replace(['<', '>', '\n', '\r'], "_")
                )
            } else {
                md_text(&r.name)
            };
            let estimates: Vec<String> = r.estimates.iter().map(|e| md_text(&e.text())).collect();
            let mut notes: Vec<String> = r.reasons.iter().map(|t| md_text(t)).collect();
            notes.extend(r.warnings.iter().map(|t| md_text(t)));
            notes.extend(r.error.iter().map(|e| format!("**error**: {}", md_text(e))));
            s += &format!(
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                r.row,
                name,
                md_text(&r.model),
                r.status.word(),
                md_text(r.verdict.as_deref().unwrap_or("")),
                estimates.join("<br>"),
                r.epochs.map_or(String::new(), |e| e.to_string()),
                r.wall_s.map_or(String::new(), |w| format!("{w:.1}")),
                notes.join("<br>")
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
    use crate::batch::summary::RowResult;

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
        assert!(s.markdown().contains("[01-x](<01-x/report.html>)"));
        assert_eq!(
            g.text(),
            "g = 9.87000 ± 0.012 m/s^2 (truth 9.81000, +0.60 %)"
        );
    }

    #[test]
    fn text_from_files_cannot_become_a_formula_html_or_a_column() {
        let mut r = row(1, RowStatus::Ok, vec![]);
        r.input = "=HYPERLINK(\"http://x\",\"y\").mp4".into();
        r.model = "@SUM(A1).toml".into();
        r.warnings = vec!["-2+3 <script>alert(1)</script> | x".into()];
        r.estimates.push(Estimate {
            name: "k".into(),
            value: -0.5,
            unit: "+1 <b>".into(),
            truth: None,
            relative_error: None,
            standard_error: None,
        });
        let s = Summary {
            format: "x".into(),
            batch_file: "<i>runs</i>.csv".into(),
            shard: None,
            rows: vec![r],
        };
        let csv = s.csv();
        let mut reader = csv::Reader::from_reader(csv.as_bytes());
        let rec = reader.records().next().unwrap().unwrap();
        let cells: Vec<&str> = rec.iter().collect();
        assert!(
            cells.contains(&"'=HYPERLINK(\"http://x\",\"y\").mp4"),
            "{cells:?}"
        );
        assert!(cells.contains(&"'@SUM(A1).toml"), "{cells:?}");
        assert!(cells.contains(&"'+1 <b>"), "{cells:?}");
        assert!(
            cells.contains(&"-0.5"),
            "a number stays a number: {cells:?}"
        );
        assert!(cells.iter().any(|c| c.starts_with("'-2+3")), "{cells:?}");
        let md = s.markdown();
        assert!(
            !md.contains("<script>") && !md.contains("<i>") && !md.contains("<b>"),
            "{md}"
        );
        let row_line = md.lines().last().unwrap();
        assert_eq!(row_line.matches(" | ").count(), 8, "nine cells: {row_line}");
    }
}
