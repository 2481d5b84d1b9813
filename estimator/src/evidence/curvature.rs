//! The final fit's curvature with the encoder held: the rollout's residuals and their Jacobian
//! in the block's trainable variables (central differences, one variable at a time), the
//! cluster-robust ("sandwich") covariance of those variables, and a Levenberg–Marquardt refit
//! for blocks that have no final solve of their own.
//!
//! The sandwich (JᵀJ)⁻¹·(Σ_g J_gᵀ r_g r_gᵀ J_g)·(JᵀJ)⁻¹ treats each cluster of clips as one
//! independent draw: the encoder's errors are smooth in time, so residuals within a clip are
//! correlated and the textbook σ²(JᵀJ)⁻¹ would understate the error many-fold.

use crate::linalg::solve;
use crate::network::Network;
use crate::physics::Clips;
use tch::{Kind, Tensor};

/// The block's trainable variables as one vector of scalars, to read and move one at a time.
pub struct Variables {
    tensors: Vec<Tensor>,
    /// (tensor, element) of each scalar; `None` for a scalar tensor.
    slots: Vec<(usize, Option<i64>)>,
}

impl Variables {
    pub fn of(network: &Network) -> Variables {
        let tensors = network.physics_variables();
        let slots = tensors
            .iter()
            .enumerate()
            .flat_map(|(i, t)| {
                let n = t.numel() as i64;
                let scalar = t.dim() == 0;
                (0..n.max(1)).map(move |e| (i, (!scalar).then_some(e)))
            })
            .collect();
        Variables { tensors, slots }
    }

    pub fn len(&self) -> usize {
        self.slots.len()
    }

    pub fn is_empty(&self) -> bool {
        self.slots.is_empty()
    }

    pub fn get(&self) -> Vec<f64> {
        self.slots
            .iter()
            .map(|&(i, e)| match e {
                None => self.tensors[i].double_value(&[]),
                Some(e) => self.tensors[i].double_value(&[e]),
            })
            .collect()
    }

    pub fn set(&self, values: &[f64]) {
        tch::no_grad(|| {
            for (&(i, e), &v) in self.slots.iter().zip(values) {
                let t = &self.tensors[i];
                let _ = match e {
                    None => t.shallow_clone().fill_(v),
                    Some(e) => t.get(e).fill_(v),
                };
            }
        });
    }
}

/// Residuals (latent − rollout) of held latents `z` [N, T(, D)], clip by clip, flattened.
pub fn residuals(network: &Network, z: &Tensor, clips: Clips) -> Vec<f64> {
    let steps = z.size()[1];
    let r = tch::no_grad(|| z - network.rollout_held(z, clips, steps));
    Vec::<f64>::try_from(&r.to_kind(Kind::Double).contiguous().view([-1])).unwrap_or_default()
}

/// The residuals at the block's current variables and their Jacobian [rows × variables]
/// (central differences; the variables are put back). `None` if any is not finite.
pub fn jacobian(
    network: &Network,
    vars: &Variables,
    z: &Tensor,
    clips: Clips,
) -> Option<(Vec<f64>, Vec<f64>)> {
    let x0 = vars.get();
    let at = |x: &[f64]| {
        vars.set(x);
        network.prepare();
        residuals(network, z, clips)
    };
    let r0 = residuals(network, z, clips);
    let (rows, m) = (r0.len(), x0.len());
    let mut jac = vec![0.0; rows * m];
    for j in 0..m {
        let h = step(x0[j]);
        let mut x = x0.clone();
        x[j] = x0[j] + h;
        let plus = at(&x);
        x[j] = x0[j] - h;
        let minus = at(&x);
        if plus.len() != rows || minus.len() != rows {
            at(&x0);
            return None;
        }
        for r in 0..rows {
            jac[r * m + j] = (plus[r] - minus[r]) / (2.0 * h);
        }
    }
    vars.set(&x0);
    network.prepare();
    (r0.iter().chain(&jac).all(|v| v.is_finite())).then_some((r0, jac))
}

/// The central-difference step for a variable at `x` (raw variables are logarithms, offsets
/// or scales of order one).
pub fn step(x: f64) -> f64 {
    1e-4 * x.abs().max(0.1)
}

/// The inverse of the symmetric `m`×`m` matrix `a`, column by column; `None` when singular.
pub fn inverse(a: &[f64], m: usize) -> Option<Vec<f64>> {
    let mut inv = vec![0.0; m * m];
    for c in 0..m {
        let mut e = vec![0.0; m];
        e[c] = 1.0;
        let col = solve(a, &e, m)?;
        for r in 0..m {
            inv[r * m + c] = col[r];
        }
    }
    inv.iter().all(|v| v.is_finite()).then_some(inv)
}

/// Fewer independent clusters than this give no covariance: the sandwich's middle is a sum of
/// one outer product per cluster, and with a handful it can come out near zero by chance.
pub const MIN_CLUSTERS: usize = 5;

