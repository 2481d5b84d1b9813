//! The object's position refined by its picture: a patch cut around its blob in the frame where
//! the blob has its usual size, matched (`patch`) in every frame of the tracklet's time near
//! where the blob (or the last match) puts it, and, for the object, on past the tracklet's ends
//! about where its last matches carry it (`beyond`: its blob fades where it moves less than its
//! size about where it rests). A spring's coils or a hand merged into the blob pull its
//! centroid; they change the match's score, not its place.

use super::link::Tracklet;
use super::patch::{best_match, Patch};
pub use super::patch::{Match, LEAST_SCORE};
use physvid_shared::video::SmallFrames;

/// The patch is at most this many pixels either side of its centre (a larger object is matched
/// by its middle), and the search at most this far from the guess.
const LARGEST_HALF: usize = 12;
const FURTHEST: usize = 24;

/// Past a tracklet's ends the matches go on until this many frames in a row show none (as a
/// tracklet may miss frames: `link`'s gap).
const ONWARD_GAP: usize = 3;

/// What matches one tracklet's object: its patch, the search's reach about a guess within the
/// tracklet, and about where the last matches carry it beyond.
struct Matcher {
    patch: Patch,
    reach: usize,
    near: usize,
}

impl Matcher {
    fn of(frames: &SmallFrames, tracklet: &Tracklet) -> Option<Matcher> {
        let (w, h) = frames.size;
        let usual = tracklet.usual_area();
        let half = ((usual.sqrt() / 2.0).ceil() as usize + 2).clamp(3, LARGEST_HALF);
        // The fastest step seen between consecutive sightings widens the search.
        let fastest = tracklet
            .frames
            .windows(2)
            .zip(tracklet.blobs.windows(2))
            .map(|(f, b)| (b[1].x - b[0].x).hypot(b[1].y - b[0].y) / (f[1] - f[0]) as f64)
            .fold(0.0, f64::max);
        let reach = ((1.5 * fastest).ceil() as usize + 2).min(FURTHEST);
        // Beyond the tracklet a quarter of the fastest step about where the last two matches
        // carry it (an oscillation's step changes by (2π/N)² of its swing a frame, N frames a
        // period).
        let near = ((fastest / 4.0).ceil() as usize + 2).min(reach);
        // The reference: the sighting whose size is nearest the usual one, with room for the
        // patch.
        let mut order: Vec<usize> = (0..tracklet.blobs.len()).collect();
        order.sort_by(|&a, &b| {
            (tracklet.blobs[a].area - usual)
                .abs()
                .total_cmp(&(tracklet.blobs[b].area - usual).abs())
        });
        let patch = order.iter().find_map(|&i| {
            let b = tracklet.blobs[i];
            let at = (b.x.round() as usize, b.y.round() as usize);
            Patch::cut(frames.frame(tracklet.frames[i]), (w, h), at, half)
        })?;
        Some(Matcher { patch, reach, near })
    }
}

/// The matches of `tracklet`'s object in each frame from its first to its last (None where it
/// is not seen), each searched about its blob or the last match.
pub fn refine(frames: &SmallFrames, tracklet: &Tracklet) -> Vec<(usize, Match)> {
    let Some(m) = Matcher::of(frames, tracklet) else {
        return Vec::new();
    };
    let first = tracklet.frames[0];
    let last = *tracklet.frames.last().expect("a tracklet has a frame");
    let mut blob_at = tracklet.frames.iter().zip(&tracklet.blobs).peekable();
    let mut previous: Option<(f64, f64)> = None;
    let mut found = Vec::new();
    for k in first..=last {
        let mut guess = previous;
        while let Some((f, b)) = blob_at.peek() {
            if **f < k {
                blob_at.next();
                continue;
            }
            if **f == k {
                guess = Some((b.x, b.y));
            }
            break;
        }
        if let Some(hit) = guess.and_then(|g| best_match(frames, &m.patch, g, m.reach, k)) {
            previous = Some((hit.x, hit.y));
            found.push((k, hit));
        }
    }
    found
}

/// `tracklet`'s matches `within` it (`refine`) carried on past its ends while its patch is
/// seen: its blob fades where the object moves less than its own size about where it rests,
/// since the median background holds it there. Each search is about where the last two
/// matches carry it; the matches stop [`ONWARD_GAP`] frames after the last.
pub fn beyond(
    frames: &SmallFrames,
    tracklet: &Tracklet,
    within: &[(usize, Match)],
) -> Vec<(usize, Match)> {
    let (Some(m), Some(&(first, _)), Some(&(last, _))) =
        (Matcher::of(frames, tracklet), within.first(), within.last())
    else {
        return within.to_vec();
    };
    let carried = |k: usize, guess: (f64, f64)| best_match(frames, &m.patch, guess, m.near, k);
    let ahead = onward(within, last + 1..frames.len(), &carried);
    let rev: Vec<(usize, Match)> = within.iter().rev().copied().collect();
    let mut all = onward(&rev, (0..first).rev(), &carried);
    all.reverse();
    all.extend_from_slice(within);
    all.extend(ahead);
    all
}

