//! `generate`: renders every sample of a dataset in parallel (rayon over samples).

use crate::config::GenConfig;
use crate::perturb::{apply_all, Clip};
use crate::render::Canvas;
use crate::sampling::sample_rng;
use physvid_shared::SampleTruth;
use rand_distr::{Distribution, StandardNormal};
use rayon::prelude::*;

/// Rendered frames ([N, T, C, H, W] row-major) and the ground truth of every sample (its
/// latents frame-major, `latent_dims` numbers per frame).
#[derive(Debug, Clone)]
pub struct Generated {
    pub frames: Vec<f32>,
    pub samples: Vec<SampleTruth>,
    pub latents: Vec<Vec<f64>>,
    /// The first clip (its index in the data set) whose rendered frames show no motion within
    /// the frame, with the most any pixel changed in it.
    pub still: Option<(usize, f32)>,
    /// The first clip whose motion or truth is not finite (an overflow at extreme `--set`
    /// values): nothing of it is drawn, and the data set is refused.
    pub overflow: Option<usize>,
}

/// A clip whose frames differ from its first by less than this anywhere (a 512th of the grey
/// range, below what an 8-bit camera records) shows no motion.
pub const MIN_CHANGE: f32 = 1.0 / 512.0;

/// Renders the dataset described by `cfg`. The output depends only on `cfg`, never on the
/// number of threads: sample i uses random stream i and writes only its own slice.
pub fn generate(cfg: &GenConfig) -> Generated {
    generate_samples(cfg, 0..cfg.samples)
}

/// Renders samples `range` of the dataset (identical to the same samples of [`generate`]).
pub fn generate_samples(cfg: &GenConfig, range: std::ops::Range<usize>) -> Generated {
    let pixels = cfg.scene.channels(cfg.color) * cfg.size * cfg.size;
    let per_sample = cfg.frames * pixels;
    let dims = cfg.scene.latent_dims();
    let mut frames = vec![0f32; range.len() * per_sample];
    let scene = cfg.scene;
    let truths: Vec<(SampleTruth, Vec<f64>, f32)> = frames
        .par_chunks_mut(per_sample)
        .enumerate()
        .map_init(
            || Canvas::new(cfg.size),
            |canvas, (i, clip)| {
                let mut rng = sample_rng(cfg.seed, range.start + i);
                let (truth, latents) =
                    scene.sample(&cfg.params, &mut rng, cfg.frames, cfg.dt, cfg.size);
                let finite = latents
                    .iter()
                    .chain(truth.0.values())
                    .all(|v| v.is_finite());
                if !finite {
                    return (truth, latents, f32::NAN);
                }
                for (z, frame) in latents
                    .chunks_exact(dims)
                    .zip(clip.chunks_exact_mut(pixels))
                {
                    scene.render(&cfg.params, z, cfg.size, canvas, frame);
                }
                // The largest change from the first frame, before any perturbation.
                let (first, rest) = clip.split_at(pixels);
                let change = rest
                    .chunks_exact(pixels)
                    .flat_map(|f| f.iter().zip(first).map(|(a, b)| (a - b).abs()))
                    .fold(0.0f32, f32::max);
                if !cfg.perturbations.is_empty() {
                    let mut c = Clip {
                        frames: clip,
                        frames_per_clip: cfg.frames,
                        channels: pixels / (cfg.size * cfg.size),
                        size: cfg.size,
                        dt: cfg.dt,
                        canvas,
                    };
                    apply_all(&cfg.perturbations, &mut c, cfg.seed, range.start + i);
                }
                if cfg.noise > 0.0 {
                    let sigma = cfg.noise as f32;
                    for v in clip.iter_mut() {
                        let n: f32 = StandardNormal.sample(&mut rng);
                        *v = (*v + sigma * n).clamp(0.0, 1.0);
                    }
                }
                (truth, latents, change)
            },
        )
        .collect();
    let still = truths
        .iter()
        .enumerate()
        .find(|(_, t)| t.2 < MIN_CHANGE)
        .map(|(i, t)| (range.start + i, t.2));
    let overflow = truths
        .iter()
        .position(|t| t.2.is_nan())
        .map(|i| range.start + i);
    let (samples, latents) = truths.into_iter().map(|(s, l, _)| (s, l)).unzip();
    Generated {
        frames,
        samples,
        latents,
        still,
        overflow,
    }
}
