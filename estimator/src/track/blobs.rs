//! What differs from the background (`background`) in each frame: the connected blobs of the
//! pixels that differ from it by well over the noise, in the object's sense, each with its
//! centroid, its area and its long axis.

use super::background::Background;
use physvid_shared::video::region::components;
use physvid_shared::video::SmallFrames;

/// Blobs smaller than this many pixels are noise.
const LEAST_AREA: usize = 3;

/// A region's ink is the level, in the object's sense, that its most-different twentieth of
/// pixels reach: the object's own where it covers whole pixels (a disc's inside, a rod's
/// middle), not one pixel's noise.
const INK: f64 = 0.95;

/// One connected region that differs from the background, in the frame's pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Blob {
    pub area: f64,
    /// The centroid weighted by the difference.
    pub x: f64,
    pub y: f64,
    /// Its long axis (the principal direction of the second moments of the region it lies in
    /// before the opening, each pixel weighted by how much of it the object covers: `blobs`),
    /// radians from the picture's x towards its y, in (−π/2, π/2]…
    pub axis: f64,
    /// …and how much longer it is along that axis than across it: the ratio of the second
    /// moments along and across (1 for a disc or a square; (L/W)² for a thin bar).
    pub elongation: f64,
    /// The pixels of the region it lies in before the opening (its rod or string with it),
    /// whose axis is `axis`: whole where the opening broke a thin rod into pieces.
    pub region_area: f64,
}

#[cfg(test)]
impl Blob {
    /// A round blob of `area` pixels centred at (`x`, `y`).
    pub fn round(area: f64, x: f64, y: f64) -> Blob {
        Blob {
            area,
            x,
            y,
            axis: 0.0,
            elongation: 1.0,
            region_area: area,
        }
    }
}

/// The blobs of frame `k` against `bg`: pixels beyond the threshold in the object's sense (the
/// frame taken at the common level), opened by a 3×3 cross (a speck or a one-pixel line goes),
/// 8-connected, at least [`LEAST_AREA`] pixels; each blob's long axis that of the pixels beyond
/// the threshold connected to it before the opening (a thin rod or string the opening took
/// still turns with it), each weighted by how much of it the object covers: its difference
/// over the wall's own from the region's ink ([`INK`]). Weighted by the difference alone, a
/// textured wall weighs the object's pixels by the wall behind them (±6 levels on a contrast
/// of 145 turned a swing's rod by 1.7′ rms, 0.3′ so).
pub fn blobs(frames: &SmallFrames, k: usize, bg: &Background) -> Vec<Blob> {
    let (w, h) = frames.size;
    let level = bg.level[k] as f64;
    // Each pixel in the object's sense, and the wall's.
    let frame = frames.frame(k);
    let seen = |i: usize| bg.polarity * (frame[i] as f64 - level);
    let wall = |i: usize| bg.polarity * bg.median[i] as f64;
    let diff: Vec<f64> = (0..w * h).map(|i| (seen(i) - wall(i)).max(0.0)).collect();
    let beyond: Vec<bool> = diff.iter().map(|&d| d > bg.threshold).collect();
    let on = dilate(&erode(&beyond, w, h), w, h);
    let (labels, count) = components(&on, w, h);
    let (reached, reach_count) = components(&beyond, w, h);
    // Each blob's pixels and moments, and the region it lies in before the opening (the
    // opening only takes pixels away, so a blob lies in one).
    let mut blob = vec![(0usize, Moments::default()); count];
    let mut within = vec![0; count];
    let mut held = vec![false; reach_count];
    for i in 0..w * h {
        if let (Some(r), Some(l)) = (reached[i], labels[i]) {
            blob[l].0 += 1;
            blob[l].1.add((i % w) as f64, (i / w) as f64, diff[i]);
            within[l] = r;
            held[r] = true;
        }
    }
    // The regions that hold a blob: their pixels' levels, their ink, their cover's moments.
    let mut inks: Vec<Vec<f64>> = vec![Vec::new(); reach_count];
    for (i, r) in reached.iter().enumerate() {
        if let Some(r) = r.filter(|&r| held[r]) {
            inks[r].push(seen(i));
        }
    }
    let ink: Vec<f64> = inks
        .iter_mut()
        .map(|v| match v.len() {
            0 => 0.0,
            n => {
                let at = ((n - 1) as f64 * INK).round() as usize;
                *v.select_nth_unstable_by(at, f64::total_cmp).1
            }
        })
        .collect();
    let mut region = vec![Moments::default(); reach_count];
    for (i, r) in reached.iter().enumerate() {
        if let Some(r) = r.filter(|&r| held[r]) {
            let cover = diff[i] / (ink[r] - wall(i)).max(bg.threshold);
            region[r].add((i % w) as f64, (i / w) as f64, cover);
        }
    }
    blob.into_iter()
        .zip(within)
        .filter(|(b, _)| b.0 >= LEAST_AREA && b.1.weight > 0.0)
        .map(|((area, m), r)| {
            let (axis, elongation) = region[r].axis();
            Blob {
                area: area as f64,
                region_area: inks[r].len() as f64,
                x: m.sums[0] / m.weight,
                y: m.sums[1] / m.weight,
                axis,
                elongation,
            }
        })
        .collect()
}

