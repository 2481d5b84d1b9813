//! The object's own track, the second route to an answer: a recording decoded at
//! [`TRACK_SIDE`] pixels, what differs from its median background followed from frame to frame
//! (`blobs`, `link`; in its grey, else in its colour's distance from grey), the longest-lived
//! thing kept, its position along its motion's own axis, and each law of `laws` fitted where
//! it holds (`segment`); where nothing guides the latent, the same read again on frames
//! steadied against a camera's shake (`steady`), kept where it guides; and where nothing that
//! moves guides, the brightness of what changes in place (`light`), kept where its decay guides
//! or nothing that moves has a law. It reads no model and trains nothing: seconds on a
//! recording, and an answer to set beside the latent's.

mod angles;
pub mod background;
pub mod blobs;
mod choose;
mod fit;
mod frame;
mod guiding;
pub mod laws;
mod light;
pub mod link;
mod lucas_kanade;
pub(crate) mod metres;
mod object;
mod patch;
mod plane;
mod pyramid;
mod read_at;
mod reading;
mod release;
mod rod;
mod route;
pub mod segment;
mod steady;
mod tank;
pub mod template;
mod uniform;

pub use choose::ALIKE;
pub use guiding::{rate_of, GUIDING_ERROR, GUIDING_PERIODS, RATE_NAMES};
/// A route with one law for other modules' tests.
#[cfg(test)]
pub(crate) use route::tests::route as test_route;
pub use route::{LawSpan, TrackRoute};

use crate::data::CameraShake;
use physvid_shared::video::{small_chroma, small_frames, SmallFrames, VideoError, VideoInfo};
pub use reading::Reading;
use reading::{readings, times, Clock};
use serde::Serialize;
use std::path::Path;

/// The long side of the frames the track is read on (pixels): the video layer's, which decodes
/// them beside its look at the recording's fields.
pub use physvid_shared::video::TRACK_SIDE;

/// A tracklet must live at least this many frames to be followed.
const LEAST_FRAMES: usize = 12;

/// The fastest object crosses this many of the frame's long sides in a second (a ball dropped
/// 2.3 m past a 2.5-m picture: about 3), so a frame's step is its share at the frames' rate.
const FASTEST: f64 = 4.0;

/// The track: one position a frame where the object was seen (pixels of the displayed frame,
/// times in seconds of real time from the first frame read), and its quality (its blob's size
/// (its picture's correlation with the reference patch, `template`, or its blob's size against
/// its usual size: a hand over it, a blur or a turn lowers either).
#[derive(Debug, Clone, Serialize)]
pub struct Track {
    pub t: Vec<f64>,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub quality: Vec<f64>,
    /// Each sample's time on the file's own timeline (as a player shows it; `--start` reads
    /// these), which differs from `t` for a slow-motion capture.
    pub file_s: Vec<f64>,
    /// The position along the motion's own axis (the principal direction of the path), pixels
    /// from its mean (the plane's pixels where one is given: `on_plane`).
    pub along: Vec<f64>,
    /// How the positions were read from the thing followed.
    pub reading: Reading,
    /// The axis (a unit vector in the picture, y down).
    pub axis: (f64, f64),
    /// The track's noise along the axis (pixels, `segment::noise`).
    pub noise: f64,
    /// The object's usual size: the side of a square of its blob's usual area (pixels of the
    /// displayed frame; the part of it that differs from the background in the object's sense).
    pub size: f64,
    /// The displayed frame's width and height (pixels).
    pub picture: (usize, usize),
    /// Frames read, and the picture's threshold for a change (grey levels).
    pub frames: usize,
    pub threshold: f64,
    /// Each position on the plane of the motion (metres from the rectangle's first corner)
    /// where one is given (`--plane`); `along`, `axis` and `noise` are then the plane's, in
    /// its pixels (`Plane::per_metre`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub on_plane: Vec<(f64, f64)>,
    /// For a brightness (`Reading::Brightness`), the box of the region that changes (pixels of
    /// the displayed frame: left, top, right, bottom), where its light is read.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub region: Option<(f64, f64, f64, f64)>,
    /// Where the frames were steadied against a camera's shake before this was read (`steady`),
    /// the largest shift taken off (pixels of the displayed frame); the positions are then
    /// those of the background's picture.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steadied: Option<f64>,
}

