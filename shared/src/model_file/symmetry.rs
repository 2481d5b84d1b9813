//! Which parameters a transformation of the data moves, found numerically: for a change of the
//! observed variables' scale (x → λ·x for every state, as a latent read up to scale does), of
//! their offset (observed x → x + c), or of the time unit (a motion κ times faster), solve for
//! the parameters p' with which the law holds for the transformed states at sampled points.
//! A parameter that must change depends on the latent's arbitrary scale (or offset) and is in
//! latent units until a calibration fixes them; the others are determined by the data alone.
//! No solution means the law pins that scale (or offset) itself.

use super::system::CompiledSystem;
use super::ModelFile;
use crate::linalg::solve;

/// A transformation of the data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Transform {
    /// Every state multiplied by λ.
    Scale(f64),
    /// Every observed state shifted by c.
    Shift(f64),
    /// The motion κ times faster.
    Time(f64),
}

/// What the law leaves free: for scale and offset, `None` when the law pins them, else which
/// parameters move with them.
#[derive(Debug, Clone, PartialEq)]
pub struct Symmetries {
    pub scale: Option<Vec<bool>>,
    pub shift: Option<Vec<bool>>,
}

impl Symmetries {
    /// Whether parameter `j` depends on the latent's arbitrary scale or offset.
    pub fn latent_units(&self, j: usize) -> bool {
        [&self.scale, &self.shift]
            .iter()
            .any(|s| s.as_ref().is_some_and(|moved| moved[j]))
    }
}

/// Sample points per state for the fits.
const POINTS: usize = 24;

/// A deterministic sequence in [0, 1) (splitmix64).
fn unit(i: u64) -> f64 {
    let mut z = i.wrapping_add(1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    (z ^ (z >> 31)) as f64 / u64::MAX as f64
}

/// The parameters with which `file`'s law holds for the data transformed by `tr`, starting from
/// `p`; `None` when no parameters make it hold (the law pins what `tr` changes). Under a change
/// of scale or of time unit the states the latent does not observe (a velocity) may take a
/// factor of their own, which is solved for too.
pub fn transformed(
    file: &ModelFile,
    sys: &CompiledSystem,
    p: &[f64],
    tr: Transform,
) -> Option<Vec<f64>> {
    let (n, m) = (sys.n, sys.m);
    let hidden: Vec<usize> = (0..n).filter(|i| !file.observed.contains(i)).collect();
    let h = if matches!(tr, Transform::Shift(_)) {
        0
    } else {
        hidden.len()
    };
    // New states Y = S·x (+ c on the observed), moving κ times faster.
    let (observed_factor, kappa, shift) = match tr {
        Transform::Scale(l) => (l, 1.0, 0.0),
        Transform::Shift(c) => (1.0, 1.0, c),
        Transform::Time(k) => (1.0, k, 0.0),
    };
    let points: Vec<(Vec<f64>, f64)> = (0..POINTS)
        .map(|k| {
            let x = (0..n)
                .map(|i| {
                    let (lo, hi) = file.initial[i].unwrap_or((-1.5, 1.5));
                    let (lo, hi) = if hi - lo < 1e-9 {
                        (lo - 1.0, hi + 1.0)
                    } else {
                        (lo, hi)
                    };
                    lo + (hi - lo) * unit((k * n + i) as u64)
                })
                .collect();
            (x, 5.0 * unit((POINTS * n + k) as u64 + 7919))
        })
        .collect();
    let mut f = vec![0.0; n];
    // The old law at each point: f(x, p, κt).
    let old: Vec<Vec<f64>> = points
        .iter()
        .map(|(x, t)| {
            sys.eval(x, p, kappa * t, &mut f, None);
            f.clone()
        })
        .collect();
    let factors = |u: &[f64]| -> Vec<f64> {
        let mut s = vec![observed_factor; n];
        for (k, &i) in hidden.iter().enumerate().take(h) {
            s[i] = u[m + k];
        }
        if h == 0 {
            for &i in &hidden {
                s[i] = 1.0;
            }
        }
        s
    };
    let new_state = |x: &[f64], s: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|i| {
                s[i] * x[i]
                    + if file.observed.contains(&i) {
                        shift
                    } else {
                        0.0
                    }
            })
            .collect()
    };
    let (mut jx, mut jp) = (vec![0.0; n * n], vec![0.0; n * m]);
    let cost_of = |u: &[f64], f: &mut [f64]| -> f64 {
        let s = factors(u);
        points
            .iter()
            .zip(&old)
            .map(|((x, t), fo)| {
                sys.eval(&new_state(x, &s), &u[..m], *t, f, None);
                (0..n)
                    .map(|i| (f[i] - kappa * s[i] * fo[i]).powi(2))
                    .sum::<f64>()
            })
            .sum()
    };
    let norm: f64 = old
        .iter()
        .flatten()
        .map(|v| (kappa * observed_factor * v).powi(2))
        .sum::<f64>()
        .sqrt();
    let mut u: Vec<f64> = p
        .iter()
        .copied()
        .chain(std::iter::repeat_n(observed_factor * kappa, h))
        .collect();
    let k = m + h;
    let mut cost = cost_of(&u, &mut f);
    let mut damping = 1e-6;
    for _ in 0..200 {
        if cost.sqrt() <= 1e-10 * norm.max(1e-300) {
            break;
        }
        let s = factors(&u);
        let (mut jtj, mut jtr) = (vec![0.0; k * k], vec![0.0; k]);
        let mut row = vec![0.0; k];
        for ((x, t), fo) in points.iter().zip(&old) {
            sys.eval(
                &new_state(x, &s),
                &u[..m],
                *t,
                &mut f,
                Some((&mut jx, &mut jp)),
            );
            for i in 0..n {
                let r = f[i] - kappa * s[i] * fo[i];
                row[..m].copy_from_slice(&jp[i * m..(i + 1) * m]);
                for (c, &j) in hidden.iter().enumerate().take(h) {
                    row[m + c] = jx[i * n + j] * x[j] - if i == j { kappa * fo[i] } else { 0.0 };
                }
                for a in 0..k {
                    jtr[a] += row[a] * r;
                    for b in 0..k {
                        jtj[a * k + b] += row[a] * row[b];
                    }
                }
            }
        }
        let scale = (0..k)
            .map(|a| jtj[a * k + a])
            .fold(0.0, f64::max)
            .max(1e-300);
        for a in 0..k {
            jtj[a * k + a] += damping * scale;
        }
        let Some(step) = solve(&jtj, &jtr, k) else {
            break;
        };
        let trial: Vec<f64> = u.iter().zip(&step).map(|(a, s)| a - s).collect();
        let c = cost_of(&trial, &mut f);
        if c.is_finite() && c < cost {
            u = trial;
            cost = c;
            damping = (damping / 10.0).max(1e-12);
        } else {
            damping *= 10.0;
            if damping > 1e6 {
                break;
            }
        }
    }
    (cost.sqrt() <= 1e-7 * norm.max(1e-300)).then(|| u[..m].to_vec())
}

