//! The damped oscillation c + e^(−ζt)(a cos ωt + b sin ωt) by variable projection: ω and ζ
//! searched (a grid of ω, then Levenberg–Marquardt on both), c, a and b solved for at each;
//! γ0, γ1 and the amplitude at the span's start.

use super::{covariance, from_first, linear, sum_sq, Fitted, Value};
use physvid_shared::linalg::solve;

/// e^(−zt) at times `t`.
fn decay(t: &[f64], z: f64) -> Vec<f64> {
    t.iter().map(|&s| (-z * s).exp()).collect()
}

/// (cos wt, sin wt) at times `t` ([`Rotation`]).
fn turns(t: &[f64], w: f64) -> (Vec<f64>, Vec<f64>) {
    let mut rotation = Rotation::new(w);
    t.iter()
        .enumerate()
        .map(|(k, &tk)| rotation.at(t, k, tk))
        .unzip()
}

/// cos ωt and sin ωt carried from sample to sample by the rotation through ω times the step
/// between them (one sine and cosine per distinct step), anew from the time itself every
/// [`ROTATION_RUN`] samples so that rounding cannot build up: the grid's thousands of fits and
/// Levenberg–Marquardt's, without a sine and a cosine a sample.
struct Rotation {
    w: f64,
    /// (cos, sin) at the last sample.
    at: (f64, f64),
    /// The rotations of the last few distinct steps (a container's clock rounds a frame's step
    /// two ways, a gap is a multiple of it).
    rotations: [(f64, (f64, f64)); 4],
    next: usize,
}

impl Rotation {
    fn new(w: f64) -> Rotation {
        Rotation {
            w,
            at: (1.0, 0.0),
            rotations: [(f64::NAN, (0.0, 1.0)); 4],
            next: 0,
        }
    }

    /// (cos ωt, sin ωt) at `t[k]` = `tk`, the samples taken in order.
    fn at(&mut self, t: &[f64], k: usize, tk: f64) -> (f64, f64) {
        let w = self.w;
        let (c, s) = self.at;
        self.at = if k.is_multiple_of(ROTATION_RUN) {
            let (s, c) = (w * tk).sin_cos();
            (c, s)
        } else {
            // Steps that rounding alone tells apart share a rotation.
            let d = tk - t[k - 1];
            let same = |r: &&(f64, (f64, f64))| (r.0 - d).abs() <= 1e-12 * d.abs();
            let rot = match self.rotations.iter().find(same) {
                Some(r) => r.1,
                None => {
                    let r = (w * d).sin_cos();
                    self.rotations[self.next] = (d, r);
                    self.next = (self.next + 1) % self.rotations.len();
                    r
                }
            };
            (c * rot.1 - s * rot.0, s * rot.1 + c * rot.0)
        };
        self.at
    }
}

/// The columns 1, e^(−zt) cos wt and e^(−zt) sin wt from their `decay` and `turns`: a step
/// in z alone or in w alone computes only what it changes (Levenberg–Marquardt's Jacobian).
fn columns(e: &[f64], (cos, sin): &(Vec<f64>, Vec<f64>)) -> Vec<Vec<f64>> {
    vec![
        vec![1.0; e.len()],
        e.iter().zip(cos).map(|(e, c)| e * c).collect(),
        e.iter().zip(sin).map(|(e, s)| e * s).collect(),
    ]
}

/// The undamped angular frequency on a log grid from half a cycle in `span` to the samples'
/// Nyquist frequency (`step` apart) that leaves the least residual of `u` on c + a cos ωt +
/// b sin ωt at times `t`.
fn grid_frequency(t: &[f64], u: &[f64], span: f64, step: f64) -> f64 {
    let (lo, hi) = (std::f64::consts::PI / span, std::f64::consts::PI / step);
    const GRID: usize = 400;
    let mut best = (f64::INFINITY, lo);
    for i in 0..GRID {
        let w = lo * (hi / lo).powf(i as f64 / (GRID - 1) as f64);
        if let Some(s) = undamped_residual(t, u, w) {
            if s < best.0 {
                best = (s, w);
            }
        }
    }
    best.1
}

