//! `LatentVsTruth`: how well the encoded validation latents match the ground truth of gen
//! data: an affine fit for a scalar latent; for body positions (x, y per body), similarity
//! fits of the relative vector and of each body (the law fixes the latent up to a similarity).

use crate::data::ClipData;
use physvid_shared::{AffineFit, SimilarityFit};
use serde::{Deserialize, Serialize};

/// The latent's check against the truth.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(untagged)]
pub enum LatentVsTruth {
    Scalar(AffineFit),
    Planar(PlanarFit),
}

/// Similarity fits of planar body positions.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PlanarFit {
    /// Of the relative vector (last body minus first): what the spring's law reads.
    pub relative: SimilarityFit,
    /// Of each latent body against the true body it matches best.
    pub bodies: Vec<SimilarityFit>,
    /// `relative`'s R².
    pub r2: f64,
}

impl LatentVsTruth {
    /// The R² of the fit that matters (the relative vector's for body positions).
    pub fn r2(&self) -> f64 {
        match self {
            LatentVsTruth::Scalar(f) => f.r2,
            LatentVsTruth::Planar(f) => f.r2,
        }
    }

    /// Fits the encoded validation latents (one row of T·D values per clip) against the ground
    /// truth of the same clips; `None` without ground truth or when either does not vary.
    pub fn of(data: &ClipData, dims: usize, encoded: &[Vec<f32>]) -> Option<LatentVsTruth> {
        let meta = data.meta.as_ref()?;
        let n_train = data.n_train() as usize;
        let pairs = encoded
            .iter()
            .enumerate()
            .filter_map(|(i, row)| meta.latents.get(n_train + i).map(|t| (t, row)));
        if dims == 1 {
            let (truth, latent): (Vec<f64>, Vec<f64>) = pairs
                .flat_map(|(t, row)| row.iter().zip(t).map(|(&z, &q)| (q, z as f64)))
                .unzip();
            return AffineFit::of(&truth, &latent).map(LatentVsTruth::Scalar);
        }
        let bodies = dims / 2;
        // Points per body, then the relative vector, for the truth and the latent.
        let mut truth = vec![Vec::new(); bodies + 1];
        let mut latent = vec![Vec::new(); bodies + 1];
        for (t, row) in pairs {
            let row: Vec<f64> = row.iter().map(|&v| v as f64).collect();
            for (points, values) in [(&mut truth, t.as_slice()), (&mut latent, row.as_slice())] {
                for frame in values.chunks_exact(dims) {
                    for b in 0..bodies {
                        points[b].push([frame[2 * b], frame[2 * b + 1]]);
                    }
                    let last = 2 * (bodies - 1);
                    points[bodies].push([frame[last] - frame[0], frame[last + 1] - frame[1]]);
                }
            }
        }
        let relative = SimilarityFit::of(&truth[bodies], &latent[bodies])?;
        let bodies = (0..bodies)
            .map(|b| {
                (0..truth.len() - 1)
                    .filter_map(|j| SimilarityFit::of(&truth[j], &latent[b]))
                    .max_by(|x, y| x.r2.total_cmp(&y.r2))
            })
            .collect::<Option<Vec<_>>>()?;
        Some(LatentVsTruth::Planar(PlanarFit {
            r2: relative.r2,
            relative,
            bodies,
        }))
    }
}
