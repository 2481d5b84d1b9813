//! Principal components of frames: the leading directions of a sample of standardised frames,
//! found from the sample's Gram matrix (a frame has thousands of pixels, the sample hundreds of
//! frames). Shared by the spectral start and the verdict's harmonic check.

use tch::{Device, Kind, Tensor};

/// Frames used for the principal components (evenly spaced over the frames given).
pub const PCA_FRAMES: i64 = 512;

/// Up to `count` leading principal directions [D, k] (double precision, unit length, largest
/// variance first) of `frames` [M, D], and each direction's share of the sample's variance;
/// `None` when the frames do not vary.
pub fn principal_directions(frames: &Tensor, count: i64) -> Option<(Tensor, Vec<f64>)> {
    let (m, _) = frames.size2().ok()?;
    let take = PCA_FRAMES.min(m);
    if take < 2 {
        return None;
    }
    let idx = Tensor::arange(take, (Kind::Int64, Device::Cpu))
        .multiply_scalar(m as f64 / take as f64)
        .to_kind(Kind::Int64)
        .to_device(frames.device());
    let sample = frames.index_select(0, &idx).to_kind(Kind::Double);
    let sample = &sample - sample.mean_dim(0, true, Kind::Double);
    // Eigenvalues σ² of the Gram matrix, directions Sᵀu/σ.
    let (evals, u) = sample.matmul(&sample.tr()).linalg_eigh("L");
    let evals = Vec::<f64>::try_from(&evals.to_device(Device::Cpu)).ok()?;
    let top = evals.last().copied().filter(|&e| e > 0.0)?;
    let total: f64 = evals.iter().filter(|&&e| e > 0.0).sum();
    // Keep components with real variance (relative to the first), largest first.
    let k = evals
        .iter()
        .rev()
        .take(count as usize)
        .take_while(|&&e| e.sqrt() > 1e-6 * top.sqrt())
        .count() as i64;
    if k == 0 {
        return None;
    }
    let order = Tensor::arange_start_step(take - 1, take - 1 - k, -1, (Kind::Int64, Device::Cpu))
        .to_device(frames.device());
    let kept: Vec<f64> = evals.iter().rev().take(k as usize).copied().collect();
    let sigma = Tensor::from_slice(&kept).sqrt().to_device(frames.device());
    let v = sample.tr().matmul(&u.index_select(1, &order)) / sigma.unsqueeze(0);
    let shares = kept.iter().map(|e| e / total).collect();
    Some((v, shares))
}

/// `frames` [M, D] projected onto `directions` [D, k] (in the frames' own precision, the
/// result in double), [M, k].
pub fn project(frames: &Tensor, directions: &Tensor) -> Tensor {
    frames
        .matmul(&directions.to_kind(frames.kind()))
        .to_kind(Kind::Double)
}
