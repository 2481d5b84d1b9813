//! The pixel values' scale: frames are read as they come (a `.npy` of raw sensor counts, of
//! values times 1e-12 or 1e30), so they are first brought to a range near one by a power of two
//! (exact in floating point: frames already in [0, 1] are left bit for bit as they were), and a
//! value far outside the frames' own spread (a hot pixel of 3e38 among values near one) is
//! refused, naming where it is, rather than let it set the scale of everything else.

/// Values farther than this many times the frames' spread from their median are refused.
pub const OUTLIER: f64 = 1e6;

/// Values sampled for the spread.
const SAMPLE: usize = 1 << 20;

/// Rescales `frames` (each `frame_len` values) by a power of two so that their spread (the
/// range between the 0.1 and 99.9 percentiles) lies in [0.5, 2); `Err((index, value, spread))`
/// names the first value beyond [`OUTLIER`] spreads from the median.
pub fn rescale(frames: &mut [f32]) -> Result<f64, (usize, f32, f64)> {
    let step = (frames.len() / SAMPLE).max(1);
    let mut sample: Vec<f32> = frames.iter().step_by(step).copied().collect();
    if sample.is_empty() {
        return Ok(1.0);
    }
    sample.sort_by(f32::total_cmp);
    let at = |q: f64| sample[((sample.len() - 1) as f64 * q).round() as usize] as f64;
    let (lo, hi, median) = (at(0.001), at(0.999), at(0.5));
    let spread = if hi > lo {
        hi - lo
    } else {
        // Nearly every value equal: the extremes give the spread.
        (sample[sample.len() - 1] as f64 - sample[0] as f64).max(f64::MIN_POSITIVE)
    };
    if let Some(i) = frames
        .iter()
        .position(|&v| (v as f64 - median).abs() > OUTLIER * spread)
    {
        return Err((i, frames[i], spread));
    }
    let factor = 2f64.powi(-(spread.log2().round() as i32));
    if factor != 1.0 {
        // In f64: the factor for values below f32's normal range (under 1.2e-38) is itself
        // beyond f32's largest, and a power of two times a float is exact in f64.
        frames
            .iter_mut()
            .for_each(|v| *v = (f64::from(*v) * factor) as f32);
    }
    Ok(factor)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_range_is_untouched_and_scaled_frames_come_back() {
        let base: Vec<f32> = (0..1000)
            .map(|i| (i as f32 * 0.37).sin() * 0.5 + 0.5)
            .collect();
        let mut same = base.clone();
        assert_eq!(rescale(&mut same), Ok(1.0));
        assert_eq!(same, base);
        for k in [-12, -3, 5, 12, 30] {
            let mut scaled: Vec<f32> = base.iter().map(|v| v * 10f32.powi(k)).collect();
            rescale(&mut scaled).unwrap();
            let ratio = scaled[7] / base[7];
            assert!((0.5..2.0).contains(&ratio), "{k}: {ratio}");
            assert!(scaled
                .iter()
                .zip(&base)
                .all(|(a, b)| (a - b * ratio).abs() <= 1e-6 * ratio));
        }
        // Below f32's normal range (frames of 1e-39): brought back near one, finite, to the
        // few bits such floats keep (training on them diverged: the factor was infinite).
        let mut tiny: Vec<f32> = base.iter().map(|v| v * 1e-39).collect();
        rescale(&mut tiny).unwrap();
        let ratio = tiny[7] / base[7];
        assert!((0.5..2.0).contains(&ratio), "{ratio}");
        assert!(tiny
            .iter()
            .zip(&base)
            .all(|(a, b)| a.is_finite() && (a - b * ratio).abs() <= 1e-4 * ratio));
    }

    #[test]
    fn a_hot_pixel_is_named() {
        let mut f: Vec<f32> = (0..1000).map(|i| (i % 7) as f32 / 7.0).collect();
        f[123] = 3e38;
        let (i, v, _) = rescale(&mut f).unwrap_err();
        assert_eq!((i, v), (123, 3e38));
    }
}
