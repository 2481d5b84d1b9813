//! Classical RK4 with fixed sub-steps, integrated together with the exact derivatives of the
//! discrete map (forward-mode through every stage) with respect to the initial state and,
//! optionally, the parameters: what the least-squares fit and the gradients need.

use super::OdeSystem;

/// What to integrate.
#[derive(Debug, Clone, Copy)]
pub struct Span {
    /// Time of the first frame.
    pub t0: f64,
    /// Seconds between frames.
    pub dt: f64,
    pub frames: usize,
    /// RK4 steps per frame.
    pub substeps: usize,
}

/// An observed trajectory: the observed components at every frame, `y` [frames × o], and their
/// derivatives, `dy` [frames × o × k], with respect to the initial state (first n columns)
/// and, when asked, the parameters (next m columns).
#[derive(Debug, Clone)]
pub struct Track {
    pub y: Vec<f64>,
    pub dy: Vec<f64>,
    /// Columns of `dy`: n, or n + m.
    pub k: usize,
}

/// Scratch buffers of one integration.
struct Work {
    f: Vec<f64>,
    jx: Vec<f64>,
    jp: Vec<f64>,
    xs: Vec<f64>,
    ss: Vec<f64>,
    kx: [Vec<f64>; 4],
    ks: [Vec<f64>; 4],
}

/// Integrates `sys` from `x0` with parameters `p` over `span`, observing `observed`; the
/// parameter sensitivities are carried when `with_params`.
pub fn integrate(
    sys: &dyn OdeSystem,
    x0: &[f64],
    p: &[f64],
    span: Span,
    observed: &[usize],
    with_params: bool,
) -> Track {
    let (n, m) = (sys.states(), sys.params());
    let k = if with_params { n + m } else { n };
    let o = observed.len();
    let zeros = |len: usize| vec![0.0; len];
    let mut w = Work {
        f: zeros(n),
        jx: zeros(n * n),
        jp: zeros(n * m),
        xs: zeros(n),
        ss: zeros(n * k),
        kx: [zeros(n), zeros(n), zeros(n), zeros(n)],
        ks: [zeros(n * k), zeros(n * k), zeros(n * k), zeros(n * k)],
    };
    let mut x = x0.to_vec();
    // The tangent S = ∂x/∂(x0, p) [n × k], the identity on the x0 block at the start.
    let mut s = zeros(n * k);
    for i in 0..n {
        s[i * k + i] = 1.0;
    }
    let mut track = Track {
        y: Vec::with_capacity(span.frames * o),
        dy: Vec::with_capacity(span.frames * o * k),
        k,
    };
    let h = span.dt / span.substeps as f64;
    for frame in 0..span.frames {
        for &c in observed {
            track.y.push(x[c]);
            track.dy.extend_from_slice(&s[c * k..(c + 1) * k]);
        }
        if frame + 1 == span.frames {
            break;
        }
        for sub in 0..span.substeps {
            let t = span.t0 + frame as f64 * span.dt + sub as f64 * h;
            step(sys, &mut x, &mut s, p, t, h, k, &mut w);
        }
    }
    track
}