/// The residual sum of squares of `u` (at times `t`) on c + a cos ωt + b sin ωt, from the
/// normal equations' sums with no column kept: the grid's thousands of fits ([`Rotation`]).
fn undamped_residual(t: &[f64], u: &[f64], w: f64) -> Option<f64> {
    let n = t.len() as f64;
    let mean = u.iter().sum::<f64>() / n;
    let (mut sc, mut ss, mut scc, mut scs, mut sss) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let (mut suc, mut sus, mut suu) = (0.0, 0.0, 0.0);
    let mut rotation = Rotation::new(w);
    for (k, (&tk, &uk)) in t.iter().zip(u).enumerate() {
        let (c, s) = rotation.at(t, k, tk);
        let v = uk - mean;
        sc += c;
        ss += s;
        scc += c * c;
        scs += c * s;
        sss += s * s;
        suc += v * c;
        sus += v * s;
        suu += v * v;
    }
    let m = [n, sc, ss, sc, scc, scs, ss, scs, sss];
    let b = [0.0, suc, sus];
    let coef = solve(&m, &b, 3)?;
    Some((suu - coef.iter().zip(&b).map(|(x, y)| x * y).sum::<f64>()).max(0.0))
}

/// Samples carried by rotation before cos ωt and sin ωt are taken from the time anew.
const ROTATION_RUN: usize = 32;

/// The damped oscillation fitted to `u` at times `t`, from (ζ, ω) = `start` or else from the
/// best undamped ω of a grid.
pub(super) fn oscillation(t: &[f64], u: &[f64], start: Option<[f64; 2]>) -> Option<Fitted> {
    let n = t.len();
    let (t, span, step) = from_first(t, 8)?;
    let residual =
        |e: &[f64], turns: &(Vec<f64>, Vec<f64>)| linear(&columns(e, turns), u).map(|(_, r)| r);
    let start = start.unwrap_or_else(|| [0.0, grid_frequency(&t, u, span, step)]);
    // Levenberg–Marquardt on (ζ, ω), the decay and the turns at p kept.
    let mut p = start;
    let (mut e, mut wt) = (decay(&t, p[0]), turns(&t, p[1]));
    let mut r = residual(&e, &wt)?;
    let mut s = sum_sq(&r);
    let mut lambda = 1e-3;
    for _ in 0..100 {
        let mut jac = [vec![0.0; n], vec![0.0; n]];
        for (k, col) in jac.iter_mut().enumerate() {
            let h = 1e-6 * p[k].abs().max(1e-2);
            let mut q = p;
            q[k] += h;
            let rq = match k {
                0 => residual(&decay(&t, q[0]), &wt)?,
                _ => residual(&e, &turns(&t, q[1]))?,
            };
            for (c, (a, b)) in col.iter_mut().zip(rq.iter().zip(&r)) {
                *c = (a - b) / h;
            }
        }
        let a = [
            sum_sq(&jac[0]),
            jac[0].iter().zip(&jac[1]).map(|(x, y)| x * y).sum(),
            0.0,
            sum_sq(&jac[1]),
        ];
        let g = [
            jac[0].iter().zip(&r).map(|(x, y)| x * y).sum::<f64>(),
            jac[1].iter().zip(&r).map(|(x, y)| x * y).sum::<f64>(),
        ];
        let mut moved = false;
        while lambda < 1e12 {
            let m = [a[0] * (1.0 + lambda), a[1], a[1], a[3] * (1.0 + lambda)];
            let Some(d) = solve(&m, &[-g[0], -g[1]], 2) else {
                lambda *= 10.0;
                continue;
            };
            let q = [p[0] + d[0], p[1] + d[1]];
            let (eq, wq) = (decay(&t, q[0]), turns(&t, q[1]));
            if let Some(rq) = residual(&eq, &wq) {
                let sq = sum_sq(&rq);
                if sq < s {
                    let gain = (s - sq) / s.max(1e-300);
                    p = q;
                    (e, wt) = (eq, wq);
                    r = rq;
                    s = sq;
                    lambda = (lambda * 0.3).max(1e-12);
                    moved = gain > 1e-12;
                    break;
                }
            }
            lambda *= 10.0;
        }
        if !moved {
            break;
        }
    }
    let (z, w) = (p[0], p[1]);
    // Beyond the samples' Nyquist frequency, or decaying within a cycle, nothing oscillates.
    if !(w > 0.0 && w <= std::f64::consts::PI / step && z.abs() < w) {
        return None;
    }
    let cols = columns(&e, &wt);
    let (c, r) = linear(&cols, u)?;
    // The model's Jacobian in (c, a, b, ζ, ω).
    let (a, b) = (c[1], c[2]);
    let dz: Vec<f64> = t
        .iter()
        .zip(cols[1].iter().zip(&cols[2]))
        .map(|(&s, (ec, es))| -s * (a * ec + b * es))
        .collect();
    let dw: Vec<f64> = t
        .iter()
        .zip(cols[1].iter().zip(&cols[2]))
        .map(|(&s, (ec, es))| s * (-a * es + b * ec))
        .collect();
    let mut full = cols.clone();
    full.push(dz);
    full.push(dw);
    let cov = covariance(&full, &r)?;
    let (vz, vw, vzw) = (cov[3 * 5 + 3], cov[4 * 5 + 4], cov[3 * 5 + 4]);
    let g0 = w * w + z * z;
    let g0_var = 4.0 * (w * w * vw + z * z * vz + 2.0 * w * z * vzw);
    let curve = u.iter().zip(&r).map(|(u, r)| u - r).collect();
    Some(Fitted {
        values: vec![
            Value {
                name: "gamma0",
                value: g0,
                error: g0_var.max(0.0).sqrt(),
                unit: "1/s^2",
            },
            Value {
                name: "gamma1",
                value: 2.0 * z,
                error: 2.0 * vz.max(0.0).sqrt(),
                unit: "1/s",
            },
            amplitude(a, b, [cov[6], cov[12], cov[7]]),
        ],
        residuals: r,
        curve,
        periods: Some(w * span / std::f64::consts::TAU),
        shape: [z, w],
    })
}

