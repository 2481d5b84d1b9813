//! An observable that is not a position, read the way a position is: where nothing that moves
//! guides the latent (an LED dimming as its capacitor drains, in place), the picture's brightness
//! over the region that changes, one number a frame, with the laws of a level fitted where they
//! hold (`fit::levels`). A camera's exposure scales the whole picture at once (a phone's
//! brightens it as the light dims): each frame is read against its own median first, the
//! region is the largest connected part of the pixels whose value then moves by at least the
//! picture's threshold for a change between their low and high frames, and the rest of the
//! picture is the reference the region's light is divided by.

use super::background::Background;
use super::reading::{Clock, Reading};
use super::{fit, Track, TrackRoute, LEAST_FRAMES};
use physvid_shared::video::region::components;
use physvid_shared::video::SmallFrames;

/// A pixel's low and high values are those at this share of its frames from either end (a
/// frame's passing glint or a dropped frame is not a change).
const TAIL: f64 = 0.05;

/// Each frame's median grey level over the recording's mean of them: the exposure's gain.
fn gains(frames: &SmallFrames) -> Vec<f64> {
    let medians: Vec<f64> = (0..frames.len())
        .map(|i| {
            let mut histogram = [0usize; 256];
            let frame = frames.frame(i);
            for v in frame {
                histogram[*v as usize] += 1;
            }
            let mut seen = 0;
            histogram
                .iter()
                .position(|&c| {
                    seen += c;
                    2 * seen >= frame.len()
                })
                .unwrap_or(0)
                .max(1) as f64
        })
        .collect();
    let usual = medians.iter().sum::<f64>() / medians.len().max(1) as f64;
    medians.iter().map(|m| m / usual).collect()
}

/// The largest connected part of the pixels whose value (each frame divided by its `gain`)
/// changes by at least `threshold` grey levels between their low and high frames ([`TAIL`]).
fn changing(frames: &SmallFrames, gain: &[f64], threshold: f64) -> Vec<bool> {
    let (w, h) = frames.size;
    let n = frames.len();
    let mut values = vec![0.0f64; n];
    let lo_at = ((n - 1) as f64 * TAIL).round() as usize;
    let hi_at = ((n - 1) as f64 * (1.0 - TAIL)).round() as usize;
    let on: Vec<bool> = (0..w * h)
        .map(|p| {
            for (i, v) in values.iter_mut().enumerate() {
                *v = f64::from(frames.frame(i)[p]) / gain[i];
            }
            let lo = *values.select_nth_unstable_by(lo_at, f64::total_cmp).1;
            let hi = *values.select_nth_unstable_by(hi_at, f64::total_cmp).1;
            hi - lo >= threshold
        })
        .collect();
    let (labels, count) = components(&on, w, h);
    let mut sizes = vec![0usize; count];
    for l in labels.iter().flatten() {
        sizes[*l] += 1;
    }
    let largest = (0..count).max_by_key(|&c| (sizes[c], std::cmp::Reverse(c)));
    labels
        .iter()
        .map(|l| l.is_some() && *l == largest)
        .collect()
}