impl Track {
    /// The track as CSV: one row a sample (t, the file's time, x, y, quality, along; where a
    /// plane is given, the position on it in metres).
    pub fn csv(&self) -> String {
        let plane = !self.on_plane.is_empty();
        let mut s = String::from("t_s,file_s,x_px,y_px,quality,along_px");
        s += if plane {
            ",plane_x_m,plane_y_m\n"
        } else {
            "\n"
        };
        for i in 0..self.t.len() {
            s += &format!(
                "{},{},{},{},{},{}",
                self.t[i], self.file_s[i], self.x[i], self.y[i], self.quality[i], self.along[i]
            );
            if let Some((px, py)) = self.on_plane.get(i) {
                s += &format!(",{px},{py}");
            }
            s += "\n";
        }
        s
    }
}

/// Tracklets tried as the object: this many, those that move the most (`Tracklet::reach`: a
/// toss's ball, seen for 24 frames, came after the flickering bands of the stick beside it,
/// seen for all 32, when the longest-lived were tried), each read two ways (its blobs'
/// centroids, its picture's matches).
const TRIED: usize = 8;

/// A tracklet whose centroid moves less than this (pixels of the frames read) is a flicker.
const LEAST_EXTENT: f64 = 2.0;

/// Follows the object of `input` (trimmed to `span`) and fits each law where it holds: of the
/// [`TRIED`] longest-lived things that move, the one a law explains the most motion of; of
/// the readings of that same thing (its blobs, its picture's matches, linked one way or
/// another), the one whose law holds the longest, and of those alike in length (within
/// `choose::ALIKE` of it), the reading by its rod's axes (a shaking camera moves the centroids,
/// not the axes, and a swing's centroid is not on its arc: `rod`); `None` where nothing lives
/// long enough to follow.
pub fn follow(
    input: &Path,
    info: &VideoInfo,
    span: (Option<f64>, Option<f64>),
    fps: Option<f64>,
) -> Result<Option<TrackRoute>, VideoError> {
    let all = candidates(input, info, span, fps)?;
    Ok(object::chosen(&all).cloned())
}

/// [`follow`] on the video file `input`, probed first (the Python package's `track`).
pub fn follow_file(
    input: &Path,
    span: (Option<f64>, Option<f64>),
    fps: Option<f64>,
) -> Result<Option<TrackRoute>, VideoError> {
    let info = physvid_shared::video::probe(input)?;
    follow(input, &info, span, fps)
}

