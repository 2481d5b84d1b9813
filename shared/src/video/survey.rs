//! Framing by itself: a quick pass over a recording at low resolution (the long side at most
//! [`SURVEY_SIDE`] pixels) that finds where the picture moves, so the encoder sees the moving
//! object rather than a frame that is mostly wall. Each frame's mean is taken out first (a
//! flickering light or an auto-exposure moves every pixel alike, not one region), the temporal
//! standard deviation of every pixel is the motion map, and the region is the bounding box of
//! the connected part of the map with the most motion (a person walking by elsewhere is a part
//! of its own), widened by a margin. Where motion fills most of the frame, the whole frame is
//! kept.

use super::free::{departures, free_in, Departures, FreeSpan};
use super::region::{blur, components, Bounds};
use super::small::{small_frames, SURVEY_SIDE};
use super::timescale::Thumbnails;
use super::{Crop, VideoError, VideoInfo};
use std::path::Path;

/// A pixel of the map is moving when its motion is at least this fraction of the map's
/// strongest (after smoothing).
const MOVING: f32 = 0.2;

/// The range map's parts grow the region only where that makes it at least this much larger
/// (measured: a fall whose ends the variance map shows, 2.2× and more; the fringe of a swing's
/// arc on the rod-and-bob renders, 1.0–1.2×).
const ALONG_A_PATH: f64 = 1.5;

/// A region covering more of the frame than this is not worth a crop.
const WHOLE_FRAME: f64 = 0.6;

/// What the survey found.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Survey {
    /// The region where the picture moves, in pixels of the displayed frame; `None` when
    /// motion fills most of the frame (keep it whole) or nothing moves.
    pub crop: Option<Crop>,
    /// The region's share of the frame's area, and of all the motion.
    pub area_share: f64,
    pub motion_share: f64,
    /// Separate moving regions found (a second one: something else moves too).
    pub regions: usize,
    /// The motion map (width × height, row-major, 0–1) and its size, for a figure.
    #[serde(skip)]
    pub map: Vec<f32>,
    #[serde(skip)]
    pub map_size: (usize, usize),
    /// Frames surveyed.
    pub frames: usize,
    /// The motion's period in frames, where the picture's change repeats
    /// (`timescale::Thumbnails::period`), when asked for; `None` for a motion that does not
    /// come back.
    pub period_frames: Option<f64>,
    /// The free motion (`free`), in frames surveyed, where something beside the object (a
    /// hand) takes the picture at the start or the end: the map, the region and the period
    /// are measured on it alone.
    pub free: Option<FreeSpan>,
    /// Each surveyed frame's departure from the background (`free::Departures`), for the
    /// report's figure of the picture's change over time; `None` for fewer than 16 frames.
    #[serde(skip)]
    pub change: Option<Departures>,
    /// The time of the first surveyed frame on the file's timeline (`--start`, else 0).
    #[serde(skip)]
    pub first_s: f64,
}

/// Surveys `input` (trimmed to `start`..`end` seconds, as the decode will be) for where it
/// moves, and with `period` for the motion's period too (a second or so more on a long
/// recording: only the model's choice asks).
pub fn survey(
    input: &Path,
    info: &VideoInfo,
    (start, end): (Option<f64>, Option<f64>),
    period: bool,
) -> Result<Survey, VideoError> {
    let small = small_frames(input, info, (start, end), SURVEY_SIDE)?;
    let (w, h) = small.size;
    let frames = small.pixels;
    let change = departures(&frames, (w, h));
    let free = change.as_ref().and_then(free_in);
    let span = free.map_or(0..frames.len() / (w * h), |f| f.first..f.last + 1);
    let mut stats = MotionStats::new(w * h);
    let mut thumbnails = period.then(|| Thumbnails::new((w, h)));
    for frame in frames.chunks_exact(w * h).skip(span.start).take(span.len()) {
        stats.add(frame);
        if let Some(t) = thumbnails.as_mut() {
            t.add(frame);
        }
    }
    let found = stats.survey((w, h), (info.width, info.height));
    // The period where the picture moves most (in survey pixels).
    let region = found.crop.map(|c| {
        let s = w as f64 / info.width as f64;
        let at = |v: usize| (v as f64 * s).floor() as usize;
        (at(c.x), at(c.y), at(c.w).max(1), at(c.h).max(1))
    });
    Ok(Survey {
        period_frames: thumbnails.and_then(|t| t.period(region)),
        free,
        change,
        first_s: start.unwrap_or(0.0),
        ..found
    })
}

