//! A camera's shake taken off the latent route's frames (`CameraShake`): each decoded frame
//! moved back by the shift the object's track measured in the frame of its time
//! (`track::steady`), so that the encoder sees the still picture a hand-held camera shook.

use physvid_shared::video::{shifted, Crop, DecodedVideo};
use serde::{Deserialize, Serialize};

/// The camera's shift in each frame the track read, against the frames' median picture
/// (pixels of the displayed frame: the frame's point p + shift shows the still picture's p),
/// by the frame's time on the file's timeline (seconds, increasing).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CameraShake {
    pub file_s: Vec<f64>,
    pub shift: Vec<(f64, f64)>,
}

/// The largest of `shifts` (x, y) by its size.
pub fn largest_shift(shifts: &[(f64, f64)]) -> f64 {
    shifts.iter().map(|s| s.0.hypot(s.1)).fold(0.0, f64::max)
}

impl CameraShake {
    /// The largest shift (pixels of the displayed frame).
    pub fn largest(&self) -> f64 {
        largest_shift(&self.shift)
    }

    /// The shift of the frame read nearest to `t` (seconds of the file's timeline): a hand's
    /// shake changes from one frame to the next, so it is not interpolated.
    pub fn at(&self, t: f64) -> (f64, f64) {
        let k = self.file_s.partition_point(|&s| s < t);
        let nearest = match (k.checked_sub(1), self.file_s.get(k)) {
            (Some(j), Some(&after)) if t - self.file_s[j] <= after - t => j,
            (Some(j), None) => j,
            _ => k,
        };
        self.shift.get(nearest).copied().unwrap_or((0.0, 0.0))
    }

    /// `decoded`'s frames (its first at `first_s` on the file's timeline, each a `crop` of the
    /// displayed frame, which is the whole frame where `None`) each moved back by its shift,
    /// in their own pixels.
    pub fn steady(&self, decoded: &mut DecodedVideo, first_s: f64, crop: Option<Crop>) {
        let (w, h) = decoded.size;
        let whole = (decoded.info.width, decoded.info.height);
        let (cw, ch) = crop.map_or(whole, |c| (c.w, c.h));
        let per = (cw as f64 / w as f64, ch as f64 / h as f64);
        let rate = decoded.timeline_fps.unwrap_or(decoded.fps);
        let start = first_s + decoded.first_s;
        for (k, frame) in decoded.frames.chunks_mut(w * h).enumerate() {
            let (sx, sy) = self.at(start + k as f64 / rate);
            let moved = shifted(frame, (w, h), (-sx / per.0) as f32, (-sy / per.1) as f32);
            frame.copy_from_slice(&moved);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_frame_takes_the_shift_of_the_nearest_frame_read() {
        let shake = CameraShake {
            file_s: vec![0.0, 0.1, 0.2],
            shift: vec![(0.0, 0.0), (2.0, -1.0), (4.0, 0.0)],
        };
        assert_eq!(shake.largest(), 4.0);
        assert_eq!(shake.at(-1.0), (0.0, 0.0));
        assert_eq!(shake.at(0.06), (2.0, -1.0));
        assert_eq!(shake.at(0.14), (2.0, -1.0));
        assert_eq!(shake.at(0.16), (4.0, 0.0));
        assert_eq!(shake.at(9.0), (4.0, 0.0));
    }

    /// Two frames of 8×6, a crop of 32×12 of a 64×48 frame (4 and 2 displayed pixels a pixel):
    /// a bright dot at (3, 2) in the first; in the second the camera moved by (4, 2) displayed
    /// pixels, so the dot shows at (4, 3). Steadied, the second's dot is back at (3, 2).
    #[test]
    fn each_frame_is_moved_back_in_its_own_pixels() {
        let (w, h) = (8, 6);
        let mut frames = vec![0.0f32; 2 * w * h];
        frames[2 * w + 3] = 1.0;
        frames[w * h + 3 * w + 4] = 1.0;
        let info = physvid_shared::video::VideoInfo {
            width: 64,
            height: 48,
            container_fps: Some(10.0),
            capture_fps: None,
            rotation: 0,
            expected_frames: Some(2),
            fields: None,
            frame_times: vec![0.0, 0.1],
        };
        let mut decoded = DecodedVideo {
            info,
            fps: 10.0,
            frames,
            clip_starts: vec![0],
            hop: 1,
            size: (w, h),
            timeline_fps: None,
            clock_note: None,
            first_s: 0.0,
        };
        let shake = CameraShake {
            file_s: vec![1.0, 1.1],
            shift: vec![(0.0, 0.0), (4.0, 2.0)],
        };
        let crop = Crop {
            x: 8,
            y: 8,
            w: 32,
            h: 12,
        };
        shake.steady(&mut decoded, 1.0, Some(crop));
        let second = &decoded.frames[w * h..];
        assert!((second[2 * w + 3] - 1.0).abs() < 1e-6, "{second:?}");
        assert!((second.iter().sum::<f32>() - 1.0).abs() < 1e-6);
        assert!((decoded.frames[2 * w + 3] - 1.0).abs() < 1e-6);
    }
}
