//! `estimate`'s library: decoder-free physical parameter estimation from video (CVPR 2025,
//! arXiv 2410.01376) on libtorch: an encoder maps frames to a latent, a physics block with
//! learnable parameters rolls it forward, and the loss compares the two. The models live in
//! `physics/`, one file each; see ARCHITECTURE.md for the map.
//!
//! A program calls it with a typed [`Request`] (what `estimate`'s flags become) and gets the
//! fit, its verdict and the model choice back, with nothing written:
//!
//! ```
//! # fn main() -> anyhow::Result<()> {
//! use generator::{generate_to_disk, GenConfig, SceneRef};
//! // The paper's intensity set, small: 200 clips of 32×32 (γ0 4.0016, γ1 0.08).
//! let dir = tempfile::tempdir()?;
//! let mut set = GenConfig::new(SceneRef::by_name("intensity").unwrap(), dir.path().join("set"));
//! (set.samples, set.size, set.seed) = (200, 32, 5);
//! generate_to_disk(&set.validate()?)?;
//!
//! let mut req = estimator::Request::new(dir.path().join("set"));
//! req.training.threads = 2;
//! req.quiet = true;
//! let fit = estimator::estimation(&req)?;
//! let gamma0 = fit.report.run.parameters.iter().find(|p| p.name == "gamma0").unwrap();
//! assert!((gamma0.estimate / 4.0016 - 1.0).abs() < 0.01, "{}", gamma0.estimate);
//! println!("{}", fit.report.verdict.text());
//! # Ok(())
//! # }
//! ```

pub mod agreement;
pub mod analysis;
pub mod batch;
pub mod calibration;
pub mod choice;
pub mod cli;
pub mod config;
pub mod data;
pub mod device;
pub mod digits;
pub mod encoder;
pub mod error;
pub mod evidence;
pub mod guide;
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
pub mod track;
pub mod train;
pub mod verdict;
pub mod windows;

pub use cli::EstimateArgs;
pub use config::{Request, RunConfig};
pub use error::EstimateError;
pub use run::{chooses, estimate, estimation, estimation_watched, run, Estimation, Watch};
