//! A descent read from the object's track (`TrackedMotion`: a constant acceleration the track
//! holds, `guide::measured` and `guide::sighted`): its release where the track saw it, and its
//! line where the path's own is another (a toss's path bends; its fall is along the
//! acceleration); a toss's rise kept with its fall; the whole descent where the picture finds
//! none. The track does the picture's work there: no colour, no share of the picture that
//! moves. The descent lasts at least as long as the track saw its law hold.

use super::descent::Descent;
use super::request::TrackedMotion;
use crate::encoder::centroid::Line;
use physvid_shared::video::{DecodedVideo, VideoOptions};

/// The track's acceleration and the path's line are one line where the cosine of the angle
/// between them is at least this (8°: a straight path lies along its acceleration, a toss's
/// line across its parabola far off it): the picture's line and its bend by perspective are
/// kept.
const SAME_LINE: f64 = 0.99;

/// How the decoded frames sit on the file's timeline and in the displayed picture.
pub struct Geometry {
    /// `--start` (seconds of the file's timeline) and frames a second of the timeline.
    start: f64,
    fps: f64,
    frames: usize,
    /// Decoded pixels per displayed pixel, across and down (the crop resized).
    scale: (f64, f64),
}

impl Geometry {
    pub fn of(decoded: &DecodedVideo, opts: &VideoOptions, fps: f64) -> Geometry {
        let (cw, ch) = opts.crop.map_or(
            (decoded.info.width as f64, decoded.info.height as f64),
            |c| (c.w as f64, c.h as f64),
        );
        Geometry {
            start: opts.start.unwrap_or(0.0),
            fps,
            frames: decoded.frame_count(),
            scale: (
                decoded.size.0 as f64 / cw.max(1.0),
                decoded.size.1 as f64 / ch.max(1.0),
            ),
        }
    }

    /// A time of the file's timeline in frames of the decode.
    fn frame(&self, t: f64) -> f64 {
        (t - self.start) * self.fps
    }

    /// A direction of the displayed picture in the decoded frames (a unit vector).
    fn direction(&self, [x, y]: [f64; 2]) -> Option<[f64; 2]> {
        let (x, y) = (x * self.scale.0, y * self.scale.1);
        let n = x.hypot(y);
        (n > 0.0).then(|| [x / n, y / n])
    }
}

/// The descent `found` in the picture, read with the track's motion `t`: the release the track
/// saw, the acceleration's line where the path's is another; or, where the picture found none,
/// the descent the track holds (from its release to its span's end). `None` where neither
/// gives one.
pub fn descent(found: Option<Descent>, t: &TrackedMotion, g: &Geometry) -> Option<Descent> {
    let axis = g.direction(t.axis)?;
    let release = t.release.map(|r| g.frame(r));
    let Some(mut d) = found else {
        let release = release?;
        let last = (g.frame(t.span.1).floor().max(0.0) as usize).min(g.frames.checked_sub(1)?);
        if release >= last as f64 {
            return None;
        }
        let d = Descent {
            release,
            first: 0,
            last,
            travel: t.travel,
            bend: None,
            line: Line { axis, bend: 0.0 },
            crowded: 0.0,
            colour: false,
            rising: false,
        };
        return Some(rising(d.released_at(release), t, g));
    };
    if let Some(r) = release {
        // The vertex of the law the track holds within its noise: no position pulled by
        // a hand beside the object reads it (`Descent::crowded` is the picture's).
        d = Descent {
            crowded: 0.0,
            ..d.released_at(r)
        };
    }
    d = rising(d, t, g);
    // The law holds on the track until its span's end: the free motion lasts at least that
    // long, whatever else in the picture stops moving first or starts moving across it (a
    // hanging mass that pulls a cart, then leaves the frame).
    let held = (g.frame(t.span.1).floor().max(0.0) as usize).min(g.frames.saturating_sub(1));
    if d.release < held as f64 {
        d.last = d.last.max(held);
    }
    let cos = (axis[0] * d.line.axis[0] + axis[1] * d.line.axis[1]).abs();
    if cos < SAME_LINE {
        d.line = Line { axis, bend: 0.0 };
        d.bend = None;
    }
    Some(d)
}

