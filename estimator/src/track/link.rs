//! Blobs joined frame to frame into tracklets: each blob continues the tracklet it lies
//! nearest (`Nearest`: to its last blob, or to the nearer of that and the last blob carried on
//! at its last velocity, so that a ball passing a flickering stick goes on with the ball's
//! tracklet, not the flicker's), within a step of its last blob that grows with the frames
//! missed, and of a size within a factor of its own; the rest start tracklets of their own.
//! The track tries both ways' tracklets (`tracklets`): neither joins every object best (the
//! carried-on one splits a spring's mass where a hand lets go of it).

use super::blobs::Blob;

/// A tracklet may miss this many frames (hidden, blurred into the wall) and go on.
const GAP: usize = 3;

/// Sizes of one object differ by less than this factor from frame to frame.
const SIZE_FACTOR: f64 = 4.0;

/// What a blob is nearest to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Nearest {
    /// The tracklet's last blob.
    Last,
    /// The nearer of its last blob and that blob carried on at its last velocity.
    Path,
}

/// One thing followed over frames: the frame indices and its blob in each.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tracklet {
    pub frames: Vec<usize>,
    pub blobs: Vec<Blob>,
}

impl Tracklet {
    fn last(&self) -> (usize, Blob) {
        (
            *self.frames.last().expect("a tracklet has a frame"),
            *self.blobs.last().expect("a tracklet has a blob"),
        )
    }

    /// Where it would be at frame `k` at its last velocity (its last two blobs'; at rest
    /// where it has one).
    fn predicted(&self, k: usize) -> (f64, f64) {
        let (f, last) = self.last();
        let n = self.frames.len();
        if n < 2 {
            return (last.x, last.y);
        }
        let (g, prev) = (self.frames[n - 2], self.blobs[n - 2]);
        let s = (k - f) as f64 / (f - g) as f64;
        (
            last.x + s * (last.x - prev.x),
            last.y + s * (last.y - prev.y),
        )
    }

    /// Its blobs' median size (pixels).
    pub fn usual_area(&self) -> f64 {
        let mut areas: Vec<f64> = self.blobs.iter().map(|b| b.area).collect();
        let mid = areas.len() / 2;
        *areas.select_nth_unstable_by(mid, f64::total_cmp).1
    }

    /// How much it moves: its frames times its extent (what the object does, far and for
    /// long; a flicker lives long in place, a passing speck moves for a few frames).
    pub fn reach(&self) -> f64 {
        self.frames.len() as f64 * self.extent()
    }

    /// How far its centroid moves over the tracklet (the larger side of the box it spans).
    pub fn extent(&self) -> f64 {
        let span = |f: fn(&Blob) -> f64| {
            let (lo, hi) = self
                .blobs
                .iter()
                .map(f)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(v), h.max(v))
                });
            hi - lo
        };
        span(|b| b.x).max(span(|b| b.y))
    }
}

/// The tracklets of `frames` (each frame's blobs), a blob moving at most `step` pixels a
/// frame.
pub fn link(frames: &[Vec<Blob>], step: f64, nearest: Nearest) -> Vec<Tracklet> {
    let mut tracklets: Vec<Tracklet> = Vec::new();
    for (k, blobs) in frames.iter().enumerate() {
        let mut pairs = Vec::new();
        for (ti, t) in tracklets.iter().enumerate() {
            let (f, last) = t.last();
            if k - f > GAP {
                continue;
            }
            for (bi, b) in blobs.iter().enumerate() {
                let d = (b.x - last.x).hypot(b.y - last.y);
                let ratio = b.area.max(last.area) / b.area.min(last.area).max(1.0);
                if d <= step * (k - f) as f64 && ratio < SIZE_FACTOR {
                    let near = match nearest {
                        Nearest::Last => d,
                        Nearest::Path => {
                            let (px, py) = t.predicted(k);
                            d.min((b.x - px).hypot(b.y - py))
                        }
                    };
                    pairs.push((near, ti, bi));
                }
            }
        }
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut taken_t = vec![false; tracklets.len()];
        let mut taken_b = vec![false; blobs.len()];
        for (_, ti, bi) in pairs {
            if taken_t[ti] || taken_b[bi] {
                continue;
            }
            taken_t[ti] = true;
            taken_b[bi] = true;
            tracklets[ti].frames.push(k);
            tracklets[ti].blobs.push(blobs[bi]);
        }
        for (bi, b) in blobs.iter().enumerate() {
            if !taken_b[bi] {
                tracklets.push(Tracklet {
                    frames: vec![k],
                    blobs: vec![*b],
                });
            }
        }
    }
    tracklets
}

