//! The batch file: a CSV whose rows name an input and the flags that differ per row. Its columns
//! are checked against `estimate`'s own flags (the clap definition is the one list), so an
//! unknown column is refused before any row runs.

use crate::error::{input_error, EstimateError};
use crate::EstimateArgs;
use clap::CommandFactory;
use physvid_shared::cli::parse_name_values;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// Columns that are not flags.
const INPUT: &str = "input";
const NAME: &str = "name";
const TRUTH: &str = "truth";

/// Flags a row may not set: where the batch writes, and the batch's own flags.
pub const BATCH_ONLY: [&str; 7] = ["out", "quiet", "batch", "shard", "merge", "help", "version"];

/// One row of the batch file.
#[derive(Debug, Clone)]
pub struct BatchRow {
    /// From 1, in file order (comment lines not counted).
    pub number: usize,
    /// The row's directory under --out: `NN-LABEL`, LABEL the `name` cell or the input's name.
    pub dir: String,
    /// The `input` cell, resolved against the batch file's folder.
    pub input: PathBuf,
    /// As written in the file.
    pub input_text: String,
    /// Known values from the `truth` cell.
    pub truth: Vec<(String, f64)>,
    /// The row's flags, appended to the command line's.
    pub flags: Vec<OsString>,
    /// Why the row cannot run (a bad `truth` or switch cell): reported as its failure.
    pub problem: Option<String>,
}

/// Reads and checks a batch file. A missing or malformed file, a missing `input` column, an
/// unknown or batch-only column, or a duplicate `name`: an error naming it (exit code 2).
pub fn read_batch_file(path: &Path) -> Result<Vec<BatchRow>, EstimateError> {
    let bad = |what: String| input_error(format!("--batch {}: {what}", path.display()));
    physvid_shared::input::check_kind(path).map_err(&bad)?;
    let text = std::fs::read_to_string(path).map_err(|e| bad(format!("cannot read it ({e})")))?;
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| bad(format!("not CSV ({e})")))?
        .iter()
        .map(str::to_string)
        .collect();
    let flags = settable_flags();
    let mut columns = Vec::new();
    for (i, h) in header.iter().enumerate() {
        let column = if h == INPUT || h == NAME || h == TRUTH {
            Column::Special
        } else if BATCH_ONLY.contains(&h.as_str()) {
            return Err(bad(format!(
                "column '{h}' is the batch's own (give it on the command line)"
            )));
        } else if let Some(&(_, _, takes_value)) = flags.iter().find(|(n, _, _)| n == h) {
            Column::Flag(takes_value)
        } else {
            let names: Vec<&str> = flags.iter().map(|(n, _, _)| n.as_str()).collect();
            return Err(bad(format!(
                "unknown column '{h}' (column {}); columns are input, name, truth and these \
                 flags without dashes: {}",
                i + 1,
                names.join(", ")
            )));
        };
        if header[..i].contains(h) {
            return Err(bad(format!("column '{h}' appears twice")));
        }
        columns.push(column);
    }
    let Some(input_col) = header.iter().position(|h| h == INPUT) else {
        return Err(bad(
            "no 'input' column (the recording or data set of each row)".into(),
        ));
    };
    // "./x" rather than "x" for a batch file in the current folder: an input named "-x" must
    // not read as a flag in the row's command.
    let base = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let mut rows: Vec<BatchRow> = Vec::new();
    for (i, record) in reader.records().enumerate() {
        let record = record.map_err(|e| bad(format!("{e}")))?;
        let number = i + 1;
        let cell = |name: &str| {
            header
                .iter()
                .position(|h| h == name)
                .and_then(|c| record.get(c))
                .unwrap_or("")
        };
        let input_text = record.get(input_col).unwrap_or("").to_string();
        if input_text.is_empty() {
            return Err(bad(format!("row {number} has no input")));
        }
        let mut problem = None;
        let truth = parse_name_values(&cell(TRUTH).replace(';', ",")).unwrap_or_else(|e| {
            problem = Some(format!("truth '{}': {e}", cell(TRUTH)));
            Vec::new()
        });
        let mut flags = Vec::new();
        for ((h, column), value) in header.iter().zip(&columns).zip(record.iter()) {
            match column {
                Column::Special => {}
                _ if value.is_empty() => {}
                Column::Flag(true) => {
                    flags.push(OsString::from(format!("--{h}")));
                    flags.push(OsString::from(value));
                }
                Column::Flag(false) => match value.to_ascii_lowercase().as_str() {
                    "true" | "yes" | "1" => flags.push(OsString::from(format!("--{h}"))),
                    "false" | "no" | "0" => {}
                    _ => problem = Some(format!("{h} '{value}': a switch takes true or false")),
                },
            }
        }
        let label = match cell(NAME) {
            "" => Path::new(&input_text)
                .file_stem()
                .map_or("row".into(), |s| s.to_string_lossy().into_owned()),
            name => name.to_string(),
        };
        let label = sanitize(&label);
        if let Some(other) = rows.iter().find(|r| r.dir == label) {
            if !cell(NAME).is_empty() {
                return Err(bad(format!(
                    "rows {} and {number} have the same name '{label}'",
                    other.number
                )));
            }
        }
        rows.push(BatchRow {
            number,
            dir: label,
            input: base.join(&input_text),
            input_text,
            truth,
            flags,
            problem,
        });
    }
    if rows.is_empty() {
        return Err(bad("no rows".into()));
    }
    let width = rows.len().to_string().len().max(2);
    for r in &mut rows {
        r.dir = format!("{:0width$}-{}", r.number, r.dir);
    }
    Ok(rows)
}

