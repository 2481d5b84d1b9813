//! Writing a generated dataset: `generate_to_disk` streams pieces of samples to a writer thread
//! while the next piece renders, then writes `meta.json` (`dataset_meta`) and the preview.

use crate::config::GenConfig;
use crate::error::{invalid, ConfigError};
use crate::generate::{generate_samples, Generated};
use physvid_shared::contact_sheet::{contact_sheet, encode_png};
use physvid_shared::meta::{GeneratorInfo, PerturbationSpec, FORMAT_NAME, FORMAT_VERSION};
use physvid_shared::{DatasetError, DatasetFiles, DatasetMeta, DatasetWriter, ModelSpec};

/// Version written into `meta.json`.
pub const GENERATOR_VERSION: &str = env!("CARGO_PKG_VERSION");

/// Samples rendered per piece handed to the writer thread.
const SAMPLES_PER_PIECE: usize = 64;

/// The metadata of a generated dataset.
pub fn dataset_meta(cfg: &GenConfig, g: &Generated) -> DatasetMeta {
    let scene = cfg.scene;
    DatasetMeta {
        format: FORMAT_NAME.into(),
        format_version: FORMAT_VERSION,
        generator: GeneratorInfo {
            name: "gen".into(),
            version: GENERATOR_VERSION.into(),
        },
        scenario: scene.name().into(),
        model: ModelSpec {
            name: scene.model_name().into(),
            parameters: scene.model_parameters(&cfg.params),
            file: scene.model_source().map(str::to_string),
        },
        dt: cfg.dt,
        shape: cfg.shape(),
        seed: cfg.seed,
        noise: cfg.noise,
        latent_mapping: scene.mapping_text().into(),
        calibration: scene.calibration(&cfg.params, cfg.size, &g.latents),
        fps: scene.fps(cfg.dt),
        clip_start_times: scene
            .released_from_rest()
            .then(|| g.samples.iter().map(|s| s.0["start_time"]).collect()),
        sampling: scene.sampling_text().into(),
        samples: g.samples.clone(),
        latent_dims: scene.latent_dims(),
        latents: g.latents.clone(),
        perturbations: cfg
            .perturbations
            .iter()
            .map(|p| PerturbationSpec {
                name: p.perturbation.name().into(),
                level: p.level,
                description: p.perturbation.help().into(),
            })
            .collect(),
    }
}

/// The refusal of a data set with a clip that shows no motion within the frame (`still`: the
/// clip and its largest change) or whose motion overflows (`overflow`), naming the flags that
/// set the motion.
pub(crate) fn refused(
    cfg: &GenConfig,
    still: Option<(usize, f32)>,
    overflow: Option<usize>,
) -> Result<(), ConfigError> {
    if let Some(clip) = overflow {
        return Err(refusal(
            cfg,
            format!(
                "clip {clip}'s motion is not finite at these values (it overflows): the data \
                 set would hold no number for it; choose values nearer the physical range"
            ),
        ));
    }
    if let Some((clip, change)) = still {
        return Err(refusal(
            cfg,
            format!(
                "clip {clip} shows no motion within the frame (no pixel changes by more than \
                 1/512 of the grey range, largest change {change:.1e}): the object is outside \
                 the frame, too small, or does not move within a clip at these values"
            ),
        ));
    }
    Ok(())
}

/// A refusal of the data set `cfg` describes for `why`, naming the flag behind its values
/// (`--set` for the scenes that take it, else `--dt`).
fn refusal(cfg: &GenConfig, why: String) -> ConfigError {
    let (flag, what) = if cfg.scene.accepts_set() {
        let values: Vec<String> = cfg
            .params
            .iter()
            .map(|(k, v)| format!("{k}={}", physvid_shared::cli::num(*v)))
            .collect();
        ("--set", values.join(","))
    } else {
        ("--dt", format!("{}", cfg.dt))
    };
    invalid(flag, what, why)
}

/// The preview PNG: up to four clips × all frames, magnified 2×, from the frames of the first
/// clips (at least four, or all of them).
pub fn preview_png(cfg: &GenConfig, first_frames: &[f32]) -> Vec<u8> {
    let rows: Vec<usize> = (0..cfg.samples.min(4)).collect();
    encode_png(&contact_sheet(first_frames, cfg.shape(), &rows, 2))
}

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
        still: None,
        overflow: None,
    };
    let (mut still, mut overflow) = (None, None);
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
            if g.still.is_some() || g.overflow.is_some() {
                // Nothing is renamed into place: the writer's partial files go with it.
                (still, overflow) = (g.still, g.overflow);
                break;
            }
            if start == 0 {
                let [_, t, c, h, w] = cfg.shape();
                let per_sample = t * c * h * w;
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
    if let Err(e) = refused(cfg, still, overflow) {
        drop(writer); // Nothing is renamed into place.
        return Err(e.into());
    }
    let meta = dataset_meta(cfg, &truth);
    let png = preview_png(cfg, &preview_frames);
    Ok(writer.finish(&meta, &png)?)
}
