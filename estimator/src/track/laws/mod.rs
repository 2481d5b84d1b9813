//! The laws fitted to a track, each by least squares on the frames' own times: a damped
//! oscillation of the position along the motion's axis, c + e^(−ζt)(a cos ωt + b sin ωt)
//! (γ0 = ω² + ζ², γ1 = 2ζ: the oscillator's z'' + γ1 z' + γ0 z = 0, and a swing's g/L at small
//! angles), found by variable projection (ω and ζ searched, the rest solved for), and a
//! constant acceleration in the picture's plane, p0 + v0 t + a t²/2 in x and y (a fall, a toss,
//! a roll, the release's velocity free), and a swing about a pivot (`swing`): its angle as the
//! pendulum at any amplitude, or as the damped oscillator (a restoring turn that grows with the
//! angle); and for a quantity that is not a position (a brightness), an exponential decay
//! (`decay`) and Torricelli's drain (`drain`).
//! Standard errors from the Jacobian, widened for residuals that follow one another (their
//! lag-one correlation).

mod acceleration;
mod bent;
mod decay;
mod drain;
mod oscillation;
mod released;
pub mod swing;

use acceleration::acceleration;
use decay::decay;
use drain::drain;
pub use drain::drained;
use oscillation::oscillation;
use physvid_shared::linalg::solve;
pub(crate) use released::released;
use serde::Serialize;
use swing::{angular, swing};

/// The laws a track is tried against.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TrackLaw {
    Oscillation,
    ConstantAcceleration,
    Swing,
    AngularOscillation,
    /// A level that decays exponentially: fitted to an observable that is not a position (a
    /// light's brightness, `Reading::Brightness`), and only to one.
    Decay,
    /// A level that drains as Torricelli's law has it (`drain`), on the same observables.
    Drain,
}

impl TrackLaw {
    pub const ALL: [TrackLaw; 4] = [
        TrackLaw::Oscillation,
        TrackLaw::ConstantAcceleration,
        TrackLaw::Swing,
        TrackLaw::AngularOscillation,
    ];

    /// The laws of an observable that is not a position.
    pub const OF_LEVELS: [TrackLaw; 2] = [TrackLaw::Decay, TrackLaw::Drain];

    /// Whether it is a law of an observable that is not a position ([`Self::OF_LEVELS`]).
    pub fn of_a_level(self) -> bool {
        Self::OF_LEVELS.contains(&self)
    }

    pub fn name(self) -> &'static str {
        match self {
            TrackLaw::Oscillation => "oscillation",
            TrackLaw::ConstantAcceleration => "constant acceleration",
            TrackLaw::Swing => "swing",
            TrackLaw::AngularOscillation => "angular oscillation",
            TrackLaw::Decay => "exponential decay",
            TrackLaw::Drain => "drain",
        }
    }

    /// What the track does where the law holds, for a sentence ("the track swings over …").
    pub fn verb(self) -> &'static str {
        match self {
            TrackLaw::Oscillation => "oscillates",
            TrackLaw::ConstantAcceleration => "accelerates at a constant rate",
            TrackLaw::Swing => "swings",
            TrackLaw::AngularOscillation => "oscillates about a pivot",
            TrackLaw::Decay => "decays",
            TrackLaw::Drain => "drains",
        }
    }

    /// Free parameters of the law (both coordinates for the acceleration; the swing's circle
    /// and its five).
    pub fn freedom(self) -> usize {
        match self {
            TrackLaw::Oscillation => 5,
            TrackLaw::ConstantAcceleration => 6,
            TrackLaw::Swing | TrackLaw::AngularOscillation => 8,
            TrackLaw::Decay | TrackLaw::Drain => 3,
        }
    }

    /// The law fitted to the samples `t` (s), `u` (the position along the axis) and `xy` (the
    /// position in the picture), all of one span; a nonlinear fit starts from `near`'s
    /// solution where given (a span grown from one fitted before), else searches.
    pub fn fit(
        self,
        t: &[f64],
        u: &[f64],
        xy: &[(f64, f64)],
        near: Option<&Fitted>,
    ) -> Option<Fitted> {
        match self {
            TrackLaw::Oscillation => oscillation(t, u, near.map(|f| f.shape)),
            TrackLaw::ConstantAcceleration => acceleration(t, xy, near.map(|f| f.shape)),
            TrackLaw::Swing => swing(t, u, xy, near.map(|f| f.shape)),
            TrackLaw::AngularOscillation => angular(t, u, xy, near.map(|f| f.shape)),
            TrackLaw::Decay => decay(t, u, near.map(|f| f.shape)),
            TrackLaw::Drain => drain(t, u, near.map(|f| f.shape)),
        }
    }
}

