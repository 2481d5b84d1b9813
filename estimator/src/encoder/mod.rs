//! `Encoder`: maps each frame to its latent (one number, or several for models with a vector
//! latent). The MLPs (`mlp.rs`) read flattened pixels; the keypoint net (`keypoints.rs`) reads
//! body positions off the image; the centroid (`centroid.rs`) one object's position.

pub mod blur;
pub mod centroid;
mod keypoints;
mod mlp;
pub mod template;

pub use keypoints::polarity;

use tch::nn::{self, Module};
use tch::Tensor;

/// Encoder architectures.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum EncoderKind {
    /// D → 16 → 1 with ReLU: fast, and accurate on every synthetic set.
    Small,
    /// The paper's D → 1000 → 100 → 1 with ReLU.
    Paper,
    /// D → 1: an affine map of the pixels (enough when brightness or coverage is affine in z).
    Linear,
    /// Body positions: the centroids of each body's share of what differs from the mean frame
    /// (vector latents of (x, y) per body only).
    Keypoints,
    /// The position of one object: the centroid of where the frame differs most from the
    /// background (or, where that jumps between things, where a template of the object
    /// matches best), mapped affinely to the latent (falls, slides, a bob or a mass).
    Centroid,
}

impl EncoderKind {
    pub fn name(self) -> &'static str {
        match self {
            EncoderKind::Small => "small",
            EncoderKind::Paper => "paper",
            EncoderKind::Linear => "linear",
            EncoderKind::Keypoints => "keypoints",
            EncoderKind::Centroid => "centroid",
        }
    }

    /// Whether the first layer reads every pixel with a weight of its own (small, paper,
    /// linear), rather than through a fixed or shared front end (keypoints, centroid).
    pub fn is_dense(self) -> bool {
        matches!(
            self,
            EncoderKind::Small | EncoderKind::Paper | EncoderKind::Linear
        )
    }

    /// Whether this encoder can give `dims` numbers per frame (keypoints give an (x, y) pair
    /// per body, so an even number of at least two).
    pub fn gives(self, dims: usize) -> bool {
        self != EncoderKind::Keypoints || (dims >= 2 && dims.is_multiple_of(2))
    }
}

/// The encoder of a run: a fixed front end (none but for the centroid) and a learned net.
#[derive(Debug)]
pub struct Encoder {
    front: Option<centroid::Front>,
    net: Box<dyn Module>,
    dims: i64,
}

impl Encoder {
    /// An encoder of frames of `frame` = (C, H, W) to `dims` latent numbers; `train` holds the
    /// standardised training clips (the keypoint encoder reads which way bodies differ from
    /// the mean frame off them); the centroid reads the object where `at` says
    /// (`centroid::Front`: a descent's position along its line, or an object located as found).
    pub fn new(
        path: &nn::Path,
        frame: (i64, i64, i64),
        kind: EncoderKind,
        dims: i64,
        train: &Tensor,
        at: centroid::Where,
    ) -> Encoder {
        let inputs = frame.0 * frame.1 * frame.2;
        let front = (kind == EncoderKind::Centroid).then(|| centroid::Front::new(frame, train, at));
        let net: Box<dyn Module> = match kind {
            // The small encoder widens with the latent.
            EncoderKind::Small => Box::new(mlp::mlp(path, inputs, &[16 * dims], dims)),
            EncoderKind::Paper => Box::new(mlp::mlp(path, inputs, &[1000, 100], dims)),
            EncoderKind::Linear => Box::new(mlp::mlp(path, inputs, &[], dims)),
            EncoderKind::Keypoints => {
                let polarity = keypoints::polarity(train);
                Box::new(keypoints::Keypoints::new(path, frame, dims / 2, polarity))
            }
            EncoderKind::Centroid => Box::new(centroid::head(path, dims)),
        };
        Encoder { front, net, dims }
    }

    /// What the learned net reads of clips `x` [B, T, pixels]: the fixed front end's output
    /// [B, T, k] (computed without gradients, 64 clips at a time), or `x` itself. Training
    /// computes it once (`train::Trainer`): recomputed at every step, the centroid's front end
    /// had taken the shared pendulum recording's run from 9.6 to 27.9 s.
    pub fn input(&self, x: &Tensor) -> Tensor {
        let Some(front) = &self.front else {
            return x.shallow_clone();
        };
        let (b, t, d) = x.size3().expect("clips are [B, T, pixels]");
        tch::no_grad(|| {
            let parts: Vec<Tensor> = (0..b)
                .step_by(64)
                .map(|s| {
                    let n = (b - s).min(64);
                    let p = front.positions(&x.narrow(0, s, n).reshape([n * t, d]));
                    p.view([n, t, -1])
                })
                .collect();
            Tensor::cat(&parts, 0)
        })
    }

    /// Latents of clips `x` [B, T, pixels]: [B, T] for one number per frame, else
    /// [B, T, dims]; all B·T frames in one pass.
    pub fn encode(&self, x: &Tensor) -> Tensor {
        self.encode_input(&self.input(x))
    }

    /// Latents of what [`Encoder::input`] made of clips: the learned net alone.
    pub fn encode_input(&self, i: &Tensor) -> Tensor {
        let (b, t, d) = i.size3().expect("inputs are [B, T, k]");
        let z = self.net.forward(&i.reshape([b * t, d]));
        if self.dims == 1 {
            z.view([b, t])
        } else {
            z.view([b, t, self.dims])
        }
    }
}

/// Test frames [F·H·W]: a light wall (0.8) with dark rectangles (0.6 darker, their edges drawn at
/// their fraction of a pixel), those of frame f `rects(rows[f])` as [top, bottom, left, right].
#[cfg(test)]
fn drawn(rows: &[f64], h: i64, w: i64, rects: impl Fn(f64) -> Vec<[f64; 4]>) -> Vec<f32> {
    let mut v = vec![0.8f32; rows.len() * (h * w) as usize];
    let cover =
        |from: f64, to: f64, p: i64| (((p + 1) as f64).min(to) - (p as f64).max(from)).max(0.0);
    for (f, &r) in rows.iter().enumerate() {
        for [top, bottom, left, right] in rects(r) {
            for y in 0..h {
                for x in 0..w {
                    let c = cover(top, bottom, y) * cover(left, right, x);
                    v[f * (h * w) as usize + (y * w + x) as usize] -= (0.6 * c) as f32;
                }
            }
        }
    }
    v
}