/// The tracklets both ways (`Nearest`) at least `least` frames long, each once, those that
/// move the most (`Tracklet::reach`) first.
pub fn tracklets(frames: &[Vec<Blob>], step: f64, least: usize, extent: f64) -> Vec<Tracklet> {
    let mut all: Vec<Tracklet> = Vec::new();
    for nearest in [Nearest::Last, Nearest::Path] {
        for t in link(frames, step, nearest) {
            if t.frames.len() >= least && t.extent() >= extent && !all.contains(&t) {
                all.push(t);
            }
        }
    }
    all.sort_by(|a, b| b.reach().total_cmp(&a.reach()));
    all
}

/// Pieces of one thing are of a usual size within this factor of each other (a frame's size
/// may differ by [`SIZE_FACTOR`]; a tracklet's median, over many frames, much less). The
/// others' occluded rod and bob are rejoined alike at 1.2–3 (docs/status.md); the shared
/// recordings' tracks are the same at 1.2 and 1.5, and the phone spring's changes at 3.
const SAME_SIZE: f64 = 1.5;

/// Pieces of one thing lie in the box the first spans grown by this share of its extent on
/// every side (the same motion's region). Set on the others' occluded rod and bob, left out
/// one render at a time (docs/status.md: 0.5 chosen in all 36 folds, the track right on 29
/// held out; 27 at 0, the same at 0.5–2); the shared recordings' tracks alike at 0.5–2.
const GROW: f64 = 0.5;

