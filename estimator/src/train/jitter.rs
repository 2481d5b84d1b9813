//! Fresh sensor noise on the training frames of a dense encoder (one whose first layer reads
//! every pixel), so that it does not read the frames' own noise. Where its first layer has more
//! weights than there are training frames (gen's free fall: 1600 frames, 2500 pixels × 16
//! units) each frame's noise is a private code it can map to whatever latent the law wants: the
//! training loss falls while the validation error rises (σ = 0.02 on the free fall: g −8.7 %);
//! elsewhere the noise it reads passes into the latent (a linear read of a noisy tank: k
//! +2.1 %, its law 6.3 % unexplained). Each epoch the training frames get new noise at twice
//! the level they already carry: reading the frames' fixed noise through a weight then costs
//! four times the variance it could explain (noise injection acts as a ridge penalty of σ² on
//! the weights). On the free fall at ×1 g came out −5.6 %, at ×2 −2.6 %, at ×3 −2.3 %.

use crate::config::RunConfig;
use crate::data::ClipData;
use tch::{Kind, Tensor};

/// Frames sampled for the noise estimate.
const SAMPLE: i64 = 256;
/// The added noise against the frames' own.
const FACTOR: f64 = 2.0;
/// At or below this level (in the standardised frames' units) no noise is added. Noise-free
/// renders read a little off their moving edges (gen's clean sets, every scene at seed 0:
/// 0 for most, 0.0015 for free fall setting 3, 0.0032 for the spring, 0.0051 for scale), and
/// fresh noise there only moved their answers about (free fall setting 3: −0.5 % → +1.1 %);
/// gen's lowest sensor noise (σ 0.02 on the free fall) reads 0.073, and σ 0.004 (0.016)
/// already cost −2.5 % without it.
const NEGLIGIBLE: f64 = 0.01;

/// The pixel noise of standardised frames `x` [N, T, C·H·W] of `frame` = (C, H, W): the
/// median absolute discrete Laplacian over the frames' interiors, scaled to a Gaussian's σ
/// (a smooth picture's Laplacian is near zero; edges touch few pixels).
pub fn pixel_noise(x: &Tensor, frame: (i64, i64, i64)) -> f64 {
    let (c, h, w) = frame;
    if h < 3 || w < 3 {
        return 0.0;
    }
    tch::no_grad(|| {
        let f = x.reshape([-1, c, h, w]);
        let n = f.size()[0].min(SAMPLE);
        let f = f.narrow(0, 0, n).to_kind(Kind::Float);
        let centre = f.narrow(2, 1, h - 2).narrow(3, 1, w - 2);
        let around = (f.narrow(2, 0, h - 2).narrow(3, 1, w - 2)
            + f.narrow(2, 2, h - 2).narrow(3, 1, w - 2)
            + f.narrow(2, 1, h - 2).narrow(3, 0, w - 2)
            + f.narrow(2, 1, h - 2).narrow(3, 2, w - 2))
            / 4.0;
        let mad = (centre - around)
            .abs()
            .flatten(0, -1)
            .median()
            .double_value(&[]);
        // For white noise of σ: Var(Laplacian) = σ²·(1 + 4/16); median |N(0, s)| = 0.6745·s.
        mad / (0.6745 * 1.25f64.sqrt())
    })
}

/// The noise to add to each batch of the training inputs `train` (what the encoder reads):
/// twice the frames' own where the encoder is dense, `None` for other encoders and for frames
/// without noise.
pub fn level(cfg: &RunConfig, data: &ClipData, train: &Tensor) -> Option<f64> {
    if !cfg.encoder.is_dense() {
        return None;
    }
    let [_, _, c, h, w] = data.shape.map(|s| s as i64);
    added(pixel_noise(train, (c, h, w)))
}

/// Twice `noise`, or `None` where it is negligible.
fn added(noise: f64) -> Option<f64> {
    (noise > NEGLIGIBLE).then_some(FACTOR * noise)
}

/// `x` with fresh Gaussian noise of standard deviation `sigma`, when there is one.
pub fn jittered(x: Tensor, sigma: Option<f64>) -> Tensor {
    match sigma {
        Some(s) => &x + x.randn_like() * s,
        None => x,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_level_is_read_off_a_picture_and_not_off_its_edges() {
        tch::manual_seed(3);
        // A smooth ramp, then one with a bright 10-px square (edges), each with white noise
        // of σ 0.1 on it: 40 × 2 frames of 30 × 30 interior pixels.
        let (h, w) = (32i64, 32i64);
        let frames = |picture: &Tensor| picture.view([1, 1, h * w]).repeat([40, 2, 1]);
        let ramp = Tensor::arange(w, (Kind::Float, tch::Device::Cpu)).view([1, w]) / w as f64;
        let ramp = ramp.expand([h, w], true).contiguous();
        let square = ramp.copy();
        let _ = square.narrow(0, 8, 10).narrow(1, 8, 10).fill_(2.0);
        for clean in [frames(&ramp), frames(&square)] {
            assert!(pixel_noise(&clean, (1, h, w)) < 1e-6);
        }
        let noisy = |clean: Tensor| &clean + clean.randn_like() * 0.1;
        // 72 000 samples: the median's sampling error is well under 3 %.
        let s = pixel_noise(&noisy(frames(&ramp)), (1, h, w));
        assert!((s / 0.1 - 1.0).abs() < 0.03, "{s}");
        // The square's border puts 76 of the 900 interior pixels (p = 8.4 %) far out in the
        // tail: the median read is then |N|'s 0.5/(1 − p) = 54.6 % quantile, 1.11 × its
        // median; at most that, with the same sampling margin.
        let edged = pixel_noise(&noisy(frames(&square)), (1, h, w));
        assert!(edged > s && edged / 0.1 < 1.11 * 1.03, "{edged}");
        assert_eq!(added(s), Some(2.0 * s));
        assert_eq!(added(0.0), None);
        assert_eq!(added(NEGLIGIBLE), None);
    }
}
