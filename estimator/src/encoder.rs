//! `Encoder`: the MLP that maps each flattened frame to one scalar latent z.

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
}

impl EncoderKind {
    pub fn name(self) -> &'static str {
        match self {
            EncoderKind::Small => "small",
            EncoderKind::Paper => "paper",
            EncoderKind::Linear => "linear",
        }
    }

    pub fn hidden_layers(self) -> &'static [i64] {
        match self {
            EncoderKind::Small => &[16],
            EncoderKind::Paper => &[1000, 100],
            EncoderKind::Linear => &[],
        }
    }
}

/// An MLP with ReLU between layers and Kaiming-uniform (fan-in, ReLU gain) weights, tch's default.
#[derive(Debug)]
pub struct Encoder {
    seq: nn::Sequential,
}

impl Encoder {
    pub fn new(path: &nn::Path, inputs: i64, kind: EncoderKind) -> Encoder {
        let mut seq = nn::seq();
        let mut width = inputs;
        for (i, &h) in kind.hidden_layers().iter().enumerate() {
            seq = seq
                .add(nn::linear(
                    path / format!("fc{i}"),
                    width,
                    h,
                    Default::default(),
                ))
                .add_fn(|x| x.relu());
            width = h;
        }
        seq = seq.add(nn::linear(path / "out", width, 1, Default::default()));
        Encoder { seq }
    }

    /// Latents of clips `x` [B, T, D] → [B, T], all B·T frames in one pass.
    pub fn encode(&self, x: &Tensor) -> Tensor {
        let (b, t, d) = x.size3().expect("clips are [B, T, D]");
        self.seq.forward(&x.reshape([b * t, d])).view([b, t])
    }
}
