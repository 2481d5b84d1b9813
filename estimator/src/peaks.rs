//! The classical damping measurement of appendix A.6, as a cross-check of the learned one:
//! find the swings of a recording's encoded latent (between crossings of the equilibrium),
//! measure each one's amplitude and fit a line to ln(amplitude) against time. For
//! x'' = … − ζ·x' the envelope decays as e^(−ζt/2), so ζ = −2·slope.

use physvid_shared::AffineFit;
use serde::Serialize;

/// A decay rate read off peaks, beside the learned value it checks.
#[derive(Debug, Clone, Serialize)]
pub struct PeakDecay {
    /// The parameter it measures (e.g. "damping").
    pub name: String,
    /// −2 × the slope of ln(peak) against time (1/s).
    pub estimate: f64,
    /// Its standard error, from the regression.
    pub std_error: f64,
    /// The learned value.
    pub learned: f64,
    /// Whether the learned value lies within two standard errors.
    pub agrees: bool,
    /// Swing amplitudes used: (mid-time of the swing in s, amplitude in latent units).
    pub peaks: Vec<(f64, f64)>,
}

/// Fewer peaks than this give no estimate.
const MIN_PEAKS: usize = 4;

/// The swing amplitudes of `series` (sampled every `dt` s) around `centre`. Between two
/// crossings of the centre (with hysteresis of a tenth of the typical excursion, so noise near
/// the centre makes no spurious swings) lies one half-swing; half-swings cut by the ends of the
/// series, or far from the typical duration (something else moved), are left out. Each whole
/// swing (two adjacent half-swings, swings not overlapping) gives one amplitude: that of the
/// least-squares sinusoid c + a·cos ωt + b·sin ωt over its samples, at the typical frequency,
/// which weighs every sample instead of the single noisiest one at the top, and whose own
/// constant c cancels an error in the centre.
pub fn swing_peaks(series: &[f64], dt: f64, centre: f64) -> Vec<(f64, f64)> {
    let dev: Vec<f64> = series.iter().map(|v| v - centre).collect();
    let mut sorted: Vec<f64> = dev.iter().map(|v| v.abs()).collect();
    sorted.sort_by(f64::total_cmp);
    let typical = sorted.get(sorted.len() * 9 / 10).copied().unwrap_or(0.0);
    let band = 0.1 * typical;
    if band.is_nan() || band <= 0.0 {
        return Vec::new();
    }
    // Indices where the signal has settled on one side after being on the other.
    let mut side = 0i8;
    let mut crossings = Vec::new();
    for (i, &v) in dev.iter().enumerate() {
        let s = if v > band {
            1
        } else if v < -band {
            -1
        } else {
            continue;
        };
        if s != side {
            if side != 0 {
                crossings.push(i);
            }
            side = s;
        }
    }
    let mut lengths: Vec<usize> = crossings.windows(2).map(|w| w[1] - w[0]).collect();
    lengths.sort_unstable();
    let Some(&median) = lengths.get(lengths.len() / 2) else {
        return Vec::new();
    };
    let typical_length =
        |n: usize| (n as f64) >= 0.6 * median as f64 && (n as f64) <= 1.4 * median as f64;
    let omega = std::f64::consts::PI / (median as f64 * dt);
    let mut out = Vec::new();
    let mut i = 0;
    while i + 2 < crossings.len() {
        let (a, m, b) = (crossings[i], crossings[i + 1], crossings[i + 2]);
        if !(typical_length(m - a) && typical_length(b - m)) {
            i += 1;
            continue;
        }
        if let Some(amp) = sinusoid_amplitude(&series[a..b], a, dt, omega) {
            out.push(((a + b - 1) as f64 * dt / 2.0, amp));
        }
        i += 2;
    }
    out
}

/// √(a² + b²) of the least-squares c + a·cos ωt + b·sin ωt through `samples` (the first at
/// frame `first`, `dt` apart).
fn sinusoid_amplitude(samples: &[f64], first: usize, dt: f64, omega: f64) -> Option<f64> {
    let (mut m, mut r) = ([0.0; 9], [0.0; 3]);
    for (k, &v) in samples.iter().enumerate() {
        let wt = omega * (first + k) as f64 * dt;
        let row = [1.0, wt.cos(), wt.sin()];
        for p in 0..3 {
            r[p] += row[p] * v;
            for q in 0..3 {
                m[p * 3 + q] += row[p] * row[q];
            }
        }
    }
    let c = crate::linalg::solve(&m, &r, 3)?;
    Some(c[1].hypot(c[2]))
}