/// The scale and offset symmetries of `file`'s law at its starting parameters.
pub fn symmetries(file: &ModelFile, sys: &CompiledSystem) -> Symmetries {
    let p = file.starts();
    let moved = |q: Vec<f64>| -> Vec<bool> {
        q.iter()
            .zip(&p)
            .map(|(a, b)| (a - b).abs() > 1e-6 * b.abs().max(1e-9))
            .collect()
    };
    Symmetries {
        scale: transformed(file, sys, &p, Transform::Scale(1.7)).map(moved),
        shift: transformed(file, sys, &p, Transform::Shift(0.37)).map(moved),
    }
}

#[cfg(test)]
mod tests {
    use super::super::parse_text;
    use super::*;

    fn file(params: &str, states: &str, observed: &str) -> ModelFile {
        parse_text(&format!("name = \"m\"\n[parameters]\n{params}\n[state]\n{states}\n[observed]\nlatent = [{observed}]\n")).unwrap()
    }

    #[test]
    fn scale_dependence_is_found_for_each_kind_of_law() {
        let duffing = file(
            "a = { start = 1.0, positive = true }\nb = { start = 0.1 }\nc = { start = 0.1, min = 0.0 }",
            "x = \"v\"\nv = \"-a*x - b*x^3 - c*v\"",
            "\"x\"",
        );
        let s = symmetries(&duffing, &CompiledSystem::new(&duffing));
        assert_eq!(s.scale, Some(vec![false, true, false]));
        assert_eq!(s.shift, None);
        let cooling = file(
            "r = { start = 0.5, positive = true }\nTa = { start = 0.2 }",
            "T = \"-r*(T - Ta)\"",
            "\"T\"",
        );
        let s = symmetries(&cooling, &CompiledSystem::new(&cooling));
        assert_eq!(s.scale, Some(vec![false, true]));
        assert_eq!(s.shift, Some(vec![false, true]));
        let pendulum = file(
            "w2 = { start = 10.0, positive = true }\nzeta = { start = 0.1 }",
            "th = \"om\"\nom = \"-w2*sin(th) - zeta*om\"",
            "\"th\"",
        );
        let s = symmetries(&pendulum, &CompiledSystem::new(&pendulum));
        assert_eq!((s.scale, s.shift), (None, None));
        let sys = CompiledSystem::new(&duffing);
        let q = transformed(&duffing, &sys, &[1.0, 0.1, 0.1], Transform::Time(2.0)).unwrap();
        for (a, b) in q.iter().zip([4.0, 0.4, 0.2]) {
            assert!((a - b).abs() < 1e-9, "{q:?}");
        }
    }
}
