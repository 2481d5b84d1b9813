//! `EstimateError`: what can go wrong in `estimate`, split into bad input (exit 2) and failures.

use physvid_shared::DatasetError;
use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum EstimateError {
    /// The input dataset or file is unusable.
    #[error(transparent)]
    Dataset(#[from] DatasetError),
    /// An output folder refused (not this tool's, busy, a link out of it) or unwritable.
    #[error(transparent)]
    Output(#[from] physvid_shared::outdir::OutputError),
    /// A recording that cannot be decoded or cut into clips, or ffmpeg missing.
    #[error(transparent)]
    Video(#[from] physvid_shared::video::VideoError),
    /// A flag or the input contradicts itself; the text names the flag or file and the fix.
    #[error("{0}")]
    Input(String),
    #[error(
        "--device cuda: libtorch sees no CUDA GPU on this machine; use --device cpu (or auto)"
    )]
    NoCuda,
    #[error("libtorch: {0}")]
    Torch(#[from] tch::TchError),
    #[error("cannot write {path}")]
    Write {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("cannot draw {path}: {reason}")]
    Plot { path: PathBuf, reason: String },
    /// `--batch` or `--merge`: some rows failed (exit code 1); the others' results are written.
    #[error("{failed} of {total} rows failed; see {summary}")]
    RowsFailed {
        failed: usize,
        total: usize,
        summary: PathBuf,
    },
    /// An estimate whose verdict is `unreliable` (exit code 4): its files are written, and the
    /// verdict's reasons say why it should not be used.
    #[error("the answer is unreliable (the verdict's reasons are above and in {0})")]
    Unreliable(PathBuf),
    /// Training ran but gave no estimate (exit code 3); nothing is written.
    #[error("no estimate: {0}; nothing written")]
    NoEstimate(String),
    /// A library caller stopped the run (`run::Watch::cancel`); nothing is written.
    #[error("cancelled; nothing written")]
    Cancelled,
}

impl EstimateError {
    /// Whether the error is the user's input (exit code 2) rather than a failure (exit code 1).
    pub fn is_bad_input(&self) -> bool {
        match self {
            EstimateError::Dataset(DatasetError::Write { .. }) => false,
            EstimateError::Output(e) => e.is_bad_input(),
            EstimateError::Video(physvid_shared::video::VideoError::Scratch { .. }) => false,
            EstimateError::Dataset(_)
            | EstimateError::Video(_)
            | EstimateError::Input(_)
            | EstimateError::NoCuda => true,
            _ => false,
        }
    }
}

/// Shorthand for an [`EstimateError::Input`].
pub fn input_error(msg: impl Into<String>) -> EstimateError {
    EstimateError::Input(msg.into())
}

/// Prints a binary's error on one line and picks its exit code: 2 for bad input, 3 for no
/// estimate, 4 for an unreliable one, 1 otherwise.
pub fn exit_with(program: &str, result: anyhow::Result<()>) -> std::process::ExitCode {
    std::process::ExitCode::from(exit_code(program, result))
}

/// [`exit_with`]'s code as a number (for an exit that skips the libraries' teardown,
/// [`exit_now`]).
pub fn exit_code(program: &str, result: anyhow::Result<()>) -> u8 {
    match result {
        Ok(()) => 0,
        Err(e) => {
            // One line, whatever a file name or a model file put in the message.
            physvid_shared::term::eprint_line(&format!("{program}: error: {e:#}"));
            let refused = e
                .downcast_ref::<physvid_shared::outdir::OutputError>()
                .is_some_and(|e| e.is_bad_input());
            let code = match e.downcast_ref::<EstimateError>() {
                Some(e) if e.is_bad_input() => 2,
                Some(EstimateError::NoEstimate(_)) => 3,
                Some(EstimateError::Unreliable(_)) => 4,
                _ if refused => 2,
                _ => 1,
            };
            code
        }
    }
}

/// Ends the process now with `code`, its output flushed, without running the libraries'
/// teardown: libtorch's static destructors (its operator registry) took 0.05 s of every run,
/// a tenth of a short roll's whole decode-to-answer time. Every file is written and closed
/// before (the run's outputs are dropped on return from it).
pub fn exit_now(code: u8) -> ! {
    use std::io::Write;
    let _ = std::io::stdout().flush();
    let _ = std::io::stderr().flush();
    // SAFETY: `_exit` ends the process at once; nothing after it runs, and every Rust value
    // holding a resource that must be released (files, temporary folders) was dropped.
    unsafe { libc::_exit(i32::from(code)) }
}
