//! Code shared by `gen` and `estimate`: the closed-form dynamics, the on-disk dataset format
//! (`frames.npy` + `meta.json` + `preview.png`) with its validating reader, and label-free checks.
//!
//! This crate never depends on libtorch: rendering and reading datasets build without it.

pub mod affine;
pub mod atomic;
pub mod child;
pub mod cli;
pub mod contact_sheet;
pub mod dataset;
pub mod dynamics;
pub mod error;
pub mod escape;
pub mod input;
pub mod interrupt;
pub mod linalg;
pub mod memory;
pub mod meta;
pub mod model_file;
pub mod npy;
pub mod outdir;
pub mod recurrence;
pub mod rk4;
pub mod stats;
pub mod systems;
pub mod term;
pub mod video;

pub use affine::{AffineFit, SimilarityFit};
pub use atomic::{write_atomic, PendingFile};
pub use dataset::{
    read_dataset, read_dataset_header, write_dataset, Dataset, DatasetFiles, DatasetHeader,
    DatasetWriter,
};
pub use dynamics::DampedOscillator;
pub use error::DatasetError;
pub use meta::{Calibration, DatasetMeta, ModelSpec, PositionPoint, ReferencePoint, SampleTruth};