/// One value a law gives, with its standard error and unit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Value {
    pub name: &'static str,
    pub value: f64,
    pub error: f64,
    pub unit: &'static str,
}

impl Value {
    /// Its symbol in a sentence (γ0, g/L; else its name).
    pub fn symbol(&self) -> &'static str {
        match self.name {
            "gamma0" => "γ0",
            "gamma1" => "γ1",
            "g_over_l" => "g/L",
            "gamma" => "γ",
            other => other,
        }
    }
}

/// A law fitted to one span.
#[derive(Debug, Clone, PartialEq)]
pub struct Fitted {
    pub values: Vec<Value>,
    /// The residuals (for the acceleration, x's then y's), in pixels.
    pub residuals: Vec<f64>,
    /// The fitted positions along the axis (the acceleration's: along its direction), one per
    /// sample.
    pub curve: Vec<f64>,
    /// How many periods the span holds (the oscillation), for the law to be seen at all.
    pub periods: Option<f64>,
    /// The nonlinear parameters found (the oscillation's ζ and ω; the acceleration's bend, 0
    /// for none, and vertex), to start a nearby fit.
    pub shape: [f64; 2],
}

impl Fitted {
    pub fn rms(&self) -> f64 {
        (self.residuals.iter().map(|r| r * r).sum::<f64>() / self.residuals.len().max(1) as f64)
            .sqrt()
    }

    pub fn value(&self, name: &str) -> Option<&Value> {
        self.values.iter().find(|v| v.name == name)
    }
}

/// Least squares of `y` on the columns `cols`: the coefficients and the residuals.
pub(super) fn linear(cols: &[Vec<f64>], y: &[f64]) -> Option<(Vec<f64>, Vec<f64>)> {
    let k = cols.len();
    let mut m = vec![0.0; k * k];
    let mut b = vec![0.0; k];
    for i in 0..k {
        // The normal matrix is symmetric: each product's sum is the same either way round.
        for j in 0..i {
            m[i * k + j] = m[j * k + i];
        }
        for j in i..k {
            m[i * k + j] = cols[i].iter().zip(&cols[j]).map(|(a, c)| a * c).sum();
        }
        b[i] = cols[i].iter().zip(y).map(|(a, c)| a * c).sum();
    }
    let c = solve(&m, &b, k)?;
    let r = (0..y.len())
        .map(|n| y[n] - (0..k).map(|i| c[i] * cols[i][n]).sum::<f64>())
        .collect();
    Some((c, r))
}

/// The lag-one correlation of residuals `r`, clamped to 0–0.9: how far they follow one another
/// (n of them are worth n (1 − ρ)/(1 + ρ) independent ones).
pub fn lag_one(r: &[f64]) -> f64 {
    let ss: f64 = r.iter().map(|v| v * v).sum();
    if ss > 0.0 {
        (r.windows(2).map(|w| w[0] * w[1]).sum::<f64>() / ss).clamp(0.0, 0.9)
    } else {
        0.0
    }
}

/// The covariance of parameters whose model has the Jacobian columns `cols`, from residuals
/// `r`: s²·(JᵀJ)⁻¹, s² widened by (1 + ρ)/(1 − ρ) for the residuals' lag-one correlation ρ.
pub(super) fn covariance(cols: &[Vec<f64>], r: &[f64]) -> Option<Vec<f64>> {
    let k = cols.len();
    let n = r.len();
    if n <= k {
        return None;
    }
    let mut m = vec![0.0; k * k];
    for i in 0..k {
        for j in 0..k {
            m[i * k + j] = cols[i].iter().zip(&cols[j]).map(|(a, c)| a * c).sum();
        }
    }
    let ss: f64 = r.iter().map(|v| v * v).sum();
    let rho = lag_one(r);
    let s2 = ss / (n - k) as f64 * (1.0 + rho) / (1.0 - rho);
    let mut inv = vec![0.0; k * k];
    for j in 0..k {
        let mut e = vec![0.0; k];
        e[j] = 1.0;
        let col = solve(&m, &e, k)?;
        for i in 0..k {
            inv[i * k + j] = col[i] * s2;
        }
    }
    Some(inv)
}

