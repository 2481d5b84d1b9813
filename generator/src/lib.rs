//! `gen`'s library: renders seeded synthetic videos of a damped oscillator (intensity, position
//! or scale of a disc) with tiny-skia and writes them in the shared dataset format.

pub mod config;
pub mod generate;
pub mod render;
pub mod sampling;
pub mod scenario;

pub use config::{ConfigError, GenConfig};
pub use generate::{generate, Generated};
pub use scenario::Scenario;

use physvid_shared::contact_sheet::{contact_sheet, encode_png};
use physvid_shared::dataset::check_output_dir;
use physvid_shared::meta::{GeneratorInfo, FORMAT_NAME, FORMAT_VERSION};
use physvid_shared::{write_dataset, DampedOscillator, DatasetFiles, DatasetMeta, ModelSpec};
use std::time::Instant;

/// Version written into `meta.json`.
pub const GENERATOR_VERSION: &str = env!("CARGO_PKG_VERSION");

/// The metadata of a generated dataset.
pub fn dataset_meta(cfg: &GenConfig, g: &Generated) -> DatasetMeta {
    let model = DampedOscillator {
        omega: cfg.omega,
        zeta: cfg.zeta,
    };
    DatasetMeta {
        format: FORMAT_NAME.into(),
        format_version: FORMAT_VERSION,
        generator: GeneratorInfo {
            name: "gen".into(),
            version: GENERATOR_VERSION.into(),
        },
        scenario: cfg.scenario.name().into(),
        model: ModelSpec {
            name: "damped-oscillator".into(),
            parameters: [
                ("omega", cfg.omega),
                ("zeta", cfg.zeta),
                ("gamma0", model.gamma0()),
                ("gamma1", model.gamma1()),
            ]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect(),
        },
        dt: cfg.dt,
        shape: cfg.shape(),
        seed: cfg.seed,
        noise: cfg.noise,
        latent_mapping: cfg.scenario.mapping_text().into(),
        sampling: sampling::SAMPLING_TEXT.into(),
        samples: g.samples.clone(),
        latents: g.latents.clone(),
    }
}

/// The preview PNG: up to four clips × all frames, magnified 2×.
pub fn preview_png(cfg: &GenConfig, frames: &[f32]) -> Vec<u8> {
    let rows: Vec<usize> = (0..cfg.samples.min(4)).collect();
    encode_png(&contact_sheet(frames, cfg.shape(), &rows, 2))
}

/// Renders and writes the dataset; returns the written paths.
pub fn generate_to_disk(cfg: &GenConfig) -> anyhow::Result<DatasetFiles> {
    check_output_dir(&cfg.out, cfg.force)?;
    let g = generate(cfg);
    let meta = dataset_meta(cfg, &g);
    let png = preview_png(cfg, &g.frames);
    Ok(write_dataset(&cfg.out, &g.frames, &meta, &png, cfg.force)?)
}

/// Runs `gen`: generates, writes and reports where the files are.
pub fn run(cfg: &GenConfig) -> anyhow::Result<()> {
    let start = Instant::now();
    let files = generate_to_disk(cfg)?;
    let [n, t, c, h, w] = cfg.shape();
    eprintln!(
        "gen: {} set, {n}×{t}×{c}×{h}×{w} float32 ({:.1} MB), seed {}, in {:.2} s",
        cfg.scenario,
        (n * t * c * h * w * 4) as f64 / 1e6,
        cfg.seed,
        start.elapsed().as_secs_f64()
    );
    println!("frames:  {}", files.frames.display());
    println!("meta:    {}", files.meta.display());
    println!("preview: {}", files.preview.display());
    Ok(())
}