/// `d`, where the track saw the object rise toward its release (`moving_before`: a toss), kept
/// from the track's span's start, the law holding on both sides of the vertex.
fn rising(mut d: Descent, t: &TrackedMotion, g: &Geometry) -> Descent {
    if t.moving_before {
        let start = g.frame(t.span.0).ceil().max(0.0) as usize;
        d.first = start.min(d.release.floor().max(0.0) as usize);
        d.rising = true;
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    fn geometry() -> Geometry {
        Geometry {
            start: 1.0,
            fps: 30.0,
            frames: 60,
            scale: (0.5, 0.25),
        }
    }

    fn toss(release: Option<f64>) -> TrackedMotion {
        TrackedMotion {
            moving_before: true,
            span: (1.2, 2.5),
            release,
            axis: [0.0, 1.0],
            travel: 0.4,
            frame: None,
        }
    }

    #[test]
    fn where_the_picture_finds_no_descent_the_track_gives_it() {
        let d = descent(None, &toss(Some(1.5)), &geometry()).unwrap();
        assert!((d.release - 15.0).abs() < 1e-9);
        assert_eq!(d.last, 45);
        assert_eq!(d.line.axis, [0.0, 1.0]);
        // A toss: kept from the track's span's start (1.2 s, frame 6), its rise.
        assert_eq!((d.first, d.rising), (6, true));
        let mut dropped = toss(Some(1.5));
        dropped.moving_before = false;
        let d = descent(None, &dropped, &geometry()).unwrap();
        assert!(d.first > 6 && d.first <= 15 && !d.rising, "{d:?}");
        // A release the track did not see gives no descent of its own.
        assert!(descent(None, &toss(None), &geometry()).is_none());
    }

    #[test]
    fn the_picture_s_line_is_kept_where_it_is_the_acceleration_s() {
        let picture = Descent {
            release: 10.0,
            first: 8,
            last: 50,
            travel: 0.5,
            bend: None,
            line: Line {
                axis: [0.0, 1.0],
                bend: 0.01,
            },
            crowded: 0.0,
            colour: false,
            rising: false,
        };
        let crowded = Descent {
            crowded: 0.4,
            ..picture
        };
        let d = descent(Some(crowded), &toss(Some(1.2)), &geometry()).unwrap();
        assert_eq!(d.line.bend, 0.01);
        // The release is the track's, not read where a hand crowds the picture.
        assert_eq!(d.crowded, 0.0);
        assert!((d.release - 6.0).abs() < 1e-9);
        // Across the picture's line: the acceleration's, unbent.
        let mut across = toss(None);
        across.axis = [1.0, 0.0];
        let d = descent(Some(picture), &across, &geometry()).unwrap();
        assert_eq!((d.line.axis, d.line.bend), ([1.0, 0.0], 0.0));
        assert_eq!(d.release, 10.0);
    }

    #[test]
    fn the_descent_lasts_as_long_as_the_track_saw_its_law_hold() {
        // The picture's descent ends at frame 20 (something else in the frame stops it); the
        // track's law holds to 2.5 s, frame 45: kept to there. One that ends later keeps its end.
        let picture = |last| Descent {
            release: 10.0,
            first: 8,
            last,
            travel: 0.5,
            bend: None,
            line: Line {
                axis: [0.0, 1.0],
                bend: 0.0,
            },
            crowded: 0.0,
            colour: false,
            rising: false,
        };
        let d = descent(Some(picture(20)), &toss(Some(1.3)), &geometry()).unwrap();
        assert_eq!(d.last, 45);
        let d = descent(Some(picture(55)), &toss(Some(1.3)), &geometry()).unwrap();
        assert_eq!(d.last, 55);
    }
}
