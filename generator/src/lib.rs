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
        clip_start_times: cfg
            .scenario
            .system()
            .filter(|s| s.released_from_rest())
            .map(|_| g.samples.iter().map(|s| s.0["start_time"]).collect()),
        sampling: if cfg.scenario.system().is_some() {
            sampling::DELFYS_SAMPLING_TEXT.into()
        } else {
            sampling::SAMPLING_TEXT.into()
        },
        samples: g.samples.clone(),
        latents: g.latents.clone(),
    }
}

/// Fractions of the physical quantity's range at which `reference_points` are taken.
pub const REFERENCE_FRACTIONS: [f64; 5] = [0.1, 0.3, 0.5, 0.7, 0.9];

/// The calibration a user would measure for a Delfys75 scene: the scene's scale, and the
/// physical quantity at five reference frames spread over its range (those nearest to 10, 30,
/// 50, 70 and 90 % of it), which is what turns latent units into SI units (appendix A.6 measures
/// h0 = 7 cm and ht = 1 cm likewise; marks inside the range, rather than at its ends, where a
/// clip's first or last frame sits, make the scale less sensitive to any one frame).
fn delfys_calibration(
    cfg: &GenConfig,
    system: delfys::System,
    g: &Generated,
) -> std::collections::BTreeMap<String, serde_json::Value> {
    use serde_json::json;
    let mut c = std::collections::BTreeMap::new();
    let ppm = system.pixels_per_metre(&cfg.params, cfg.size);
    let all = || {
        g.latents
            .iter()
            .enumerate()
            .flat_map(|(i, clip)| clip.iter().enumerate().map(move |(k, &z)| (i, k, z)))
    };
    let lo = all().map(|p| p.2).fold(f64::INFINITY, f64::min);
    let hi = all().map(|p| p.2).fold(f64::NEG_INFINITY, f64::max);
    let points: Vec<serde_json::Value> = REFERENCE_FRACTIONS
        .iter()
        .map(|f| {
            let target = lo + f * (hi - lo);
            // The first frame nearest the target (a strict `<` keeps ties deterministic).
            let mut best = (0, 0, f64::NAN);
            for (i, k, z) in all() {
                if best.2.is_nan() || (z - target).abs() < (best.2 - target).abs() {
                    best = (i, k, z);
                }
            }
            json!({"clip": best.0, "frame": best.1, "value": best.2})
        })
        .collect();
    let quantity = match system {
        delfys::System::Pendulum => "angle theta (rad)",
        delfys::System::Torricelli => "water level h (m)",
        delfys::System::SlidingBlock => "distance along the incline s (m)",
        delfys::System::Led => "brightness I/I(0)",
        delfys::System::FreeFall => "distance from the camera h (m)",
    };
    c.insert("reference_points".into(), json!(points));
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
