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
    #[error(
        "--out {path}: the folder is not empty; choose a new folder, or pass --force to write \
         the data set there (frames.npy, meta.json and preview.png are replaced; nothing of \
         another name is touched)"
    )]
    NotEmpty { path: PathBuf },
    /// An array larger than the memory this machine can give (its header read, nothing
    /// allocated).
    #[error(
        "{path}: its {} of values need about {} to train on (the array, its tensor and their \
         standardised copy), more than the {} this machine has free; use fewer clips or \
         smaller frames",
        gb(*bytes), gb(bytes.saturating_mul(3)), gb(*available)
    )]
    TooLarge {
        path: PathBuf,
        bytes: u64,
        available: u64,
    },
    /// The output folder was refused (not this tool's, busy, a link out of it): bad input.
    #[error("{0}")]
    Refused(String),
}

fn gb(bytes: u64) -> String {
    format!("{:.1} GB", bytes as f64 / 1e9)
}
