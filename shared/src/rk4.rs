//! The ground truth's integrator: classical RK4 with fixed sub-steps, for the trajectories `gen`
//! renders (the pendulum, the two-body spring, every model file). `estimate` integrates with
//! its own RK4 (`physics/ode/rk4.rs`), which also carries the exact sensitivities its fits
//! need; the two are kept apart so that an error in the one under test cannot hide in the
//! truth it is measured against.

/// `frames` states `dt` apart [frames × n] of x' = f(t, x) from `x0` at `t0`, with `substeps`
/// RK4 steps per frame. `f(t, x, out)` writes the derivative into `out`.
pub fn trajectory(
    mut f: impl FnMut(f64, &[f64], &mut [f64]),
    x0: &[f64],
    t0: f64,
    dt: f64,
    frames: usize,
    substeps: usize,
) -> Vec<f64> {
    let n = x0.len();
    let h = dt / substeps.max(1) as f64;
    let mut x = x0.to_vec();
    let mut out = Vec::with_capacity(frames * n);
    let (mut k1, mut k2, mut k3, mut k4) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut tmp = vec![0.0; n];
    let mut t = t0;
    for frame in 0..frames {
        out.extend_from_slice(&x);
        if frame + 1 == frames {
            break;
        }
        for _ in 0..substeps.max(1) {
            f(t, &x, &mut k1);
            for i in 0..n {
                tmp[i] = x[i] + 0.5 * h * k1[i];
            }
            f(t + 0.5 * h, &tmp, &mut k2);
            for i in 0..n {
                tmp[i] = x[i] + 0.5 * h * k2[i];
            }
            f(t + 0.5 * h, &tmp, &mut k3);
            for i in 0..n {
                tmp[i] = x[i] + h * k3[i];
            }
            f(t + h, &tmp, &mut k4);
            for i in 0..n {
                x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
            t += h;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn follows_the_damped_oscillator_and_a_time_dependent_law() {
        let o = crate::DampedOscillator {
            omega: 2.0,
            zeta: 0.1,
        };
        let (a, phi) = (1.0, 0.0);
        // x = A e^(−ζt) cos(ωt), v = x'.
        let v0 = -o.zeta * a;
        let path = trajectory(
            |_, x, d| {
                d[0] = x[1];
                d[1] = -o.gamma0() * x[0] - o.gamma1() * x[1];
            },
            &[a, v0],
            0.0,
            0.1,
            50,
            8,
        );
        for k in 0..50 {
            let t = k as f64 * 0.1;
            assert!(
                (path[2 * k] - o.latent(a, phi, t)).abs() < 1e-7,
                "frame {k}"
            );
        }
        // x' = t from 1 at t0 = 1: x = (t² + 1)/2, exact for a polynomial of degree 2.
        let x = trajectory(|t, _, d| d[0] = t, &[1.0], 1.0, 0.5, 5, 1);
        for (k, v) in x.iter().enumerate() {
            let t = 1.0 + 0.5 * k as f64;
            assert!((v - (t * t + 1.0) / 2.0).abs() < 1e-12);
        }
    }
}
