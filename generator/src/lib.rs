//! `gen`'s library: renders seeded synthetic videos of known dynamics (the damped oscillator's
//! disc scenes and the Delfys75 systems, `scenes/`) with tiny-skia and writes them in the shared
//! dataset format.

pub mod cli;
pub mod config;
pub mod error;
pub mod generate;
pub mod memory;
pub mod perturb;
pub mod render;
pub mod sampling;
pub mod scenes;
pub mod write;

pub use cli::GenArgs;
pub use config::GenConfig;
pub use error::ConfigError;
pub use generate::{generate, generate_samples, Generated};
pub use memory::{generate_in_memory, InMemory};
pub use scenes::{SceneRef, SCENES};
pub use write::{dataset_meta, generate_to_disk, preview_png, GENERATOR_VERSION};

use std::time::Instant;

/// Runs `gen`: generates, writes and reports where the files are.
pub fn run(cfg: &GenConfig) -> anyhow::Result<()> {
    let start = Instant::now();
    let files = generate_to_disk(cfg)?;
    let [n, t, c, h, w] = cfg.shape();
    eprintln!(
        "gen: {} set, {n}×{t}×{c}×{h}×{w} float32 ({:.1} MB), seed {}, in {:.2} s",
        cfg.scene,
        (n * t * c * h * w * 4) as f64 / 1e6,
        cfg.seed,
        start.elapsed().as_secs_f64()
    );
    physvid_shared::term::print(&format!(
        "frames:  {}\nmeta:    {}\npreview: {}",
        files.frames.display(),
        files.meta.display(),
        files.preview.display()
    ))?;
    Ok(())
}
