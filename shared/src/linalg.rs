//! Dense linear algebra on small f64 systems: the shooting fits, the peak fits, a model
//! file's symmetry analysis.

/// Solves the n×n system `m`·x = `b` by Gaussian elimination with partial pivoting.
pub fn solve(m: &[f64], b: &[f64], n: usize) -> Option<Vec<f64>> {
    let mut a = m.to_vec();
    let mut x = b.to_vec();
    for col in 0..n {
        let piv =
            (col..n).max_by(|&i, &j| a[i * n + col].abs().total_cmp(&a[j * n + col].abs()))?;
        if a[piv * n + col].abs().is_nan() || a[piv * n + col].abs() <= 1e-300 {
            return None;
        }
        if piv != col {
            for j in 0..n {
                a.swap(piv * n + j, col * n + j);
            }
            x.swap(piv, col);
        }
        for r in col + 1..n {
            let f = a[r * n + col] / a[col * n + col];
            for j in col..n {
                a[r * n + j] -= f * a[col * n + j];
            }
            x[r] -= f * x[col];
        }
    }
    for col in (0..n).rev() {
        let s: f64 = (col + 1..n).map(|j| a[col * n + j] * x[j]).sum();
        x[col] = (x[col] - s) / a[col * n + col];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}
