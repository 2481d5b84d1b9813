//! Helpers of `reproduce`'s end-to-end tests: the binary, its quick tables, their files.
#![allow(dead_code)]

use physvid_testkit::{stderr, TestCommand};
use std::collections::HashMap;
use std::path::Path;

/// The `reproduce` binary as a command.
pub fn reproduce() -> TestCommand {
    TestCommand::new(env!("CARGO_BIN_EXE_reproduce"))
}

/// Runs `reproduce TABLE --quick` into `out` on two threads.
pub fn reproduce_quick(table: &str, out: &Path) {
    reproduce_quick_with(table, out, &[]);
}

/// As [`reproduce_quick`], with `extra` flags.
pub fn reproduce_quick_with(table: &str, out: &Path, extra: &[&str]) {
    let o = reproduce()
        .args([
            table,
            "--quick",
            "--quiet",
            "--threads",
            "2",
            "--device",
            "cpu",
        ])
        .args(extra)
        .out(out)
        .output();
    assert!(o.status.success(), "reproduce {table}: {}", stderr(&o));
}

/// The rows of `<out>/<table>.csv` as column → text maps.
pub fn read_csv(out: &Path, table: &str) -> Vec<HashMap<String, String>> {
    let text = std::fs::read_to_string(out.join(format!("{table}.csv"))).expect("csv written");
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    lines
        .map(|l| {
            header
                .iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect()
        })
        .collect()
}

/// A CSV cell as a number.
pub fn num(row: &HashMap<String, String>, col: &str) -> f64 {
    row[col]
        .parse()
        .unwrap_or_else(|_| panic!("{col} = '{}' is not a number", row[col]))
}

pub fn markdown(out: &Path, table: &str) -> String {
    std::fs::read_to_string(out.join(format!("{table}.md"))).expect("md written")
}

/// The rows of `<out>/<table>.csv` without their wall time, each as sorted `column=value` cells
/// (what two runs of one table share).
pub fn rows_without_wall(out: &Path, table: &str) -> Vec<Vec<String>> {
    read_csv(out, table)
        .into_iter()
        .map(|mut r| {
            r.remove("wall_s");
            let mut v: Vec<String> = r.into_iter().map(|(k, v)| format!("{k}={v}")).collect();
            v.sort();
            v
        })
        .collect()
}
