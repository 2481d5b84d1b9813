//! The final solve of the linear second-order blocks with the latent read through a smooth
//! monotone map of the modelled state instead of an affine one: z = c + h(x), h(x) = x +
//! s·Σ_{j=2..5} k_j·(x/s)^j. A trained encoder is affine in the observed variable only to
//! about 1 % (and under pixel noise it compresses the extremes by a few percent, where an
//! encoder regresses to the mean): the damping, a change of amplitude of a percent or two
//! per clip, absorbs that curvature when the map must be affine (γ1 1 % low on the clean
//! position set, 6–10 % on noisy scale sets). The polynomial acts on the fitted trajectory,
//! not on the encoded values: terms in powers of noisy latents would carry their noise into
//! the fit (errors in variables) and bias γ1 far more than they correct.

use super::oscillator::two_step_solve::{dot, responses};
use crate::linalg::solve;

/// Highest power of the map's polynomial.
const DEGREE: usize = 5;
/// The map's terms: the offset c and k_2..k_DEGREE.
pub(crate) const MAP_TERMS: usize = DEGREE;
/// Global unknowns: the recurrence's (a, b) and the map's terms.
const GLOBALS: usize = 2 + MAP_TERMS;
/// The map must keep at least this slope (h' = 1 is affine) over the fitted trajectories'
/// values between the [`TAIL`] and 1 − [`TAIL`] quantiles (a polynomial bends most in the
/// sparse tails, where it matters least).
const MIN_SLOPE: f64 = 0.1;
const TAIL: f64 = 0.005;

/// The polynomial c + h(x), h(x) = k_1·x + s·Σ_{j=2..DEGREE} k_j·(x/s)^j, with its terms
/// `k` = [c, k_2, …, k_DEGREE] and, after them, k_1 where it is free (1 otherwise).
pub(crate) struct SmoothRead {
    /// s: the spread of the values read, which keeps every term of order one.
    pub scale: f64,
}

impl SmoothRead {
    /// The read of `values`, scaled by their spread; `None` when they do not spread.
    pub fn of(values: &[f64]) -> Option<SmoothRead> {
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let scale = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
        (scale.is_finite() && scale > 0.0).then_some(SmoothRead { scale })
    }

    pub fn value(&self, k: &[f64], x: f64) -> f64 {
        let h: f64 = self
            .powers(x)
            .iter()
            .zip(&k[1..MAP_TERMS])
            .map(|(p, kj)| p * kj)
            .sum();
        k[0] + k.get(MAP_TERMS).unwrap_or(&1.0) * x + h
    }

    /// h'(x).
    pub fn slope(&self, k: &[f64], x: f64) -> f64 {
        let u = x / self.scale;
        let mut power = 1.0;
        let mut d = *k.get(MAP_TERMS).unwrap_or(&1.0);
        for (j, kj) in k[1..MAP_TERMS].iter().enumerate() {
            power *= u;
            d += (j + 2) as f64 * kj * power;
        }
        d
    }

    /// s·(x/s)^j for j = 2..DEGREE: the value's derivatives in k_2..k_DEGREE.
    pub fn powers(&self, x: f64) -> [f64; DEGREE - 1] {
        let u = x / self.scale;
        let mut power = u;
        std::array::from_fn(|_| {
            power *= u;
            self.scale * power
        })
    }

    /// Whether h stays increasing (slope at least [`MIN_SLOPE`]) between the [`TAIL`] and
    /// 1 − [`TAIL`] quantiles of `values`.
    pub fn increasing(&self, k: &[f64], mut values: Vec<f64>) -> bool {
        if values.is_empty() {
            return false;
        }
        values.sort_by(f64::total_cmp);
        let at = |f: f64| values[((values.len() - 1) as f64 * f).round() as usize];
        let (lo, hi) = (at(TAIL), at(1.0 - TAIL));
        (0..=100).all(|i| self.slope(k, lo + (hi - lo) * i as f64 / 100.0) >= MIN_SLOPE)
    }
}

/// The two-step coefficients (a, b) that best fit `clips` [N][T] with each clip's initial
/// state fitted and the latent read through the smooth map, searched from `ab` (the affine
/// solve's); `None` when no finite, monotone fit improves on the affine one.
pub fn solve_with_smooth_map(clips: &[Vec<f64>], ab: [f64; 2]) -> Option<[f64; 2]> {
    let steps = clips.first()?.len();
    if steps < 3 || clips.len() * steps < 10 * GLOBALS {
        return None;
    }
    let values: Vec<f64> = clips.iter().flatten().copied().collect();
    let fit = Fit {
        clips,
        read: SmoothRead::of(&values)?,
    };
    let mut g = vec![0.0; GLOBALS];
    g[..2].copy_from_slice(&ab);
    let mut states = fit.affine_states(ab)?;
    let affine_cost = fit.cost(&g, &mut states)?;
    let cost = levenberg_marquardt(
        &mut g,
        &mut states,
        affine_cost,
        60,
        |g, states| Some(fit.normal_equations(g, states)),
        |g, step| g.iter().zip(step).map(|(v, s)| v + s).collect(),
        |g, states| fit.cost(g, states),
    );
    let monotone = fit.read.increasing(&g[2..], fit.trajectories(&g, &states));
    (monotone && cost < affine_cost && g.iter().all(|v| v.is_finite())).then(|| [g[0], g[1]])
}

