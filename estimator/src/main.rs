//! `estimate`: command-line entry point; parses flags into a validated `EstimateConfig` and calls `run`.

use clap::Parser;
use estimator::cli::EstimateArgs;
use estimator::error::exit_with;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = match EstimateArgs::try_parse() {
        Ok(args) => args,
        Err(e) => return physvid_shared::cli::exit_on_clap_error(e),
    };
    let result = args
        .into_config()
        .validate()
        .map_err(anyhow::Error::from)
        .and_then(|cfg| estimator::run(&cfg));
    exit_with("estimate", result)
}
