//! The classical damping measurement of appendix A.6, as a cross-check of the learned one:
//! find the swing peaks of a recording's encoded latent (the largest excursion from the
//! equilibrium between two crossings of it) and fit a line to ln(peak) against time. For
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
    /// Swing amplitudes used: (time in s, amplitude in latent units).
    pub peaks: Vec<(f64, f64)>,
}

/// Fewer peaks than this give no estimate.
const MIN_PEAKS: usize = 4;

/// The swing amplitudes of `series` (sampled every `dt` s) around `centre`. Between two
/// crossings of the centre (with hysteresis of a tenth of the typical excursion, so noise near
/// the centre makes no spurious swings) lies one half-swing; its peak is the largest excursion,
/// refined by a parabola through its neighbours. Half-swings cut by the ends of the series, or
/// far from the typical duration (something else moved), are left out, and each pair of
/// adjacent half-swings gives one amplitude, the mean of its two peaks at their mean time, which
/// cancels an error in the centre.
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
    // (index of the half-swing, time, peak) of the typical half-swings.
    let halves: Vec<(usize, f64, f64)> = crossings
        .windows(2)
        .enumerate()
        .filter(|(_, w)| typical_length(w[1] - w[0]))
        .filter_map(|(h, w)| {
            let k = (w[0]..w[1]).max_by(|&i, &j| dev[i].abs().total_cmp(&dev[j].abs()))?;
            let (mut t, mut peak) = (k as f64, dev[k].abs());
            if k > 0 && k + 1 < dev.len() {
                let (l, c, r) = (dev[k - 1].abs(), dev[k].abs(), dev[k + 1].abs());
                let curv = l - 2.0 * c + r;
                if curv < 0.0 {
                    let shift = 0.5 * (l - r) / curv;
                    if shift.abs() <= 1.0 {
                        t += shift;
                        peak = c - 0.25 * (l - r) * shift;
                    }
                }
            }
            Some((h, t * dt, peak))
        })
        .collect();
    halves
        .windows(2)
        .filter(|w| w[1].0 == w[0].0 + 1)
        .map(|w| ((w[0].1 + w[1].1) / 2.0, (w[0].2 + w[1].2) / 2.0))
        .collect()
}

/// ζ = −2·slope of ln(peak) against time, with its standard error; `None` with fewer than
/// [`MIN_PEAKS`] peaks.
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

    #[test]
    fn recovers_the_decay_of_a_noisy_damped_swing() {
        // x = 0.8·e^(−ζt/2)·cos(3t) + 0.3 at 60 fps for 20 s, ζ = 0.05, with a little noise.
        let (zeta, dt) = (0.05, 1.0 / 60.0);
        let series: Vec<f64> = (0..1200)
            .map(|k| {
                let t = k as f64 * dt;
                0.8 * (-zeta * t / 2.0).exp() * (3.0 * t).cos()
                    + 0.3
                    + 0.002 * ((k * 37 % 11) as f64 - 5.0) / 5.0
            })
            .collect();
        // The centre given is off by 0.05: pairs of opposite peaks cancel that.
        let peaks = swing_peaks(&series, dt, 0.35);
        assert!(peaks.len() >= 16, "{}", peaks.len());
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
        // A glitch at the end (quick crossings) is not a swing (it may close the last one).
        let mut glitched = series.clone();
        glitched.extend([0.9, -0.6, 0.9, -0.6, 0.9]);
        let g = swing_peaks(&glitched, dt, 0.35);
        assert!(
            g.len() <= peaks.len() + 1 && g.iter().all(|p| p.0 < 19.9),
            "{g:?}"
        );
    }
}