/// The brightness of what changes in `frames` (`bg`'s threshold), divided by the exposure's
/// gain (the rest of the picture's mean against its mean over the recording), as a track at
/// the region's centroid with each law of a level where it holds; `None` where nothing changes
/// or everything does (no reference is left), or there are too few frames.
pub(super) fn brightness(
    frames: &SmallFrames,
    clock: &Clock,
    bg: &Background,
) -> Option<TrackRoute> {
    let n = frames.len();
    if n < LEAST_FRAMES {
        return None;
    }
    let (w, _) = frames.size;
    let region = changing(frames, &gains(frames), bg.threshold);
    let inside = region.iter().filter(|r| **r).count();
    if inside == 0 || inside == region.len() {
        return None;
    }
    let (mut cx, mut cy) = (0.0, 0.0);
    let (mut lo, mut hi) = ((f64::INFINITY, f64::INFINITY), (0.0f64, 0.0f64));
    for (p, _) in region.iter().enumerate().filter(|(_, r)| **r) {
        let (x, y) = ((p % w) as f64, (p / w) as f64);
        cx += x;
        cy += y;
        lo = (lo.0.min(x), lo.1.min(y));
        hi = (hi.0.max(x + 1.0), hi.1.max(y + 1.0));
    }
    let (cx, cy) = (cx / inside as f64, cy / inside as f64);
    let outside = region.len() - inside;
    let (mut lit, mut rest) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in 0..n {
        let (mut a, mut b) = (0u64, 0u64);
        for (v, r) in frames.frame(i).iter().zip(&region) {
            if *r {
                a += u64::from(*v);
            } else {
                b += u64::from(*v);
            }
        }
        lit.push(a as f64 / inside as f64);
        rest.push(b as f64 / outside as f64);
    }
    let usual = rest.iter().sum::<f64>() / n as f64;
    let u: Vec<f64> = lit
        .iter()
        .zip(&rest)
        .map(|(l, r)| l * usual / r.max(1.0))
        .collect();
    let (sx, sy) = clock.scale;
    let at = ((cx + 0.5) * sx, (cy + 0.5) * sy);
    let t = clock.t.to_vec();
    let fitted = fit::levels(&t, u, at);
    let track = Track {
        x: vec![at.0; n],
        y: vec![at.1; n],
        quality: vec![1.0; n],
        file_s: clock.file.to_vec(),
        along: fitted.along,
        axis: fitted.axis,
        noise: fitted.noise,
        size: (inside as f64).sqrt() * sx,
        picture: clock.picture,
        frames: n,
        threshold: bg.threshold,
        on_plane: Vec::new(),
        region: Some((lo.0 * sx, lo.1 * sy, hi.0 * sx, hi.1 * sy)),
        steadied: None,
        reading: Reading::Brightness,
        t,
    };
    Some(TrackRoute::read(track, fitted.laws, fitted.chosen))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::background;
    use crate::track::laws::TrackLaw;

    /// 48×32 frames at 30 a second for 6 s: a glow at (30, 12) whose brightness decays at
    /// `rate` from 1 s, on a textured wall whose exposure jitters by a grey level.
    fn dimming(rate: f64) -> (SmallFrames, Vec<f64>) {
        let (w, h, n) = (48usize, 32usize, 180usize);
        let t: Vec<f64> = (0..n).map(|k| k as f64 / 30.0).collect();
        let mut pixels = Vec::with_capacity(w * h * n);
        for (k, &s) in t.iter().enumerate() {
            let b = if s < 1.0 {
                1.0
            } else {
                (-rate * (s - 1.0)).exp()
            };
            let exposure = ((k * 7919) % 3) as f64 - 1.0;
            for y in 0..h {
                for x in 0..w {
                    let wall = 60.0 + ((x * 31 + y * 17) % 11) as f64;
                    let r2 = (x as f64 - 30.0).powi(2) + (y as f64 - 12.0).powi(2);
                    let glow = 150.0 * b * (-r2 / 18.0).exp();
                    pixels.push((wall + glow + exposure).round().clamp(0.0, 255.0) as u8);
                }
            }
        }
        (
            SmallFrames {
                pixels,
                size: (w, h),
            },
            t,
        )
    }

    #[test]
    fn a_dimming_glow_is_read_as_its_brightness_and_its_decay_found() {
        let (frames, t) = dimming(0.5);
        let clock = Clock::shown(&t, (48, 32), 10.0);
        let bg = background::background(&frames);
        let route = brightness(&frames, &clock, &bg).expect("a reading");
        assert_eq!(route.track.reading, Reading::Brightness);
        // At the glow's centre (pixel centres at half pixels).
        assert!(
            (route.track.x[0] - 30.5).abs() < 1.0,
            "{}",
            route.track.x[0]
        );
        assert!(
            (route.track.y[0] - 12.5).abs() < 1.0,
            "{}",
            route.track.y[0]
        );
        // Its region about it, within the picture.
        let (x0, y0, x1, y1) = route.track.region.unwrap();
        assert!(x0 < 30.0 && 31.0 < x1 && y0 < 12.0 && 13.0 < y1 && x1 <= 48.0 && y1 <= 32.0);
        assert_eq!(route.chosen, Some(TrackLaw::Decay));
        let span = route.chosen_span().unwrap();
        let g = span.values.iter().find(|v| v.name == "gamma").unwrap();
        assert!((g.value - 0.5).abs() < 0.01, "{g:?}");
        // The light held steady before 1 s is not the decay.
        assert!(span.first_s > 0.9, "{}", span.first_s);
    }

    #[test]
    fn a_picture_where_nothing_changes_has_no_brightness_to_read() {
        let (mut frames, t) = dimming(0.5);
        let first = frames.frame(0).to_vec();
        let m = first.len();
        for k in 0..frames.len() {
            frames.pixels[k * m..(k + 1) * m].copy_from_slice(&first);
        }
        let clock = Clock::shown(&t, (48, 32), 10.0);
        let bg = background::background(&frames);
        assert!(brightness(&frames, &clock, &bg).is_none());
    }
}
