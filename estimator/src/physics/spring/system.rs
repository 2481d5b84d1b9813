//! The spring's equations as an `OdeSystem`: both bodies' positions and velocities, the force
//! k·(|d| − l)·d̂ on body one and its opposite on body two, with exact Jacobians.

use crate::physics::ode::OdeSystem;

/// RK4 sub-steps per frame: at √(2k)·dt/4 ≤ 0.3 the phase error over a clip is below 1e-4.
pub const SUBSTEPS_PER_FRAME: usize = 4;

/// State (x1, y1, x2, y2, vx1, vy1, vx2, vy2), parameters (k, l).
pub struct SpringSystem;

impl OdeSystem for SpringSystem {
    fn states(&self) -> usize {
        8
    }
    fn params(&self) -> usize {
        2
    }
    fn eval(
        &self,
        x: &[f64],
        p: &[f64],
        _t: f64,
        f: &mut [f64],
        jac: Option<(&mut [f64], &mut [f64])>,
    ) {
        let (k, l) = (p[0], p[1]);
        let d = [x[2] - x[0], x[3] - x[1]];
        let r = (d[0] * d[0] + d[1] * d[1] + 1e-12).sqrt();
        let u = [d[0] / r, d[1] / r];
        // Body one's acceleration a = k·(d − l·u); body two's is −a.
        let a = [k * (d[0] - l * u[0]), k * (d[1] - l * u[1])];
        f[..4].copy_from_slice(&x[4..8]);
        f[4..8].copy_from_slice(&[a[0], a[1], -a[0], -a[1]]);
        if let Some((jx, jp)) = jac {
            jx.fill(0.0);
            for i in 0..4 {
                jx[i * 8 + 4 + i] = 1.0;
            }
            // ∂a/∂d = k·(I − l·(I − u·uᵀ)/r); d = p2 − p1.
            for i in 0..2 {
                for j in 0..2 {
                    let eye = if i == j { 1.0 } else { 0.0 };
                    let dd = k * (eye - l * (eye - u[i] * u[j]) / r);
                    jx[(4 + i) * 8 + j] = -dd;
                    jx[(4 + i) * 8 + 2 + j] = dd;
                    jx[(6 + i) * 8 + j] = dd;
                    jx[(6 + i) * 8 + 2 + j] = -dd;
                }
            }
            jp.fill(0.0);
            for i in 0..2 {
                let (dk, dl) = (d[i] - l * u[i], -k * u[i]);
                jp[(4 + i) * 2] = dk;
                jp[(4 + i) * 2 + 1] = dl;
                jp[(6 + i) * 2] = -dk;
                jp[(6 + i) * 2 + 1] = -dl;
            }
        }
    }
    /// Positions from the first frame, velocities from the first three.
    fn guess(&self, obs: &[f64], _observed: &[usize], dt: f64) -> Vec<f64> {
        let mut x = obs[..4].to_vec();
        for c in 0..4 {
            let v = if obs.len() >= 12 {
                (-3.0 * obs[c] + 4.0 * obs[4 + c] - obs[8 + c]) / (2.0 * dt)
            } else {
                (obs[4 + c] - obs[c]) / dt
            };
            x.push(v);
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::ode::rk4::{integrate, Span};
    use generator::scenes::spring::spring_trajectory;

    #[test]
    fn rollout_matches_gens_trajectory() {
        // gen's own trajectory (RK4, 64 sub-steps per frame) against the block's integrator.
        let s = [20.0, 30.0, 44.0, 33.0, 3.0, -5.0, -6.0, 2.0];
        let (k, l, dt) = (2.0, 24.0, 0.3);
        let truth = spring_trajectory(s, k, l, 12, dt);
        let span = Span {
            t0: 0.0,
            dt,
            frames: 12,
            substeps: SUBSTEPS_PER_FRAME,
        };
        let track = integrate(&SpringSystem, &s, &[k, l], span, &[0, 1, 2, 3], false);
        let err = track
            .y
            .iter()
            .zip(&truth)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(err < 1e-3, "max position error {err} px");
    }

    #[test]
    fn jacobians_match_finite_differences() {
        let (x, p) = ([1.0, 2.0, 3.5, 0.5, 0.1, -0.2, 0.3, 0.4], [2.0, 1.7]);
        let (mut f, mut jx, mut jp) = (vec![0.0; 8], vec![0.0; 64], vec![0.0; 16]);
        SpringSystem.eval(&x, &p, 0.0, &mut f, Some((&mut jx, &mut jp)));
        let eps = 1e-6;
        // Columns 0..8 move the state, 8..10 the parameters.
        for j in 0..10 {
            let (mut xa, mut pa, mut xb, mut pb) = (x, p, x, p);
            if j < 8 {
                xa[j] += eps;
                xb[j] -= eps;
            } else {
                pa[j - 8] += eps;
                pb[j - 8] -= eps;
            }
            let (mut fa, mut fb) = (vec![0.0; 8], vec![0.0; 8]);
            SpringSystem.eval(&xa, &pa, 0.0, &mut fa, None);
            SpringSystem.eval(&xb, &pb, 0.0, &mut fb, None);
            for i in 0..8 {
                let fd = (fa[i] - fb[i]) / (2.0 * eps);
                let an = if j < 8 {
                    jx[i * 8 + j]
                } else {
                    jp[i * 2 + j - 8]
                };
                assert!((fd - an).abs() < 1e-6, "∂f{i}/∂(column {j}): {fd} vs {an}");
            }
        }
    }
}
