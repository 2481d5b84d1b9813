//! The two-step coefficients (a, b) that fit encoded clips best, solved on the host in f64:
//! the rollout z0·p + z1·q of z[t+1] = a·z[t] + b·z[t−1] is linear in the initial state, so the
//! state is projected out (each clip's least-squares state, or its first two frames) and only
//! (a, b) is searched, by Levenberg–Marquardt. With the encoder held this is the exact optimum
//! that the optimiser's steps on γ only jitter around. The coefficients map back to the
//! oscillator's (γ0, γ1) for either integrator.

/// Where each clip's rollout starts (as the block's [`crate::physics::RolloutStart`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StateFit {
    /// The least-squares state over the whole clip.
    LeastSquares,
    /// The first two frames.
    FirstFrames,
}

/// The impulse responses p, q [steps] of the recurrence to (1, 0) and (0, 1), unrolled in f64.
pub(crate) fn responses(a: f64, b: f64, steps: usize) -> (Vec<f64>, Vec<f64>) {
    let mut p = vec![1.0, 0.0];
    let mut q = vec![0.0, 1.0];
    for t in 1..steps.saturating_sub(1) {
        p.push(a * p[t] + b * p[t - 1]);
        q.push(a * q[t] + b * q[t - 1]);
    }
    p.truncate(steps);
    q.truncate(steps);
    (p, q)
}

/// The rollout residuals of every clip (rows of `clips`, each `steps` long) for (a, b), or
/// `None` when they are not finite or the least-squares state is undetermined.
fn residuals(clips: &[Vec<f64>], ab: [f64; 2], fit: StateFit) -> Option<Vec<f64>> {
    let steps = clips.first()?.len();
    let (p, q) = responses(ab[0], ab[1], steps);
    let (pp, qq, pq) = (dot(&p, &p), dot(&q, &q), dot(&p, &q));
    let det = pp * qq - pq * pq;
    if fit == StateFit::LeastSquares && (det.abs() <= 1e-12 * pp * qq || !det.is_finite()) {
        return None;
    }
    let mut out = Vec::with_capacity(clips.len() * steps);
    for z in clips {
        let (z0, z1) = match fit {
            StateFit::LeastSquares => {
                let (zp, zq) = (dot(z, &p), dot(z, &q));
                ((zp * qq - zq * pq) / det, (zq * pp - zp * pq) / det)
            }
            StateFit::FirstFrames => (z[0], z[1]),
        };
        out.extend((0..steps).map(|t| z[t] - z0 * p[t] - z1 * q[t]));
    }
    out.iter().all(|r| r.is_finite()).then_some(out)
}

pub(crate) fn dot(u: &[f64], v: &[f64]) -> f64 {
    u.iter().zip(v).map(|(x, y)| x * y).sum()
}

fn cost(r: &[f64]) -> f64 {
    dot(r, r)
}

