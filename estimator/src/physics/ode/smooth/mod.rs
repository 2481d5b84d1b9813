//! The shooting blocks' final solve repeated with a one-coordinate latent read through a
//! smooth monotone map of the modelled state, as the oscillator's (`physics/smooth_map.rs`):
//! the observed value is c + h(y), h(y) = y + s·Σ_{j=2..5} k_j·(y/s)^j, with y the trajectory,
//! fitted with the parameters and each clip's initial state. A trained encoder is affine in
//! the observed variable only to about 1 %, and a light damping absorbs that curvature when
//! the map must be affine (the Duffing file's c on the position scene). Where reference
//! frames calibrate the map, they fix its units here too: the map's linear coefficient is
//! then free and the references' known values must read through the same map.

use super::block::{host, ShootingBlock};
use super::refine::project_out;
use super::rk4::{integrate, Span};
use super::shooting::inverse;
use crate::linalg::solve;
use crate::physics::smooth_map::{add_row, levenberg_marquardt, SmoothRead, MAP_TERMS};
use crate::physics::Clips;
use tch::Tensor;

/// Unknowns beside the clips' states: the physical parameters, then the map's terms.
struct Smooth<'a> {
    block: &'a ShootingBlock,
    target: &'a [f64],
    t0: Vec<f64>,
    frames: usize,
    read: SmoothRead,
    /// The reference frames' observed values (through the affine map) and known values.
    refs: Option<(Vec<f64>, Vec<f64>)>,
}

impl ShootingBlock {
    /// Refines the parameters on latents `z` [N, T, 1] with the smooth map, from where
    /// [`ShootingBlock::refine`] left them; keeps the result only where it lowers the misfit
    /// and the map stays increasing over the data. Returns whether the parameters changed.
    pub fn refine_smooth(&self, z: &Tensor, clips: Clips, iterations: usize) -> bool {
        let (n_clips, t, d) = z.size3().expect("[N, T, D]");
        if d != 1 || self.observed.len() != 1 || t < 3 {
            return false;
        }
        let target = host(&tch::no_grad(|| self.to_observed(z)));
        let Some(read) = SmoothRead::of(&target) else {
            return false;
        };
        let refs = self
            .references
            .borrow()
            .as_ref()
            .and_then(|(z_ref, known)| {
                let (s, c) = self.map.scale_offset()?;
                let read = tch::no_grad(|| (z_ref - c) / s);
                Some((host(&read), host(known)))
            });
        let fit = Smooth {
            block: self,
            target: &target,
            t0: clips
                .start
                .map(host)
                .unwrap_or_else(|| vec![0.0; n_clips as usize]),
            frames: t as usize,
            read,
            refs,
        };
        let m = self.system.params();
        let mut g = host(&self.physical());
        g.extend([0.0; MAP_TERMS]);
        if fit.refs.is_some() {
            g.push(1.0);
        }
        let warm = self.warm.borrow();
        let mut states: Vec<Vec<f64>> = (0..n_clips as usize)
            .map(|i| {
                clips
                    .ids
                    .and_then(|ids| warm.get(&ids[i]).cloned())
                    .unwrap_or_else(|| {
                        let clip = &target[i * t as usize..(i + 1) * t as usize];
                        self.system.guess(clip, &self.observed, self.dt)
                    })
            })
            .collect();
        drop(warm);
        let Some(affine_cost) = fit.cost(&g, &mut states) else {
            return false;
        };
        let step = |g: &[f64], delta: &[f64]| -> Vec<f64> {
            g.iter()
                .zip(delta)
                .enumerate()
                .map(|(k, (v, d))| self.bounds.get(k).map_or(v + d, |b| b.step(*v, *d)))
                .collect()
        };
        let cost = levenberg_marquardt(
            &mut g,
            &mut states,
            affine_cost,
            iterations,
            |g, states| fit.normal_equations(g, states),
            step,
            |g, states| fit.cost(g, states),
        );
        let monotone = fit.read.increasing(&g[m..], fit.trajectories(&g, &states));
        let usable = monotone && cost < affine_cost && g.iter().all(|v| v.is_finite());
        if usable {
            self.set_physical(&g[..m]);
        }
        usable
    }
}