/// The pieces of one thing hidden for longer than [`GAP`] frames (a bob passing behind an
/// occluder every swing) joined: `all[first]` with each tracklet listed after it that shares
/// none of the joined frames, whose usual size is within [`SAME_SIZE`] of its own, and whose
/// blobs lie in the box `all[first]` spans, grown by [`GROW`] of its extent on every side.
/// `None` where no piece joins. A piece of something else joined breaks the law there: the
/// law's span on the joined track says whether they are one thing.
pub fn rejoined(all: &[Tracklet], first: usize) -> Option<Tracklet> {
    let one = all.get(first)?;
    let usual = one.usual_area();
    let grow = GROW * one.extent();
    let (lo, hi) = one.blobs.iter().fold(
        (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        ),
        |(lo, hi), b| {
            (
                (lo.0.min(b.x), lo.1.min(b.y)),
                (hi.0.max(b.x), hi.1.max(b.y)),
            )
        },
    );
    let inside = |b: &Blob| {
        (lo.0 - grow..=hi.0 + grow).contains(&b.x) && (lo.1 - grow..=hi.1 + grow).contains(&b.y)
    };
    let mut joined: Vec<(usize, Blob)> =
        one.frames.iter().copied().zip(one.blobs.clone()).collect();
    // The frames the joined pieces hold.
    let frames = all
        .iter()
        .flat_map(|t| t.frames.last())
        .max()
        .map_or(0, |k| k + 1);
    let mut held = vec![false; frames];
    one.frames.iter().for_each(|&k| held[k] = true);
    let mut pieces = 1;
    for t in &all[first + 1..] {
        let a = t.usual_area();
        let alike = a.max(usual) / a.min(usual).max(f64::MIN_POSITIVE) < SAME_SIZE;
        let apart = t.frames.iter().all(|&k| !held[k]);
        if alike && apart && t.blobs.iter().all(inside) {
            t.frames.iter().for_each(|&k| held[k] = true);
            joined.extend(t.frames.iter().copied().zip(t.blobs.clone()));
            pieces += 1;
        }
    }
    if pieces < 2 {
        return None;
    }
    joined.sort_by_key(|(k, _)| *k);
    Some(Tracklet {
        frames: joined.iter().map(|(k, _)| *k).collect(),
        blobs: joined.into_iter().map(|(_, b)| b).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn blob(x: f64, y: f64) -> Blob {
        Blob::round(10.0, x, y)
    }

    #[test]
    fn the_pieces_of_one_thing_hidden_between_them_are_rejoined() {
        let piece = |frames: std::ops::Range<usize>, x0: f64, area: f64| Tracklet {
            frames: frames.clone().collect(),
            blobs: frames
                .map(|k| Blob::round(area, x0 + (k % 10) as f64, 5.0))
                .collect(),
        };
        let all = [
            piece(0..10, 0.0, 10.0),
            // Its own size, its own region, hidden for ten frames between: joined.
            piece(20..30, 2.0, 12.0),
            // At the same time as the first: another thing.
            piece(5..15, 1.0, 10.0),
            // Far away, or twice the size: others.
            piece(40..50, 500.0, 10.0),
            piece(60..70, 0.0, 20.0),
        ];
        let j = rejoined(&all, 0).unwrap();
        let want: Vec<usize> = (0..10).chain(20..30).collect();
        assert_eq!(j.frames, want);
        assert_eq!(j.blobs[10].x, 2.0);
        // Nothing to join: none.
        assert!(rejoined(&all[3..], 0).is_none());
    }

    #[test]
    fn two_things_are_two_tracklets_and_a_gap_is_bridged() {
        let frames: Vec<Vec<Blob>> = (0..10)
            .map(|k| {
                let mut v = vec![blob(5.0 + k as f64, 5.0)];
                if k != 4 && k != 5 {
                    v.push(blob(50.0, 10.0 + 2.0 * k as f64));
                }
                v
            })
            .collect();
        let t = link(&frames, 3.0, Nearest::Last);
        assert_eq!(t.len(), 2);
        assert_eq!(t[0].frames.len(), 10);
        assert_eq!(t[1].frames.len(), 8);
        assert!((t[1].extent() - 18.0).abs() < 1e-9);
    }

    #[test]
    fn a_thing_that_moves_far_reaches_further_than_a_flicker_that_lives_long() {
        let frames: Vec<Vec<Blob>> = (0..30)
            .map(|k| {
                let mut v = vec![blob(5.0 + (k % 2) as f64 * 2.5, 5.0)];
                if (6..26).contains(&k) {
                    v.push(blob(40.0 + 10.0 * k as f64, 60.0));
                }
                v
            })
            .collect();
        let mut t = link(&frames, 12.0, Nearest::Last);
        t.sort_by(|a, b| b.reach().total_cmp(&a.reach()));
        assert_eq!(t[0].frames.len(), 20);
        assert_eq!(t[1].frames.len(), 30);
    }

    #[test]
    fn a_jump_beyond_the_step_starts_another() {
        let frames = vec![
            vec![blob(0.0, 0.0)],
            vec![blob(1.0, 0.0)],
            vec![blob(30.0, 0.0)],
        ];
        assert_eq!(link(&frames, 5.0, Nearest::Path).len(), 2);
    }

    /// A ball passes a flicker that lives in place: nearest its last blob, the flicker takes
    /// the ball beyond it; carried on at its velocity, the ball keeps its own.
    #[test]
    fn a_ball_carried_on_at_its_velocity_keeps_its_tracklet_past_a_flicker() {
        let frames: Vec<Vec<Blob>> = (0..12)
            .map(|k| {
                // The flicker is gone the frame the ball comes out from behind it.
                let mut v = if k == 6 {
                    vec![]
                } else {
                    vec![blob(20.0, 20.0 + (k % 2) as f64)]
                };
                if k != 5 {
                    v.push(blob(4.0 * k as f64, 30.0 - 1.5 * k as f64));
                }
                v
            })
            .collect();
        let ball = |t: &[Tracklet]| -> usize {
            t.iter()
                .filter(|t| t.blobs[0].x == 0.0)
                .map(|t| t.frames.len())
                .sum()
        };
        assert_eq!(ball(&link(&frames, 12.0, Nearest::Path)), 11);
        assert!(ball(&link(&frames, 12.0, Nearest::Last)) < 11);
        let both = tracklets(&frames, 12.0, 2, 1.0);
        assert!(both
            .iter()
            .any(|t| t.frames.len() == 11 && t.blobs[0].x == 0.0));
    }
}
