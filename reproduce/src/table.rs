//! `Table`: one reproduced table, its cells formatted for TABLE.md and raw for TABLE.csv, and
//! the atomic writing of both.

use physvid_shared::write_atomic;
use std::path::{Path, PathBuf};

/// The "checks with reasons" cell of a verdict: the checks that gave a reason, worst first,
/// one name for a check's consecutive reasons; a note that holds nothing against the answer
/// (graded ok: `Reason::unless`) named "(note)".
pub fn checks(v: &estimator::verdict::Verdict) -> Cell {
    Cell::text(checks_named(v))
}

/// [`checks`]' words.
pub fn checks_named(v: &estimator::verdict::Verdict) -> String {
    let mut names: Vec<String> = v
        .reasons
        .iter()
        .map(|r| match r.grade {
            estimator::verdict::Grade::Ok => format!("{} (note)", r.check),
            _ => r.check.to_string(),
        })
        .collect();
    names.dedup();
    names.join(", ")
}

/// The detection and false-alarm rates in a sentence about `what`: how many answers were
/// right and how many of them were not graded ok, the same for the wrong ones.
pub fn rates(what: &str, right: (usize, usize), wrong: (usize, usize)) -> String {
    let share = |n: usize, of: usize| {
        if of == 0 {
            "–".to_string()
        } else {
            format!("{:.0} %", 100.0 * n as f64 / of as f64)
        }
    };
    format!(
        "Over the {what}: {} right, {} of them not graded ok (false alarms {}); {} wrong, {} of \
         them not graded ok (detection {}).",
        right.0,
        right.1,
        share(right.1, right.0),
        wrong.0,
        wrong.1,
        share(wrong.1, wrong.0),
    )
}

/// One cell: text, a number shown with fixed decimals, or a relative error shown in percent.
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    Text(String),
    Num(f64, usize),
    /// A relative error (fraction); Markdown shows it as a signed percentage.
    Rel(f64),
    Empty,
}

impl Cell {
    pub fn text(s: impl Into<String>) -> Cell {
        Cell::Text(s.into())
    }

    /// `v` with `decimals`, or empty for `None`.
    pub fn num(v: Option<f64>, decimals: usize) -> Cell {
        v.map_or(Cell::Empty, |v| Cell::Num(v, decimals))
    }

    pub fn rel(v: Option<f64>) -> Cell {
        v.map_or(Cell::Empty, Cell::Rel)
    }

    fn markdown(&self) -> String {
        match self {
            Cell::Text(s) => s.clone(),
            Cell::Num(v, d) => format!("{v:.d$}", d = *d),
            Cell::Rel(v) => format!("{:+.2} %", v * 100.0),
            Cell::Empty => "–".into(),
        }
    }

    fn csv(&self) -> String {
        match self {
            Cell::Text(s) if s.contains([',', '"']) => format!("\"{}\"", s.replace('"', "\"\"")),
            Cell::Text(s) => s.clone(),
            Cell::Num(v, _) | Cell::Rel(v) => format!("{v}"),
            Cell::Empty => String::new(),
        }
    }
}

/// A reproduced table with what made it.
#[derive(Debug, Clone)]
pub struct Table {
    /// File stem: `table3` → table3.md, table3.csv.
    pub name: &'static str,
    pub title: String,
    /// (Markdown header, CSV header) per column.
    pub columns: Vec<(String, String)>,
    pub rows: Vec<Vec<Cell>>,
    /// Lines under the table: the data, the flags, what the columns mean, the findings.
    pub notes: Vec<String>,
    /// Pictures written beside it (file name, bytes), each shown among its notes.
    pub pictures: Vec<(String, Vec<u8>)>,
    /// The command that regenerates it.
    pub command: String,
    pub wall_s: f64,
}

impl Table {
    pub fn new(name: &'static str, title: impl Into<String>, columns: &[(&str, &str)]) -> Table {
        Table {
            name,
            title: title.into(),
            columns: columns
                .iter()
                .map(|(m, c)| (m.to_string(), c.to_string()))
                .collect(),
            rows: Vec::new(),
            notes: Vec::new(),
            pictures: Vec::new(),
            command: String::new(),
            wall_s: 0.0,
        }
    }

    pub fn push(&mut self, row: Vec<Cell>) {
        assert_eq!(row.len(), self.columns.len(), "row width of {}", self.name);
        self.rows.push(row);
    }