impl Smooth<'_> {
    fn span(&self, i: usize) -> Span {
        Span {
            t0: self.t0[i],
            dt: self.block.dt,
            frames: self.frames,
            substeps: self.block.substeps,
        }
    }

    fn clip(&self, i: usize) -> &[f64] {
        &self.target[i * self.frames..(i + 1) * self.frames]
    }

    fn unknowns(&self) -> usize {
        self.block.system.params() + MAP_TERMS + usize::from(self.refs.is_some())
    }

    fn map(&self, k: &[f64], y: f64) -> f64 {
        self.read.value(k, y)
    }

    fn slope(&self, g: &[f64], y: f64) -> f64 {
        self.read.slope(&g[self.block.system.params()..], y)
    }

    /// The summed squared misfit with each clip's state refitted by Gauss–Newton from
    /// `states` (updated in place); `None` when an integration is not finite.
    fn cost(&self, g: &[f64], states: &mut [Vec<f64>]) -> Option<f64> {
        let sys = self.block.system.as_ref();
        let (n, m) = (sys.states(), sys.params());
        let (p, k) = g.split_at(m);
        let obs = &self.block.observed;
        let misfit = |x: &[f64], i: usize| -> Option<(f64, Vec<f64>, Vec<f64>)> {
            let track = integrate(sys, x, p, self.span(i), obs, false);
            let y = track.y;
            let c: f64 = y
                .iter()
                .zip(self.clip(i))
                .map(|(y, z)| (z - self.map(k, *y)).powi(2))
                .sum();
            c.is_finite().then_some((c, y, track.dy))
        };
        let mut total = 0.0;
        for (i, x) in states.iter_mut().enumerate() {
            let (mut c, mut y, mut dy) = misfit(x, i)?;
            for _ in 0..8 {
                let (mut a, mut b) = (vec![0.0; n * n], vec![0.0; n]);
                for (r, (yr, zr)) in y.iter().zip(self.clip(i)).enumerate() {
                    let h = self.slope(g, *yr);
                    let res = zr - self.map(k, *yr);
                    let row = &dy[r * n..(r + 1) * n];
                    for u in 0..n {
                        b[u] += h * row[u] * res;
                        for v in 0..n {
                            a[u * n + v] += h * h * row[u] * row[v];
                        }
                    }
                }
                let trace = (0..n).map(|u| a[u * n + u]).sum::<f64>();
                for u in 0..n {
                    a[u * n + u] += 1e-12 * trace + 1e-300;
                }
                let Some(delta) = solve(&a, &b, n) else { break };
                let trial: Vec<f64> = x.iter().zip(&delta).map(|(v, d)| v + d).collect();
                match misfit(&trial, i) {
                    Some((ct, yt, dyt)) if ct < c => {
                        let flat = c - ct <= 1e-12 * c;
                        (*x, c, y, dy) = (trial, ct, yt, dyt);
                        if flat {
                            break;
                        }
                    }
                    _ => break,
                }
            }
            total += c;
        }
        if let Some((read, known)) = &self.refs {
            total += read
                .iter()
                .zip(known)
                .map(|(r, x)| (r - self.map(k, *x)).powi(2))
                .sum::<f64>();
        }
        total.is_finite().then_some(total)
    }

    /// JᵀJ and Jᵀr in the unknowns (raw variables for bounded parameters) at the fitted
    /// `states`, each clip's state columns projected out.
    fn normal_equations(&self, g: &[f64], states: &[Vec<f64>]) -> Option<(Vec<f64>, Vec<f64>)> {
        let sys = self.block.system.as_ref();
        let (n, m) = (sys.states(), sys.params());
        let w = self.unknowns();
        let (p, k) = g.split_at(m);
        let (mut jtj, mut jtr) = (vec![0.0; w * w], vec![0.0; w]);
        for (i, x) in states.iter().enumerate() {
            let track = integrate(sys, x, p, self.span(i), &self.block.observed, true);
            let cols = track.k;
            let rows = track.y.len();
            let (mut jx, mut jg, mut res) =
                (vec![0.0; rows * n], vec![0.0; rows * w], vec![0.0; rows]);
            for r in 0..rows {
                let y = track.y[r];
                let h = self.slope(g, y);
                res[r] = self.clip(i)[r] - self.map(k, y);
                for u in 0..n {
                    jx[r * n + u] = h * track.dy[r * cols + u];
                }
                for a in 0..m {
                    let raw = self.block.bounds[a].slope(p[a]);
                    jg[r * w + a] = h * track.dy[r * cols + n + a] * raw;
                }
                jg[r * w + m] = 1.0;
                jg[r * w + m + 1..r * w + m + MAP_TERMS].copy_from_slice(&self.read.powers(y));
                if w > m + MAP_TERMS {
                    jg[r * w + m + MAP_TERMS] = y;
                }
            }
            let mut a = vec![0.0; n * n];
            for r in 0..rows {
                for u in 0..n {
                    for v in 0..n {
                        a[u * n + v] += jx[r * n + u] * jx[r * n + v];
                    }
                }
            }
            let trace = (0..n).map(|u| a[u * n + u]).sum::<f64>();
            let ainv = inverse(&a, n, 1e-12 * trace + 1e-300)?;
            let projected = project_out(&jx, &ainv, &jg, n, w);
            for (row, res) in projected.chunks_exact(w).zip(&res) {
                add_row(&mut jtj, &mut jtr, row, *res);
            }
        }
        // The references' rows: the map's terms only.
        for (read, x) in self.refs.iter().flat_map(|(r, k)| r.iter().zip(k)) {
            let mut row = vec![0.0; w];
            row[m] = 1.0;
            row[m + 1..m + MAP_TERMS].copy_from_slice(&self.read.powers(*x));
            if w > m + MAP_TERMS {
                row[m + MAP_TERMS] = *x;
            }
            add_row(&mut jtj, &mut jtr, &row, read - self.map(k, *x));
        }
        jtj.iter().all(|v| v.is_finite()).then_some((jtj, jtr))
    }

    /// Every frame's value of the trajectories of `states`.
    fn trajectories(&self, g: &[f64], states: &[Vec<f64>]) -> Vec<f64> {
        let sys = self.block.system.as_ref();
        let p = &g[..sys.params()];
        states
            .iter()
            .enumerate()
            .flat_map(|(i, x)| integrate(sys, x, p, self.span(i), &self.block.observed, false).y)
            .collect()
    }
}

#[cfg(test)]
mod tests;