enum Column {
    Special,
    /// A flag, and whether it takes a value (else a switch).
    Flag(bool),
}

/// `estimate`'s flags a row may set (from its clap definition): long name, argument id, and
/// whether it takes a value (else a switch).
fn settable_flags() -> Vec<(String, String, bool)> {
    EstimateArgs::command()
        .get_arguments()
        .filter_map(|a| {
            let long = a.get_long()?;
            (!BATCH_ONLY.contains(&long)).then(|| {
                let id = a.get_id().as_str().to_string();
                (long.to_string(), id, a.get_action().takes_values())
            })
        })
        .collect()
}

/// The flags `base` (the command line's) and `row` (a row's) as one list in which each flag is
/// given once: a flag the row sets replaces the command line's (`estimate` refuses a flag given
/// twice).
pub fn merged_flags(base: &[OsString], row: &[OsString]) -> Vec<OsString> {
    let takes_value: Vec<String> = settable_flags()
        .into_iter()
        .filter(|(_, _, v)| *v)
        .map(|(long, _, _)| format!("--{long}"))
        .collect();
    // Each flag with its value, if it takes one.
    let items = |flags: &[OsString]| -> Vec<Vec<OsString>> {
        let mut out: Vec<Vec<OsString>> = Vec::new();
        let mut i = 0;
        while i < flags.len() {
            let with_value = takes_value.iter().any(|t| flags[i] == OsString::from(t));
            let n = if with_value { 2 } else { 1 };
            out.push(flags[i..(i + n).min(flags.len())].to_vec());
            i += n;
        }
        out
    };
    let row_items = items(row);
    let mut out: Vec<OsString> = items(base)
        .into_iter()
        .filter(|b| !row_items.iter().any(|r| r[0] == b[0]))
        .flatten()
        .collect();
    out.extend(row_items.into_iter().flatten());
    out
}

/// The flags of the batch's own command line that every row takes (those a row may set, as
/// given), as arguments.
pub fn command_line_flags(matches: &clap::ArgMatches) -> Vec<OsString> {
    let mut flags = Vec::new();
    for (long, id, takes_value) in settable_flags() {
        if matches.value_source(&id) != Some(clap::parser::ValueSource::CommandLine) {
            continue;
        }
        if takes_value {
            for raw in matches.get_raw(&id).into_iter().flatten() {
                flags.push(OsString::from(format!("--{long}")));
                flags.push(raw.to_os_string());
            }
        } else {
            flags.push(OsString::from(format!("--{long}")));
        }
    }
    flags
}

/// A label safe as a directory name: letters, digits, '.', '_' and '-' kept, the rest '_'.
fn sanitize(label: &str) -> String {
    let s: String = label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "._-".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    match s.trim_start_matches('.') {
        "" => "row".into(),
        t => t.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<Vec<BatchRow>, EstimateError> {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("runs.csv");
        std::fs::write(&path, text).unwrap();
        read_batch_file(&path)
    }

    #[test]
    fn rows_become_flags_and_directories() {
        let rows = read(
            "# a comment\ninput,model,start,preview,truth,name\n\
             a/clip.mp4,pendulum,1.5,true,length=0.45,\n\
             b.npy,torricelli,,false,,jar 2\n",
        )
        .unwrap();
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[0].dir, "01-clip");
        assert_eq!(rows[1].dir, "02-jar_2");
        let flags: Vec<String> = rows[0]
            .flags
            .iter()
            .map(|f| f.to_string_lossy().into_owned())
            .collect();
        assert_eq!(
            flags,
            ["--model", "pendulum", "--start", "1.5", "--preview"]
        );
        assert_eq!(rows[0].truth, [("length".to_string(), 0.45)]);
        assert!(rows[0].input.ends_with("a/clip.mp4"));
        assert_eq!(rows[1].flags.len(), 2);
    }

    #[test]
    fn bad_files_are_refused_naming_the_column() {
        let e = read("input,modle\nx,pendulum\n").unwrap_err().to_string();
        assert!(
            e.contains("unknown column 'modle'") && e.contains("model"),
            "{e}"
        );
        let e = read("input,out\nx,y\n").unwrap_err().to_string();
        assert!(e.contains("'out' is the batch's own"), "{e}");
        let e = read("model\npendulum\n").unwrap_err().to_string();
        assert!(e.contains("no 'input' column"), "{e}");
        let e = read("input,name\nx,a\ny,a\n").unwrap_err().to_string();
        assert!(e.contains("same name 'a'"), "{e}");
        assert!(read("input\n").is_err());
        let rows = read("input,preview,truth\nx,maybe,g=x\n").unwrap();
        assert!(rows[0].problem.is_some());
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { cases: 128, rng_seed: proptest::test_runner::RngSeed::Fixed(50), ..Default::default() })]

        /// Any batch file is rows or one message, never a panic; a row's folder is one plain
        /// name inside --out.
        #[test]
        fn any_batch_file_is_rows_or_one_message(
            header in proptest::sample::select(vec!["input", "input,name", "input,name,model", "input,seed,truth", "name"]),
            cells in proptest::collection::vec("[ -~\\n\"=@+|<>/.]{0,24}", 0..12),
        ) {
            let text = format!("{header}\n{}", cells.join("\n"));
            match read(&text) {
                Ok(rows) => {
                    for r in rows {
                        proptest::prop_assert!(!r.dir.contains('/') && r.dir != ".." && !r.dir.is_empty());
                    }
                }
                Err(e) => proptest::prop_assert!(!e.to_string().is_empty()),
            }
        }
    }
}