/// The cluster-robust covariance [m × m] of the variables from residuals `r` and Jacobian `jac`
/// whose rows belong to `cluster[row]` (0..groups); `None` with fewer than [`MIN_CLUSTERS`]
/// clusters or a singular JᵀJ (a direction the data do not determine at all).
pub fn sandwich(r: &[f64], jac: &[f64], cluster: &[usize], m: usize) -> Option<Vec<f64>> {
    let rows = r.len();
    let groups = cluster.iter().copied().max().map_or(0, |g| g + 1);
    if groups < MIN_CLUSTERS || m == 0 {
        return None;
    }
    let mut jtj = vec![0.0; m * m];
    let mut scores = vec![0.0; groups * m];
    for row in 0..rows {
        let jr = &jac[row * m..(row + 1) * m];
        for a in 0..m {
            scores[cluster[row] * m + a] += jr[a] * r[row];
            for b in 0..m {
                jtj[a * m + b] += jr[a] * jr[b];
            }
        }
    }
    // A tiny ridge relative to the diagonal keeps an exactly flat direction from dividing by
    // zero; it then shows as an enormous variance.
    let top = (0..m).map(|a| jtj[a * m + a]).fold(0.0, f64::max);
    if top <= 0.0 {
        return None;
    }
    for a in 0..m {
        jtj[a * m + a] += 1e-12 * top;
    }
    let bread = inverse(&jtj, m)?;
    let mut meat = vec![0.0; m * m];
    for g in 0..groups {
        let s = &scores[g * m..(g + 1) * m];
        for a in 0..m {
            for b in 0..m {
                meat[a * m + b] += s[a] * s[b];
            }
        }
    }
    let scale = groups as f64 / (groups - 1) as f64;
    let bm = matmul(&bread, &meat, m);
    Some(
        matmul(&bm, &bread, m)
            .into_iter()
            .map(|v| v * scale)
            .collect(),
    )
}

/// The product of two `m`×`m` matrices.
pub fn matmul(a: &[f64], b: &[f64], m: usize) -> Vec<f64> {
    let mut out = vec![0.0; m * m];
    for i in 0..m {
        for k in 0..m {
            let aik = a[i * m + k];
            for j in 0..m {
                out[i * m + j] += aik * b[k * m + j];
            }
        }
    }
    out
}

/// Levenberg–Marquardt on the block's variables over held latents `z` (the rollout's squared
/// residuals; Jacobians by central differences): the final solve of blocks without one of
/// their own. Returns whether the variables moved.
pub fn refit(network: &Network, z: &Tensor, clips: Clips, iterations: usize) -> bool {
    let vars = Variables::of(network);
    let m = vars.len();
    if m == 0 {
        return false;
    }
    let cost = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
    let mut x = vars.get();
    let mut lambda = 1e-3;
    let mut moved = false;
    for _ in 0..iterations {
        let Some((r, jac)) = jacobian(network, &vars, z, clips) else {
            break;
        };
        let c0 = cost(&r);
        let rows = r.len();
        let (mut h, mut g) = (vec![0.0; m * m], vec![0.0; m]);
        for row in 0..rows {
            let jr = &jac[row * m..(row + 1) * m];
            for a in 0..m {
                g[a] += jr[a] * r[row];
                for b in 0..m {
                    h[a * m + b] += jr[a] * jr[b];
                }
            }
        }
        let mut accepted = false;
        for _ in 0..6 {
            let mut hm = h.clone();
            for a in 0..m {
                hm[a * m + a] += lambda * h[a * m + a] + 1e-15;
            }
            // r = z − ŷ, so ∂r/∂x = −∂ŷ/∂x and the Gauss–Newton step is −(JᵀJ)⁻¹Jᵀr.
            let Some(step) = solve(&hm, &g.iter().map(|v| -v).collect::<Vec<_>>(), m) else {
                lambda *= 8.0;
                continue;
            };
            let trial: Vec<f64> = x.iter().zip(&step).map(|(a, b)| a + b).collect();
            vars.set(&trial);
            network.prepare();
            let c1 = cost(&residuals(network, z, clips));
            if c1.is_finite() && c1 < c0 {
                x = trial;
                lambda = (lambda / 4.0).max(1e-9);
                accepted = true;
                moved = true;
                break;
            }
            vars.set(&x);
            network.prepare();
            lambda *= 8.0;
        }
        if !accepted || (c0 - cost(&residuals(network, z, clips))).abs() <= 1e-10 * c0 {
            break;
        }
    }
    moved
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sandwich_of_independent_clusters_matches_the_textbook_variance() {
        // y = a·x + noise, one row per cluster: the sandwich is White's estimator, which for
        // homoscedastic residuals is close to σ²/Σx².
        let n = 4000;
        let xs: Vec<f64> = (0..n)
            .map(|i| ((i * 37 % 101) as f64 / 50.0) - 1.0)
            .collect();
        let noise: Vec<f64> = (0..n)
            .map(|i| (((i * 7919) % 1000) as f64 / 1000.0 - 0.5) * 0.2)
            .collect();
        let jac: Vec<f64> = xs.iter().map(|x| -x).collect();
        let cluster: Vec<usize> = (0..n).collect();
        let cov = sandwich(&noise, &jac, &cluster, 1).unwrap();
        let sxx: f64 = xs.iter().map(|x| x * x).sum();
        let s2: f64 = noise.iter().map(|v| v * v).sum::<f64>() / n as f64;
        let textbook = s2 / sxx;
        assert!(
            (cov[0] / textbook - 1.0).abs() < 0.2,
            "{} vs {textbook}",
            cov[0]
        );
        // Correlated within clusters of 10 identical rows: ten times the textbook value.
        let cluster10: Vec<usize> = (0..n).map(|i| i / 10).collect();
        let r10: Vec<f64> = (0..n).map(|i| noise[i / 10 * 10]).collect();
        let x10: Vec<f64> = (0..n).map(|i| -xs[i / 10 * 10]).collect();
        let cov10 = sandwich(&r10, &x10, &cluster10, 1).unwrap();
        let cov1 = sandwich(&r10, &x10, &cluster, 1).unwrap();
        assert!(cov10[0] > 5.0 * cov1[0], "{} vs {}", cov10[0], cov1[0]);
        assert!(sandwich(&noise, &jac, &vec![0; n], 1).is_none());
        let four: Vec<usize> = (0..n).map(|i| i % 4).collect();
        assert!(sandwich(&noise, &jac, &four, 1).is_none());
    }
}
