//! `ShootingBlock`: a `PhysicsBlock` for any `OdeSystem`. Each clip's latent is read through the
//! observation map as observed state values, the clip's initial state is fitted on the host
//! (`shooting.rs`, in parallel over clips), and the rollout handed back to autograd is the
//! first-order surrogate
//!
//! ŷ = ȳ + Jp·(p − p̄) − Jx·(JxᵀJx)⁻¹·Jxᵀ·(ȳ + Jp·(p − p̄) − θ),
//!
//! whose value is the fitted trajectory ȳ (the correction vanishes at the least-squares
//! optimum) and whose gradients are those of the trajectory through the best initial state:
//! the projection onto the tangent space for the latents θ, (I − P)·Jp for the parameters (the
//! implicit function theorem, to first order). One batch costs a few tensor operations.

use super::map::ObservationMap;
use super::rk4::Span;
use super::shooting::{fit_clip, ClipFit, POOR_FIT};
use super::{not_finite_at, OdeSystem};
use crate::physics::Clips;
use crate::physics::{Bounds, ParamSpec};
use std::cell::RefCell;
use std::collections::HashMap;
use tch::nn;
use tch::{Device, Kind, Tensor};

/// A tensor's values on the host, flattened.
pub(super) fn host(x: &Tensor) -> Vec<f64> {
    Vec::<f64>::try_from(
        &x.detach()
            .to_device(Device::Cpu)
            .to_kind(Kind::Double)
            .contiguous()
            .view([-1]),
    )
    .expect("a float tensor")
}

/// The misfit of a clip of `rows` values above which its fit is retried (see [`POOR_FIT`]),
/// from the variance of all values of the batch `target`.
pub(super) fn poor_cost(target: &[f64], rows: usize) -> f64 {
    let n = target.len().max(1) as f64;
    let mean = target.iter().sum::<f64>() / n;
    let variance = target.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    POOR_FIT * variance * rows as f64
}

/// A clip whose best trajectory leaves a mean squared misfit above this multiple of the batch's
/// latent variance has no trajectory near it at these parameters (a guard for latents that are
/// still forming: where the spring's bodies overlap, the force's direction flips and fits can go
/// wild): it is left out of the step (its surrogate is its own detached latent) rather than fed
/// the gradients of a wild trajectory. Ordinary misfits, up to the latent's whole variance,
/// carry the gradient that moves the parameters.
pub const FAILED_FIT: f64 = 100.0;