/// The (a, b) minimising the summed squared rollout residual of `clips` [N][T ≥ 3], searched
/// from `start`; `None` when no finite fit is found.
pub fn solve_two_step(clips: &[Vec<f64>], start: [f64; 2], fit: StateFit) -> Option<[f64; 2]> {
    if clips.first().is_none_or(|c| c.len() < 3) {
        return None;
    }
    let mut ab = start;
    let mut r = residuals(clips, ab, fit)?;
    let mut c = cost(&r);
    let mut lambda = 1e-3;
    for _ in 0..100 {
        // Central differences in f64: the residuals are smooth polynomials in (a, b).
        let mut jac = [Vec::new(), Vec::new()];
        for (k, col) in jac.iter_mut().enumerate() {
            let h = 1e-6 * ab[k].abs().max(1e-3);
            let (mut up, mut down) = (ab, ab);
            up[k] += h;
            down[k] -= h;
            let (ru, rd) = (residuals(clips, up, fit)?, residuals(clips, down, fit)?);
            *col = ru
                .iter()
                .zip(&rd)
                .map(|(u, d)| (u - d) / (2.0 * h))
                .collect();
        }
        let jtj = [
            [dot(&jac[0], &jac[0]), dot(&jac[0], &jac[1])],
            [dot(&jac[1], &jac[0]), dot(&jac[1], &jac[1])],
        ];
        let jtr = [dot(&jac[0], &r), dot(&jac[1], &r)];
        let mut improved = false;
        while lambda < 1e12 {
            let m = [
                [jtj[0][0] * (1.0 + lambda), jtj[0][1]],
                [jtj[1][0], jtj[1][1] * (1.0 + lambda)],
            ];
            let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
            let step = [
                -(jtr[0] * m[1][1] - jtr[1] * m[0][1]) / det,
                -(jtr[1] * m[0][0] - jtr[0] * m[1][0]) / det,
            ];
            let trial = [ab[0] + step[0], ab[1] + step[1]];
            if let Some(rt) = residuals(clips, trial, fit).filter(|rt| cost(rt) < c) {
                let converged = step[0].abs() <= 1e-12 * ab[0].abs().max(1e-3)
                    && step[1].abs() <= 1e-12 * ab[1].abs().max(1e-3);
                c = cost(&rt);
                (ab, r) = (trial, rt);
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
    ab.iter().all(|x| x.is_finite()).then_some(ab)
}

/// (γ0, γ1) of the exact propagator with coefficients `ab`, on the branch of ωd·dt (cos is
/// periodic: θ, 2π − θ, 2π + θ, … give the same coefficients) nearest the current `gamma0`;
/// `None` when no positive γ0 has them (a negative real root).
pub fn exact_gammas(ab: [f64; 2], dt: f64, gamma0: f64) -> Option<Vec<f64>> {
    let [a, b] = ab;
    if b >= 0.0 {
        return None;
    }
    let rho = (-b).sqrt();
    let g1 = -2.0 * rho.ln() / dt;
    let c = a / (2.0 * rho);
    let g0 = if c.abs() < 1.0 {
        // The branch nearest the current θ = ωd·dt.
        let now = ((gamma0 - g1 * g1 / 4.0).max(0.0)).sqrt() * dt;
        let base = c.acos();
        let tau = std::f64::consts::TAU;
        let k = (now / tau).round();
        let theta = [k * tau + base, k * tau - base, (k + 1.0) * tau - base]
            .into_iter()
            .filter(|t| *t > 0.0)
            .min_by(|x, y| (x - now).abs().total_cmp(&(y - now).abs()))?;
        (theta / dt).powi(2) + g1 * g1 / 4.0
    } else if c >= 1.0 {
        g1 * g1 / 4.0 - (c.acosh() / dt).powi(2)
    } else {
        return None;
    };
    (g0 > 0.0 && g0.is_finite() && g1.is_finite()).then(|| vec![g0, g1])
}

/// (γ0, γ1) of the paper's Euler step with coefficients `ab`: a = 2 − dt·γ1 − dt²·γ0,
/// b = dt·γ1 − 1.
pub fn euler_gammas(ab: [f64; 2], dt: f64) -> Option<Vec<f64>> {
    let g1 = (1.0 + ab[1]) / dt;
    let g0 = (2.0 - ab[0] - dt * g1) / (dt * dt);
    (g0 > 0.0 && g0.is_finite() && g1.is_finite()).then(|| vec![g0, g1])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clips(a: f64, b: f64, offsets: bool) -> Vec<Vec<f64>> {
        (0..30)
            .map(|i| {
                let (p, q) = responses(a, b, 20);
                let (z0, z1) = (0.3 + 0.05 * i as f64, -0.2 + 0.03 * i as f64);
                (0..20)
                    .map(|t| {
                        let wobble = if offsets {
                            1e-3 * ((t * 7 + i) as f64).sin()
                        } else {
                            0.0
                        };
                        z0 * p[t] + z1 * q[t] + wobble
                    })
                    .collect()
            })
            .collect()
    }

    #[test]
    fn recovers_the_coefficients_of_exact_rollouts_from_a_distant_start() {
        let (a, b) = (1.6, -0.97);
        for fit in [StateFit::LeastSquares, StateFit::FirstFrames] {
            let ab = solve_two_step(&clips(a, b, false), [1.2, -0.8], fit).unwrap();
            assert!(
                (ab[0] - a).abs() < 1e-8 && (ab[1] - b).abs() < 1e-8,
                "{ab:?}"
            );
        }
    }

    #[test]
    fn the_solution_is_a_minimum_of_the_residual() {
        let data = clips(1.6, -0.97, true);
        let fit = StateFit::LeastSquares;
        let ab = solve_two_step(&data, [1.5, -0.9], fit).unwrap();
        let best = cost(&residuals(&data, ab, fit).unwrap());
        for (da, db) in [(1e-4, 0.0), (-1e-4, 0.0), (0.0, 1e-4), (0.0, -1e-4)] {
            let other = cost(&residuals(&data, [ab[0] + da, ab[1] + db], fit).unwrap());
            assert!(other > best, "{da} {db}: {other} ≤ {best}");
        }
    }

    #[test]
    fn gammas_round_trip_through_the_coefficients_on_the_current_branch() {
        let dt = 0.2;
        for (g0, g1) in [(4.0, 0.08), (0.5, 0.3), (300.0, 0.5), (1.0, 2.5)] {
            let x: f64 = (g0 - g1 * g1 / 4.0) * dt * dt;
            let c = if x >= 0.0 {
                x.sqrt().cos()
            } else {
                (-x).sqrt().cosh()
            };
            let ab = [2.0 * (-g1 * dt / 2.0).exp() * c, -(-g1 * dt).exp()];
            let back = exact_gammas(ab, dt, g0 * 1.01).unwrap();
            assert!(
                (back[0] / g0 - 1.0).abs() < 1e-9 && (back[1] - g1).abs() < 1e-9,
                "{back:?}"
            );
        }
    }
}
