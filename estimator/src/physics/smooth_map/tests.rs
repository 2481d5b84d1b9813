//! Tests of `smooth_map.rs`.
use super::*;

/// Clips of the recurrence (a, b) read through `read`.
fn clips(a: f64, b: f64, read: impl Fn(f64) -> f64) -> Vec<Vec<f64>> {
    (0..60)
        .map(|i| {
            let (p, q) = responses(a, b, 20);
            let amp = 0.5 + 0.5 * (i as f64 * 0.618).fract();
            let (z0, z1) = (amp * (i as f64).cos(), amp * (i as f64 + 0.4).cos());
            (0..20).map(|t| read(z0 * p[t] + z1 * q[t])).collect()
        })
        .collect()
}

#[test]
fn recovers_the_recurrence_through_a_compressing_read() {
    // A damped oscillation (γ1 = 0.08 at dt 0.2) read through a map that flattens the
    // extremes: the affine solve sees too little decay, the smooth map removes the bias.
    let (a, b) = (1.8275, -(-0.016f64).exp());
    let data = clips(a, b, |x| 0.1 + x - 0.08 * x * x * x);
    let affine = crate::physics::oscillator::two_step_solve::solve_two_step(
        &data,
        [a, b],
        crate::physics::oscillator::two_step_solve::StateFit::LeastSquares,
    )
    .unwrap();
    let smooth = solve_with_smooth_map(&data, affine).unwrap();
    assert!((affine[1] - b).abs() > 1e-4, "{affine:?}");
    assert!(
        (smooth[0] - a).abs() < 1e-6 && (smooth[1] - b).abs() < 1e-6,
        "{smooth:?} vs {a} {b}"
    );
}

#[test]
fn an_affine_read_is_left_where_the_affine_solve_put_it() {
    let (a, b) = (1.8275, -(-0.016f64).exp());
    let data = clips(a, b, |x| 0.3 * x);
    // Exact data: nothing to improve, so no answer; the caller keeps the affine one.
    assert!(solve_with_smooth_map(&data, [a, b]).is_none_or(|s| (s[1] - b).abs() < 1e-9));
}