/// Levenberg–Marquardt over the unknowns `g` from the misfit `cost` at `g`, for at most
/// `iterations` accepted steps: `normal` gives JᵀJ and Jᵀr at (g, states), `step` the unknowns
/// after a step, `eval` the misfit at trial unknowns with inner `states` refitted from the
/// current ones (kept when the step is). Returns the final misfit.
pub(crate) fn levenberg_marquardt<S: Clone>(
    g: &mut Vec<f64>,
    states: &mut S,
    mut cost: f64,
    iterations: usize,
    normal: impl Fn(&[f64], &S) -> Option<(Vec<f64>, Vec<f64>)>,
    step: impl Fn(&[f64], &[f64]) -> Vec<f64>,
    eval: impl Fn(&[f64], &mut S) -> Option<f64>,
) -> f64 {
    let w = g.len();
    let mut lambda = 1e-3;
    for _ in 0..iterations {
        let Some((jtj, jtr)) = normal(g, states) else {
            break;
        };
        let mut improved = false;
        while lambda < 1e12 {
            let mut m = jtj.clone();
            for a in 0..w {
                m[a * w + a] = m[a * w + a] * (1.0 + lambda) + 1e-300;
            }
            let Some(delta) = solve(&m, &jtr, w) else {
                lambda *= 4.0;
                continue;
            };
            let trial = step(g, &delta);
            let mut trial_states = states.clone();
            if let Some(next) = eval(&trial, &mut trial_states).filter(|c| *c < cost) {
                let converged = cost - next <= 1e-10 * cost
                    || delta
                        .iter()
                        .zip(g.iter())
                        .all(|(d, v)| d.abs() <= 1e-10 * v.abs().max(1e-3));
                cost = next;
                (*g, *states) = (trial, trial_states);
                lambda = (lambda / 3.0).max(1e-12);
                improved = !converged;
                break;
            }
            lambda *= 4.0;
        }
        if !improved {
            break;
        }
    }
    cost
}

/// Adds a row of J and its residual to JᵀJ [w × w] and Jᵀr [w].
pub(crate) fn add_row(jtj: &mut [f64], jtr: &mut [f64], row: &[f64], res: f64) {
    let w = row.len();
    for a in 0..w {
        jtr[a] += row[a] * res;
        for b in 0..w {
            jtj[a * w + b] += row[a] * row[b];
        }
    }
}

/// The clips and the map's polynomial.
struct Fit<'a> {
    clips: &'a [Vec<f64>],
    read: SmoothRead,
}

