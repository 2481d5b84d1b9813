//! A model file's equations compiled for integration: f(x, p, t) and its Jacobians ∂f/∂x and
//! ∂f/∂p on one tape (symbolic derivatives, common subexpressions computed once), and a plain
//! RK4 trajectory for `gen`.

use super::expr::{Slots, Tape, TapeBuilder};
use super::ModelFile;
use std::cell::RefCell;

/// The most variables (states + parameters + t) a file may have.
pub const MAX_VARIABLES: usize = 64;

/// Tapes of at most this many slots run on an array on the stack, whose accesses are never
/// checked (`Slots`); a larger array costs more to clear than it saves.
const SMALL: usize = 32;

/// f and its Jacobians, compiled onto one tape: f's n outputs first (so f alone evaluates a
/// prefix), then ∂f/∂x row-major, then ∂f/∂p.
#[derive(Debug, Clone)]
pub struct CompiledSystem {
    pub n: usize,
    pub m: usize,
    tape: Tape,
    /// The tape's nodes that compute f.
    f_len: usize,
}

thread_local! {
    /// The scratch values of a tape too large for `SMALL`, one buffer per thread.
    static BUFFER: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

impl CompiledSystem {
    /// Compiles `file`'s equations and their derivatives.
    pub fn new(file: &ModelFile) -> CompiledSystem {
        let (n, m) = (file.states.len(), file.parameters.len());
        let mut b = TapeBuilder::default();
        for e in &file.equations {
            b.output(e);
        }
        let f_len = b.len();
        for e in &file.equations {
            for j in 0..n {
                b.output(&e.derivative(j));
            }
        }
        for e in &file.equations {
            for j in 0..m {
                b.output(&e.derivative(n + j));
            }
        }
        CompiledSystem {
            n,
            m,
            tape: b.finish(),
            f_len,
        }
    }

    /// Operations per evaluation of f and of f with its Jacobians.
    pub fn cost(&self) -> (usize, usize) {
        (self.tape.steps(self.f_len), self.tape.len())
    }

    /// f(x, p, t) into `f`; with `jac`, ∂f/∂x [n×n] and ∂f/∂p [n×m] too, row-major.
    pub fn eval(
        &self,
        x: &[f64],
        p: &[f64],
        t: f64,
        f: &mut [f64],
        jac: Option<(&mut [f64], &mut [f64])>,
    ) {
        let len = self.tape.buffer_len().max(self.n + self.m + 1);
        if len <= SMALL {
            self.eval_in(x, p, t, f, jac, &mut [0.0; SMALL]);
        } else {
            BUFFER.with_borrow_mut(|buf| {
                if buf.len() < len {
                    buf.resize(len, 0.0);
                }
                self.eval_in(x, p, t, f, jac, buf.as_mut_slice());
            });
        }
    }

    /// [`CompiledSystem::eval`] with the tape's buffer `buf`.
    fn eval_in<S: Slots + ?Sized>(
        &self,
        x: &[f64],
        p: &[f64],
        t: f64,
        f: &mut [f64],
        jac: Option<(&mut [f64], &mut [f64])>,
        buf: &mut S,
    ) {
        let (n, m) = (self.n, self.m);
        for (k, v) in x[..n].iter().chain(&p[..m]).chain([&t]).enumerate() {
            buf.set(k as u32, *v);
        }
        let upto = if jac.is_some() {
            self.tape.nodes()
        } else {
            self.f_len
        };
        self.tape.run_loaded(upto, buf);
        for (i, fi) in f[..n].iter_mut().enumerate() {
            *fi = self.tape.output(i, buf);
        }
        if let Some((jx, jp)) = jac {
            for (k, out) in jx[..n * n].iter_mut().enumerate() {
                *out = self.tape.output(n + k, buf);
            }
            for (k, out) in jp[..n * m].iter_mut().enumerate() {
                *out = self.tape.output(n + n * n + k, buf);
            }
        }
    }

    /// The RK4 trajectory from `x0` at time `t0`: `frames` states `dt` apart [frames × n],
    /// `substeps` RK4 steps per frame.
    pub fn trajectory(
        &self,
        p: &[f64],
        x0: &[f64],
        t0: f64,
        dt: f64,
        frames: usize,
        substeps: usize,
    ) -> Vec<f64> {
        crate::rk4::trajectory(
            |t, x, out| self.eval(x, p, t, out, None),
            x0,
            t0,
            dt,
            frames,
            substeps,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::super::parse_text;
    use super::*;

    #[test]
    fn the_oscillator_file_follows_the_closed_form_and_its_jacobians_are_exact() {
        let f = parse_text(
            "name = \"osc\"\n[parameters]\ngamma0 = { start = 4.0016, positive = true }\ngamma1 = { start = 0.08 }\n[state]\nx = \"v\"\nv = \"-gamma0*x - gamma1*v\"\n[observed]\nlatent = [\"x\"]\n",
        )
        .unwrap();
        let sys = CompiledSystem::new(&f);
        let osc = crate::DampedOscillator {
            omega: 2.0,
            zeta: 0.04,
        };
        let p = [osc.gamma0(), osc.gamma1()];
        let (a, phi, dt) = (0.8, 0.3, 0.2);
        let x0 = osc.latent(a, phi, 0.0);
        let v0 = (osc.latent(a, phi, 1e-6) - osc.latent(a, phi, -1e-6)) / 2e-6;
        let traj = sys.trajectory(&p, &[x0, v0], 0.0, dt, 20, 8);
        for k in 0..20 {
            let want = osc.latent(a, phi, k as f64 * dt);
            assert!((traj[2 * k] - want).abs() < 1e-5, "frame {k}");
        }
        let (mut fv, mut jx, mut jp) = ([0.0; 2], [0.0; 4], [0.0; 4]);
        sys.eval(&[0.3, -0.2], &p, 0.0, &mut fv, Some((&mut jx, &mut jp)));
        assert_eq!(jx, [0.0, 1.0, -p[0], -p[1]]);
        assert_eq!(jp, [0.0, 0.0, -0.3, 0.2]);
        // Reading a state, a parameter or a constant is no operation: f is −γ0·x, −γ1·v and
        // their difference (or a negation in place of one product), its Jacobians −γ0, −γ1,
        // −x and −v where not already computed.
        let (f_ops, all) = sys.cost();
        assert!(f_ops <= 4 && all <= f_ops + 4, "{:?}", sys.cost());
    }
}
