//! A model file's equations compiled for integration: f(x, p, t) and its Jacobians ∂f/∂x and
//! ∂f/∂p on one tape (symbolic derivatives, common subexpressions computed once), and a plain
//! RK4 trajectory for `gen`.

use super::expr::{Split, TapeBuilder};
use super::ModelFile;

/// The most variables (states + parameters + t) a file may have.
pub const MAX_VARIABLES: usize = 64;

/// f and its Jacobians, compiled onto one tape: f's n outputs first (so f alone evaluates a
/// prefix), then ∂f/∂x row-major, then ∂f/∂p; split so that what depends on the parameters
/// alone is computed once for many evaluations at the same parameters ([`CompiledSystem::at`]).
#[derive(Debug, Clone)]
pub struct CompiledSystem {
    pub n: usize,
    pub m: usize,
    /// The tape split by the states and t, which vary, and may stop after f or after ∂f/∂x.
    split: Split,
    /// The tape's nodes that compute f.
    f_len: usize,
}

/// Where [`Split::eval`] stops: after f, after ∂f/∂x, after ∂f/∂p.
const F: usize = 0;
const F_JX: usize = 1;
const ALL: usize = 2;

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
        let jx_len = b.len();
        for e in &file.equations {
            for j in 0..m {
                b.output(&e.derivative(n + j));
            }
        }
        let all = b.len();
        // The states and t (the variable after the parameters) vary within an integration.
        let varying: Vec<usize> = (0..n).chain([n + m]).collect();
        CompiledSystem {
            n,
            m,
            split: Split::new(
                b.finish(),
                &varying,
                &[(f_len, n), (jx_len, n + n * n), (all, n + n * n + n * m)],
            ),
            f_len,
        }
    }

    /// Operations per evaluation of f and of f with its Jacobians (the whole tape, before the
    /// split).
    pub fn cost(&self) -> (usize, usize) {
        let tape = self.split.tape();
        (tape.steps(self.f_len), tape.len())
    }

    /// The law at parameters `p`, for many evaluations: the operations that read only the
    /// parameters and constants done here, once.
    pub fn at(&self, p: &[f64]) -> AtParams<'_> {
        let (n, m) = (self.n, self.m);
        let mut vars = vec![0.0; n + m + 1];
        vars[n..n + m].copy_from_slice(&p[..m]);
        AtParams {
            sys: self,
            buf: self.split.prepare(&vars),
        }
    }

    /// f(x, p, t) into `f`; with `jac`, ∂f/∂x [n×n] and ∂f/∂p [n×m] too, row-major. For one
    /// evaluation; many at the same parameters go through [`CompiledSystem::at`].
    pub fn eval(
        &self,
        x: &[f64],
        p: &[f64],
        t: f64,
        f: &mut [f64],
        jac: Option<(&mut [f64], &mut [f64])>,
    ) {
        self.at(p).eval(x, t, f, jac.map(|(jx, jp)| (jx, Some(jp))));
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
        let mut law = self.at(p);
        crate::rk4::trajectory(
            |t, x, out| law.eval(x, t, out, None),
            x0,
            t0,
            dt,
            frames,
            substeps,
        )
    }
}

/// A [`CompiledSystem`] at fixed parameters (from [`CompiledSystem::at`]).
pub struct AtParams<'a> {
    sys: &'a CompiledSystem,
    /// The tape's buffer, the parameters' part of it computed.
    buf: Vec<f64>,
}

impl AtParams<'_> {
    /// f(x, t) into `f`; with `jac`, ∂f/∂x [n×n] and, where asked, ∂f/∂p [n×m] too, row-major
    /// (the operations only ∂f/∂p needs are skipped otherwise).
    #[inline]
    pub fn eval(
        &mut self,
        x: &[f64],
        t: f64,
        f: &mut [f64],
        jac: Option<(&mut [f64], Option<&mut [f64]>)>,
    ) {
        let (split, buf, x) = (&self.sys.split, &mut self.buf, &x[..self.sys.n]);
        match jac {
            None => split.eval(F, x, t, buf, &mut [f]),
            Some((jx, None)) => split.eval(F_JX, x, t, buf, &mut [f, jx]),
            Some((jx, Some(jp))) => split.eval(ALL, x, t, buf, &mut [f, jx, jp]),
        }
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