/// Running per-pixel mean, variance and range of frames with each frame's own mean taken out.
pub struct MotionStats {
    n: usize,
    mean: Vec<f64>,
    m2: Vec<f64>,
    lo: Vec<f32>,
    hi: Vec<f32>,
}

impl MotionStats {
    pub fn new(pixels: usize) -> MotionStats {
        MotionStats {
            n: 0,
            mean: vec![0.0; pixels],
            m2: vec![0.0; pixels],
            lo: vec![f32::INFINITY; pixels],
            hi: vec![f32::NEG_INFINITY; pixels],
        }
    }

    /// Adds a frame (grey bytes).
    pub fn add(&mut self, frame: &[u8]) {
        let level = frame.iter().map(|&v| v as f64).sum::<f64>() / frame.len().max(1) as f64;
        self.n += 1;
        let n = self.n as f64;
        for (i, &v) in frame.iter().enumerate() {
            let x = v as f64 - level;
            let d = x - self.mean[i];
            self.mean[i] += d / n;
            self.lo[i] = self.lo[i].min(x as f32);
            self.hi[i] = self.hi[i].max(x as f32);
            self.m2[i] += d * (x - self.mean[i]);
        }
    }

    /// `region` (the part `best` of the motion map's `labels`) grown along the path of what
    /// moves there. An object that crosses the frame once (a fall from rest: it rests at the
    /// ends and crosses in a few frames) varies each pixel of its way for a frame or two, so
    /// the variance map shows its ends and not the way between; how far each pixel ever departs
    /// from the rest of its frame shows the whole way. The parts of that range map (above the
    /// frame's median range, what noise alone spans) that touch the region join it where they
    /// reach well beyond it ([`ALONG_A_PATH`]; a swing's range
    /// adds only the fringe of its arc, which is left as it was); where the way then takes most
    /// of the frame, the whole frame is kept, as for any region that large.
    fn along_its_path(
        &self,
        region: Bounds,
        labels: &[Option<usize>],
        best: usize,
        (w, h): (usize, usize),
    ) -> Bounds {
        let range: Vec<f32> = self.hi.iter().zip(&self.lo).map(|(h, l)| h - l).collect();
        let range = blur(&range, w, h);
        // Above the frame's typical range (what noise alone spans over the recording).
        let mut sorted = range.clone();
        sorted.sort_by(f32::total_cmp);
        let usual = sorted[sorted.len() / 2];
        let top = sorted[sorted.len() - 1];
        let on: Vec<bool> = range
            .iter()
            .map(|&v| v - usual >= MOVING * (top - usual))
            .collect();
        let (parts, _) = components(&on, w, h);
        let mut touching: Vec<usize> = (0..w * h)
            .filter(|&i| labels[i] == Some(best))
            .filter_map(|i| parts[i])
            .collect();
        touching.sort_unstable();
        touching.dedup();
        let Some(path) = Bounds::of(w, w * h, |i| {
            parts[i].is_some_and(|p| touching.binary_search(&p).is_ok())
        }) else {
            return region;
        };
        let grown = region.union(path);
        if grown.share(w, h) >= ALONG_A_PATH * region.share(w, h) {
            grown
        } else {
            region
        }
    }

