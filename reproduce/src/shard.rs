//! A table's estimations spread over a cluster's job array and merged back: `--shard I/N`
//! runs the estimations of each table's job list whose index i has i mod N = I − 1 and records
//! their runs in `OUT/TABLE.shard-I-of-N.cbor` instead of writing the table; `--merge DIR...`
//! makes the table from the shards' records, running nothing, and checks that they come from
//! the same table, options and shard count, each estimation once. Tables whose estimations
//! follow one another (`verdict`, `real`, `others`: `Runner::estimate` one at a time) run
//! whole in shard 1; the other shards skip them. The merged table equals the table made whole, wall times
//! aside (CPU runs are deterministic).

use crate::worker::Run;
use estimator::cli::Shard;
use estimator::error::input_error;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// How this process takes part in a sharded run.
pub enum Sharding {
    /// Runs this shard's estimations and records them.
    Shard(Shard),
    /// Takes every estimation from the shards' records in these folders.
    Merge(Vec<PathBuf>),
}

/// The table stops here: this shard's estimations of it are done (or it belongs to shard 1).
#[derive(Debug)]
pub struct Sharded;

impl std::fmt::Display for Sharded {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("the rest of this table belongs to other shards")
    }
}

impl std::error::Error for Sharded {}

/// Which estimation of a table: a job of its job list, or the n-th single estimation.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Call {
    Job(usize),
    One(usize),
}

/// One recorded estimation: which it is, what it ran (its data and flags, checked on merging),
/// and its run.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct Entry {
    call: Call,
    what: String,
    run: Run,
}

/// A shard's record of one table.
#[derive(Debug, Serialize, Deserialize)]
struct Record {
    table: String,
    quick: bool,
    shard: Shard,
    runs: Vec<Entry>,
}

/// The table being made: its name, the single estimations counted so far, and the runs
/// recorded (a shard) or read from the records (a merge, on first use).
#[derive(Default)]
struct Table {
    name: String,
    ones: usize,
    runs: BTreeMap<Call, Entry>,
    loaded: bool,
}

/// The sharding of a `reproduce` run, table by table.
pub struct State {
    pub mode: Sharding,
    quick: bool,
    table: Mutex<Table>,
}

impl State {
    pub fn new(mode: Sharding, quick: bool) -> State {
        State {
            mode,
            quick,
            table: Mutex::new(Table::default()),
        }
    }

    /// A new table begins.
    pub fn begin(&self, table: &str) {
        *self.table.lock().expect("no job panicked") = Table {
            name: table.to_string(),
            ..Table::default()
        };
    }

    /// Whether this process records runs (a shard) rather than reads them (a merge).
    pub fn records(&self) -> bool {
        matches!(self.mode, Sharding::Shard(_))
    }

    /// Whether this process runs job `i` (a shard holds every N-th; a merge runs none).
    pub fn holds_job(&self, i: usize) -> bool {
        match &self.mode {
            Sharding::Shard(s) => s.holds(i + 1),
            Sharding::Merge(_) => false,
        }
    }

    /// The next single estimation's call, and whether this process runs it (shard 1 does).
    pub fn next_one(&self) -> (Call, bool) {
        let mut t = self.table.lock().expect("no job panicked");
        t.ones += 1;
        let runs = matches!(&self.mode, Sharding::Shard(s) if s.index == 1);
        (Call::One(t.ones - 1), runs)
    }

    /// Records `run` of `call` (a shard).
    pub fn record(&self, call: Call, what: String, run: &Run) {
        let mut t = self.table.lock().expect("no job panicked");
        t.runs.insert(
            call.clone(),
            Entry {
                call,
                what,
                run: run.clone(),
            },
        );
    }

    /// The run of `call` from the shards' records (a merge), checked against `what`.
    pub fn recorded(&self, call: Call, what: &str) -> anyhow::Result<Run> {
        let mut t = self.table.lock().expect("no job panicked");
        if let (Sharding::Merge(dirs), false) = (&self.mode, t.loaded) {
            t.runs = self.load(&t.name, dirs)?;
            t.loaded = true;
        }
        let e = t.runs.get(&call).ok_or_else(|| {
            input_error(format!(
                "--merge: no shard recorded {} estimation {call:?} ({what}); merge every shard's folder",
                t.name
            ))
        })?;
        if e.what != what {
            return Err(input_error(format!(
                "--merge: {} estimation {call:?} was recorded as '{}', this table runs '{what}': \
                 shards of other options (--quick, the table's version)",
                t.name, e.what
            ))
            .into());
        }
        Ok(e.run.clone())
    }

    /// Writes this shard's record of the table into `out`; returns how many runs it holds.
    pub fn write(&self, out: &Path) -> anyhow::Result<(PathBuf, usize)> {
        let Sharding::Shard(shard) = &self.mode else {
            anyhow::bail!("only a shard writes a record");
        };
        let t = self.table.lock().expect("no job panicked");
        let record = Record {
            table: t.name.clone(),
            quick: self.quick,
            shard: *shard,
            runs: t.runs.values().cloned().collect(),
        };
        let path = out.join(file_name(&t.name, *shard));
        let mut bytes = Vec::new();
        ciborium::into_writer(&record, &mut bytes)?;
        physvid_shared::write_atomic(&path, &bytes)?;
        Ok((path, record.runs.len()))
    }

    /// Every run the shards in `dirs` recorded of `table`.
    fn load(&self, table: &str, dirs: &[PathBuf]) -> anyhow::Result<BTreeMap<Call, Entry>> {
        let mut runs = BTreeMap::new();
        let mut count = None;
        let mut seen = Vec::new();
        for dir in dirs {
            let prefix = format!("{table}.shard-");
            let entries = std::fs::read_dir(dir)
                .map_err(|e| input_error(format!("--merge {}: {e}", dir.display())))?;
            for entry in entries {
                let path = entry?.path();
                let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
                if !name.is_some_and(|n| n.starts_with(&prefix) && n.ends_with(".cbor")) {
                    continue;
                }
                let bytes = std::fs::read(&path)?;
                let record: Record = ciborium::from_reader(bytes.as_slice()).map_err(|e| {
                    input_error(format!("{}: not a shard record: {e}", path.display()))
                })?;
                if record.quick != self.quick {
                    return Err(input_error(format!(
                        "--merge: {} was made {} --quick; merge as it was made",
                        path.display(),
                        if record.quick { "with" } else { "without" }
                    ))
                    .into());
                }
                if *count.get_or_insert(record.shard.count) != record.shard.count {
                    return Err(input_error(format!(
                        "--merge: {} is of another shard count",
                        path.display()
                    ))
                    .into());
                }
                if seen.contains(&record.shard.index) {
                    return Err(input_error(format!(
                        "--merge: shard {}/{} of {table} appears twice",
                        record.shard.index, record.shard.count
                    ))
                    .into());
                }
                seen.push(record.shard.index);
                for e in record.runs {
                    runs.insert(e.call.clone(), e);
                }
            }
        }
        let n = count.ok_or_else(|| {
            input_error(format!(
                "--merge: no shard record of {table} in the folders given"
            ))
        })?;
        if seen.len() != n {
            seen.sort_unstable();
            return Err(input_error(format!(
                "--merge: {table} has {} of its {n} shards ({seen:?}); merge every shard's folder",
                seen.len()
            ))
            .into());
        }
        Ok(runs)
    }
}

/// A shard's record file of `table`.
fn file_name(table: &str, shard: Shard) -> String {
    format!("{table}.shard-{}-of-{}.cbor", shard.index, shard.count)
}
