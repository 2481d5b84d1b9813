//! The keypoint encoder for body positions. What moves is found without masks: the frames are
//! standardised against the mean training frame (`data`), so a static camera's background drops
//! out and what is left, taken with the sign of its skew (bright bodies on a dark mean or dark
//! on bright), is the moving bodies' mass g. A small convolutional net splits every pixel's
//! mass between the bodies (a softmax over one channel per body), and each body's latent is
//! the centroid of its share, in half the larger frame side from the centre.
//!
//! Why this shape: a centroid of mass carried by the bodies is affine in their positions, so
//! whatever split the net learns, the latent is a mixture of the true positions (exactly, up to
//! overlaps and the background showing through): body one's share of each body's mass a₁, a₂
//! and body two's b₁, b₂ give d = (b₂ − a₂)·(true d) — the law holds with k unchanged and l
//! scaled, and the KL term on d (`physics::spring`) pushes the split towards whole bodies. An
//! MLP on pixels, or a free heat map per body, can also satisfy the loss with the free-particle
//! solution (k → 0, both "bodies" affine in the centre of mass); measured, they find it.

use tch::nn::{self, Module};
use tch::{Kind, Tensor};

/// Channels of the two hidden convolutions.
const HIDDEN: [i64; 2] = [8, 16];
/// Kernel width of every convolution: three give a 13-cell receptive field (39 px of a 64-px
/// frame pooled by 3, about twice a 20-px digit).
const KERNEL: i64 = 5;
/// The mass grid's shorter side is pooled down to about this many cells (by a whole factor: a
/// 64-px frame by 3, to 21). Measured against 32 cells (a 64-px frame pooled by 2) on the
/// spring's default set: the run 100.6 → 53.9 s on 2 cores (the convolutions were 85 % of an
/// epoch), k +0.150 → +0.157 %, rest length +0.724 → +0.516 %. Held out, 32 cells collapsed
/// to the free particle on the default scene at seeds 1 and 2 and with k = 3, where 21 cells
/// found k within 0.3 % (docs/status.md).
const GRID: i64 = 21;

/// Conv(5) → ReLU → Conv(5) → ReLU → Conv(5) to one channel per body, softmax over bodies,
/// centroid of each body's share of the mass.
#[derive(Debug)]
pub struct Keypoints {
    convs: Vec<nn::Conv2D>,
    /// Channels, height and width of a frame.
    frame: (i64, i64, i64),
    /// Frames are average-pooled by this factor first.
    pool: i64,
    /// +1 when the bodies are brighter than the mean frame, −1 when darker.
    polarity: f64,
}

impl Keypoints {
    /// `bodies` keypoints of frames of `frame` = (C, H, W) whose standardised pixels skew
    /// towards `polarity`'s sign.
    pub fn new(path: &nn::Path, frame: (i64, i64, i64), bodies: i64, polarity: f64) -> Keypoints {
        let conv = |i: usize, from: i64, to: i64| {
            // PyTorch's default bound 1/√fan_in, weights and biases: tch's default (Kaiming
            // with the ReLU gain) is 2.4× wider per layer, and three layers of it saturate
            // the split's softmax at the start, where its gradient vanishes (measured: the
            // split then never finds the bodies).
            let bound = 1.0 / ((from * KERNEL * KERNEL) as f64).sqrt();
            let init = nn::Init::Uniform {
                lo: -bound,
                up: bound,
            };
            let cfg = nn::ConvConfig {
                padding: KERNEL / 2,
                ws_init: init,
                bs_init: init,
                ..Default::default()
            };
            nn::conv2d(path / format!("conv{i}"), from, to, KERNEL, cfg)
        };
        let convs = vec![
            conv(0, frame.0, HIDDEN[0]),
            conv(1, HIDDEN[0], HIDDEN[1]),
            conv(2, HIDDEN[1], bodies),
        ];
        Keypoints {
            convs,
            frame,
            pool: (frame.1.min(frame.2) / GRID).max(1),
            polarity: if polarity < 0.0 { -1.0 } else { 1.0 },
        }
    }
}

/// Which way standardised frames `x` skew: the sign of their third moment (sparse bright
/// bodies give a long positive tail).
pub fn polarity(x: &Tensor) -> f64 {
    let third = x.pow_tensor_scalar(3).mean(Kind::Float).double_value(&[]);
    if third < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// `x` [N, C, H, W] laid out channels-last (NHWC strides, the same shape and values).
fn channels_last(x: &Tensor) -> Tensor {
    x.permute([0, 2, 3, 1]).contiguous().permute([0, 3, 1, 2])
}

/// Coordinates of the centres of `n` cells of `size` units each, centred on 0.
pub(super) fn centres(n: i64, size: f64, like: &Tensor) -> Tensor {
    (Tensor::arange(n, (Kind::Float, like.device())) + 0.5 - n as f64 / 2.0) * size
}

impl Module for Keypoints {
    /// Frames [F, C·H·W] → keypoints [F, 2·bodies] as (x1, y1, x2, y2, …).
    fn forward(&self, x: &Tensor) -> Tensor {
        let (c, h, w) = self.frame;
        let f = x.size()[0];
        let mut x = x.view([f, c, h, w]);
        if self.pool > 1 {
            x = x.avg_pool2d(
                [self.pool, self.pool],
                [self.pool, self.pool],
                [0, 0],
                false,
                true,
                None,
            );
        }
        let (gh, gw) = (x.size()[2], x.size()[3]);
        // On the CPU convolved channels-last (oneDNN; measured: the spring's epoch 1.48 →
        // 1.16 s on 2 cores, k and l the same to 6 digits); on a GPU as measured there.
        let layout = |t: &Tensor| {
            if t.device() == tch::Device::Cpu {
                channels_last(t)
            } else {
                t.shallow_clone()
            }
        };
        let mut y = layout(&x);
        for (i, conv) in self.convs.iter().enumerate() {
            y = y.conv2d(
                &layout(&conv.ws),
                conv.bs.as_ref(),
                [1, 1],
                [KERNEL / 2, KERNEL / 2],
                [1, 1],
                1,
            );
            if i + 1 < self.convs.len() {
                y = y.relu();
            }
        }
        let k = y.size()[1];
        let mass = (&x * self.polarity)
            .relu()
            .sum_dim_intlist(1, true, Kind::Float)
            .view([f, 1, gh * gw]);
        let share = y.view([f, k, gh * gw]).softmax(1, Kind::Float) * mass;
        let share =
            (&share / (share.sum_dim_intlist(-1, true, Kind::Float) + 1e-6)).view([f, k, gh, gw]);
        // Cells in half the larger side, the same unit on both axes.
        let cell = 2.0 / gh.max(gw) as f64;
        let px = (share.sum_dim_intlist(2, false, Kind::Float) * centres(gw, cell, &x))
            .sum_dim_intlist(-1, false, Kind::Float);
        let py = (share.sum_dim_intlist(3, false, Kind::Float) * centres(gh, cell, &x))
            .sum_dim_intlist(-1, false, Kind::Float);
        Tensor::stack(&[px, py], -1).view([f, 2 * k])
    }
}
