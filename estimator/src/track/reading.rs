//! One picture's readings of the things that move: the tracklets linked from its blobs (and
//! the pieces of the one that moves the most, hidden from each other, rejoined), each read as
//! its blobs' centroids, as those of its whole blobs alone (a blob cut by the threshold or
//! merged with clutter a gap) and as its picture's matches (`template`; the object's carried
//! on past its tracklet's ends), and the route of each reading: its axis, its noise and each
//! law's span (`fit`).

use super::template::{self, Match};
use super::{
    background, blobs, fit, link, object::chosen, rod, Track, TrackRoute, LEAST_EXTENT,
    LEAST_FRAMES, TRIED,
};
use physvid_shared::video::{SmallFrames, VideoInfo};
use rayon::prelude::*;
use serde::Serialize;

/// The routes of one picture of the recording (its grey or its chroma, over its background
/// `bg`): the [`TRIED`] tracklets that move the most and the first's pieces rejoined
/// (`link::rejoined`), each read as its blobs' centroids, as those of its whole blobs alone
/// (`whole`), by its rod's axes where its regions are whole (`rod`) and as its picture's
/// matches; and the matches of the thing whose reading `chosen` keeps carried on past its
/// tracklet's ends (`template::beyond`).
pub(super) fn readings(
    frames: &SmallFrames,
    bg: &background::Background,
    clock: &Clock,
) -> Vec<TrackRoute> {
    let n = frames.len();
    // Each frame's blobs on the pool's threads, in the frames' order.
    let found: Vec<Vec<blobs::Blob>> = (0..n)
        .into_par_iter()
        .map(|i| blobs::blobs(frames, i, bg))
        .collect();
    let tracklets = link::tracklets(&found, clock.reach, LEAST_FRAMES, LEAST_EXTENT);
    // The thing that moves the most, its pieces hidden from each other joined, tried too.
    let joined = link::rejoined(&tracklets, 0);
    let tried: Vec<&link::Tracklet> = tracklets.iter().take(TRIED).chain(joined.iter()).collect();
    // Each tracklet's readings and their routes on the pool's threads (most of a track's time:
    // the matches and the laws' fits), in the order tried, with its matches.
    let routes: Vec<(Vec<TrackRoute>, Sightings)> = tried
        .par_iter()
        .map(|t| {
            let all = centroids(t);
            let whole = whole(&all);
            let rod = rod::rod(&all, t);
            let matches = template::refine(frames, t);
            let size = t.usual_area().sqrt();
            let routes = [
                (Reading::Centroids, Some(all)),
                (Reading::Whole, whole),
                (Reading::Rod, rod),
                (Reading::Matches, Some(matches.clone())),
            ]
            .into_iter()
            .filter_map(|(reading, sightings)| {
                route_of(&sightings?, reading, size, clock, n, bg.threshold)
            })
            .collect();
            (routes, matches)
        })
        .collect();
    // Which tracklet each reading is of.
    let of: Vec<usize> = (0..routes.len())
        .flat_map(|i| std::iter::repeat_n(i, routes[i].0.len()))
        .collect();
    let (routes, matches): (Vec<Vec<TrackRoute>>, Vec<_>) = routes.into_iter().unzip();
    let mut all: Vec<TrackRoute> = routes.into_iter().flatten().collect();
    // The object's picture matched on past its tracklet's ends (`template::beyond`), a
    // reading beside the others: the whole recording's fits for one tracklet, not for all.
    let object = chosen(&all).and_then(|c| all.iter().position(|o| std::ptr::eq(o, c)));
    if let Some(k) = object.map(|i| of[i]) {
        let within = &matches[k];
        let beyond = template::beyond(frames, tried[k], within);
        if beyond.len() > within.len() {
            let size = tried[k].usual_area().sqrt();
            all.extend(route_of(
                &beyond,
                Reading::Matches,
                size,
                clock,
                n,
                bg.threshold,
            ));
        }
    }
    all
}

/// A reading's sightings: each frame's index and the object's place in it.
type Sightings = Vec<(usize, Match)>;

