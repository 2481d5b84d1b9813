//! Which reading of which thing is the object's: of the things followed, the one a law explains
//! the most motion of, and of its readings, the one held longest or by its rod.

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
    let held = |c: &&TrackRoute| c.held_s();
    let Some(long) = same
        .iter()
        .copied()
        .max_by(|a, b| held(a).total_cmp(&held(b)))
    else {
        return Some(most);
    };
    // Of the readings held alike in length (as `choose` weighs laws), the rod's, then the
    // longest.
    let rod = |c: &&TrackRoute| c.track.reading == Reading::Rod;
    let chosen = same
        .iter()
        .copied()
        .filter(|c| held(c) >= ALIKE * held(&long))
        .max_by(|a, b| {
            rod(a)
                .cmp(&rod(b))
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
        // Of two readings held alike neither by a rod, the longer.
        let all = [
            reading(Reading::Matches, 5.3),
            reading(Reading::Centroids, 5.72),
        ];
        assert_eq!(chosen(&all).unwrap().track.reading, Reading::Centroids);
    }
}
