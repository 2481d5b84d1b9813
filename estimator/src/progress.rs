//! Progress display: an indicatif bar on a terminal, plain lines otherwise, nothing with --quiet.

use crate::train::outcome::EpochRecord;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// Shows training progress for one run.
pub enum Progress {
    Bar(ProgressBar),
    Lines { every: usize },
    Quiet,
}

impl Progress {
    pub fn new(max_epochs: usize, quiet: bool) -> Progress {
        if quiet {
            Progress::Quiet
        } else if std::io::stderr().is_terminal() {
            let bar = ProgressBar::with_draw_target(
                Some(max_epochs as u64),
                ProgressDrawTarget::stderr(),
            );
            bar.set_style(
                ProgressStyle::with_template(
                    "{spinner} epoch {pos}/{len} [{elapsed_precise}] {wide_msg}",
                )
                .expect("valid template"),
            );
            Progress::Bar(bar)
        } else {
            Progress::Lines { every: 10 }
        }
    }

    pub fn epoch(&self, rec: &EpochRecord, names: &[&str]) {
        let params: Vec<String> = names
            .iter()
            .zip(&rec.parameters)
            .map(|(n, v)| format!("{n} {v:.5}"))
            .collect();
        let text = format!(
            "loss {:.3e} (val {:.3e})  {}",
            rec.train_loss,
            rec.val_loss,
            params.join("  ")
        );
        match self {
            Progress::Bar(bar) => {
                bar.set_position(rec.epoch as u64);
                bar.set_message(text);
            }
            Progress::Lines { every } => {
                if rec.epoch == 1 || rec.epoch.is_multiple_of(*every) {
                    eprintln!("epoch {:>4}  {text}", rec.epoch);
                }
            }
            Progress::Quiet => {}
        }
    }

    pub fn finish(&self) {
        if let Progress::Bar(bar) = self {
            bar.finish_and_clear();
        }
    }
}