/// The matches after the last of `found` (its order the frames' `ks`), each sought by `seek`
/// in its frame about where its last two matches carry it, until [`ONWARD_GAP`] frames in a
/// row show none.
fn onward(
    found: &[(usize, Match)],
    ks: impl Iterator<Item = usize>,
    seek: &dyn Fn(usize, (f64, f64)) -> Option<Match>,
) -> Vec<(usize, Match)> {
    let mut seen: Vec<(usize, Match)> = found.iter().rev().take(2).rev().copied().collect();
    if seen.is_empty() {
        return Vec::new();
    }
    let (mut added, mut missed) = (Vec::new(), 0);
    for k in ks {
        let (f, m) = seen[seen.len() - 1];
        let guess = match seen.len() {
            1 => (m.x, m.y),
            _ => {
                let (g, p) = seen[0];
                let s = (k as f64 - f as f64) / (f as f64 - g as f64);
                (m.x + s * (m.x - p.x), m.y + s * (m.y - p.y))
            }
        };
        match seek(k, guess) {
            Some(m) => {
                missed = 0;
                seen = vec![seen[seen.len() - 1], (k, m)];
                added.push((k, m));
            }
            None => {
                missed += 1;
                if missed > ONWARD_GAP {
                    break;
                }
            }
        }
    }
    added
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::blobs::Blob;

    /// A bright 5×5 cross-shaped mark at each of `places` on a textured wall, drawn by area
    /// sampling, one frame a place.
    fn drawn(places: &[(f64, f64)], (w, h): (usize, usize)) -> SmallFrames {
        let mut pixels = Vec::new();
        for &(px, py) in places {
            for y in 0..h {
                for x in 0..w {
                    let mut cover = 0.0;
                    for s in 0..16 {
                        let sx = x as f64 + (s % 4) as f64 / 4.0 + 0.125 - px;
                        let sy = y as f64 + (s / 4) as f64 / 4.0 + 0.125 - py;
                        if (sx.abs() < 2.5 && sy.abs() < 0.8) || (sy.abs() < 2.5 && sx.abs() < 0.8)
                        {
                            cover += 1.0 / 16.0;
                        }
                    }
                    let wall = 60.0 + 20.0 * (((x * 7 + y * 3) % 5) as f64 / 5.0);
                    pixels.push((wall + (230.0 - wall) * cover).round() as u8);
                }
            }
        }
        SmallFrames {
            pixels,
            size: (w, h),
        }
    }

    /// The mark moving by fractions of a pixel; its blob's centroid is put 2 px off to stand
    /// for a hand beside it.
    #[test]
    fn the_match_finds_the_mark_to_a_tenth_of_a_pixel_whatever_pulls_its_blob() {
        let places: Vec<(f64, f64)> = (0..12)
            .map(|k| (14.0 + 1.37 * k as f64, 15.0 + 0.41 * k as f64))
            .collect();
        let frames = drawn(&places, (48, 32));
        let tracklet = Tracklet {
            frames: (0..12).collect(),
            blobs: places
                .iter()
                .map(|&(x, y)| Blob::round(9.0, x + 2.0, y))
                .collect(),
        };
        let found = refine(&frames, &tracklet);
        assert_eq!(found.len(), 12);
        // The matches follow the mark's displacement (the patch's centre is the reference
        // frame's rounded blob place, so compare steps from the first).
        let (x0, y0) = (found[0].1.x - places[0].0, found[0].1.y - places[0].1);
        for (k, m) in &found {
            assert!((m.x - places[*k].0 - x0).abs() < 0.15, "frame {k}: {m:?}");
            assert!((m.y - places[*k].1 - y0).abs() < 0.15, "frame {k}: {m:?}");
            assert!(m.score > LEAST_SCORE, "frame {k}: {m:?}");
        }
    }

    /// A mark swinging ±6 px, 16 frames a period, for 80 frames, its blob seen only over
    /// frames 30–45 (elsewhere, say, too near where it rests to differ from the background):
    /// beyond the tracklet the matches follow it over every frame, both ways, as closely as
    /// within it (where the wall's texture biases a match by a fraction of a pixel); within it
    /// they are the tracklet's own.
    #[test]
    fn beyond_its_tracklet_the_mark_is_followed_over_the_whole_recording() {
        let places: Vec<(f64, f64)> = (0..80)
            .map(|k| {
                let phase = std::f64::consts::TAU * k as f64 / 16.0;
                (24.0 + 6.0 * phase.cos(), 16.0 + 0.5 * phase.sin())
            })
            .collect();
        let frames = drawn(&places, (48, 32));
        let seen = 30..46;
        let tracklet = Tracklet {
            frames: seen.clone().collect(),
            blobs: seen
                .clone()
                .map(|k| Blob::round(9.0, places[k].0, places[k].1))
                .collect(),
        };
        let within = refine(&frames, &tracklet);
        assert_eq!(within.len(), seen.len());
        let all = beyond(&frames, &tracklet, &within);
        assert_eq!(all.len(), 80);
        assert!(all.iter().enumerate().all(|(i, (k, _))| *k == i));
        assert_eq!(&all[30..46], &within[..]);
        let (x0, y0) = (all[30].1.x - places[30].0, all[30].1.y - places[30].1);
        let off =
            |(k, m): &(usize, Match)| (m.x - places[*k].0 - x0).hypot(m.y - places[*k].1 - y0);
        let worst = |s: &[(usize, Match)]| s.iter().map(off).fold(0.0, f64::max);
        // Sub-pixel within the tracklet, and no worse beyond it than within.
        assert!(worst(&within) < 0.25, "{}", worst(&within));
        assert!(worst(&all) <= worst(&within) + 1e-6, "{}", worst(&all));
        // Where the mark leaves the picture the matches stop: frames of wall alone after 80.
        let mut wall = frames.pixels.clone();
        let blank = drawn(&[(-20.0, -20.0)], (48, 32)).pixels;
        (0..10).for_each(|_| wall.extend_from_slice(&blank));
        let longer = SmallFrames {
            pixels: wall,
            size: (48, 32),
        };
        assert_eq!(beyond(&longer, &tracklet, &within).len(), 80);
    }
}
