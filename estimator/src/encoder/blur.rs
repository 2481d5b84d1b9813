//! The frames blurred for locating an object (`centroid`): where the plain map's peak jumps
//! between things, a blob outweighs a thin line there.

use tch::{Kind, Tensor};

/// The Gaussian blur (pixels) of the smoothed map an object is located on where the plain
/// map's peak jumps between things (`data::object`): a faint bob under a dark rod, whose
/// ghost in the background frame (where the rod hangs most of the time) outweighs the bob
/// pixel for pixel but not blob for blob. Measured on a rendered rod and bob at low contrast,
/// 62×90 pixels: 0 and 1 px leave the path jumping (its second differences 1.3–1.5× its first),
/// 2 and 3 px give a smooth one (0.2×) whose x is affine in sin θ to R² 0.9998.
pub const SMOOTH_PX: f64 = 2.0;

/// Images blurred in one pass of the convolution.
const BLURRED_AT_ONCE: i64 = 256;

/// Frames `x` [F, C·H·W] blurred by a Gaussian of [`SMOOTH_PX`] pixels (each channel, zero
/// beyond the edges) and standardised again, [F, C·H·W].
pub(super) fn smoothed(x: &Tensor, (c, h, w): (i64, i64, i64)) -> Tensor {
    let f = x.size()[0];
    let r = (3.0 * SMOOTH_PX).ceil() as i64;
    let taps: Vec<f32> = (-r..=r)
        .map(|k| (-0.5 * (k as f64 / SMOOTH_PX).powi(2)).exp() as f32)
        .collect();
    let sum: f32 = taps.iter().sum();
    let kernel =
        Tensor::from_slice(&taps.iter().map(|t| t / sum).collect::<Vec<_>>()).to_device(x.device());
    let img = x.reshape([f * c, 1, h, w]);
    // A few hundred images a pass: the convolution's working memory grows with the batch (all
    // 3 280 frames of a recording at once took 2 GB, where the frames are 73 MB).
    let parts: Vec<Tensor> = img
        .split(BLURRED_AT_ONCE, 0)
        .iter()
        .map(|part| {
            let down = part.conv2d(
                &kernel.view([1, 1, -1, 1]),
                None::<Tensor>,
                [1, 1],
                [r, 0],
                [1, 1],
                1,
            );
            down.conv2d(
                &kernel.view([1, 1, 1, -1]),
                None::<Tensor>,
                [1, 1],
                [0, r],
                [1, 1],
                1,
            )
        })
        .collect();
    let both = Tensor::cat(&parts, 0);
    let both = both.reshape([f, c * h * w]);
    &both / both.square().mean(Kind::Float).sqrt().clamp_min(1e-9)
}
