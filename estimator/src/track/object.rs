//! Which reading of which thing is the object's: of the things followed, the one a law explains
//! the most motion of, and of its readings moving by its law alike long, its rod's, else the one
//! whose positions scatter least about a smooth motion, else the longest.

use super::choose::ALIKE;
use super::{Reading, TrackRoute};

/// Of the readings `all`, the object's (`follow`); a brightness whose decay guides the latent
/// before any reading of a thing that moves (`candidates` reads it only where none guides),
/// and readings of steadied frames (kept only where they guide) before those as shot.
pub(super) fn chosen(all: &[TrackRoute]) -> Option<&TrackRoute> {
    let light = |c: &&TrackRoute| c.track.reading == Reading::Brightness && c.guiding().is_some();
    if let Some(l) = all.iter().find(light) {
        return Some(l);
    }
    // Readings of steadied frames are kept only where they guide, and only where nothing read
    // as shot does: they come first.
    let steadied: Vec<&TrackRoute> = all.iter().filter(|c| c.track.steadied.is_some()).collect();
    let all: Vec<&TrackRoute> = if steadied.is_empty() {
        all.iter().collect()
    } else {
        steadied
    };
    let by = |a: &&TrackRoute, b: &&TrackRoute| {
        a.explained()
            .total_cmp(&b.explained())
            .then(a.track.t.len().cmp(&b.track.t.len()))
    };
    let most = all.iter().copied().max_by(by)?;
    let same: Vec<&TrackRoute> = all
        .iter()
        .copied()
        .filter(|c| c.explained() > 0.0 && most.same_thing(c))
        .collect();
    let moving = |c: &&TrackRoute| c.moving_s();
    let held = |c: &&TrackRoute| c.held_s();
    let Some(long) = same
        .iter()
        .copied()
        .max_by(|a, b| moving(a).total_cmp(&moving(b)))
    else {
        return Some(most);
    };
    // Of the readings moving by the law alike long (as `choose` weighs laws; a span read from
    // rest from its release), the rod's, then the one of least noise (each reading's own: what a
    // smooth motion leaves of its points), then the one held longest. A noisier reading of the
    // same thing holds its law longer only by its wider tolerance: a uniform cart larger than
    // the template's patch, matched by its middle, scatters 3 px along the rail and held its
    // parabola from 0.48 s, before its release, to 2.63 s; its centroids from the release
    // (0.5 s) to 2.57 s at 0.1 px (`scripts/carts_suite.py`).
    let rod = |c: &&TrackRoute| c.track.reading == Reading::Rod;
    let chosen = same
        .iter()
        .copied()
        .filter(|c| moving(c) >= ALIKE * moving(&long))
        .max_by(|a, b| {
            rod(a)
                .cmp(&rod(b))
                .then(b.track.noise.total_cmp(&a.track.noise))
                .then(held(a).total_cmp(&held(b)))
                .then(by(a, b))
        })
        .unwrap_or(long);
    Some(chosen)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::test_route;

    /// A reading `how` of the test route's thing whose law holds for `held` seconds.
    fn reading(how: Reading, held: f64) -> TrackRoute {
        let (mut r, _) = test_route();
        r.track.reading = how;
        r.laws[0].last_s = r.laws[0].first_s + held;
        r
    }

    #[test]
    fn of_readings_held_alike_the_rods_and_else_the_longest() {
        // The swings suite's 25° swing: its centroids held 5.72 s along a line (2.86 px rms),
        // its rod 5.28 s on its arc (0.06 px): within a tenth, the rod's.
        let all = [
            reading(Reading::Centroids, 5.72),
            reading(Reading::Rod, 5.28),
        ];
        assert_eq!(chosen(&all).unwrap().track.reading, Reading::Rod);
        // A rod held under nine tenths as long is not.
        let all = [
            reading(Reading::Centroids, 5.72),
            reading(Reading::Rod, 5.1),
        ];
        assert_eq!(chosen(&all).unwrap().track.reading, Reading::Centroids);
        // Of two readings held alike neither by a rod, of equal noise, the longer…
        let all = [
            reading(Reading::Matches, 5.3),
            reading(Reading::Centroids, 5.72),
        ];
        assert_eq!(chosen(&all).unwrap().track.reading, Reading::Centroids);
        // …and of unequal noise, the steadier.
        let mut steadier = reading(Reading::Matches, 5.3);
        steadier.track.noise = all[1].track.noise / 2.0;
        let all = [steadier, reading(Reading::Centroids, 5.72)];
        assert_eq!(chosen(&all).unwrap().track.reading, Reading::Matches);
    }
}
