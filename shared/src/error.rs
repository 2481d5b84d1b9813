//! `DatasetError`: every way reading or writing a dataset can fail, each naming the file.

use std::path::PathBuf;

/// Errors of the dataset format: I/O, malformed `.npy` files, inconsistent metadata.
#[derive(Debug, thiserror::Error)]
pub enum DatasetError {
    #[error("cannot read {path}")]
    Read {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("cannot write {path}")]
    Write {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{path} is not a valid .npy file: {reason}")]
    MalformedNpy { path: PathBuf, reason: String },
    #[error("{path} holds dtype '{found}', expected little-endian float32 ('<f4'); convert it with numpy: np.save(path, arr.astype('<f4'))")]
    WrongDtype { path: PathBuf, found: String },
    #[error("{path} has shape {found:?} (rank {rank}), expected rank {expected} ({layout})")]
    WrongRank {
        path: PathBuf,
        found: Vec<usize>,
        rank: usize,
        expected: usize,
        layout: &'static str,
    },
    #[error("{path} is stored in Fortran order; save it in C order (np.ascontiguousarray)")]
    FortranOrder { path: PathBuf },
    #[error("{path}: {reason}")]
    BadMeta { path: PathBuf, reason: String },
    #[error("{path} is inconsistent with {other}: {reason}")]
    Inconsistent {
        path: PathBuf,
        other: PathBuf,
        reason: String,
    },
    #[error("{path} is not empty; pass --force to overwrite it")]
    NotEmpty { path: PathBuf },
}