/// ζ = −2·slope of ln(peak) against time, with its standard error; `None` with fewer than
/// `MIN_PEAKS` peaks.
pub fn decay_rate(peaks: &[(f64, f64)]) -> Option<(f64, f64)> {
    let pts: Vec<(f64, f64)> = peaks
        .iter()
        .filter(|p| p.1 > 0.0)
        .map(|&(t, a)| (t, a.ln()))
        .collect();
    if pts.len() < MIN_PEAKS {
        return None;
    }
    let (t, y): (Vec<f64>, Vec<f64>) = pts.iter().copied().unzip();
    let fit = AffineFit::of(&t, &y)?;
    let n = t.len() as f64;
    let mt = t.iter().sum::<f64>() / n;
    let sxx: f64 = t.iter().map(|v| (v - mt).powi(2)).sum();
    let sse: f64 = t
        .iter()
        .zip(&y)
        .map(|(a, b)| (b - fit.intercept - fit.slope * a).powi(2))
        .sum();
    let se = (sse / (n - 2.0) / sxx).sqrt();
    Some((-2.0 * fit.slope, 2.0 * se))
}

/// The peak-decay cross-check of `name` (learned value `learned`) on a recording's latent.
pub fn cross_check(
    name: &str,
    learned: f64,
    series: &[f64],
    dt: f64,
    centre: f64,
) -> Option<PeakDecay> {
    let peaks = swing_peaks(series, dt, centre);
    let (estimate, std_error) = decay_rate(&peaks)?;
    Some(PeakDecay {
        name: name.into(),
        estimate,
        std_error,
        learned,
        agrees: (learned - estimate).abs() <= 2.0 * std_error,
        peaks,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 0.8·e^(−ζt/2)·cos(3t) + 0.3 at 60 fps for 20 s, plus `noise` × a deterministic
    /// pseudo-random number in [−1, 1], and on about one sample in ten a spike of up to
    /// `spike` either way.
    fn swing(zeta: f64, noise: f64, spike: f64) -> Vec<f64> {
        let dt = 1.0 / 60.0;
        let mut state = 12345u64;
        let mut uniform = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        (0..1200)
            .map(|k| {
                let t = k as f64 * dt;
                let (u, v) = (uniform(), uniform());
                let s = 0.8 * (-zeta * t / 2.0).exp() * (3.0 * t).cos() + 0.3 + noise * u;
                if v.abs() > 0.9 {
                    s + spike * uniform()
                } else {
                    s
                }
            })
            .collect()
    }

    #[test]
    fn recovers_the_decay_of_a_noisy_damped_swing() {
        let (zeta, dt) = (0.05, 1.0 / 60.0);
        let series = swing(zeta, 0.002, 0.0);
        // The centre given is off by 0.05: each swing's own constant absorbs that.
        let peaks = swing_peaks(&series, dt, 0.35);
        assert!(peaks.len() >= 8, "{}", peaks.len());
        let (z, se) = decay_rate(&peaks).unwrap();
        assert!((z - zeta).abs() < 0.002 && se < 0.002, "{z} ± {se}");
        let c = cross_check("damping", z, &series, dt, 0.35).unwrap();
        assert!(c.agrees, "{c:?}");
        assert!(
            !cross_check("damping", 0.1, &series, dt, 0.35)
                .unwrap()
                .agrees
        );
        assert!(decay_rate(&peaks[..3]).is_none());
        // A glitch at the end (quick crossings) is not a swing.
        let mut glitched = series.clone();
        glitched.extend([0.9, -0.6, 0.9, -0.6, 0.9]);
        let g = swing_peaks(&glitched, dt, 0.35);
        assert!(
            g.len() <= peaks.len() + 1 && g.iter().all(|p| p.0 < 19.9),
            "{g:?}"
        );
    }

    #[test]
    fn spikes_at_the_tops_do_not_hide_a_light_damping() {
        // ζ = 0.015 (the amplitude falls by 14 % in 20 s) with spikes of up to 0.3 on one
        // sample in ten, as an encoder makes on a real recording: the largest sample of each
        // swing is then mostly a spike, whose size does not decay (that reading gives
        // 0.012 ± 0.008 here); the fitted sinusoid averages the spikes away.
        let (zeta, dt) = (0.015, 1.0 / 60.0);
        let series = swing(zeta, 0.01, 0.3);
        let (z, se) = decay_rate(&swing_peaks(&series, dt, 0.3)).unwrap();
        assert!((z - zeta).abs() < 2.0 * se && se < 0.002, "{z} ± {se}");
    }
}
