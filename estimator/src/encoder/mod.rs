//! `Encoder`: maps each frame to its latent (one number, or several for models with a vector
//! latent). The MLPs (`mlp.rs`) read flattened pixels; the keypoint net (`keypoints.rs`) reads
//! body positions off the image; the centroid (`centroid.rs`) one object's position.

pub mod centroid;
mod keypoints;
mod mlp;

pub use keypoints::polarity;

use tch::nn::{self, Module};
use tch::Tensor;

/// Encoder architectures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, serde::Serialize)]
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
    /// The position of one object crossing the frame: the centroid of where the frame differs
    /// most from the mean frame, mapped affinely to the latent (falls and slides).
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

    /// Whether this encoder can give `dims` numbers per frame (keypoints give an (x, y) pair
    /// per body, so an even number of at least two).
    pub fn gives(self, dims: usize) -> bool {
        self != EncoderKind::Keypoints || (dims >= 2 && dims.is_multiple_of(2))
    }
}

/// The encoder of a run.
#[derive(Debug)]
pub struct Encoder {
    net: Box<dyn Module>,
    dims: i64,
}

impl Encoder {
    /// An encoder of frames of `frame` = (C, H, W) to `dims` latent numbers; `train` holds the
    /// standardised training clips (the keypoint encoder reads which way bodies differ from
    /// the mean frame off them).
    pub fn new(
        path: &nn::Path,
        frame: (i64, i64, i64),
        kind: EncoderKind,
        dims: i64,
        train: &Tensor,
    ) -> Encoder {
        let inputs = frame.0 * frame.1 * frame.2;
        let net: Box<dyn Module> = match kind {
            // The small encoder widens with the latent.
            EncoderKind::Small => Box::new(mlp::mlp(path, inputs, &[16 * dims], dims)),
            EncoderKind::Paper => Box::new(mlp::mlp(path, inputs, &[1000, 100], dims)),
            EncoderKind::Linear => Box::new(mlp::mlp(path, inputs, &[], dims)),
            EncoderKind::Keypoints => {
                let polarity = keypoints::polarity(train);
                Box::new(keypoints::Keypoints::new(path, frame, dims / 2, polarity))
            }
            EncoderKind::Centroid => Box::new(centroid::Centroid::new(path, frame, dims, train)),
        };
        Encoder { net, dims }
    }

    /// Latents of clips `x` [B, T, pixels]: [B, T] for one number per frame, else
    /// [B, T, dims]; all B·T frames in one pass.
    pub fn encode(&self, x: &Tensor) -> Tensor {
        let (b, t, d) = x.size3().expect("clips are [B, T, pixels]");
        let z = self.net.forward(&x.reshape([b * t, d]));
        if self.dims == 1 {
            z.view([b, t])
        } else {
            z.view([b, t, self.dims])
        }
    }
}
