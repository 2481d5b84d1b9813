//! `estimate`'s library: decoder-free physical parameter estimation from video (CVPR 2025,
//! arXiv 2410.01376) on libtorch: an MLP encoder maps frames to a latent, a physics block with
//! learnable parameters rolls it forward, and the loss compares the two.

pub mod blocks;
pub mod calibration;
pub mod cli;
pub mod config;
pub mod data;
pub mod encoder;
pub mod ensemble;
pub mod error;
pub mod loss;
pub mod pendulum;
pub mod physics;
pub mod plots;
pub mod progress;
pub mod recording;
pub mod report;
pub mod reproduce;
pub mod run;
pub mod spectral;
pub mod timeline;
pub mod train;

pub use config::{DeviceChoice, EstimateConfig, ModelKind};
pub use error::EstimateError;
pub use run::run;