/// Every reading tried as the object, in the order tried: the [`TRIED`] longest-lived things
/// that move, each as its blobs' centroids and as its picture's matches, with each law fitted
/// where it holds; where no law but a rod's explains any of them, the same of the frames' colour
/// (`small_chroma`); where none guides, the same on the frames steadied against the camera's
/// shake (`Steady`), kept where they guide, and the brightness of what changes in place
/// (`light`; on the steadied frames where as shot its decay does not guide), kept where its
/// decay guides or none has a law: what `follow` chooses among.
pub fn candidates(
    input: &Path,
    info: &VideoInfo,
    span: (Option<f64>, Option<f64>),
    fps: Option<f64>,
) -> Result<Vec<TrackRoute>, VideoError> {
    let frames = small_frames(input, info, span, TRACK_SIDE)?;
    let n = frames.len();
    if n < LEAST_FRAMES {
        return Ok(Vec::new());
    }
    let (w, h) = frames.size;
    let (t_all, file_all) = times(info, span, n, fps);
    let mut steps: Vec<f64> = t_all
        .windows(2)
        .map(|p| p[1] - p[0])
        .filter(|d| *d > 0.0)
        .collect();
    steps.sort_by(f64::total_cmp);
    let frame_s = steps.get(steps.len() / 2).copied().unwrap_or(1.0 / 30.0);
    let clock = Clock {
        t: &t_all,
        file: &file_all,
        scale: (info.width as f64 / w as f64, info.height as f64 / h as f64),
        picture: (info.width, info.height),
        reach: (FASTEST * frame_s).min(0.5) * w.max(h) as f64,
    };
    let bg = background::background(&frames);
    let mut all = readings(&frames, &bg, &clock);
    // Where no law explains what the grey shows, the same frames' colour: an object as
    // bright as the wall behind it differs there (read second: a ball's colour follows it
    // through its bounce too, whose arc outlasts the drop the grey kept). A law of its rod's
    // axes alone does not count: they are read from the same blobs as its centroids, which
    // follow no law where the grey sees the thing in pieces, and its colour may see it whole
    // (the 90° GIF's grey rod holds a swing over 15 of its 25 frames, 2.4 s at 4 px; its
    // colour's centroids over 37, 3.6 s).
    if !all
        .iter()
        .any(|c| c.explained() > 0.0 && c.track.reading != Reading::Rod)
    {
        let chroma = small_chroma(input, info, span, TRACK_SIDE)?;
        if chroma.len() == n && chroma.size == frames.size {
            all.extend(readings(&chroma, &background::background(&chroma), &clock));
        }
    }
    // Where nothing guides, the same read on the frames steadied against a camera's shake (a
    // hand-held camera moves every edge of a still picture, and the object with them), those
    // readings kept that guide.
    let steady = (!all.iter().any(|c| c.guiding().is_some()))
        .then(|| Steady::of(&frames))
        .flatten();
    if let Some(s) = &steady {
        all.extend(s.guiding(&clock));
    }
    // Where nothing that moves guides the latent (no clear oscillation or swing), what changes
    // in place: the brightness of the region that changes (an LED dimming), one number a frame;
    // kept where nothing that moves follows a law, or where its decay guides (a hand that
    // flipped the switch moved by a law of its own for a second). Where its decay does not
    // guide, it is read again on the frames steadied against a camera's shake (a hand-held
    // camera moves every edge of a still picture in place, and the region that changes is then
    // theirs), kept where its decay guides there.
    let lawless = !all.iter().any(|c| c.explained() > 0.0);
    if lawless || !all.iter().any(|c| c.guiding().is_some()) {
        let guides = |l: &Option<TrackRoute>| l.as_ref().is_some_and(|l| l.guiding().is_some());
        let mut light = light::brightness(&frames, &clock, &bg);
        if !guides(&light) {
            let steadied = steady.as_ref().and_then(|s| s.brightness(&clock));
            if guides(&steadied) {
                light = steadied;
            }
        }
        all.extend(light.filter(|l| lawless || l.guiding().is_some()));
    }
    // Where the camera shook from frame to frame (not a slow drift), the latent route reads
    // the steadied frames whatever the track was read on.
    if let Some(s) = steady
        .as_ref()
        .filter(|s| s.steadied.step() >= steady::JITTER)
    {
        let shake = s.shake(&clock);
        let as_shot = all.iter_mut().filter(|c| c.shake.is_none());
        as_shot.for_each(|c| c.shake = Some(shake.clone()));
    }
    Ok(all)
}

/// A recording's frames steadied against the camera's shake (`steady::steadied`) and their
/// own background.
struct Steady {
    steadied: steady::Steadied,
    bg: background::Background,
}

impl Steady {
    /// `frames` steadied against the camera's shake; `None` where it held still.
    fn of(frames: &SmallFrames) -> Option<Steady> {
        let steadied = steady::steadied(frames)?;
        let bg = background::background(&steadied.frames);
        Some(Steady { steadied, bg })
    }

    /// `route` marked as read on these frames, with their shifts for the latent route's.
    fn marked(&self, mut route: TrackRoute, clock: &Clock) -> TrackRoute {
        route.track.steadied = Some(self.steadied.largest() * clock.scale.0);
        route.shake = Some(self.shake(clock));
        route
    }

    /// The readings of the things that move on these frames that guide the latent.
    fn guiding(&self, clock: &Clock) -> Vec<TrackRoute> {
        readings(&self.steadied.frames, &self.bg, clock)
            .into_iter()
            .filter(|c| c.guiding().is_some())
            .map(|c| self.marked(c, clock))
            .collect()
    }

    /// The camera's shake, for the latent route's frames (pixels of the displayed frame, by
    /// the frames' times on the file's timeline).
    fn shake(&self, clock: &Clock) -> CameraShake {
        let (kx, ky) = clock.scale;
        let shifts = &self.steadied.shifts;
        CameraShake {
            file_s: clock.file.to_vec(),
            shift: shifts.iter().map(|&(x, y)| (x * kx, y * ky)).collect(),
        }
    }

    /// The brightness of what changes in place (`light`) on these frames.
    fn brightness(&self, clock: &Clock) -> Option<TrackRoute> {
        light::brightness(&self.steadied.frames, clock, &self.bg).map(|l| self.marked(l, clock))
    }
}
