//! Label-free check: fit the exact two-step recurrence of a damped cosine,
//! s[t+1] − c = a·(s\[t\] − c) + b·(s[t−1] − c), by least squares over many series.

use crate::dynamics::gammas_from_recurrence;

/// Result of [`fit_two_step_recurrence`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RecurrenceFit {
    pub a: f64,
    pub b: f64,
    /// The offset c of the statistic.
    pub offset: f64,
    /// Root-mean-square residual of the one-step prediction.
    pub rms_residual: f64,
}

impl RecurrenceFit {
    /// (γ0, γ1) of the damped oscillator with this propagator at step `dt`, if under-damped.
    pub fn gammas(&self, dt: f64) -> Option<(f64, f64)> {
        gammas_from_recurrence(self.a, self.b, dt)
    }
}

/// Solves a 3×3 linear system by Gaussian elimination with partial pivoting.
fn solve3(mut m: [[f64; 3]; 3], mut v: [f64; 3]) -> Option<[f64; 3]> {
    for col in 0..3 {
        let piv = (col..3).max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))?;
        if m[piv][col].abs() < 1e-300 {
            return None;
        }
        m.swap(col, piv);
        v.swap(col, piv);
        for row in col + 1..3 {
            let f = m[row][col] / m[col][col];
            let pivot_row = m[col];
            for (x, p) in m[row].iter_mut().zip(pivot_row).skip(col) {
                *x -= f * p;
            }
            v[row] -= f * v[col];
        }
    }
    let mut x = [0.0; 3];
    for row in (0..3).rev() {
        let s: f64 = (row + 1..3).map(|k| m[row][k] * x[k]).sum();
        x[row] = (v[row] - s) / m[row][row];
    }
    Some(x)
}

/// Fits s[t+1] = a·s\[t\] + b·s[t−1] + d over every window of every series (one shared a, b, d),
/// with d = c·(1 − a − b). Returns `None` when the system is degenerate (e.g. constant series).
pub fn fit_two_step_recurrence<'a, I>(series: I) -> Option<RecurrenceFit>
where
    I: IntoIterator<Item = &'a [f64]> + Clone,
{
    let mut ata = [[0.0; 3]; 3];
    let mut aty = [0.0; 3];
    let mut count = 0usize;
    for s in series.clone() {
        for w in s.windows(3) {
            let row = [w[1], w[0], 1.0];
            for i in 0..3 {
                for j in 0..3 {
                    ata[i][j] += row[i] * row[j];
                }
                aty[i] += row[i] * w[2];
            }
            count += 1;
        }
    }
    if count < 3 {
        return None;
    }
    let [a, b, d] = solve3(ata, aty)?;
    let mut sse = 0.0;
    for s in series {
        for w in s.windows(3) {
            let r = w[2] - (a * w[1] + b * w[0] + d);
            sse += r * r;
        }
    }
    let denom = 1.0 - a - b;
    let offset = if denom.abs() > 1e-12 { d / denom } else { 0.0 };
    Some(RecurrenceFit {
        a,
        b,
        offset,
        rms_residual: (sse / count as f64).sqrt(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::DampedOscillator;

    #[test]
    fn recovers_gammas_from_an_affine_image_of_z() {
        let o = DampedOscillator::PAPER;
        let dt = 0.2;
        let series: Vec<Vec<f64>> = (0..20)
            .map(|i| {
                let (a, phi) = (0.5 + 0.02 * i as f64, 0.3 * i as f64);
                (0..20)
                    .map(|k| 3.0 - 2.0 * o.latent(a, phi, k as f64 * dt))
                    .collect()
            })
            .collect();
        let fit = fit_two_step_recurrence(series.iter().map(Vec::as_slice)).unwrap();
        let (g0, g1) = fit.gammas(dt).unwrap();
        assert!((g0 - 4.0016).abs() < 1e-8, "{g0}");
        assert!((g1 - 0.08).abs() < 1e-8, "{g1}");
        assert!((fit.offset - 3.0).abs() < 1e-6);
    }

    #[test]
    fn degenerate_input_is_none() {
        let flat = vec![1.0; 10];
        assert!(fit_two_step_recurrence([flat.as_slice()]).is_none());
    }
}
