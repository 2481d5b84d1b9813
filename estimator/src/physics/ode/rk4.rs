//! Classical RK4 with fixed sub-steps, integrated together with the exact derivatives of the
//! discrete map (forward-mode through every stage) with respect to the initial state and,
//! optionally, the parameters: what the least-squares fit and the gradients need.

use super::{FixedLaw, OdeSystem};

/// The law integrated: the system's own evaluation, or its evaluator at fixed parameters.
enum Law<'a> {
    Plain(&'a dyn OdeSystem, &'a [f64]),
    Fixed(Box<dyn FixedLaw + 'a>),
}

impl Law<'_> {
    /// f into `f`, ∂f/∂x into `jx` and, `with_params`, ∂f/∂p into `jp`, at (x, t).
    fn eval(
        &mut self,
        x: &[f64],
        t: f64,
        f: &mut [f64],
        jx: &mut [f64],
        jp: &mut [f64],
        with_params: bool,
    ) {
        match self {
            Law::Plain(sys, p) => sys.eval(x, p, t, f, Some((jx, jp))),
            Law::Fixed(law) => law.eval(x, t, f, Some((jx, with_params.then_some(jp)))),
        }
    }
}

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

/// Scratch of one integration, carved from one allocation.
struct Work<'a> {
    jx: &'a mut [f64],
    jp: &'a mut [f64],
    /// A stage's point and tangent.
    xs: &'a mut [f64],
    ss: &'a mut [f64],
    /// Each stage's slope, f, and that of the tangent.
    kx: [&'a mut [f64]; 4],
    ks: [&'a mut [f64]; 4],
}

/// The first `len` values of `rest`, which keeps the others.
fn carve<'a>(rest: &mut &'a mut [f64], len: usize) -> &'a mut [f64] {
    let (head, tail) = std::mem::take(rest).split_at_mut(len);
    *rest = tail;
    head
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
    // x, S, Jx, Jp, the stage's point and tangent, the four stages' slopes.
    let mut arena = vec![0.0; 2 * n + n * (n + m) + 2 * n * k + 4 * n + 4 * n * k];
    let mut rest = arena.as_mut_slice();
    let x = carve(&mut rest, n);
    x.copy_from_slice(x0);
    // The tangent S = ∂x/∂(x0, p) [n × k], the identity on the x0 block at the start.
    let s = carve(&mut rest, n * k);
    for i in 0..n {
        s[i * k + i] = 1.0;
    }
    let mut w = Work {
        jx: carve(&mut rest, n * n),
        jp: carve(&mut rest, n * m),
        xs: carve(&mut rest, n),
        ss: carve(&mut rest, n * k),
        kx: std::array::from_fn(|_| carve(&mut rest, n)),
        ks: std::array::from_fn(|_| carve(&mut rest, n * k)),
    };
    let mut track = Track {
        y: Vec::with_capacity(span.frames * o),
        dy: Vec::with_capacity(span.frames * o * k),
        k,
    };
    let h = span.dt / span.substeps as f64;
    let mut law = match sys.at(p) {
        Some(fixed) => Law::Fixed(fixed),
        None => Law::Plain(sys, p),
    };
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
            step(&mut law, x, s, t, h, k, &mut w);
        }
    }
    track
}

/// One RK4 step of the state `x` and its tangent `s` [n × k] (k > n: with the parameters').
fn step(law: &mut Law, x: &mut [f64], s: &mut [f64], t: f64, h: f64, k: usize, w: &mut Work) {
    let n = x.len();
    let m = k - n;
    const C: [f64; 4] = [0.0, 0.5, 0.5, 1.0];
    for (stage, &c) in C.iter().enumerate() {
        // The stage's point: x + C·h·k_prev (and likewise the tangent); the first is x itself.
        let (xs, ss): (&[f64], &[f64]) = if stage == 0 {
            (x, s)
        } else {
            let a = c * h;
            for ((o, xi), ki) in w.xs.iter_mut().zip(&*x).zip(&*w.kx[stage - 1]) {
                *o = xi + a * ki;
            }
            for ((o, si), ki) in w.ss.iter_mut().zip(&*s).zip(&*w.ks[stage - 1]) {
                *o = si + a * ki;
            }
            (w.xs, w.ss)
        };
        law.eval(xs, t + c * h, w.kx[stage], w.jx, w.jp, k > n);
        // K = Jx·S + [0 | Jp], row by row, skipping Jx's zeros (a second-order system's
        // Jacobian is mostly zeros: the spring's 44 of 64); each element sums the same terms
        // in the same order as the full product, so the result is the same to the bit.
        let ks = &mut *w.ks[stage];
        ks.fill(0.0);
        for (i, row) in ks.chunks_exact_mut(k).enumerate() {
            for (&a, srow) in w.jx[i * n..(i + 1) * n].iter().zip(ss.chunks_exact(k)) {
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
    // Summed left to right in stage order (the answers depend on the order to the last bit).
    let b = [h / 6.0, h / 3.0, h / 3.0, h / 6.0];
    let [k1, k2, k3, k4] = &w.kx;
    for (i, v) in x.iter_mut().enumerate() {
        *v += b[0] * k1[i] + b[1] * k2[i] + b[2] * k3[i] + b[3] * k4[i];
    }
    let [k1, k2, k3, k4] = &w.ks;
    for (i, v) in s.iter_mut().enumerate() {
        *v += b[0] * k1[i] + b[1] * k2[i] + b[2] * k3[i] + b[3] * k4[i];
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
