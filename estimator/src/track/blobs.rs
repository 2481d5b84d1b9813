//! What differs from the background (`background`) in each frame: the connected blobs of the
//! pixels that differ from it by well over the noise, in the object's sense, each with its
//! centroid, its area and its long axis.

use super::background::Background;
use physvid_shared::video::region::components;
use physvid_shared::video::SmallFrames;

/// Blobs smaller than this many pixels are noise.
const LEAST_AREA: usize = 3;

/// One connected region that differs from the background, in the frame's pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Blob {
    pub area: f64,
    /// The centroid weighted by the difference.
    pub x: f64,
    pub y: f64,
    /// Its long axis (the principal direction of its difference-weighted second moments),
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
/// still turns with it).
pub fn blobs(frames: &SmallFrames, k: usize, bg: &Background) -> Vec<Blob> {
    let (w, h) = frames.size;
    let level = bg.level[k] as f64;
    let diff: Vec<f64> = frames
        .frame(k)
        .iter()
        .zip(&bg.median)
        .map(|(a, b)| (bg.polarity * (*a as f64 - level - *b as f64)).max(0.0))
        .collect();
    let beyond: Vec<bool> = diff.iter().map(|&d| d > bg.threshold).collect();
    let on = dilate(&erode(&beyond, w, h), w, h);
    let (labels, count) = components(&on, w, h);
    let (reached, reach_count) = components(&beyond, w, h);
    // Each blob's pixels and moments, and those of the region it lies in before the opening
    // (the opening only takes pixels away, so a blob lies in one).
    let mut blob = vec![(0usize, Moments::default()); count];
    let mut region = vec![(0usize, Moments::default()); reach_count];
    let mut within = vec![0; count];
    for i in 0..w * h {
        let (x, y, d) = ((i % w) as f64, (i / w) as f64, diff[i]);
        if let Some(r) = reached[i] {
            region[r].0 += 1;
            region[r].1.add(x, y, d);
            if let Some(l) = labels[i] {
                blob[l].0 += 1;
                blob[l].1.add(x, y, d);
                within[l] = r;
            }
        }
    }
    blob.into_iter()
        .zip(within)
        .filter(|(b, _)| b.0 >= LEAST_AREA && b.1.weight > 0.0)
        .map(|((area, m), r)| {
            let (axis, elongation) = region[r].1.axis();
            Blob {
                area: area as f64,
                region_area: region[r].0 as f64,
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