/// How a track's positions were read from the thing followed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Reading {
    /// Its blobs' centroids.
    Centroids,
    /// The centroids of its whole blobs alone (`whole`).
    Whole,
    /// Its blobs' long axes about the pivot they meet at, where their regions are whole
    /// (`rod`).
    Rod,
    /// Its picture's matches with a patch of it (`template`).
    Matches,
    /// Not a position: the brightness of the region that changes (`light`), in grey levels.
    Brightness,
}

/// The frames' times, their scale to the displayed picture and its size.
pub(super) struct Clock<'a> {
    pub t: &'a [f64],
    pub file: &'a [f64],
    /// The displayed picture's pixels to a pixel of the frames read, across and down: apart
    /// where the frames' sides were rounded (a 360×200 picture read at 320×178).
    pub scale: (f64, f64),
    pub picture: (usize, usize),
    /// How far the object may move in a frame (pixels of the frames read).
    pub reach: f64,
}

/// The frames' real times: `fps` where the user gave it, else the container's timestamps
/// (a slow-motion capture's scaled to its capture rate; the slots of their even clock where
/// the frames were put on it), else the container's even rate.
/// And each frame's time on the file's own timeline.
pub(super) fn times(
    info: &VideoInfo,
    span: (Option<f64>, Option<f64>),
    n: usize,
    fps: Option<f64>,
) -> (Vec<f64>, Vec<f64>) {
    let from = span.0.unwrap_or(0.0);
    let stamps = info.times_within(span.0, span.1);
    let even = |rate: f64| -> Vec<f64> { (0..n).map(|i| i as f64 / rate).collect() };
    let container = info.read_rate(info.container_fps.unwrap_or(30.0));
    // Frames put on their clock (resampled, or some at an end left out): slot k's time.
    let clock = info.clock(span.0, span.1).and_then(Result::ok);
    let file: Vec<f64> = match clock {
        Some(c) if !c.is_even() => (0..n).map(|k| c.start + k as f64 * c.interval).collect(),
        _ if stamps.len() == n => stamps.clone(),
        _ => even(container).iter().map(|t| from + t).collect(),
    };
    if let Some(f) = fps {
        return (even(info.read_rate(f)), file);
    }
    let slow = match (info.capture_fps, info.container_fps) {
        (Some(c), Some(f)) if c > f => f / c,
        _ => 1.0,
    };
    let real = file.iter().map(|t| (t - file[0]) * slow).collect();
    (real, file)
}

