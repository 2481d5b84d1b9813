//! Whether the latent folds the picture: a latent that is an even function of the motion (the
//! height of a swinging bob, |x|, x²) oscillates at twice the motion's frequency and fits a
//! law at 2ω as well as the motion fits it at ω. Frames on either side of the swing then give
//! one latent value: the part of the picture the latent does not explain is an odd function of
//! the motion, whose size the latent does determine (on the side of the swing where the bob is
//! high, the picture differs from the mean of both sides by a fixed amount, one way or the
//! other).
//!
//! Measured on the frames' leading principal components y_k: each is regressed on the latent
//! (nearest neighbours in the latent's order), e_k = y_k − E[y_k | z] is what the latent leaves
//! unexplained, and R²(e_k² | z) says how much of its size the latent determines. The folded
//! share Σ var(e_k)·R²(e_k² | z) / Σ var(y_k) is near zero for a faithful latent, even when
//! clutter, noise or light leave much of the picture unexplained (that part does not depend on
//! the latent), and a large part of the picture for a folded one.
//!
//! The neighbours must be alike pictures for this to hold. Where the object moves far between
//! frames (a fall filmed at 60 fps in 30 frames: the ball is never where it was one frame
//! before), even a faithful latent's neighbours differ by an amount that depends on where the
//! object is (how fast it moves there). For a recording, whose frames are in time order, the
//! same share measured with each frame's neighbours in time (which cannot fold) is that
//! sampling's part, and only the excess over it counts as folded.

use crate::pca::{principal_directions, project};
use serde::Serialize;
use tch::{Kind, Tensor};

/// Folded shares of the picture above this are a folded latent, between [`MAYBE_FOLDED`] and
/// it possibly one (measured: faithful latents on every `gen` scene and the shared recordings
/// below 0.01, a rod-and-bob's 2ω latent 0.15–0.34; docs/verdict.md).
pub const FOLDED: f64 = 0.1;
pub const MAYBE_FOLDED: f64 = 0.05;

/// Leading principal components examined.
pub const COMPONENTS: i64 = 6;

/// How much of the picture the latent folds.
#[derive(Debug, Clone, Serialize)]
pub struct Fold {
    /// The share of the leading components' variance that is folded (see the module's text),
    /// beyond [`Fold::sampling_share`] where that was measured.
    pub folded_share: f64,
    /// For frames in time order: the share that would seem folded with each frame's neighbours
    /// in time (the frame rate's coarseness, not a fold).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sampling_share: Option<f64>,
    /// The share the latent explains as a function of it.
    pub explained_share: f64,
    /// The share an affine function of the latent explains (the whole explained share when
    /// the picture is affine in the latent, as an LED's brightness makes it).
    pub affine_share: f64,
    /// The components examined and their share of the frames' variance.
    pub components: usize,
    pub variance_share: f64,
}

/// The frames' leading principal components, one row a frame: what any one-number coordinate
/// of the frames (the latent, the object's track) is held against.
#[derive(Debug, Clone, Default)]
pub struct Components {
    /// Each frame's projections, row-major [frames, k].
    y: Vec<f64>,
    k: usize,
    /// The components' shares of the frames' variance.
    shares: Vec<f64>,
    /// Whether the rows are frames in time order.
    timed: bool,
}

impl Components {
    /// The leading principal components of `frames` [M, D] (in time order when `timed`);
    /// `None` when the frames do not vary.
    pub fn of(frames: &Tensor, timed: bool) -> Option<Components> {
        let (v, shares) = tch::no_grad(|| principal_directions(frames, COMPONENTS))?;
        let y = tch::no_grad(|| project(frames, &v));
        let k = y.size()[1] as usize;
        let y = Vec::<f64>::try_from(&y.to_kind(Kind::Double).contiguous().view([-1])).ok()?;
        Some(Components {
            y,
            k,
            shares,
            timed,
        })
    }

    /// The frames held.
    pub fn frames(&self) -> usize {
        self.y.len() / self.k.max(1)
    }

    /// The rows `rows` alone, in their order (the frames where a track was read).
    pub fn rows(&self, rows: &[usize]) -> Components {
        let k = self.k;
        Components {
            y: rows
                .iter()
                .flat_map(|&i| self.y[i * k..(i + 1) * k].iter().copied())
                .collect(),
            ..self.clone()
        }
    }

    /// The fold of the coordinate `z` (one a row; see the module's text); `None` for fewer
    /// than 20 rows or a `z` of another length.
    pub fn fold(&self, z: &[f64]) -> Option<Fold> {
        let (m, k, y) = (z.len(), self.k, &self.y);
        if m < 20 || self.frames() != m {
            return None;
        }
        let neighbours = (m / 200).clamp(3, 20);
        let order = sorted(z);
        let in_time: Option<Vec<usize>> = self.timed.then(|| (0..m).collect());
        let (mut total, mut unexplained, mut folded, mut by_time, mut off_line) =
            (0.0, 0.0, 0.0, 0.0, 0.0);
        for c in 0..k {
            let yc: Vec<f64> = (0..m).map(|i| y[i * k + c]).collect();
            let (ve, f) = folding(&order, &yc, neighbours);
            let vy = variance(&yc);
            off_line += vy * (1.0 - affine_r2(z, &yc));
            total += vy;
            unexplained += ve;
            folded += f;
            if let Some(in_time) = &in_time {
                by_time += folding(in_time, &yc, neighbours).1;
            }
        }
        (total > 0.0).then(|| Fold {
            folded_share: (folded - by_time).max(0.0) / total,
            sampling_share: self.timed.then_some(by_time / total),
            explained_share: 1.0 - unexplained / total,
            affine_share: 1.0 - off_line / total,
            components: k,
            variance_share: self.shares.iter().sum(),
        })
    }
}

