//! One object moving about a recording's frames (a pendulum's bob, a mass on a spring), found
//! by where each frame differs from the background (the median frame): its centroid's path
//! (`encoder::centroid`), how far it travels and whether it moves smoothly (one object, not
//! the locator jumping between two). Such a recording is read by the centroid encoder
//! (`config`): an MLP on pixels bends a swing's amplitude (it compresses the large early
//! swings more than the late small ones, and the damping comes out low: γ1 −9 to −30 % on
//! rendered pendulums and a disc, where the centroid is within 1 %).

use super::descent::MIN_TRAVEL;
use crate::encoder::centroid::{self, Located};
use crate::encoder::template::Template;
use serde::Serialize;
use tch::Tensor;

/// At most this many frames, evenly spaced, are located (consecutive frames in any recording
/// of up to 80 s at 30 fps, so that the path's smoothness is measured alike on short and long
/// ones: every other frame of a 25-s clip had made a faint bob's smooth path read 0.51, one
/// frame after another 0.40).
const MAX_FRAMES: usize = 2400;

/// The path is smooth when its second differences are at most this share of its first ones
/// (a locator jumping between two objects makes them about twice as large).
const SMOOTH: f64 = 0.5;

/// An object that moves about the frames.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MovingObject {
    /// How far its centroid travels, as a share of the larger frame side.
    pub travel: f64,
    /// Its path's second differences over its first ones (rms).
    pub roughness: f64,
    /// How it was located: on the frames themselves, where that path jumped between it and
    /// something else (a rod's ghost) on the frames blurred (`encoder::blur::SMOOTH_PX`), and
    /// where that jumped too by matching its picture (`encoder::template`).
    pub located: Located,
}

/// The object moving about frames `[F, H·W]` of `size` = (W, H), or `None` when nothing
/// travels [`MIN_TRAVEL`] of the frame smoothly (a brightness or a size that changes in
/// place, several things moving), located on the frames as they are or, where that path
/// jumps, on the frames blurred, or where that jumps too by a template of its picture.
pub fn find(frames: &[f32], size: (usize, usize)) -> Option<MovingObject> {
    find_located(
        frames,
        size,
        &[Located::Frames, Located::Blurred, Located::Matched],
    )
}

/// [`find`], the object located in turn as `ways` lists; the background is taken once for all.
fn find_located(frames: &[f32], size: (usize, usize), ways: &[Located]) -> Option<MovingObject> {
    let per = size.0 * size.1;
    let n = frames.len() / per.max(1);
    if n < 8 {
        return None;
    }
    let step = n.div_ceil(MAX_FRAMES);
    let sampled: Vec<f32> = frames
        .chunks(per)
        .step_by(step)
        .flatten()
        .copied()
        .collect();
    let frame = (1, size.1 as i64, size.0 as i64);
    tch::no_grad(|| {
        let x = Tensor::from_slice(&sampled).view([-1, per as i64]);
        let (d, polarity, window) = centroid::from_background(&x, frame);
        ways.iter().find_map(|&located| {
            let path = match located {
                Located::Frames => centroid::positions(&d, frame, polarity, window),
                Located::Blurred => centroid::positions_smoothed(&d, frame),
                Located::Matched => Template::new(&x, frame)?.positions(&x, frame),
            };
            judged(&path, located)
        })
    })
}