#[cfg(test)]
impl<'a> Clock<'a> {
    /// The clock of frames at times `t` of the file's own timeline too, read at the displayed
    /// picture's size (`picture`), the object moving at most `reach` pixels a frame.
    pub fn shown(t: &'a [f64], picture: (usize, usize), reach: f64) -> Clock<'a> {
        Clock {
            t,
            file: t,
            scale: (1.0, 1.0),
            picture,
            reach,
        }
    }
}

/// A tracklet's sightings read as its blobs' centroids, their quality the blob's size against
/// its usual size.
fn centroids(tracklet: &link::Tracklet) -> Vec<(usize, Match)> {
    let usual = tracklet.usual_area();
    tracklet
        .frames
        .iter()
        .zip(&tracklet.blobs)
        .map(|(&k, b)| {
            let score = alike_in_size(b.area, usual);
            (
                k,
                Match {
                    x: b.x,
                    y: b.y,
                    score,
                },
            )
        })
        .collect()
}

/// How near `size` is to `usual`: the smaller over the larger (1 for the same size).
pub(super) fn alike_in_size(size: f64, usual: f64) -> f64 {
    size.min(usual) / size.max(usual)
}

/// A blob whose area and its tracklet's usual area differ by more than this share of the
/// larger (its centroid's quality below it) is cut by the threshold or merged with something
/// else that differs from the background (clutter crossing it, a shadow, a hand): its centroid
/// is off the object's. Set on the others' rod and bob (docs/status.md: the track right on 25
/// of 36 renders held out one at a time, 22 without this reading); the shared springs and
/// pendulum keep their spans.
pub(super) const WHOLE: f64 = 0.8;

/// The centroid reading `sightings` without its cut or merged blobs ([`WHOLE`]): gaps where
/// the object was not seen whole, a reading of its own beside the one that keeps them (a blob
/// that grows as it nears the camera, or blurs as it speeds, is whole in neither's sense but
/// the object's; the law that holds longer chooses). `None` where every blob is whole.
fn whole(sightings: &[(usize, Match)]) -> Option<Vec<(usize, Match)>> {
    let kept: Vec<(usize, Match)> = sightings
        .iter()
        .filter(|(_, m)| m.score >= WHOLE)
        .copied()
        .collect();
    (kept.len() < sightings.len()).then_some(kept)
}

/// The route of one `reading` of a tracklet (`centroids`, `whole`, `rod` or `template`'s
/// matches): the axis, the noise and each law's span.
pub(super) fn route_of(
    matches: &[(usize, Match)],
    reading: Reading,
    size: f64,
    clock: &Clock,
    n: usize,
    threshold: f64,
) -> Option<TrackRoute> {
    if matches.len() < LEAST_FRAMES {
        return None;
    }
    let scale = clock.scale;
    let t: Vec<f64> = matches.iter().map(|(k, _)| clock.t[*k]).collect();
    let file_s: Vec<f64> = matches.iter().map(|(k, _)| clock.file[*k]).collect();
    let x: Vec<f64> = matches.iter().map(|(_, m)| (m.x + 0.5) * scale.0).collect();
    let y: Vec<f64> = matches.iter().map(|(_, m)| (m.y + 0.5) * scale.1).collect();
    let quality = matches.iter().map(|(_, m)| m.score).collect();
    let xy: Vec<(f64, f64)> = x.iter().copied().zip(y.iter().copied()).collect();
    let fitted = fit::fit(&t, &xy);
    let track = Track {
        t,
        x,
        y,
        quality,
        file_s,
        along: fitted.along,
        axis: fitted.axis,
        noise: fitted.noise,
        size: size * scale.0,
        picture: clock.picture,
        frames: n,
        threshold,
        on_plane: Vec::new(),
        region: None,
        steadied: None,
        reading,
    };
    Some(TrackRoute::read(track, fitted.laws, fitted.chosen))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An oscillation along x (20 samples a second for 8 s, period 2 s), its sightings at
    /// `score` 1, but for five whose blob merged with something passing (3 px off, score 0.6).
    fn merged() -> Vec<(usize, Match)> {
        (0..160)
            .map(|k| {
                let t = k as f64 / 20.0;
                let x = 40.0 + 20.0 * (-0.05 * t).exp() * (std::f64::consts::PI * t).cos();
                let hit = (40..45).contains(&k);
                let m = Match {
                    x: x + if hit { 3.0 } else { 0.0 } + 0.01 * ((k * 7919) % 13) as f64,
                    y: 30.0,
                    score: if hit { 0.6 } else { 1.0 },
                };
                (k, m)
            })
            .collect()
    }

    #[test]
    fn a_merged_blob_is_a_gap_in_a_reading_of_its_own() {
        let all = merged();
        let kept = whole(&all).unwrap();
        assert_eq!(kept.len(), all.len() - 5);
        assert!(kept.iter().all(|(k, _)| !(40..45).contains(k)));
        // Every blob whole: no second reading.
        assert!(whole(&kept).is_none());
        // The law holds over the whole track where the merged blobs are gaps, and stops at
        // them where they are kept.
        let t: Vec<f64> = (0..160).map(|k| k as f64 / 20.0).collect();
        let clock = Clock::shown(&t, (80, 60), 20.0);
        let held = |s: &[(usize, Match)]| {
            route_of(s, Reading::Centroids, 10.0, &clock, 160, 10.0)
                .unwrap()
                .held_s()
        };
        assert!(held(&kept) > 7.5, "{}", held(&kept));
        assert!(held(&all) < 6.5, "{}", held(&all));
    }
}