/// What the neighbours in `order` leave of `y` unexplained (its variance) and the part of that
/// whose size they fix (the variance times R² of its square).
fn folding(order: &[usize], y: &[f64], k: usize) -> (f64, f64) {
    let fit = neighbour_means(order, y, k);
    let e: Vec<f64> = y.iter().zip(&fit).map(|(a, b)| a - b).collect();
    let e2: Vec<f64> = e.iter().map(|v| v * v).collect();
    let size = r2(&e2, &neighbour_means(order, &e2, k)).clamp(0.0, 1.0);
    let ve = variance(&e);
    (ve, ve * size)
}

/// R² of `y` explained by an affine function of `x`.
fn affine_r2(x: &[f64], y: &[f64]) -> f64 {
    physvid_shared::stats::correlation(x, y).powi(2)
}

/// Indices of `x` in increasing order.
fn sorted(x: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..x.len()).collect();
    order.sort_by(|&a, &b| x[a].total_cmp(&x[b]));
    order
}

/// Each value of `y` predicted by the mean of the `k` values on either side of it in `order`
/// (itself left out), in `y`'s own order.
fn neighbour_means(order: &[usize], y: &[f64], k: usize) -> Vec<f64> {
    let n = order.len();
    let mut cum = vec![0.0; n + 1];
    for (i, &o) in order.iter().enumerate() {
        cum[i + 1] = cum[i] + y[o];
    }
    let mut out = vec![0.0; n];
    for (i, &o) in order.iter().enumerate() {
        let lo = i.saturating_sub(k);
        let hi = (i + k + 1).min(n);
        let count = (hi - lo - 1).max(1) as f64;
        out[o] = (cum[hi] - cum[lo] - y[o]) / count;
    }
    out
}

fn variance(x: &[f64]) -> f64 {
    let n = x.len().max(1) as f64;
    let mean = x.iter().sum::<f64>() / n;
    x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n
}

/// 1 − Σ(y − fit)² / Σ(y − ȳ)² (0 when y does not vary).
fn r2(y: &[f64], fit: &[f64]) -> f64 {
    let v = variance(y) * y.len() as f64;
    if v <= 0.0 {
        return 0.0;
    }
    1.0 - y.iter().zip(fit).map(|(a, b)| (a - b).powi(2)).sum::<f64>() / v
}

/// R² of `y` explained by a smooth function of `x`: each value predicted by the mean of the
/// `k` values on either side of it in the order of `x` (itself left out).
pub fn smooth_r2(x: &[f64], y: &[f64], k: usize) -> f64 {
    r2(y, &neighbour_means(&sorted(x), y, k))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fold of `z` in the components of `frames`.
    fn fold(frames: &Tensor, z: &[f64], timed: bool) -> Option<Fold> {
        Components::of(frames, timed)?.fold(z)
    }

    #[test]
    fn an_even_latent_folds_the_picture_and_an_odd_one_does_not() {
        // A picture of two pixels that follow x and x² (the bob's horizontal and vertical
        // position), x sweeping back and forth.
        let n = 600;
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.05).sin()).collect();
        let pix: Vec<f32> = x
            .iter()
            .flat_map(|&v| [v as f32, (0.4 * v * v) as f32, 0.1 * (v as f32).powi(3)])
            .collect();
        let frames = Tensor::from_slice(&pix).view([n as i64, 3]);
        let faithful = fold(&frames, &x, true).unwrap();
        assert!(faithful.folded_share < 0.02, "{faithful:?}");
        assert!(faithful.explained_share > 0.98, "{faithful:?}");
        let height: Vec<f64> = x.iter().map(|v| v * v).collect();
        let folded = fold(&frames, &height, true).unwrap();
        assert!(folded.folded_share > 0.5, "{folded:?}");
        assert!(folded.sampling_share.unwrap() < 0.02, "{folded:?}");
        assert_eq!(fold(&frames, &height, false).unwrap().sampling_share, None);
    }

    #[test]
    fn an_object_that_jumps_between_frames_is_not_folded_when_its_latent_follows_it() {
        // A dot falling across 40 pixels in 30 frames, quadratically: late frames share no
        // pixel with the frame before. Its faithful latent (the position) orders the frames as
        // time does.
        let (n, w) = (30usize, 41usize);
        let pos: Vec<f64> = (0..n).map(|i| 40.0 * (i as f64 / 29.0).powi(2)).collect();
        let pix: Vec<f32> = pos
            .iter()
            .flat_map(|&p| (0..w).map(move |x| (-(x as f64 - p).powi(2) / 2.0).exp() as f32))
            .collect();
        let frames = Tensor::from_slice(&pix).view([n as i64, w as i64]);
        let raw = fold(&frames, &pos, false).unwrap();
        let timed = fold(&frames, &pos, true).unwrap();
        assert!(
            timed.folded_share < 0.01,
            "{timed:?} (without the time baseline {raw:?})"
        );
        assert!(raw.folded_share > 0.05, "{raw:?}");
    }

    #[test]
    fn smooth_r2_is_one_for_a_function_and_zero_for_noise() {
        let x: Vec<f64> = (0..500).map(|i| i as f64 / 500.0).collect();
        let y: Vec<f64> = x.iter().map(|v| (3.0 * v).sin()).collect();
        assert!(smooth_r2(&x, &y, 5) > 0.99);
        let noise: Vec<f64> = (0..500)
            .map(|i| ((i * 7919 % 1000) as f64 / 1000.0) - 0.5)
            .collect();
        assert!(smooth_r2(&x, &noise, 5) < 0.2);
    }
}
