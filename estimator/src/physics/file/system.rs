//! A model file's equations as an `OdeSystem` for the shooting machinery, and the frequency of
//! its motion at given parameters (for the data-driven start and the horizon curriculum).

use crate::physics::ode::{FixedLaw, Jacobians, LawWords, OdeSystem};
use physvid_shared::model_file::expr::Expr;
use physvid_shared::model_file::{AtParams, CompiledSystem, ModelFile};
use physvid_shared::recurrence::fit_two_step_recurrence;

/// The compiled equations, and for each state the observed coordinate it is the time derivative
/// of (a velocity `v` where the file says `x = "v"`), for the first guess. Compiled once per
/// model; each block takes a copy.
#[derive(Clone)]
pub struct FileSystem {
    pub compiled: CompiledSystem,
    derivative_of: Vec<Option<usize>>,
    observed: Vec<usize>,
    /// A typical initial state (the middle of `[initial]`'s ranges; the observed at their top).
    typical: Vec<f64>,
    /// The states, their laws as the file writes them and the parameters, for messages.
    words: LawWords,
}

impl FileSystem {
    pub fn new(file: &ModelFile) -> FileSystem {
        let n = file.states.len();
        let mut derivative_of = vec![None; n];
        for (k, &o) in file.observed.iter().enumerate() {
            if let Expr::Var(j) = file.equations[o] {
                if j < n && j != o {
                    derivative_of[j] = Some(k);
                }
            }
        }
        let typical = (0..n)
            .map(|i| match file.initial[i] {
                Some((lo, hi)) if file.observed.contains(&i) => {
                    if hi.abs() >= lo.abs() {
                        hi
                    } else {
                        lo
                    }
                }
                Some((lo, hi)) => 0.5 * (lo + hi),
                None if file.observed.contains(&i) => 1.0,
                None => 0.0,
            })
            .collect();
        FileSystem {
            compiled: CompiledSystem::new(file),
            derivative_of,
            observed: file.observed.clone(),
            typical,
            words: words(file),
        }
    }

    /// The angular frequency (rad/s) of the observed motion from the typical initial state at
    /// parameters `p`, when it oscillates: the two-step recurrence fitted to a simulated run,
    /// sampled finely enough (tried at `dt`, `dt`/8 and `dt`/64).
    pub fn frequency(&self, p: &[f64], dt: f64) -> Option<f64> {
        let n = self.compiled.n;
        let o = *self.observed.first()?;
        [1.0, 0.125, 0.015625].into_iter().find_map(|f| {
            let h = dt * f;
            let traj = self.compiled.trajectory(p, &self.typical, 0.0, h, 400, 8);
            let series: Vec<f64> = traj.chunks(n).map(|x| x[o]).collect();
            if series.iter().any(|v| !v.is_finite()) || turning_points(&series) < 2 {
                // A motion that turns back at most once (a fall, a drift) does not oscillate,
                // whatever a recurrence fitted to it says.
                return None;
            }
            let (g0, g1) = fit_two_step_recurrence([series.as_slice()])?.gammas(h)?;
            let w2 = g0 - g1 * g1 / 4.0;
            // Oscillating, and sampled at least 6 times per period.
            (w2 > 0.0 && w2.sqrt() * h < std::f64::consts::PI / 3.0).then(|| g0.sqrt())
        })
    }
}

/// The file's states, each one's law as it writes it, and its parameters.
fn words(file: &ModelFile) -> LawWords {
    LawWords {
        states: file.states.clone(),
        equations: file.equation_texts.clone(),
        parameters: file.parameters.iter().map(|p| p.name.clone()).collect(),
    }
}

/// How often `series` turns back (its successive differences change sign).
fn turning_points(series: &[f64]) -> usize {
    let d: Vec<f64> = series
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|v| *v != 0.0)
        .collect();
    d.windows(2)
        .filter(|w| w[0].signum() != w[1].signum())
        .count()
}

impl OdeSystem for FileSystem {
    fn states(&self) -> usize {
        self.compiled.n
    }
    fn params(&self) -> usize {
        self.compiled.m
    }
    fn eval(
        &self,
        x: &[f64],
        p: &[f64],
        t: f64,
        f: &mut [f64],
        jac: Option<(&mut [f64], &mut [f64])>,
    ) {
        self.compiled.eval(x, p, t, f, jac);
    }
    /// The tape's operations on the parameters alone done once an integration.
    fn at<'a>(&'a self, p: &[f64]) -> Option<Box<dyn FixedLaw + 'a>> {
        Some(Box::new(self.compiled.at(p)))
    }
    fn words(&self) -> Option<&LawWords> {
        Some(&self.words)
    }
    /// Observed states from the first frame, their derivatives from the first three frames
    /// (second-order one-sided difference), the rest at their typical value.
    fn guess(&self, obs: &[f64], _observed: &[usize], dt: f64) -> Vec<f64> {
        let d = self.observed.len();
        let at = |k: usize, c: usize| obs[k * d + c];
        let frames = obs.len() / d.max(1);
        let mut x = self.typical.clone();
        for (c, &o) in self.observed.iter().enumerate() {
            x[o] = at(0, c);
        }
        for (i, src) in self.derivative_of.iter().enumerate() {
            if let Some(c) = *src {
                x[i] = if frames >= 3 {
                    (-3.0 * at(0, c) + 4.0 * at(1, c) - at(2, c)) / (2.0 * dt)
                } else if frames == 2 {
                    (at(1, c) - at(0, c)) / dt
                } else {
                    0.0
                };
            }
        }
        x
    }
}

impl FixedLaw for AtParams<'_> {
    fn eval(&mut self, x: &[f64], t: f64, f: &mut [f64], jac: Jacobians) {
        AtParams::eval(self, x, t, f, jac);
    }
}
