//! `OutputError`: why a folder cannot be written, a refusal of the user's choice (exit code 2)
//! or a failure to write.

use std::path::{Path, PathBuf};

/// Why a folder cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error(
        "{flag} {dir}: the folder holds {count} {} this tool did not write ({names}); choose a \
         new or empty folder, or pass --force to write beside them (nothing of another name is \
         removed or changed)",
        if *count == 1 { "entry" } else { "entries" }
    )]
    NotOurs {
        flag: String,
        dir: PathBuf,
        count: usize,
        names: String,
    },
    #[error(
        "{flag} {path}: this tool did not write that file (or it changed since); move it away, \
         choose another folder, or pass --force to replace it"
    )]
    NotOurFile { flag: String, path: PathBuf },
    #[error(
        "{flag} {dir}: its entry {name} is a link to {target}, outside the folder; this tool \
         writes only inside its folder: remove the link or choose another folder"
    )]
    LinkOut {
        flag: String,
        dir: PathBuf,
        name: String,
        target: String,
    },
    #[error("{flag} {dir}: another run is writing into this folder; wait for it to end or choose another folder")]
    Busy { flag: String, dir: PathBuf },
    #[error("{flag} {dir}: {reason}")]
    Unusable {
        flag: String,
        dir: PathBuf,
        reason: String,
    },
    #[error("cannot write {path}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

impl OutputError {
    /// A refusal of the user's choice of folder (exit code 2) rather than a failure to write.
    pub fn is_bad_input(&self) -> bool {
        !matches!(self, OutputError::Io { .. })
    }
}

pub(super) fn io(path: &Path) -> impl Fn(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    }
}