/// An orthonormal basis [rows × n] of the columns of `a` [rows × n] (modified Gram–Schmidt,
/// twice): columns that add less than 1e-9 of the largest column's norm are left zero.
fn orthonormal_columns(a: &[f64], rows: usize, n: usize) -> Vec<f64> {
    let largest = (0..n)
        .map(|j| (0..rows).map(|r| a[r * n + j].powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    let mut q = vec![0.0; rows * n];
    for j in 0..n {
        let mut v: Vec<f64> = (0..rows).map(|r| a[r * n + j]).collect();
        for _ in 0..2 {
            for i in 0..j {
                let dot: f64 = (0..rows).map(|r| q[r * n + i] * v[r]).sum();
                for (r, vr) in v.iter_mut().enumerate() {
                    *vr -= dot * q[r * n + i];
                }
            }
        }
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm > 1e-9 * largest && norm > 0.0 {
            for (r, vr) in v.iter().enumerate() {
                q[r * n + j] = vr / norm;
            }
        }
    }
    q
}

/// An `OdeSystem` rolled out by shooting from each clip's least-squares initial state.
pub struct ShootingBlock {
    pub(super) system: Box<dyn OdeSystem>,
    /// Learnable parameters, as raw values (see [`Bounds`]: logarithms where positive).
    pub(super) raw: Vec<Tensor>,
    pub(super) bounds: Vec<Bounds>,
    pub map: ObservationMap,
    /// The state components the latent coordinates observe.
    pub(super) observed: Vec<usize>,
    pub(super) dt: f64,
    pub(super) substeps: usize,
    /// Each clip's last fitted initial state, by clip index: the next fit's warm start.
    pub(super) warm: RefCell<HashMap<usize, Vec<f64>>>,
    /// The last reference frames' latents and known values [R] (no host copy per step): they
    /// fix the units of the final solve through a smooth map (`smooth.rs`).
    pub(super) references: RefCell<Option<(Tensor, Tensor)>>,
    /// Where the law gave no finite value for most clips of a batch (`law_failure`).
    failure: RefCell<Option<String>>,
}

impl ShootingBlock {
    /// Registers `specs.len()` parameters (starting at `init`) under `path`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        path: &nn::Path,
        system: Box<dyn OdeSystem>,
        specs: &[ParamSpec],
        init: &[f64],
        map: ObservationMap,
        observed: Vec<usize>,
        dt: f64,
        substeps: usize,
    ) -> ShootingBlock {
        let raw = specs
            .iter()
            .zip(init)
            .map(|(s, &v)| {
                let name = format!("{}{}", s.bounds.prefix(), s.name);
                path.var(&name, &[], nn::Init::Const(s.bounds.raw(v)))
            })
            .collect();
        ShootingBlock {
            system,
            raw,
            bounds: specs.iter().map(|s| s.bounds).collect(),
            map,
            observed,
            dt,
            substeps: substeps.max(1),
            warm: RefCell::new(HashMap::new()),
            references: RefCell::new(None),
            failure: RefCell::new(None),
        }
    }

    /// The physical parameters p \[m\] (from their raw values), differentiable.
    pub fn physical(&self) -> Tensor {
        let p: Vec<Tensor> = self
            .raw
            .iter()
            .zip(&self.bounds)
            .map(|(r, b)| b.value(r))
            .collect();
        Tensor::stack(&p, 0)
    }

    /// Latents [B, T, D] in observed-state units: (z − c)/s.
    pub fn to_observed(&self, z: &Tensor) -> Tensor {
        match self.map.scale_offset() {
            None => z.shallow_clone(),
            Some((s, c)) => (z - c) / s,
        }
    }

    /// Observed-state values [B, T, D] in latent units: s·y + c.
    pub fn from_observed(&self, y: &Tensor) -> Tensor {
        match self.map.scale_offset() {
            None => y.shallow_clone(),
            Some((s, c)) => y * s + c,
        }
    }

    /// The surrogate rollout in observed-state units of `theta` [B, T, D] of the batch `clips`
    /// (their first times, 0 when unknown).
    pub fn observed_rollout(&self, theta: &Tensor, clips: Clips) -> Tensor {
        let (b, t, d) = theta.size3().expect("[B, T, D]");
        let (n, m) = (self.system.states() as i64, self.system.params() as i64);
        let target = host(theta);
        let p = self.physical();
        let p_host = host(&p);
        let rows = (t * d) as usize;
        // On the CPU the training step's fits run one clip after another (see `fit_batch`).
        let parallel = theta.device() != Device::Cpu;
        let shape = (b as usize, t as usize, rows);
        let mut fits = self.fit_batch(&target, &p_host, clips, shape, parallel);
        self.note_law_failure(&fits, &p_host, clips);
        let failed = poor_cost(&target, rows) * FAILED_FIT / POOR_FIT;
        for (i, f) in fits.iter_mut().enumerate() {
            if f.cost.is_nan() || f.cost > failed {
                f.y.copy_from_slice(&target[i * rows..(i + 1) * rows]);
                f.jx.fill(0.0);
                f.jp.fill(0.0);
                f.ainv.fill(0.0);
            }
        }
        let device = theta.device();
        let gather = |part: fn(&ClipFit) -> &[f64], shape: &[i64]| {
            let flat: Vec<f32> = fits
                .iter()
                .flat_map(|f| part(f).iter().map(|&v| v as f32))
                .collect();
            Tensor::from_slice(&flat).view(shape).to_device(device)
        };
        let y = gather(|f| &f.y, &[b, t * d]);
        let jp = gather(|f| &f.jp, &[b, t * d, m]);
        // The projection onto the trajectories near y as Q·Qᵀ, Q an orthonormal basis of Jx's
        // columns made in f64: Jx·(JxᵀJx)⁻¹·Jxᵀ in float32 stops being a projection when JxᵀJx
        // is ill-conditioned (measured on the spring while its bodies overlap: losses of 1e7).
        let basis: Vec<f32> = fits
            .iter()
            .flat_map(|f| orthonormal_columns(&f.jx, rows, n as usize))
            .map(|v| v as f32)
            .collect();
        let q = Tensor::from_slice(&basis)
            .view([b, t * d, n])
            .to_device(device);
        let dp = (&p - p.detach()).view([m, 1]);
        let base = y + jp.matmul(&dp).squeeze_dim(-1);
        let res = (&base - theta.reshape([b, t * d])).unsqueeze(-1);
        let correction = q.bmm(&q.transpose(1, 2).bmm(&res));
        (base - correction.squeeze_dim(-1)).view([b, t, d])
    }

    /// Notes where the law gave no finite value when, for most of a batch's clips, it is NaN
    /// or infinite at the very state the fit started from: a fit that fails alone falls back
    /// on its clip's latents, but a law that is not finite where the data are (x/0, √−1,
    /// exp(1000), ln of a negative latent) would leave every parameter at its start. (A
    /// solution that only leaves the law's domain within a clip is the fit's to avoid.)
    fn note_law_failure(&self, fits: &[ClipFit], p: &[f64], clips: Clips) {
        let failed = fits.iter().filter(|f| !f.cost.is_finite()).count();
        if failed * 2 <= fits.len() {
            return;
        }
        let t0 = clips.start.map(host);
        let system = self.system.as_ref();
        let at_start: Vec<String> = fits
            .iter()
            .enumerate()
            .filter(|(_, f)| !f.cost.is_finite())
            .filter_map(|(i, f)| not_finite_at(system, &f.x0, p, t0.as_ref().map_or(0.0, |t| t[i])))
            .collect();
        if at_start.len() * 2 > fits.len() {
            *self.failure.borrow_mut() = Some(format!(
                "{}, in {} of {} clips of a batch",
                at_start[0],
                at_start.len(),
                fits.len()
            ));
        }
    }

    /// Where the law gave no finite value for most clips of a batch, if it did.
    pub fn law_failure(&self) -> Option<String> {
        self.failure.borrow().clone()
    }

    /// The fits of `b` clips of `frames` frames (`rows` values each) of `target` with
    /// parameters `p`, warm-started from (and updating) the clips' last fits where the batch
    /// names its clips. With `parallel` the fits are spread over rayon's pool (`--threads`
    /// workers); each depends on its own clip alone, so the answers are the same either way.
    /// Spread where no tensor work competes for the cores: training on a GPU (the spring's
    /// epoch 530 → 106 ms on 16 cores) and the refinement and scan with the encoder held. Not in
    /// a CPU training step: libtorch's OpenMP workers spin between operations, and the fits
    /// spread beside them took the pendulum's 16-thread epoch from 66 to 123 ms.
    pub(super) fn fit_batch(
        &self,
        target: &[f64],
        p: &[f64],
        clips: Clips,
        (b, frames, rows): (usize, usize, usize),
        parallel: bool,
    ) -> Vec<ClipFit> {
        use rayon::prelude::*;
        let poor = poor_cost(target, rows);
        let t0 = clips.start.map(host).unwrap_or_else(|| vec![0.0; b]);
        let mut warm = self.warm.borrow_mut();
        let starts: Vec<Option<Vec<f64>>> = (0..b)
            .map(|i| clips.ids.and_then(|ids| warm.get(&ids[i]).cloned()))
            .collect();
        let (system, observed) = (self.system.as_ref(), &self.observed);
        let (dt, substeps) = (self.dt, self.substeps);
        let fit = |i: usize| {
            let span = Span {
                t0: t0[i],
                dt,
                frames,
                substeps,
            };
            fit_clip(
                system,
                p,
                &target[i * rows..(i + 1) * rows],
                span,
                observed,
                poor,
                starts[i].as_deref(),
            )
        };
        let fits: Vec<ClipFit> = if parallel {
            (0..b).into_par_iter().map(fit).collect()
        } else {
            (0..b).map(fit).collect()
        };
        if let Some(ids) = clips.ids {
            for (id, f) in ids.iter().zip(&fits) {
                warm.insert(*id, f.x0.clone());
            }
        }
        fits
    }

    /// Parameter values: the physical parameters, then s and c per latent coordinate (none
    /// for the identity map).
    pub fn values(&self) -> Vec<f64> {
        let mut v: Vec<f64> = Vec::<f64>::try_from(
            &self
                .physical()
                .detach()
                .to_device(Device::Cpu)
                .to_kind(Kind::Double),
        )
        .expect("a float tensor");
        if let Some((s, c)) = self.map.scale_offset() {
            for t in [s, c] {
                v.extend(
                    Vec::<f64>::try_from(&t.detach().to_device(Device::Cpu).to_kind(Kind::Double))
                        .expect("a float tensor"),
                );
            }
        }
        v
    }

    /// Fits s and c of a calibrated map (one latent coordinate) to reference frames: latents
    /// and known values \[R\], z = s·x + c by least squares.
    pub fn calibrate(&self, latents: &Tensor, values: &Tensor) {
        let ObservationMap::Calibrated { scale, offset } = &self.map else {
            return;
        };
        tch::no_grad(|| {
            let (z, th) = (latents.detach().view([-1]), values.view([-1]));
            *self.references.borrow_mut() = Some((z.shallow_clone(), th.shallow_clone()));
            let (zm, tm) = (z.mean(Kind::Float), th.mean(Kind::Float));
            let s = ((&z - &zm) * (&th - &tm)).sum(Kind::Float)
                / (&th - &tm).square().sum(Kind::Float).clamp_min(1e-12);
            let s = s.sign() * s.abs().clamp_min(1e-6);
            let c = zm - &s * tm;
            scale.shallow_clone().copy_(&s.view([1]));
            offset.shallow_clone().copy_(&c.view([1]));
        });
    }
}