    pub fn note(&mut self, line: impl Into<String>) {
        self.notes.push(line.into());
    }

    /// A picture written beside the table as `file` and shown among its notes over `caption`.
    pub fn picture(&mut self, file: String, bytes: Vec<u8>, caption: &str) {
        self.note(format!("\n{caption}:\n\n![{file}]({file})\n"));
        self.pictures.push((file, bytes));
    }

    pub fn markdown(&self) -> String {
        let mut s = format!("### {}\n\n", self.title);
        let header: Vec<&str> = self.columns.iter().map(|c| c.0.as_str()).collect();
        s += &format!("| {} |\n", header.join(" | "));
        s += &format!("|{}\n", "---|".repeat(header.len()));
        for row in &self.rows {
            let cells: Vec<String> = row.iter().map(Cell::markdown).collect();
            s += &format!("| {} |\n", cells.join(" | "));
        }
        s += "\n";
        for n in &self.notes {
            s += &format!("{n}\n");
        }
        s += &format!("\nMade by `{}` in {:.0} s.\n", self.command, self.wall_s);
        s
    }

    pub fn csv(&self) -> String {
        let header: Vec<&str> = self.columns.iter().map(|c| c.1.as_str()).collect();
        let mut s = header.join(",") + "\n";
        for row in &self.rows {
            let cells: Vec<String> = row.iter().map(Cell::csv).collect();
            s += &(cells.join(",") + "\n");
        }
        s
    }

    /// Writes `<dir>/<name>.md`, `<dir>/<name>.csv` and its pictures (each via a temporary file
    /// and a rename; the pictures first, the table last).
    pub fn write(&self, dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
        let mut written = Vec::new();
        for (file, bytes) in &self.pictures {
            let path = dir.join(file);
            write_atomic(&path, bytes)?;
            written.push(path);
        }
        let md = dir.join(format!("{}.md", self.name));
        let csv = dir.join(format!("{}.csv", self.name));
        write_atomic(&csv, self.csv().as_bytes())?;
        write_atomic(&md, self.markdown().as_bytes())?;
        written.splice(0..0, [md, csv]);
        Ok(written)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_note_is_named_as_one_beside_the_checks_that_doubt() {
        use estimator::verdict::{Grade, Reason, Verdict};
        let v = Verdict::of(vec![
            Reason::new("law", Grade::Doubtful, "10 %").unless(Some("the track agrees".into())),
            Reason::new("uncertainty", Grade::Doubtful, "γ1"),
            Reason::new("routes", Grade::Doubtful, "γ1 apart"),
            Reason::new("routes", Grade::Doubtful, "γ0 apart"),
        ]);
        assert_eq!(checks_named(&v), "uncertainty, routes, law (note)");
    }

    #[test]
    fn markdown_and_csv_hold_the_same_rows() {
        let mut t = Table::new(
            "t",
            "A table",
            &[("what", "what"), ("γ0", "gamma0"), ("error", "rel_error")],
        );
        t.push(vec![
            Cell::text("a, b"),
            Cell::num(Some(4.00161), 3),
            Cell::rel(Some(-0.0123)),
        ]);
        t.push(vec![Cell::text("c"), Cell::num(None, 3), Cell::Empty]);
        let md = t.markdown();
        assert!(md.contains("| a, b | 4.002 | -1.23 % |"), "{md}");
        assert!(md.contains("| c | – | – |"), "{md}");
        assert_eq!(
            t.csv(),
            "what,gamma0,rel_error\n\"a, b\",4.00161,-0.0123\nc,,\n"
        );
    }

    #[test]
    fn a_picture_is_written_beside_the_table_and_shown_in_it() {
        let mut t = Table::new("t", "A table", &[("what", "what")]);
        t.picture("t-frame.jpg".into(), vec![1, 2, 3], "a frame");
        let dir = tempfile::tempdir().unwrap();
        let written = t.write(dir.path()).unwrap();
        assert_eq!(written.len(), 3);
        assert_eq!(
            std::fs::read(dir.path().join("t-frame.jpg")).unwrap(),
            [1, 2, 3]
        );
        let md = std::fs::read_to_string(dir.path().join("t.md")).unwrap();
        assert!(
            md.contains("a frame:\n\n![t-frame.jpg](t-frame.jpg)"),
            "{md}"
        );
    }
}