/// The object whose positions `path` [F, 2] trace, where they travel [`MIN_TRAVEL`] of the
/// frame smoothly.
fn judged(path: &Tensor, located: Located) -> Option<MovingObject> {
    let p: Vec<f32> = Vec::try_from(path.reshape([-1])).ok()?;
    let p: Vec<[f64; 2]> = p
        .chunks(2)
        .map(|c| [f64::from(c[0]), f64::from(c[1])])
        .collect();
    if p.iter().flatten().any(|v| !v.is_finite()) {
        return None;
    }
    // Positions are in units of half the larger side.
    let travel = (0..2)
        .map(|k| {
            let (lo, hi) = p
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), q| {
                    (lo.min(q[k]), hi.max(q[k]))
                });
            (hi - lo) / 2.0
        })
        .fold(0.0, f64::max);
    let rms = |d: &[[f64; 2]]| {
        (d.iter().map(|q| q[0] * q[0] + q[1] * q[1]).sum::<f64>() / d.len().max(1) as f64).sqrt()
    };
    let first: Vec<[f64; 2]> = p
        .windows(2)
        .map(|w| [w[1][0] - w[0][0], w[1][1] - w[0][1]])
        .collect();
    let second: Vec<[f64; 2]> = first
        .windows(2)
        .map(|w| [w[1][0] - w[0][0], w[1][1] - w[0][1]])
        .collect();
    let roughness = rms(&second) / rms(&first).max(1e-12);
    (travel >= MIN_TRAVEL && roughness <= SMOOTH).then_some(MovingObject {
        travel,
        roughness,
        located,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` frames of 40×30 with a bright 4×4 square at `at(t)` (x, y) over a dim background,
    /// its edges drawn at their fraction of a pixel.
    fn frames(n: usize, at: impl Fn(usize) -> (f64, f64)) -> Vec<f32> {
        let cover = |p: usize, from: f64| {
            ((p as f64 + 1.0).min(from + 4.0) - (p as f64).max(from)).max(0.0)
        };
        let mut f = vec![0.1f32; n * 1200];
        for t in 0..n {
            let (x, y) = at(t);
            for r in 0..30 {
                for c in 0..40 {
                    f[t * 1200 + r * 40 + c] += (0.8 * cover(r, y) * cover(c, x)) as f32;
                }
            }
        }
        f
    }

    #[test]
    fn a_swinging_square_is_an_object_and_a_blinking_one_is_not() {
        let swing = frames(200, |t| (18.0 + 12.0 * (t as f64 * 0.1).cos(), 13.0));
        let o = find(&swing, (40, 30)).expect("an object");
        assert!((o.travel - 0.6).abs() < 0.05, "{o:?}");
        // Two squares far apart, shown in turn: the locator jumps between them.
        let jumping = frames(200, |t| if t % 2 == 0 { (4.0, 4.0) } else { (32.0, 22.0) });
        assert_eq!(find(&jumping, (40, 30)), None);
        // A square that stays put.
        assert_eq!(find(&frames(200, |_| (18.0, 13.0)), (40, 30)), None);
    }

    /// `n` frames of 64×48: a dark rod a pixel wide hung from (32, 2), swung to `theta(t)`,
    /// with a faint bright bob at its end, over a static textured wall.
    fn rod_and_bob(n: usize, theta: impl Fn(usize) -> f64) -> Vec<f32> {
        let (w, h, length) = (64, 48, 36.0);
        let mut f = Vec::with_capacity(n * w * h);
        for t in 0..n {
            let (dx, dy) = (length * theta(t).sin(), length * theta(t).cos());
            for r in 0..h {
                for c in 0..w {
                    let (x, y) = (c as f64 + 0.5 - 32.0, r as f64 + 0.5 - 2.0);
                    let along = ((x * dx + y * dy) / (length * length)).clamp(0.0, 1.0);
                    let rod = (x - along * dx).hypot(y - along * dy) < 0.7;
                    let bob = (x - dx).hypot(y - dy) < 4.0;
                    let wall = 0.45 + 0.1 * (x / 7.0).sin() * (y / 5.0).cos();
                    f.push(if bob {
                        0.58
                    } else if rod {
                        0.15
                    } else {
                        wall as f32
                    });
                }
            }
        }
        f
    }

    #[test]
    fn a_faint_bob_under_a_dark_rod_is_found_on_the_frames_blurred() {
        let frames = rod_and_bob(240, |t| 0.35 * (t as f64 * 0.21).cos());
        // Located pixel by pixel, the rod's ghost in the median frame (where it hangs most of
        // the time) outweighs the faint bob, and the locator jumps between the two.
        assert_eq!(find_located(&frames, (64, 48), &[Located::Frames]), None);
        let o = find(&frames, (64, 48)).expect("an object");
        assert!(o.located == Located::Blurred && o.roughness < 0.3, "{o:?}");
        // The bob swings ±12.3 px across 64: a travel of 0.38 of the larger side.
        assert!((o.travel - 0.38).abs() < 0.05, "{o:?}");
    }

    /// `n` frames of 40×64: a dark mass 4 px wide and 10 tall whose top is at row `top(t)`,
    /// hung from a spring (a thin line of 12 coils from row 2 to the mass, stretching with it)
    /// and carrying a bright card 16 px wide at its foot, over a grey wall.
    fn mass_on_spring(n: usize, top: impl Fn(usize) -> f64) -> Vec<f32> {
        let (w, h) = (40, 64);
        let cover = |p: usize, from: f64, to: f64| {
            ((p as f64 + 1.0).min(to) - (p as f64).max(from)).max(0.0)
        };
        let mut f = Vec::with_capacity(n * w * h);
        for t in 0..n {
            let y = top(t);
            for r in 0..h {
                for c in 0..w {
                    let mass = cover(r, y, y + 10.0) * cover(c, 18.0, 22.0);
                    let card = cover(r, y + 10.0, y + 11.0) * cover(c, 12.0, 28.0);
                    let phase = (r as f64 + 0.5 - 2.0) / (y - 2.0) * 12.0;
                    let coil = if phase < 12.0 && r >= 2 && (c == 19 || c == 20) {
                        0.5 + 0.5 * (std::f64::consts::TAU * phase).cos()
                    } else {
                        0.0
                    };
                    f.push((0.5 - 0.4 * mass + 0.45 * card - 0.3 * coil) as f32);
                }
            }
        }
        f
    }

    #[test]
    fn a_mass_on_a_stretching_spring_is_found_by_matching_its_picture() {
        let frames = mass_on_spring(200, |t| 24.0 + 8.0 * (t as f64 * 0.3).sin());
        // Where the frame differs most, the coils, the card and the mass take turns.
        assert_eq!(
            find_located(&frames, (40, 64), &[Located::Frames, Located::Blurred]),
            None
        );
        let o = find(&frames, (40, 64)).expect("an object");
        assert_eq!(o.located, Located::Matched, "{o:?}");
        // The mass travels 16 px of 64: a quarter of the larger side.
        assert!((o.travel - 0.25).abs() < 0.02, "{o:?}");
    }
}
