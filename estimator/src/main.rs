//! `estimate`: command-line entry point; parses and validates the flags and calls `run` (or,
//! for `--batch` and `--merge`, the batch driver).

use clap::{CommandFactory, FromArgMatches};
use estimator::error::{exit_code, exit_now};
use estimator::EstimateArgs;
use std::process::ExitCode;

fn main() -> ExitCode {
    estimator::memory::keep_freed_memory();
    // Ctrl-C or SIGTERM: temporary files and a folder this run made and left unfilled go.
    physvid_shared::interrupt::install("estimate");
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
                let base = estimator::batch::command_line_flags(&matches);
                estimator::batch::run(&args, &base, &exe)
            } else if !args.batch.merge.is_empty() {
                estimator::batch::merge(&args.batch.merge, &args.output.out, args.output.force)
            } else {
                estimator::run(&args.request()?)
            }
        });
    exit_now(exit_code("estimate", result))
}
