//! `gen`'s library: renders seeded synthetic videos of a damped oscillator (intensity, position
//! or scale of a disc) with tiny-skia and writes them in the shared dataset format.

pub mod config;
pub mod delfys;
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
    let (model, calibration, fps) = match cfg.scenario.system() {
        Some(system) => (
            ModelSpec {
                name: system.model_name().into(),
                parameters: system.estimated_parameters(&cfg.params),
            },
            delfys_calibration(cfg, system, g),
            Some(1.0 / cfg.dt),
        ),
        None => {
            let model = DampedOscillator {
                omega: cfg.omega,
                zeta: cfg.zeta,
            };
            (
                ModelSpec {
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
                Default::default(),
                None,
            )
        }
    };
    DatasetMeta {
        format: FORMAT_NAME.into(),
        format_version: FORMAT_VERSION,
        generator: GeneratorInfo {
            name: "gen".into(),
            version: GENERATOR_VERSION.into(),
        },
        scenario: cfg.scenario.name().into(),
        model,
        dt: cfg.dt,
        shape: cfg.shape(),
        seed: cfg.seed,
        noise: cfg.noise,
        latent_mapping: cfg.scenario.mapping_text().into(),
        calibration,
        fps,
        sampling: if cfg.scenario.system().is_some() {
            sampling::DELFYS_SAMPLING_TEXT.into()
        } else {
            sampling::SAMPLING_TEXT.into()
        },
        samples: g.samples.clone(),
        latents: g.latents.clone(),
    }
}

/// The calibration a user would measure for a Delfys75 scene: the scene's scale, and the
/// physical quantity at two reference frames (where it is smallest and largest), which is what
/// turns latent units into SI units (appendix A.6 measures h0 = 7 cm and ht = 1 cm likewise).
fn delfys_calibration(
    cfg: &GenConfig,
    system: delfys::System,
    g: &Generated,
) -> std::collections::BTreeMap<String, serde_json::Value> {
    use serde_json::json;
    let mut c = std::collections::BTreeMap::new();
    let ppm = system.pixels_per_metre(&cfg.params, cfg.size);
    let (mut lo, mut hi) = (
        (0usize, 0usize, f64::INFINITY),
        (0usize, 0usize, f64::NEG_INFINITY),
    );
    for (i, clip) in g.latents.iter().enumerate() {
        for (k, &z) in clip.iter().enumerate() {
            if z < lo.2 {
                lo = (i, k, z);
            }
            if z > hi.2 {
                hi = (i, k, z);
            }
        }
    }
    let quantity = match system {
        delfys::System::Pendulum => "angle theta (rad)",
        delfys::System::Torricelli => "water level h (m)",
        delfys::System::SlidingBlock => "distance along the incline s (m)",
        delfys::System::Led => "brightness I/I(0)",
        delfys::System::FreeFall => "distance from the camera h (m)",
    };
    c.insert(
        "reference_points".into(),
        json!([
            {"clip": lo.0, "frame": lo.1, "value": lo.2},
            {"clip": hi.0, "frame": hi.1, "value": hi.2},
        ]),
    );
    c.insert("quantity".into(), json!(quantity));
    match system {
        delfys::System::FreeFall => {
            c.insert("focal_px_per_m".into(), json!(ppm));
            c.insert("radius".into(), json!(cfg.params["radius"]));
            c.insert("h0".into(), json!(cfg.params["h0"]));
            c.insert("g".into(), json!(cfg.params["g"]));
        }
        delfys::System::SlidingBlock => {
            c.insert("pixels_per_metre".into(), json!(ppm));
            c.insert("incline_deg".into(), json!(cfg.params["incline_deg"]));
            c.insert("g".into(), json!(cfg.params["g"]));
        }
        delfys::System::Pendulum => {
            c.insert("pixels_per_metre".into(), json!(ppm));
            c.insert("g".into(), json!(cfg.params["g"]));
        }
        delfys::System::Torricelli => {
            c.insert("pixels_per_metre".into(), json!(ppm));
        }
        delfys::System::Led => {}
    }
    c
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
    // Ground truth of every sample; only the preview's clips keep their frames in memory.
    let mut truth = Generated {
        frames: Vec::new(),
        samples: Vec::with_capacity(cfg.samples),
        latents: Vec::with_capacity(cfg.samples),
    };
    let mut preview_frames = Vec::new();
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
                preview_frames = g.frames[..preview_samples * per_sample].to_vec();
            }
            truth.samples.extend(g.samples);
            truth.latents.extend(g.latents);
            if tx.send(g.frames).is_err() {
                break; // The writer failed; its error comes back from join.
            }
        }
        drop(tx);
        handle.join().expect("writer thread does not panic")
    });
    let writer = written?;
    let meta = dataset_meta(cfg, &truth);
    let png = preview_png(cfg, &preview_frames);
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