/// A region's difference-weighted sums: the weight, and of x, y, x², y², xy.
#[derive(Debug, Clone, Copy, Default)]
struct Moments {
    weight: f64,
    sums: [f64; 5],
}

impl Moments {
    fn add(&mut self, x: f64, y: f64, d: f64) {
        self.weight += d;
        for (m, v) in self.sums.iter_mut().zip([x, y, x * x, y * y, x * y]) {
            *m += d * v;
        }
    }

    /// The long axis (radians from x towards y) and the ratio of the second moments along and
    /// across it (the central moments' eigenvalues).
    fn axis(&self) -> (f64, f64) {
        let m = |j: usize| self.sums[j] / self.weight.max(f64::MIN_POSITIVE);
        let (x, y) = (m(0), m(1));
        let (xx, yy, xy) = (m(2) - x * x, m(3) - y * y, m(4) - x * y);
        let (mean, half) = ((xx + yy) / 2.0, ((xx - yy) / 2.0).hypot(xy));
        (
            0.5 * (2.0 * xy).atan2(xx - yy),
            (mean + half) / (mean - half).max(1e-9),
        )
    }
}

/// The 3×3 cross's erosion (a pixel stays on where it and its four neighbours are on).
fn erode(on: &[bool], w: usize, h: usize) -> Vec<bool> {
    cross(on, w, h, true)
}

/// The 3×3 cross's dilation (a pixel is on where it or one of its four neighbours is).
fn dilate(on: &[bool], w: usize, h: usize) -> Vec<bool> {
    cross(on, w, h, false)
}

