//! `gen`: command-line entry point; parses flags into a validated `GenConfig` and calls `run`.

use clap::Parser;
use generator::GenArgs;
use physvid_shared::{term, DatasetError};
use std::process::ExitCode;

fn main() -> ExitCode {
    physvid_shared::interrupt::install("gen");
    let args = match GenArgs::try_parse() {
        Ok(args) => args,
        Err(e) => return physvid_shared::cli::exit_on_clap_error(e),
    };
    if let Some(n) = args.threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
            .expect("the global thread pool is configured once");
    }
    let cfg = match args.into_config() {
        Ok(cfg) => cfg,
        Err(e) => {
            term::eprint_line(&format!("gen: error: {e}"));
            return ExitCode::from(2);
        }
    };
    match generator::run(&cfg) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            term::eprint_line(&format!("gen: error: {e:#}"));
            let bad_input = matches!(
                e.downcast_ref::<DatasetError>(),
                Some(DatasetError::NotEmpty { .. } | DatasetError::Refused(_))
            ) || e.downcast_ref::<generator::ConfigError>().is_some();
            ExitCode::from(if bad_input { 2 } else { 1 })
        }
    }
}
