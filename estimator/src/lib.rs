//! `estimate`'s library: decoder-free physical parameter estimation from video (CVPR 2025,
//! arXiv 2410.01376) on libtorch: an encoder maps frames to a latent, a physics block with
//! learnable parameters rolls it forward, and the loss compares the two. The models live in
//! `physics/`, one file each; see ARCHITECTURE.md for the map.

pub mod batch;
pub mod calibration;
pub mod choice;
pub mod cli;
pub mod config;
pub mod data;
pub mod device;
pub mod encoder;
pub mod error;
pub mod evidence;
pub mod html;
pub use physvid_shared::linalg;
pub mod loss;
pub mod memory;
pub mod network;
pub mod output;
pub mod pca;
pub mod peaks;
pub mod physics;
pub mod plots;
pub mod progress;
pub mod report;
pub mod run;
pub mod timeline;
pub mod train;
pub mod verdict;
pub mod windows;

pub use cli::EstimateArgs;
pub use config::RunConfig;
pub use error::EstimateError;
pub use run::{estimate, estimation, run};