fn cross(on: &[bool], w: usize, h: usize, all: bool) -> Vec<bool> {
    (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let neighbours = [
                Some(i),
                (x > 0).then(|| i - 1),
                (x + 1 < w).then(|| i + 1),
                (y > 0).then(|| i - w),
                (y + 1 < h).then(|| i + w),
            ];
            let mut cells = neighbours.iter().flatten().map(|&j| on[j]);
            if all {
                cells.all(|b| b)
            } else {
                cells.any(|b| b)
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::background::background;

    /// Frames of a grey wall with a dark 4×4 square at `(x, y)` (its top-left corner).
    fn square_at(places: &[(usize, usize)], (w, h): (usize, usize)) -> SmallFrames {
        let mut pixels = Vec::new();
        for &(x, y) in places {
            let mut f = vec![200u8; w * h];
            for r in y..y + 4 {
                for c in x..x + 4 {
                    f[r * w + c] = 40;
                }
            }
            pixels.extend(f);
        }
        SmallFrames {
            pixels,
            size: (w, h),
        }
    }

    #[test]
    fn a_moving_square_is_one_blob_at_its_centre() {
        let places: Vec<(usize, usize)> = (0..9).map(|k| (2 + 3 * k, 5)).collect();
        let frames = square_at(&places, (40, 16));
        let bg = background(&frames);
        assert_eq!(bg.median[0], 200);
        for (k, &(x, y)) in places.iter().enumerate() {
            let b = blobs(&frames, k, &bg);
            assert_eq!(b.len(), 1, "frame {k}: {b:?}");
            assert!((b[0].x - (x as f64 + 1.5)).abs() < 1e-9);
            assert!((b[0].y - (y as f64 + 1.5)).abs() < 1e-9);
            // The opening by a cross rounds off the square's four corners.
            assert_eq!(b[0].area, 12.0);
            assert!((b[0].elongation - 1.0).abs() < 1e-9, "{b:?}");
        }
    }

    #[test]
    fn a_picture_brightening_and_dimming_as_a_whole_keeps_one_blob() {
        // A camera's exposure moving the wall 12–30 grey levels from frame to frame (more than
        // the threshold of 10): the frame's level is taken off before it is compared.
        let places: Vec<(usize, usize)> = (0..9).map(|k| (2 + 3 * k, 5)).collect();
        let mut frames = square_at(&places, (40, 16));
        let pixels = 40 * 16;
        for k in 0..places.len() {
            let shift = [0i16, 30, -12, 18, -25, 0, 12, -30, 20][k];
            for v in &mut frames.pixels[k * pixels..(k + 1) * pixels] {
                *v = (*v as i16 + shift).clamp(0, 255) as u8;
            }
        }
        let bg = background(&frames);
        assert_eq!(bg.level[1] - bg.level[0], 30);
        for (k, &(x, _)) in places.iter().enumerate() {
            let b = blobs(&frames, k, &bg);
            assert_eq!(b.len(), 1, "frame {k}: {b:?}");
            assert!((b[0].x - (x as f64 + 1.5)).abs() < 1e-9, "frame {k}: {b:?}");
        }
    }

    #[test]
    fn a_still_picture_has_no_blobs() {
        let frames = square_at(&[(3, 3); 5], (20, 12));
        let bg = background(&frames);
        assert!(blobs(&frames, 2, &bg).is_empty());
    }

    /// A rod 1.5 px wide and 70 long (its ink 0.7 of the bob's) with a bob 6 px in radius at
    /// its end, hanging from (50, 8) at five tilts before a wall textured by ±30 grey levels:
    /// its region's axis is its tilt to a milliradian. Weighted by the difference from the wall
    /// alone, the texture under the bob turns it by milliradians.
    #[test]
    fn a_rod_s_axis_before_a_textured_wall_is_its_tilt() {
        let (w, h) = (100usize, 90usize);
        let wall = |x: f64, y: f64| 150.0 + 30.0 * (x / 3.0).sin() * (y / 4.0).sin();
        let pivot = (50.0, 8.0);
        let tilts = [-0.4, -0.2, 0.1, 0.3, 0.45f64];
        let mut pixels = Vec::new();
        for tilt in tilts {
            let (s, c) = tilt.sin_cos();
            let bob = (pivot.0 + 70.0 * s, pivot.1 + 70.0 * c);
            pixels.extend((0..w * h).map(|i| {
                let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
                let disc = (6.5 - (x - bob.0).hypot(y - bob.1)).clamp(0.0, 1.0);
                let u = ((x - pivot.0) * s + (y - pivot.1) * c).clamp(0.0, 70.0);
                let off = (x - pivot.0 - u * s).hypot(y - pivot.1 - u * c);
                let ink = disc.max(0.7 * (1.25 - off).clamp(0.0, 1.0));
                (wall(x, y) * (1.0 - ink) + 30.0 * ink).round() as u8
            }));
        }
        let frames = SmallFrames {
            pixels,
            size: (w, h),
        };
        let bg = Background {
            median: (0..w * h)
                .map(|i| wall((i % w) as f64 + 0.5, (i / w) as f64 + 0.5).round() as u8)
                .collect(),
            level: vec![0; tilts.len()],
            polarity: -1.0,
            threshold: 10.0,
            noise: 1.0,
        };
        for (k, tilt) in tilts.iter().enumerate() {
            let b = blobs(&frames, k, &bg);
            let rod = b.iter().max_by(|a, b| a.area.total_cmp(&b.area)).unwrap();
            // The axis from the picture's x, turned to point down: `tilt` from the vertical.
            let (dx, dy) = (rod.axis.cos(), rod.axis.sin());
            let from_vertical = (dx * dy.signum()).atan2(dy.abs());
            assert!(
                (from_vertical - tilt).abs() < 1e-3,
                "tilt {tilt}: axis {from_vertical}"
            );
        }
    }

    /// A bar 4 px wide and 20 long, tilted 30° down from the picture's x, moving across a
    /// grey wall: its blob's axis is its tilt, and it is far longer than wide.
    #[test]
    fn a_bar_s_blob_lies_along_its_tilt() {
        let (w, h) = (60usize, 40usize);
        let tilt = 30f64.to_radians();
        let mut pixels = Vec::new();
        for k in 0..6 {
            let (cx, cy) = (15.0 + 6.0 * k as f64, 20.0);
            pixels.extend((0..w * h).map(|i| {
                let (x, y) = ((i % w) as f64 - cx, (i / w) as f64 - cy);
                let along = x * tilt.cos() + y * tilt.sin();
                let across = -x * tilt.sin() + y * tilt.cos();
                if along.abs() <= 10.0 && across.abs() <= 2.0 {
                    30
                } else {
                    200
                }
            }));
        }
        let frames = SmallFrames {
            pixels,
            size: (w, h),
        };
        let bg = background(&frames);
        let b = blobs(&frames, 2, &bg);
        assert_eq!(b.len(), 1, "{b:?}");
        assert!((b[0].axis - tilt).abs() < 0.03, "{b:?}");
        assert!(b[0].elongation > 10.0, "{b:?}");
    }
}