impl Fit<'_> {
    fn map(&self, g: &[f64], x: f64) -> f64 {
        self.read.value(&g[2..], x)
    }

    fn slope(&self, g: &[f64], x: f64) -> f64 {
        self.read.slope(&g[2..], x)
    }

    /// Every frame's value of the trajectories of `states`.
    fn trajectories(&self, g: &[f64], states: &[[f64; 2]]) -> Vec<f64> {
        let steps = self.clips[0].len();
        let (p, q) = responses(g[0], g[1], steps);
        states
            .iter()
            .flat_map(|s| {
                (0..steps)
                    .map(|t| s[0] * p[t] + s[1] * q[t])
                    .collect::<Vec<_>>()
            })
            .collect()
    }

    /// Each clip's least-squares state with the affine map (the start of the inner fits).
    fn affine_states(&self, ab: [f64; 2]) -> Option<Vec<[f64; 2]>> {
        let steps = self.clips[0].len();
        let (p, q) = responses(ab[0], ab[1], steps);
        let (pp, qq, pq) = (dot(&p, &p), dot(&q, &q), dot(&p, &q));
        let det = pp * qq - pq * pq;
        if det.abs() <= 1e-12 * pp * qq || !det.is_finite() {
            return None;
        }
        Some(
            self.clips
                .iter()
                .map(|z| {
                    let (zp, zq) = (dot(z, &p), dot(z, &q));
                    [(zp * qq - zq * pq) / det, (zq * pp - zp * pq) / det]
                })
                .collect(),
        )
    }

    /// The summed squared residuals z − c − h(x) of every clip with its state fitted by
    /// Gauss–Newton from `states` (updated in place).
    fn cost(&self, g: &[f64], states: &mut [[f64; 2]]) -> Option<f64> {
        let steps = self.clips[0].len();
        let (p, q) = responses(g[0], g[1], steps);
        let mut out = Vec::with_capacity(self.clips.len() * steps);
        for (z, s) in self.clips.iter().zip(states.iter_mut()) {
            for _ in 0..30 {
                let (mut a, mut b, mut c, mut ra, mut rb) = (0.0, 0.0, 0.0, 0.0, 0.0);
                for t in 0..steps {
                    let x = s[0] * p[t] + s[1] * q[t];
                    let d = self.slope(g, x);
                    let r = z[t] - self.map(g, x);
                    let (jp, jq) = (d * p[t], d * q[t]);
                    (a, b, c) = (a + jp * jp, b + jp * jq, c + jq * jq);
                    (ra, rb) = (ra + jp * r, rb + jq * r);
                }
                let det = a * c - b * b;
                if !(det.is_finite() && det > 1e-300) {
                    return None;
                }
                let step = [(ra * c - rb * b) / det, (rb * a - ra * b) / det];
                s[0] += step[0];
                s[1] += step[1];
                if step[0].abs() + step[1].abs() <= 1e-13 * (s[0].abs() + s[1].abs() + 1e-12) {
                    break;
                }
            }
            for t in 0..steps {
                let x = s[0] * p[t] + s[1] * q[t];
                out.push(z[t] - self.map(g, x));
            }
        }
        out.iter().all(|r| r.is_finite()).then(|| dot(&out, &out))
    }

    /// JᵀJ and −Jᵀr of the profiled residuals in the global unknowns at the fitted `states`:
    /// each clip's Jacobian with its two state columns projected out (variable projection),
    /// the recurrence's sensitivities to (a, b) unrolled beside it.
    fn normal_equations(&self, g: &[f64], states: &[[f64; 2]]) -> (Vec<f64>, Vec<f64>) {
        let steps = self.clips[0].len();
        let (p, q) = responses(g[0], g[1], steps);
        let sens = sensitivities(g[0], g[1], &p, &q);
        let mut jtj = vec![0.0; GLOBALS * GLOBALS];
        let mut jtr = vec![0.0; GLOBALS];
        let mut jg = vec![[0.0; GLOBALS]; steps];
        let mut js = vec![[0.0; 2]; steps];
        let mut r = vec![0.0; steps];
        for (z, s) in self.clips.iter().zip(states) {
            for t in 0..steps {
                let x = s[0] * p[t] + s[1] * q[t];
                let d = self.slope(g, x);
                r[t] = z[t] - self.map(g, x);
                js[t] = [-d * p[t], -d * q[t]];
                let row = &mut jg[t];
                row[0] = -d * (s[0] * sens[0][t] + s[1] * sens[2][t]);
                row[1] = -d * (s[0] * sens[1][t] + s[1] * sens[3][t]);
                row[2] = -1.0;
                for (v, p) in row[3..].iter_mut().zip(self.read.powers(x)) {
                    *v = -p;
                }
            }
            // (JsᵀJs)⁻¹·JsᵀJg, then the projected rows Jg − Js·that.
            let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
            let mut sg = [[0.0; GLOBALS]; 2];
            for t in 0..steps {
                (a, b, c) = (
                    a + js[t][0] * js[t][0],
                    b + js[t][0] * js[t][1],
                    c + js[t][1] * js[t][1],
                );
                for k in 0..GLOBALS {
                    sg[0][k] += js[t][0] * jg[t][k];
                    sg[1][k] += js[t][1] * jg[t][k];
                }
            }
            let det = a * c - b * b;
            let coef: Vec<[f64; 2]> = (0..GLOBALS)
                .map(|k| {
                    [
                        (sg[0][k] * c - sg[1][k] * b) / det,
                        (sg[1][k] * a - sg[0][k] * b) / det,
                    ]
                })
                .collect();
            for t in 0..steps {
                let row: Vec<f64> = (0..GLOBALS)
                    .map(|k| jg[t][k] - js[t][0] * coef[k][0] - js[t][1] * coef[k][1])
                    .collect();
                add_row(&mut jtj, &mut jtr, &row, -r[t]);
            }
        }
        (jtj, jtr)
    }
}

/// ∂p/∂a, ∂p/∂b, ∂q/∂a, ∂q/∂b of the impulse responses, unrolled with the recurrence.
fn sensitivities(a: f64, b: f64, p: &[f64], q: &[f64]) -> [Vec<f64>; 4] {
    let steps = p.len();
    let unroll = |x: &[f64], lag: usize| {
        let mut d = vec![0.0; steps];
        for t in 1..steps.saturating_sub(1) {
            d[t + 1] = x[t + 1 - lag] + a * d[t] + b * d[t - 1];
        }
        d
    };
    [unroll(p, 1), unroll(p, 2), unroll(q, 1), unroll(q, 2)]
}

#[cfg(test)]
mod tests;
