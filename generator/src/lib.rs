//! `gen`'s library: renders seeded synthetic videos of a damped oscillator (intensity, position
//! or scale of a disc) with tiny-skia and writes them in the shared dataset format.

pub mod config;
pub mod generate;
pub mod render;
pub mod sampling;
pub mod scenario;

pub use config::{ConfigError, GenConfig};
pub use generate::{generate, generate_samples, Generated};
pub use scenario::Scenario;

use physvid_shared::contact_sheet::{contact_sheet, encode_png};
use physvid_shared::meta::{GeneratorInfo, FORMAT_NAME, FORMAT_VERSION};
use physvid_shared::{
    DampedOscillator, DatasetError, DatasetFiles, DatasetMeta, DatasetWriter, ModelSpec,
};
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

/// The preview PNG: up to four clips × all frames, magnified 2×, from the frames of the first
/// clips (at least four, or all of them).
pub fn preview_png(cfg: &GenConfig, first_frames: &[f32]) -> Vec<u8> {
    let rows: Vec<usize> = (0..cfg.samples.min(4)).collect();
    encode_png(&contact_sheet(first_frames, cfg.shape(), &rows, 2))
}

/// Samples rendered per piece handed to the writer thread.
const SAMPLES_PER_PIECE: usize = 64;

/// Renders and writes the dataset, streaming: while the next piece of samples renders (rayon),
/// a writer thread appends the previous one to `frames.npy` and flushes it to the device, so
/// writing overlaps rendering and memory holds only a few pieces. Returns the written paths.
pub fn generate_to_disk(cfg: &GenConfig) -> anyhow::Result<DatasetFiles> {
    let mut writer = DatasetWriter::create(&cfg.out, cfg.shape(), cfg.force)?;
    let mut all = Generated {
        frames: Vec::new(),
        samples: Vec::with_capacity(cfg.samples),
        latents: Vec::with_capacity(cfg.samples),
    };
    let preview_samples = cfg.samples.min(4);
    let written: Result<DatasetWriter, DatasetError> = std::thread::scope(|s| {
        let (tx, rx) = std::sync::mpsc::sync_channel::<Vec<f32>>(1);
        let handle = s.spawn(move || {
            for piece in rx {
                writer.write_frames(&piece)?;
            }
            Ok(writer)
        });
        for start in (0..cfg.samples).step_by(SAMPLES_PER_PIECE) {
            let end = (start + SAMPLES_PER_PIECE).min(cfg.samples);
            let g = generate_samples(cfg, start..end);
            if start == 0 {
                let per_sample = cfg.frames * cfg.size * cfg.size;
                all.frames = g.frames[..preview_samples * per_sample].to_vec();
            }
            all.samples.extend(g.samples);
            all.latents.extend(g.latents);
            if tx.send(g.frames).is_err() {
                break; // The writer failed; its error comes back from join.
            }
        }
        drop(tx);
        handle.join().expect("writer thread does not panic")
    });
    let writer = written?;
    let meta = dataset_meta(cfg, &all);
    let png = preview_png(cfg, &all.frames);
    Ok(writer.finish(&meta, &png)?)
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