    /// The motion map of `size` (w, h) and the region for a frame of `full` (w, h).
    pub fn survey(&self, size: (usize, usize), full: (usize, usize)) -> Survey {
        let (w, h) = size;
        let std: Vec<f32> = self
            .m2
            .iter()
            .map(|m| (m / self.n.max(1) as f64).sqrt() as f32)
            .collect();
        let map = blur(&std, w, h);
        let top = map.iter().copied().fold(0.0f32, f32::max);
        let empty = Survey {
            crop: None,
            area_share: 1.0,
            motion_share: 1.0,
            regions: 0,
            map: map.iter().map(|v| v / top.max(1e-12)).collect(),
            map_size: size,
            frames: self.n,
            period_frames: None,
            free: None,
            change: None,
            first_s: 0.0,
        };
        if self.n < 3 || top <= 0.0 {
            return empty;
        }
        let moving: Vec<bool> = map.iter().map(|&v| v >= MOVING * top).collect();
        let (labels, count) = components(&moving, w, h);
        let total: f64 = map.iter().map(|&v| v as f64).sum();
        // The region with the most motion.
        let mut energy = vec![0.0f64; count];
        for (i, &l) in labels.iter().enumerate() {
            if let Some(l) = l {
                energy[l] += map[i] as f64;
            }
        }
        let Some(best) = (0..count).max_by(|&a, &b| energy[a].total_cmp(&energy[b])) else {
            return empty;
        };
        let region = Bounds::of(w, w * h, |i| labels[i] == Some(best)).expect("a region");
        let region = self.along_its_path(region, &labels, best, size);
        let framed = region.with_margin(w, h);
        let (Bounds { x0, y0, x1, y1 }, area_share) = (framed, framed.share(w, h));
        let (sx, sy) = (full.0 as f64 / w as f64, full.1 as f64 / h as f64);
        let crop = Crop {
            x: (x0 as f64 * sx).floor() as usize,
            y: (y0 as f64 * sy).floor() as usize,
            w: (((x1 + 1) as f64 * sx).ceil() as usize).min(full.0)
                - (x0 as f64 * sx).floor() as usize,
            h: (((y1 + 1) as f64 * sy).ceil() as usize).min(full.1)
                - (y0 as f64 * sy).floor() as usize,
        };
        Survey {
            crop: (area_share <= WHOLE_FRAME && crop.w >= 4 && crop.h >= 4).then_some(crop),
            area_share,
            motion_share: energy[best] / total.max(1e-12),
            regions: count,
            ..empty
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 64×36 frame with a bright square of 4 at (x, y).
    fn frame(x: usize, y: usize, flicker: u8) -> Vec<u8> {
        let (w, h) = (64, 36);
        let mut f = vec![40u8 + flicker; w * h];
        for dy in 0..4 {
            for dx in 0..4 {
                f[(y + dy) * w + x + dx] = 200;
            }
        }
        f
    }

    #[test]
    fn finds_the_moving_square_despite_a_flicker() {
        let mut s = MotionStats::new(64 * 36);
        for k in 0..40 {
            // Swinging between x = 40 and 52 at y = 20; the whole frame flickers by ±10.
            let x = 46 + ((k as f64 * 0.7).sin() * 6.0).round() as isize;
            s.add(&frame(x as usize, 20, if k % 2 == 0 { 0 } else { 20 }));
        }
        let r = s.survey((64, 36), (640, 360));
        let c = r.crop.expect("a region");
        // In full-frame pixels: the square spans x 400–560, y 200–240.
        assert!(c.x <= 400 && c.x + c.w >= 560, "{c:?}");
        assert!(c.y <= 200 && c.y + c.h >= 240, "{c:?}");
        assert!(r.area_share < 0.3, "{}", r.area_share);
        assert_eq!(r.regions, 1);
    }

    #[test]
    fn a_fall_that_rests_at_both_ends_is_framed_along_its_whole_way() {
        // 40 frames at rest at the top, across the frame in 10, 60 at rest at the bottom: the
        // variance shows the two ends, the range the way between.
        let mut s = MotionStats::new(64 * 36);
        let rows = (0..110).map(|k: usize| match k {
            0..40 => 1,
            40..50 => 1 + (k - 39) * (k - 39) * 30 / 100,
            _ => 31,
        });
        for y in rows {
            s.add(&frame(30, y, 0));
        }
        let c = s.survey((64, 36), (64, 36)).crop.expect("a region");
        assert!(c.y <= 1 && c.y + c.h >= 35, "{c:?}");
        assert!(c.x <= 30 && c.x + c.w >= 34 && c.w <= 20, "{c:?}");
    }

    #[test]
    fn a_still_recording_keeps_the_whole_frame() {
        let mut s = MotionStats::new(64 * 36);
        for _ in 0..10 {
            s.add(&frame(10, 10, 0));
        }
        assert!(s.survey((64, 36), (64, 36)).crop.is_none());
    }
}
