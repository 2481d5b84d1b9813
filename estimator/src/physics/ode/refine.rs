//! The final refinement of a shooting block's physical parameters with the encoder held:
//! Levenberg–Marquardt by variable projection over many clips.

use super::block::{host, ShootingBlock};
use super::shooting::ClipFit;
use crate::linalg::solve;
use crate::physics::{Bounds, Clips};
use tch::Tensor;

impl ShootingBlock {
    /// Refines the physical parameters on latents `z` [N, T, D] with the encoder held (at the
    /// end of training):
    /// Levenberg–Marquardt on the total squared misfit of the clips' best trajectories
    /// (variable projection: each clip's initial state is re-fitted at every trial, and the
    /// parameters' Jacobian is projected off the initial state's, (I − P)·Jp). Positive
    /// parameters step in their logarithm. A small damping changes a 2-s swing by a fraction of
    /// a percent, so its gradient is weak beside the encoder's and Adam only creeps towards it;
    /// this solves it. Returns whether the parameters changed.
    pub fn refine(&self, z: &Tensor, clips: Clips, iterations: usize) -> bool {
        let (n_clips, t, d) = z.size3().expect("[N, T, D]");
        let theta = tch::no_grad(|| self.to_observed(z));
        let target = host(&theta);
        let rows = (t * d) as usize;
        let (n, m) = (self.system.states(), self.system.params());
        // The encoder is held: nothing competes with the fits for the cores.
        let shape = (n_clips as usize, t as usize, rows);
        let fit_all = |p: &[f64]| self.fit_batch(&target, p, clips, shape, true);
        let total = |fits: &[ClipFit]| fits.iter().map(|f| f.cost).sum::<f64>();
        let mut p = host(&self.physical());
        let mut fits = fit_all(&p);
        let mut cost = total(&fits);
        let mut lambda = 1e-3;
        let mut changed = false;
        for _ in 0..iterations {
            if !cost.is_finite() {
                break;
            }
            // Normal equations in the raw variables (log p for positive parameters).
            let (mut h, mut g) = (vec![0.0; m * m], vec![0.0; m]);
            for (i, f) in fits.iter().enumerate() {
                let clip = &target[i * rows..(i + 1) * rows];
                let jr = projected_jacobian(f, n, m, &p, &self.bounds);
                for r in 0..rows {
                    let res = f.y[r] - clip[r];
                    for a in 0..m {
                        g[a] += jr[r * m + a] * res;
                        for b in 0..m {
                            h[a * m + b] += jr[r * m + a] * jr[r * m + b];
                        }
                    }
                }
            }
            let mut accepted = false;
            for _ in 0..5 {
                let mut hm = h.clone();
                for a in 0..m {
                    hm[a * m + a] += lambda * h[a * m + a] + 1e-12;
                }
                let Some(step) = solve(&hm, &g.iter().map(|v| -v).collect::<Vec<_>>(), m) else {
                    lambda *= 8.0;
                    continue;
                };
                let trial: Vec<f64> = p
                    .iter()
                    .zip(&step)
                    .zip(&self.bounds)
                    .map(|((v, s), b)| b.step(*v, *s))
                    .collect();
                let trial_fits = fit_all(&trial);
                let c = total(&trial_fits);
                if c.is_finite() && c < cost {
                    (p, fits, cost) = (trial, trial_fits, c);
                    lambda = (lambda / 3.0).max(1e-9);
                    accepted = true;
                    changed = true;
                    break;
                }
                lambda *= 8.0;
            }
            if !accepted {
                break;
            }
        }
        if changed {
            self.set_physical(&p);
        }
        changed
    }
}

impl ShootingBlock {
    /// Moves the physical parameters to the best of `candidates` by the total misfit of the
    /// clips' best trajectories on latents `z` [N, T, D] (each clip fitted afresh, no warm
    /// start), when it beats the current parameters': a global look before
    /// [`ShootingBlock::refine`]'s local descent, for costs with a minimum per basin of
    /// frequency. Returns whether the parameters changed.
    pub fn scan(&self, z: &Tensor, clips: Clips, candidates: &[Vec<f64>]) -> bool {
        let (n_clips, t, d) = z.size3().expect("[N, T, D]");
        let target = host(&tch::no_grad(|| self.to_observed(z)));
        let rows = (t * d) as usize;
        let fresh = Clips {
            start: clips.start,
            ids: None,
        };
        let cost = |p: &[f64]| -> f64 {
            let shape = (n_clips as usize, t as usize, rows);
            let fits = self.fit_batch(&target, p, fresh, shape, true);
            let c: f64 = fits.iter().map(|f| f.cost).sum();
            if c.is_nan() {
                f64::INFINITY
            } else {
                c
            }
        };
        let current = host(&self.physical());
        let best = candidates
            .iter()
            .map(|p| (cost(p), p))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        match best {
            Some((c, p)) if c < cost(&current) => {
                self.set_physical(p);
                true
            }
            _ => false,
        }
    }

    /// Sets the physical parameters to `p` (through their raw values).
    pub(super) fn set_physical(&self, p: &[f64]) {
        tch::no_grad(|| {
            for ((raw, &v), b) in self.raw.iter().zip(p).zip(&self.bounds) {
                let _ = raw.shallow_clone().fill_(b.raw(v));
            }
        });
    }
}

/// (I − Jx·(JxᵀJx)⁻¹·Jxᵀ)·Jp [R × m] of a clip's fit, with the columns of bounded parameters
/// scaled by d(value)/d(raw) (derivatives with respect to their raw variable).
fn projected_jacobian(f: &ClipFit, n: usize, m: usize, p: &[f64], bounds: &[Bounds]) -> Vec<f64> {
    let mut jr = project_out(&f.jx, &f.ainv, &f.jp, n, m);
    for row in jr.chunks_exact_mut(m) {
        for (v, (b, pa)) in row.iter_mut().zip(bounds.iter().zip(p)) {
            *v *= b.slope(*pa);
        }
    }
    jr
}

/// (I − Jx·ainv·Jxᵀ)·J [R × w]: the columns of `j` with their part along the state columns
/// `jx` [R × n] taken out (variable projection), `ainv` = (JxᵀJx)⁻¹ [n × n].
pub(super) fn project_out(jx: &[f64], ainv: &[f64], j: &[f64], n: usize, w: usize) -> Vec<f64> {
    let rows = jx.len() / n.max(1);
    // Jxᵀ·J [n × w], then ainv·(Jxᵀ·J).
    let mut xtp = vec![0.0; n * w];
    for r in 0..rows {
        for i in 0..n {
            for a in 0..w {
                xtp[i * w + a] += jx[r * n + i] * j[r * w + a];
            }
        }
    }
    let mut coef = vec![0.0; n * w];
    for i in 0..n {
        for a in 0..w {
            coef[i * w + a] = (0..n).map(|k| ainv[i * n + k] * xtp[k * w + a]).sum();
        }
    }
    let mut out = vec![0.0; rows * w];
    for r in 0..rows {
        for a in 0..w {
            let along: f64 = (0..n).map(|i| jx[r * n + i] * coef[i * w + a]).sum();
            out[r * w + a] = j[r * w + a] - along;
        }
    }
    out
}
