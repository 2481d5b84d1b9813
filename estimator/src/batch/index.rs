//! A batch's `index.html`: the summary table, each row that ran linked to its report.html.

use super::summary::{RowStatus, Summary};
use crate::html::{render, style};
use minijinja::context;

/// `index.html` for a batch: the summary table, each row that ran linked to its report.
pub fn index_page(summary: &Summary) -> String {
    let rows: Vec<_> = summary
        .own_rows()
        .map(|r| {
            context! {
                row => r.row, name => r.name, input => r.input, model => r.model,
                status => r.status.word(), status_class => r.status.word().replace(' ', "-"),
                link => matches!(r.status, RowStatus::Ok | RowStatus::Unreliable)
                    .then(|| format!("{}/report.html", r.dir)),
                verdict => r.verdict.clone().unwrap_or_default(), reasons => r.reasons,
                estimates => r.estimates.iter().map(|e| e.text()).collect::<Vec<_>>(),
                epochs => r.epochs.map_or(String::new(), |e| e.to_string()),
                wall => r.wall_s.map_or(String::new(), |w| format!("{w:.1}")),
                warnings => r.warnings, error => r.error,
            }
        })
        .collect();
    let headline = format!(
        "{} rows, {} failed{}",
        rows.len(),
        summary.failed(),
        summary.shard.map_or(String::new(), |s| format!(
            "; shard {}/{}",
            s.index, s.count
        ))
    );
    render(
        "index.html",
        include_str!("index.html"),
        context! {
            style => style(),
            batch_file => summary.batch_file, headline, rows,
        },
    )
}
