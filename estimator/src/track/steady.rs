//! A camera's shake taken off the frames the track reads: each frame's shift against the
//! frames' median picture by Lucas–Kanade from coarse to fine (robust to what moves by
//! Huber's weights), and the frame moved back by it (bilinear, the edge repeated). A hand-held
//! camera's shake moves every edge of a still picture, whose differences from the background
//! then outgrow the object's or the light's; steadied, the picture differs where the object
//! moves or the light changes.

use super::background::evenly;
use super::lucas_kanade::{refined, sample, Reference};
use super::pyramid::Level;
use crate::data::largest_shift;
use physvid_shared::video::SmallFrames;
use rayon::prelude::*;

/// Frames are moved only where at least half of them are shifted by this much (pixels of the
/// frames read): a hand-held camera shakes on most frames, where a still one is pulled on a
/// few by what moves (the jar's median shift is 0.05 px, a tossed ball's 0.39, the shaken
/// renders' 0.85–3.3 px).
const STILL: f64 = 0.5;

/// A shift changing by this much a frame (the median, pixels of the frames read) is a shake the
/// latent's frames are steadied against whatever the track was read on (`Steadied::step`):
/// slow drifts change by 0.04–0.15 px (the falling ball, the phone, the suite's clutter).
pub const JITTER: f64 = 0.3;

/// Whether the camera moved is read first on this many frames, evenly spread.
const PROBED: usize = 32;

/// Frames moved back by the camera's shake, and each frame's shift.
pub struct Steadied {
    pub frames: SmallFrames,
    /// Each frame's shift (pixels of the frames read: its point p + shift shows the median
    /// picture's p).
    pub shifts: Vec<(f64, f64)>,
}

impl Steadied {
    /// The largest shift (pixels of the frames read).
    pub fn largest(&self) -> f64 {
        largest_shift(&self.shifts)
    }

    /// The median change of the shift from one frame to the next (pixels of the frames read):
    /// a hand's shake moves the picture within a clip, a slow drift barely does.
    pub fn step(&self) -> f64 {
        let steps: Vec<(f64, f64)> = (self.shifts.windows(2))
            .map(|p| (p[1].0 - p[0].0, p[1].1 - p[0].1))
            .collect();
        if steps.is_empty() {
            0.0
        } else {
            median_size(&steps)
        }
    }
}

/// The shift against `reference` of each frame of `frames` whose index is in `which` (x, y
/// in pixels: the frame shows the reference's point p at p + shift), by Lucas–Kanade from
/// coarse to fine: on the pictures halved (`pyramid::LEVELS` sizes), the smallest from no shift,
/// each finer from the coarser's doubled.
fn shifts(frames: &SmallFrames, reference: &[u8], which: &[usize]) -> Vec<(f64, f64)> {
    let fixed = Level::pyramid(reference, frames.size);
    let fixed: Vec<Reference> = fixed
        .iter()
        .map(|r| Reference::new(&r.pixels, r.size))
        .collect();
    which
        .par_iter()
        .map(|&i| {
            let moving = Level::pyramid(frames.frame(i), frames.size);
            let mut shift = (0.0, 0.0);
            for (k, (f, r)) in moving.iter().zip(&fixed).enumerate().rev() {
                if k + 1 < moving.len() {
                    shift = (2.0 * shift.0, 2.0 * shift.1);
                }
                shift = refined(&f.pixels, r, shift).unwrap_or(shift);
            }
            shift
        })
        .collect()
}

/// The median of the shifts' sizes.
fn median_size(found: &[(f64, f64)]) -> f64 {
    let mut sizes: Vec<f64> = found.iter().map(|s| s.0.hypot(s.1)).collect();
    let mid = sizes.len() / 2;
    *sizes.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// `frame` moved back by `shift` (its point p + shift put at p), bilinear, the edge repeated.
fn moved(frame: &[u8], (w, h): (usize, usize), (sx, sy): (f64, f64)) -> Vec<u8> {
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let v = sample(frame, (w, h), x as f64 + sx, y as f64 + sy);
            v.round().clamp(0.0, 255.0) as u8
        })
        .collect()
}

/// At most this many frames, evenly spread, make the median picture the frames are steadied
/// against (as `background`'s).
const MEDIAN_FRAMES: usize = 255;

/// Each pixel's median over up to [`MEDIAN_FRAMES`] frames: the still picture a shaken camera
/// saw, blurred by the shake but not shifted by it.
fn median(frames: &SmallFrames) -> Vec<u8> {
    let picked = evenly(frames.len(), MEDIAN_FRAMES);
    let (w, h) = frames.size;
    (0..w * h)
        .into_par_iter()
        .map_init(Vec::new, |values: &mut Vec<u8>, p| {
            values.clear();
            values.extend(picked.iter().map(|&i| frames.frame(i)[p]));
            let mid = values.len() / 2;
            *values.select_nth_unstable(mid).1
        })
        .collect()
}

