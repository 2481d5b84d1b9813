//! `estimate --merge DIR... --out OUT`: the summaries of one batch file's shards joined into one,
//! each row taken from the directory that ran it, its report linked relative to OUT.

use super::summary::{RowStatus, Summary};
use super::{open_out, write_summary, SUMMARY_FORMAT};
use crate::error::input_error;
use std::path::{Path, PathBuf};

/// Joins the summaries in `dirs` into `out`. Err when a summary is missing or from another
/// batch file (exit 2), or when some row was run by none of them or failed (exit 1).
pub fn merge(dirs: &[PathBuf], out: &Path, force: bool) -> anyhow::Result<()> {
    let mut merged: Option<Summary> = None;
    let out_abs = absolute(out);
    for dir in dirs {
        let path = dir.join("summary.json");
        let bad = |what: &str| input_error(format!("--merge {}: {what}", path.display()));
        let bytes = std::fs::read(&path)
            .map_err(|_| bad("no summary.json (not the --out of an `estimate --batch`)"))?;
        let summary: Summary = serde_json::from_slice(&bytes)
            .map_err(|e| bad(&format!("not a batch summary ({e})")))?;
        if summary.format != SUMMARY_FORMAT {
            return Err(bad("not a batch summary").into());
        }
        let dir_abs = absolute(dir);
        let m = merged.get_or_insert_with(|| Summary {
            shard: None,
            rows: summary
                .rows
                .iter()
                .map(|r| {
                    let mut r = r.clone();
                    r.status = RowStatus::NotRun;
                    r.error = Some("run by none of the merged directories".into());
                    r
                })
                .collect(),
            ..summary.clone()
        });
        if summary.rows.len() != m.rows.len() || summary.batch_file != m.batch_file {
            return Err(bad(&format!(
                "from batch file {} with {} rows, not {} with {} like the first",
                summary.batch_file,
                summary.rows.len(),
                m.batch_file,
                m.rows.len()
            ))
            .into());
        }
        for row in summary.own_rows() {
            let slot = &mut m.rows[row.row - 1];
            if slot.status != RowStatus::NotRun {
                return Err(bad(&format!(
                    "row {} was run by two of the merged directories",
                    row.row
                ))
                .into());
            }
            *slot = row.clone();
            let target = dir_abs.join(&row.dir);
            slot.dir = pathdiff::diff_paths(&target, &out_abs)
                .unwrap_or(target)
                .display()
                .to_string();
        }
    }
    let merged = merged.ok_or_else(|| input_error("--merge: no directories given"))?;
    let mut dir = open_out(out, force)?;
    write_summary(&mut dir, &merged)?;
    dir.finish();
    physvid_shared::term::print(merged.markdown().trim_end())?;
    Ok(merged.outcome(out.join("summary.md"))?)
}

/// `path` made absolute (symbolic links resolved where it exists), for relative links.
fn absolute(path: &Path) -> PathBuf {
    std::fs::canonicalize(path)
        .or_else(|_| std::path::absolute(path))
        .unwrap_or_else(|_| path.to_path_buf())
}
