//! `estimate`: command-line entry point; parses and validates the flags and calls `run`.

use clap::Parser;
use estimator::error::exit_with;
use estimator::EstimateArgs;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = match EstimateArgs::try_parse() {
        Ok(args) => args,
        Err(e) => return physvid_shared::cli::exit_on_clap_error(e),
    };
    let result = args
        .validate()
        .map_err(anyhow::Error::from)
        .and_then(|args| estimator::run(&args));
    exit_with("estimate", result)
}