/// `frames` moved back by their shifts against their median picture, or `None` where half of
/// them are shifted by less than [`STILL`].
pub fn steadied(frames: &SmallFrames) -> Option<Steadied> {
    if frames.is_empty() {
        return None;
    }
    // Whether the camera moved, from a few frames spread over the recording first: a still
    // camera's recording is not measured frame by frame.
    let reference = median(frames);
    let n = frames.len();
    let probe = evenly(n, PROBED);
    let probed = shifts(frames, &reference, &probe);
    if median_size(&probed) < STILL {
        return None;
    }
    let rest: Vec<usize> = (0..n).filter(|i| probe.binary_search(i).is_err()).collect();
    let measured = shifts(frames, &reference, &rest);
    let mut found = vec![(0.0, 0.0); n];
    for (&i, s) in probe.iter().zip(probed).chain(rest.iter().zip(measured)) {
        found[i] = s;
    }
    if median_size(&found) < STILL {
        return None;
    }
    let size = frames.size;
    let pixels = (0..frames.len())
        .into_par_iter()
        .flat_map_iter(|i| moved(frames.frame(i), size, found[i]))
        .collect();
    Some(Steadied {
        frames: SmallFrames { pixels, size },
        shifts: found,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A textured wall (smooth enough to be moved between pixels), seen shifted by `shift`.
    fn wall((w, h): (usize, usize), (sx, sy): (f64, f64)) -> Vec<u8> {
        let mut out = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let (u, v) = (x as f64 - sx, y as f64 - sy);
                let value = 120.0
                    + 40.0 * (u * 0.31).sin() * (v * 0.17).cos()
                    + 30.0 * (u * 0.07 + v * 0.11).sin()
                    + 25.0 * ((u - 20.0).hypot(v - 14.0) * 0.45).cos();
                out.push(value.round() as u8);
            }
        }
        out
    }

    /// Frames of a wall, five still and six shaken by up to three pixels: each shift found
    /// within a tenth of a pixel, and the steadied frames differ from the still wall by less
    /// than a sixth of what the shaken ones did, away from the edges the shift brings in. With
    /// four of them shaken, fewer than half, they are left as they are.
    #[test]
    fn a_shaken_wall_is_found_and_steadied() {
        let size = (64, 48);
        let mut shaken = vec![(0.0, 0.0); 5];
        shaken.extend([
            (1.3, -0.6),
            (-2.4, 0.8),
            (0.6, 2.7),
            (-0.2, -1.9),
            (0.9, 0.7),
            (-0.8, -1.1),
        ]);
        let still = wall(size, (0.0, 0.0));
        let frames = SmallFrames {
            pixels: shaken.iter().flat_map(|&s| wall(size, s)).collect(),
            size,
        };
        let few = SmallFrames {
            pixels: frames.pixels[..9 * 64 * 48].to_vec(),
            size,
        };
        assert!(steadied(&few).is_none());
        let all: Vec<usize> = (0..frames.len()).collect();
        let found = shifts(&frames, &still, &all);
        for (f, s) in found.iter().zip(&shaken) {
            assert!(
                (f.0 - s.0).abs() < 0.1 && (f.1 - s.1).abs() < 0.1,
                "{f:?} for {s:?}"
            );
        }
        let steady = steadied(&frames).expect("a shaken camera");
        assert!(
            (steady.largest() - 2.76).abs() < 0.3,
            "{}",
            steady.largest()
        );
        assert!(steady.step() > JITTER, "{}", steady.step());
        let inner = |a: &[u8]| -> f64 {
            let mut sum = 0.0;
            for y in 4..size.1 - 4 {
                for x in 4..size.0 - 4 {
                    let p = y * size.0 + x;
                    sum += (f64::from(a[p]) - f64::from(still[p])).abs();
                }
            }
            sum
        };
        for i in 5..shaken.len() {
            let before = inner(frames.frame(i));
            let after = inner(steady.frames.frame(i));
            assert!(after < 0.15 * before, "frame {i}: {after} against {before}");
        }
    }

    /// A wall drifting by 0.1 px a frame is steadied, but it is no shake ([`JITTER`]).
    #[test]
    fn a_slow_drift_is_no_shake() {
        let (size, drift) = ((40, 30), |k: usize| (0.1 * k as f64 - 1.5, 0.0));
        let pixels = (0..30).flat_map(|k| wall(size, drift(k))).collect();
        let frames = SmallFrames { pixels, size };
        let steady = steadied(&frames).expect("a drifting camera");
        assert!(steady.step() < JITTER / 2.0, "{}", steady.step());
    }

    /// A still wall is left as it is.
    #[test]
    fn a_still_camera_is_left_alone() {
        let size = (40, 30);
        let still = wall(size, (0.0, 0.0));
        let frames = SmallFrames {
            pixels: [0.0, 0.2, -0.3]
                .iter()
                .flat_map(|&s| wall(size, (s, -s)))
                .collect(),
            size,
        };
        let found = shifts(&frames, &still, &[0, 1, 2]);
        assert!(steadied(&frames).is_none(), "{found:?}");
    }
}
