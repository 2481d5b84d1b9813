//! A swing is no fall. A pendulum's first half swing, seen alone, is a descent from rest (it
//! starts still at one end and speeds up away from it), and a parabola fits it nearly as well
//! as the law of the swing fits the whole: a fall from rest once chose itself on a rod and bob
//! under a moving light (the others' suite, light at level 4). What tells them apart is what
//! follows: a swing comes back near where it began, again and again; a fall ends on the floor,
//! or bounces to a fraction of its height.

/// How near the start, as a share of the descent's travel, a return counts: a swing damped by
/// a quarter over the recording (the others' rod and bob) comes back within 8 %; a ball would
/// need a restitution over 0.87 to bounce back within it, and over 0.93 to do it twice.
const NEAR: f64 = 0.25;

/// The largest step between frames, as a share of the travel, by which an arrival near the
/// start counts as the object coming back (the shared ball: once it has landed, the path jumps
/// to the hand at the ceiling, 0.9 of the travel in a frame).
const STEP: f64 = 0.25;

/// How many returns make a swing.
const RETURNS: usize = 2;

/// Whether `path` (frame, pixels along it; time order) comes back near where its descent to
/// frame `last` began at least [`RETURNS`] times after it, leaving between returns for the far
/// half of the way.
pub fn swings(path: &[(usize, f64)], last: usize) -> bool {
    let (before, after): (Vec<&(usize, f64)>, Vec<_>) = path.iter().partition(|q| q.0 <= last);
    let Some(end) = before.last().map(|q| q.1) else {
        return false;
    };
    let start = before.iter().map(|q| q.1).fold(f64::INFINITY, f64::min);
    let travel = end - start;
    if travel <= 0.0 {
        return false;
    }
    let near = |p: f64| p <= start + NEAR * travel;
    let (mut returns, mut away) = (0, true);
    for w in after.windows(2) {
        let (from, to) = (w[0].1, w[1].1);
        // Arriving near the start from outside it, by a step, not a jump (something else
        // that moves there once the object has landed: the hand that dropped it).
        if away && near(to) && !near(from) && (to - from).abs() <= STEP * travel {
            returns += 1;
            away = false;
        } else if !away && to >= start + 0.5 * travel {
            away = true;
        }
    }
    returns >= RETURNS
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_swing_comes_back_and_a_bounce_does_not() {
        // A swing from −30 to 30 px, a period of 60 frames, damped by a quarter over 160.
        let swing: Vec<(usize, f64)> = (0..160)
            .map(|k| {
                let t = k as f64;
                (
                    k,
                    -30.0 * (-0.0018 * t).exp() * (std::f64::consts::TAU * t / 60.0).cos(),
                )
            })
            .collect();
        assert!(swings(&swing, 30));
        // Only one period seen: one return, not a swing yet.
        assert!(!swings(&swing[..75], 30));
        // A ball falling 200 px and bouncing to 60 % and 36 % of that.
        let mut bounce: Vec<(usize, f64)> = (0..=20).map(|k| (k, 0.5 * (k * k) as f64)).collect();
        for h in [0.6, 0.36] {
            let half = (20.0 * f64::sqrt(h)).round() as usize;
            let from = bounce.len();
            bounce.extend((0..2 * half).map(|j| {
                let u = j as f64 - half as f64;
                (from + j, 200.0 - 0.5 * (half as f64 * half as f64 - u * u))
            }));
        }
        assert!(!swings(&bounce, 20));
        // The ball on the floor, and something at the start moving now and then: jumps there.
        let mut landed = bounce[..=20].to_vec();
        for (j, p) in [200.0, 199.0, 2.0, 1.0, 200.0, 3.0, 2.0, 199.0]
            .iter()
            .enumerate()
        {
            landed.push((21 + j, *p));
        }
        assert!(!swings(&landed, 20));
    }
}
