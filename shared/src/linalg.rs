//! Dense linear algebra on small f64 systems: the shooting fits, the peak fits, a model
//! file's symmetry analysis, a descent's parabola.

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

/// Least-squares a + b·t + c·t² through `pts` (t, y), t centred for conditioning.
pub fn quadratic(pts: &[(f64, f64)]) -> Option<[f64; 3]> {
    let m = pts.len() as f64;
    let t0 = pts.iter().map(|p| p.0).sum::<f64>() / m;
    let mut a = [0.0f64; 9];
    let mut r = [0.0f64; 3];
    for &(t, y) in pts {
        let row = [1.0, t - t0, (t - t0).powi(2)];
        for i in 0..3 {
            r[i] += row[i] * y;
            for j in 0..3 {
                a[3 * i + j] += row[i] * row[j];
            }
        }
    }
    let s = solve(&a, &r, 3)?;
    // Back to t: a + b(t − t0) + c(t − t0)².
    Some([
        s[0] - s[1] * t0 + s[2] * t0 * t0,
        s[1] - 2.0 * s[2] * t0,
        s[2],
    ])
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_parabola_is_recovered_far_from_the_origin() {
        let pts: Vec<(f64, f64)> = (0..20)
            .map(|k| {
                let t = 1000.0 + k as f64;
                (t, 3.0 - 0.5 * t + 0.25 * t * t)
            })
            .collect();
        let [a, b, c] = super::quadratic(&pts).unwrap();
        assert!(
            (c - 0.25).abs() < 1e-9 && (b + 0.5).abs() < 1e-5,
            "{a} {b} {c}"
        );
        assert!((-b / (2.0 * c) - 1.0).abs() < 1e-4);
    }
}