/// The amplitude at the span's start, √(a² + b²) (pixels: a length a stick or a plane puts in
/// metres), with its standard error from a's and b's variances `[va, vb, vab]`.
fn amplitude(a: f64, b: f64, [va, vb, vab]: [f64; 3]) -> Value {
    let value = a.hypot(b);
    let var = if value > 0.0 {
        (a * a * va + b * b * vb + 2.0 * a * b * vab) / (value * value)
    } else {
        va.max(vb)
    };
    Value {
        name: "amplitude",
        value,
        error: var.max(0.0).sqrt(),
        unit: "px",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grid's residual from sums is the one the kept columns give, and the carried
    /// rotations are the sines and cosines of the times, on times with gaps and a jittered
    /// step (a variable frame rate).
    #[test]
    fn the_grids_residual_is_the_columns_residual() {
        let t: Vec<f64> = (0..300)
            .filter(|i| i % 37 != 5 && i % 53 != 9)
            .map(|i| i as f64 / 29.97 + 1e-4 * ((i * 7919) % 13) as f64)
            .collect();
        let u: Vec<f64> = t
            .iter()
            .map(|&s| 240.0 + 35.0 * (5.3 * s + 0.4).cos() + 0.2 * (71.3 * s).sin())
            .collect();
        for w in [0.4, 2.0, 5.3, 9.9, 60.0] {
            let (cos, sin) = turns(&t, w);
            for (k, &s) in t.iter().enumerate() {
                let off = (cos[k] - (w * s).cos()).abs() + (sin[k] - (w * s).sin()).abs();
                assert!(off < 1e-12, "{w} at {s}: {off}");
            }
            let fast = undamped_residual(&t, &u, w).unwrap();
            let (_, r) = linear(&columns(&decay(&t, 0.0), &turns(&t, w)), &u).unwrap();
            let slow = sum_sq(&r);
            assert!(
                (fast - slow).abs() <= 1e-8 * slow.max(1.0),
                "{w}: {fast} {slow}"
            );
        }
    }

    #[test]
    fn a_damped_oscillation_gives_back_its_gamma0_and_gamma1() {
        let (g0, g1): (f64, f64) = (35.7, 0.04);
        let z = g1 / 2.0;
        let w = (g0 - z * z).sqrt();
        let t: Vec<f64> = (0..240).map(|i| 0.5 + i as f64 / 30.0).collect();
        // A little deterministic "noise" (an incommensurate ripple of 0.05 px).
        let u: Vec<f64> = t
            .iter()
            .map(|&s| 100.0 + 20.0 * (-z * s).exp() * (w * s + 0.3).cos() + 0.05 * (37.1 * s).sin())
            .collect();
        let f = oscillation(&t, &u, None).expect("fits");
        let g = f.value("gamma0").unwrap();
        assert!((g.value / g0 - 1.0).abs() < 1e-3, "{g:?}");
        assert!(g.error > 0.0 && g.error < 0.05, "{g:?}");
        let d = f.value("gamma1").unwrap();
        assert!((d.value - g1).abs() < 0.005, "{d:?}");
        // 20 px at 0.5 s, the span's start.
        let a = f.value("amplitude").unwrap();
        let want = 20.0 * (-z * 0.5).exp();
        assert!((a.value - want).abs() < 0.02 && a.error < 0.02, "{a:?}");
        assert!(f.periods.unwrap() > 7.0);
    }
}