/// One RK4 step of the state `x` and its tangent `s` [n × k].
#[allow(clippy::too_many_arguments)]
fn step(
    sys: &dyn OdeSystem,
    x: &mut [f64],
    s: &mut [f64],
    p: &[f64],
    t: f64,
    h: f64,
    k: usize,
    w: &mut Work,
) {
    let (n, m) = (x.len(), p.len());
    const C: [f64; 4] = [0.0, 0.5, 0.5, 1.0];
    for (stage, &c) in C.iter().enumerate() {
        // The stage's point: x + C·h·k_prev (and likewise the tangent).
        if stage == 0 {
            w.xs.copy_from_slice(x);
            w.ss.copy_from_slice(s);
        } else {
            let a = c * h;
            let (kx, ks) = (&w.kx[stage - 1], &w.ks[stage - 1]);
            for i in 0..n {
                w.xs[i] = x[i] + a * kx[i];
            }
            for i in 0..n * k {
                w.ss[i] = s[i] + a * ks[i];
            }
        }
        sys.eval(&w.xs, p, t + c * h, &mut w.f, Some((&mut w.jx, &mut w.jp)));
        w.kx[stage].copy_from_slice(&w.f);
        // K = Jx·S + [0 | Jp], row by row, skipping Jx's zeros (a second-order system's
        // Jacobian is mostly zeros: the spring's 44 of 64); each element sums the same terms
        // in the same order as the full product, so the result is the same to the bit.
        let ks = &mut w.ks[stage];
        ks.fill(0.0);
        for (i, row) in ks.chunks_exact_mut(k).enumerate() {
            for (l, srow) in w.ss.chunks_exact(k).enumerate() {
                let a = w.jx[i * n + l];
                if a != 0.0 {
                    for (r, v) in row.iter_mut().zip(srow) {
                        *r += a * v;
                    }
                }
            }
            for (r, v) in row[n..].iter_mut().zip(&w.jp[i * m..(i + 1) * m]) {
                *r += v;
            }
        }
    }
    let b = [h / 6.0, h / 3.0, h / 3.0, h / 6.0];
    for (i, v) in x.iter_mut().enumerate() {
        *v += (0..4).map(|q| b[q] * w.kx[q][i]).sum::<f64>();
    }
    for (i, v) in s.iter_mut().enumerate() {
        *v += (0..4).map(|q| b[q] * w.ks[q][i]).sum::<f64>();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// θ'' = −w2·sin θ − ζ·θ'.
    struct Pendulum;

    impl OdeSystem for Pendulum {
        fn states(&self) -> usize {
            2
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
            f[0] = x[1];
            f[1] = -p[0] * x[0].sin() - p[1] * x[1];
            if let Some((jx, jp)) = jac {
                jx.copy_from_slice(&[0.0, 1.0, -p[0] * x[0].cos(), -p[1]]);
                jp.copy_from_slice(&[0.0, 0.0, -x[0].sin(), -x[1]]);
            }
        }
        fn guess(&self, obs: &[f64], _observed: &[usize], dt: f64) -> Vec<f64> {
            vec![obs[0], (obs[1] - obs[0]) / dt]
        }
    }

    #[test]
    fn sensitivities_are_the_derivatives_of_the_discrete_map() {
        let span = Span {
            t0: 0.0,
            dt: 0.1,
            frames: 15,
            substeps: 2,
        };
        let (x0, p) = ([0.9, -0.4], [10.9, 0.06]);
        let track = integrate(&Pendulum, &x0, &p, span, &[0, 1], true);
        let eps = 1e-6;
        for j in 0..4 {
            let (mut xa, mut pa, mut xb, mut pb) = (x0, p, x0, p);
            if j < 2 {
                xa[j] += eps;
                xb[j] -= eps;
            } else {
                pa[j - 2] += eps;
                pb[j - 2] -= eps;
            }
            let a = integrate(&Pendulum, &xa, &pa, span, &[0, 1], false);
            let b = integrate(&Pendulum, &xb, &pb, span, &[0, 1], false);
            for r in 0..track.y.len() {
                let fd = (a.y[r] - b.y[r]) / (2.0 * eps);
                let an = track.dy[r * 4 + j];
                assert!(
                    (fd - an).abs() < 1e-6 * (1.0 + an.abs()),
                    "col {j} row {r}: {fd} vs {an}"
                );
            }
        }
    }

    #[test]
    fn matches_a_fine_reference_trajectory() {
        // gen's own pendulum (RK4, 64 sub-steps per frame) from a 60° release.
        let (w2, zeta, dt) = (9.81 / 0.45, 0.059, 0.1);
        let truth = generator::scenes::pendulum::pendulum_trajectory(
            w2,
            zeta,
            60f64.to_radians(),
            0.0,
            20,
            dt,
        );
        let substeps = (dt / 0.05f64).ceil() as usize;
        let span = Span {
            t0: 0.0,
            dt,
            frames: 20,
            substeps,
        };
        let track = integrate(
            &Pendulum,
            &[60f64.to_radians(), 0.0],
            &[w2, zeta],
            span,
            &[0],
            false,
        );
        let err = track
            .y
            .iter()
            .zip(&truth)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(err < 3e-4, "{err}");
    }
}
