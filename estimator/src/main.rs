//! `estimate`: command-line entry point; parses and validates the flags and calls `run` (or,
//! for `--batch` and `--merge`, the batch driver).

use clap::{CommandFactory, FromArgMatches};
use estimator::error::exit_with;
use estimator::EstimateArgs;
use std::ffi::OsString;
use std::process::ExitCode;

fn main() -> ExitCode {
    let parsed = EstimateArgs::command()
        .try_get_matches()
        .and_then(|m| Ok((EstimateArgs::from_arg_matches(&m)?, m)));
    let (args, matches) = match parsed {
        Ok(p) => p,
        Err(e) => return physvid_shared::cli::exit_on_clap_error(e),
    };
    let result = args
        .validate()
        .map_err(anyhow::Error::from)
        .and_then(|args| {
            if args.batch.batch.is_some() {
                let exe = std::env::current_exe()?;
                estimator::batch::run(&args, &row_flags(&matches), &exe)
            } else if !args.batch.merge.is_empty() {
                estimator::batch::merge(&args.batch.merge, &args.output.out)
            } else {
                estimator::run(&args)
            }
        });
    exit_with("estimate", result)
}

/// The flags given on the command line that every batch row takes (all but the batch's own).
fn row_flags(matches: &clap::ArgMatches) -> Vec<OsString> {
    let cmd = EstimateArgs::command();
    let mut flags = Vec::new();
    for arg in cmd.get_arguments() {
        let (Some(long), id) = (arg.get_long(), arg.get_id().as_str()) else {
            continue;
        };
        if estimator::batch::BATCH_ONLY.contains(&long)
            || matches.value_source(id) != Some(clap::parser::ValueSource::CommandLine)
        {
            continue;
        }
        if arg.get_action().takes_values() {
            for raw in matches.get_raw(id).into_iter().flatten() {
                flags.push(OsString::from(format!("--{long}")));
                flags.push(raw.to_os_string());
            }
        } else {
            flags.push(OsString::from(format!("--{long}")));
        }
    }
    flags
}