/// The times `t` counted from their first, their span and their median step, where there are
/// at least `least` of them and they advance.
pub(super) fn from_first(t: &[f64], least: usize) -> Option<(Vec<f64>, f64, f64)> {
    if t.len() < least.max(2) {
        return None;
    }
    let t: Vec<f64> = t.iter().map(|s| s - t[0]).collect();
    let span = t[t.len() - 1];
    let step = median_step(&t);
    (span > 0.0 && step > 0.0).then_some((t, span, step))
}

/// The median step between the samples' times `t` (at least two): the Nyquist frequency π/step
/// bounds what a law may oscillate at.
pub(super) fn median_step(t: &[f64]) -> f64 {
    let mut steps: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    steps.sort_by(f64::total_cmp);
    steps[steps.len() / 2]
}

pub(super) fn sum_sq(r: &[f64]) -> f64 {
    r.iter().map(|v| v * v).sum()
}

/// The model's Jacobian at `p` (one column a parameter) by forward differences of the
/// residuals (data less model) `r` there.
pub(super) fn jacobian(
    p: &[f64],
    r: &[f64],
    residual: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
) -> Option<Vec<Vec<f64>>> {
    (0..p.len())
        .map(|k| {
            let h = 1e-6 * p[k].abs().max(1e-2);
            let mut q = p.to_vec();
            q[k] += h;
            let rq = residual(&q)?;
            Some(rq.iter().zip(r).map(|(a, b)| -(a - b) / h).collect())
        })
        .collect()
}

/// Values on the log grid a one-parameter search starts from (`searched`).
const GRID: usize = 200;

/// The one nonlinear parameter of a law fitted by variable projection (`residual`: the
/// residuals at a value, the rest solved for): Levenberg–Marquardt from `start` where given,
/// else from the best of a log grid of [`GRID`] values over `lo..hi`.
pub(super) fn searched(
    (lo, hi): (f64, f64),
    start: Option<f64>,
    residual: &dyn Fn(f64) -> Option<Vec<f64>>,
) -> Option<f64> {
    let p0 = match start {
        Some(p) => p,
        None => {
            (0..GRID)
                .map(|i| lo * (hi / lo).powf(i as f64 / (GRID - 1) as f64))
                .filter_map(|p| Some((sum_sq(&residual(p)?), p)))
                .min_by(|a, b| a.0.total_cmp(&b.0))?
                .1
        }
    };
    least_squares(&[p0], &|p: &[f64]| residual(p[0])).map(|(p, _)| p[0])
}

/// Levenberg–Marquardt from `p0` on the residuals (data less model) that `residual` gives:
/// the parameters and residuals of the least sum of squares reached. `None` where the start
/// has no residual.
pub(super) fn least_squares(
    p0: &[f64],
    residual: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
) -> Option<(Vec<f64>, Vec<f64>)> {
    let k = p0.len();
    let mut p = p0.to_vec();
    let mut r = residual(&p)?;
    let mut s = sum_sq(&r);
    let mut lambda = 1e-3;
    for _ in 0..200 {
        let Some(j) = jacobian(&p, &r, residual) else {
            break;
        };
        let mut a = vec![0.0; k * k];
        for i in 0..k {
            for m in 0..k {
                a[i * k + m] = j[i].iter().zip(&j[m]).map(|(x, y)| x * y).sum();
            }
        }
        let g: Vec<f64> = j
            .iter()
            .map(|c| c.iter().zip(&r).map(|(x, y)| x * y).sum())
            .collect();
        let mut moved = false;
        while lambda < 1e12 {
            let mut m = a.clone();
            for i in 0..k {
                m[i * k + i] *= 1.0 + lambda;
            }
            let Some(d) = solve(&m, &g, k) else {
                lambda *= 10.0;
                continue;
            };
            let q: Vec<f64> = p.iter().zip(&d).map(|(a, b)| a + b).collect();
            if let Some(rq) = residual(&q) {
                let sq = sum_sq(&rq);
                if sq < s {
                    moved = (s - sq) / s.max(1e-300) > 1e-12;
                    p = q;
                    r = rq;
                    s = sq;
                    lambda = (lambda * 0.3).max(1e-12);
                    break;
                }
            }
            lambda *= 10.0;
        }
        if !moved {
            break;
        }
    }
    Some((p, r))
}
