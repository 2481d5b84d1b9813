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
//! The noise is drawn once per training, a pool of [`POOL`] batches' worth, and each batch
//! takes a slice of it at a random offset: every batch's noise is independent Gaussian noise
//! of the level, as fresh draws are, without drawing the encoder's inputs' size of normals
//! each step (half of a 1080p spring's training time went to drawing them).

use crate::config::RunConfig;
use crate::data::ClipData;
use tch::{Device, Kind, Tensor};

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
/// The pool of noise drawn for a training, in batches: a batch's slice starts at any of a
/// batch's worth of offsets (millions), so that a frame's noise at a pixel recurs only where
/// two offsets differ by a whole number of frames.
const POOL: i64 = 2;

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

/// The noise added to each batch of the training inputs: its level and the pool its slices
/// are taken from.
pub struct Jitter {
    /// The standard deviation of the noise added.
    pub sigma: f64,
    pool: Tensor,
    /// The most inputs a batch holds (a pool of [`POOL`] of them).
    largest: i64,
}

impl Jitter {
    /// The noise for the training inputs `train` (what the encoder reads): twice the frames'
    /// own where the encoder is dense, `None` for other encoders and for frames without noise;
    /// a batch holds at most `largest` of the inputs' numbers.
    pub fn of(cfg: &RunConfig, data: &ClipData, train: &Tensor, largest: i64) -> Option<Jitter> {
        if !cfg.encoder.is_dense() {
            return None;
        }
        let [_, _, c, h, w] = data.shape.map(|s| s as i64);
        let sigma = added(pixel_noise(train, (c, h, w)))?;
        Some(Jitter::drawn(sigma, largest, train.device()))
    }

    /// A pool of [`POOL`] batches of `largest` numbers of noise `sigma` on `device`.
    fn drawn(sigma: f64, largest: i64, device: Device) -> Jitter {
        let largest = largest.max(1);
        let pool = Tensor::randn([POOL * largest], (Kind::Float, device)) * sigma;
        Jitter {
            sigma,
            pool,
            largest,
        }
    }

    /// Where each of an epoch's `batches` takes its slice of the pool (drawn on the host from
    /// the seeded generator, as the epoch's order is).
    pub fn offsets(&self, batches: usize) -> Vec<i64> {
        let span = (POOL - 1) * self.largest + 1;
        let at = Tensor::randint(span, [batches as i64], (Kind::Int64, Device::Cpu));
        Vec::<i64>::try_from(&at).expect("an index tensor")
    }

    /// `x` with the pool's slice at `offset` added.
    pub fn add(&self, x: &Tensor, offset: i64) -> Tensor {
        let n = x.numel() as i64;
        assert!(
            n <= self.largest,
            "a batch of {n} inputs against {}",
            self.largest
        );
        x + self.pool.narrow(0, offset, n).view(x.size().as_slice())
    }
}

/// Twice `noise`, or `None` where it is negligible.
fn added(noise: f64) -> Option<f64> {
    (noise > NEGLIGIBLE).then_some(FACTOR * noise)
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

    #[test]
    fn each_batch_gets_independent_noise_of_the_level_from_the_pool() {
        tch::manual_seed(5);
        let jitter = Jitter::drawn(0.3, 6000, Device::Cpu);
        let x = Tensor::zeros([2, 3, 1000], (Kind::Float, Device::Cpu));
        let offsets = jitter.offsets(50);
        assert!(
            offsets.iter().all(|&o| (0..=6000).contains(&o)),
            "{offsets:?}"
        );
        assert!(offsets.windows(2).any(|w| w[0] != w[1]));
        let a = jitter.add(&x, offsets[0]);
        let b = jitter.add(&x, offsets[1]);
        assert_eq!(a.size(), x.size());
        let sd = f64::try_from(a.std(false)).unwrap();
        assert!((sd / 0.3 - 1.0).abs() < 0.05, "{sd}");
        // Two slices at different offsets: the same pixel's noise is uncorrelated (6000
        // pairs: a correlation's sampling error is 0.013).
        let r = f64::try_from((&a * &b).mean(Kind::Float)).unwrap() / (0.3 * 0.3);
        assert!(r.abs() < 0.06, "{r}");
    }
}
