//! When two halves' values disagree: the rule by which a value refitted on the earlier and the
//! later half of its data (or the low and the high half of its range) says the law does not
//! hold alike over it. The verdict's consistency check applies it to the latent's halves, the
//! routes check to the track's, and the track's choice of law to each oscillation's span
//! (`track::choose`): one rule wherever halves are weighed.

/// Halves further apart than this many standard errors of their difference, and by more than
/// [`MATERIAL`] of the value, are doubtful: the errors leave the encoder's own small bias
/// across the range out (correct answers on `gen`'s scenes differ by up to 1.2 % between
/// halves, at up to 26 standard errors), and the verdict is about differences that matter.
pub const DISAGREE: f64 = 5.0;
pub const MATERIAL: f64 = 0.02;

/// Halves that differ by at least [`LARGE`] of the value are doubtful from this many standard
/// errors on. Measured before it was set: a damping read by the small MLP off a swinging
/// object it compresses (three renders held out of the tuning: a bob under a bright string,
/// bright and dark, a box under a dark spring; γ1 −28 %, −31 %, −68 %, all graded ok) put the
/// earlier and later halves 50–72 % apart at 4.0–4.4 standard errors; on the 162 model-choice
/// runs on `gen`'s scenes (three seeds, clean and two levels of footage of others) halves this
/// far apart at this many errors came twice: an LED's γ −11.6 % (graded ok) and one +2.0 %
/// (already doubtful); every other right answer's halves within 29 % or 2.3 errors.
pub const DISAGREE_LARGE: f64 = 3.5;
pub const LARGE: f64 = 0.4;

/// Halves that differ by at least [`VAST`] of the value (most of it: one half a damping, the
/// other next to none) are doubtful from this many standard errors on: the value is then not
/// what the data say alike over the recording. Set on the others' suite
/// (`scripts/others_suite.py`, seed 7), where a camera shaken by a pixel or two let the small
/// MLP read the damping 56 % and 79 % high, both graded ok: earlier and later halves 90 % and
/// 98 % apart at 2.6 and 3.0 errors (the later half near zero); no right answer there came
/// within reach (the furthest, 135 % apart at 1.3 errors), none of the shared recordings, and
/// none of the 162 model-choice runs (every right answer within 29 % or 2.3 errors). Held out
/// (the suite drawn with seed 11): it caught a damping read 31 % low under moving clutter
/// (123 % apart at 2.8 errors), and no right answer (the furthest 97 % apart at 1.5 errors).
pub const DISAGREE_VAST: f64 = 2.5;
pub const VAST: f64 = 0.8;

/// How many standard errors halves `values` with `errors` lie apart, and the limit they
/// crossed, where they disagree: beyond [`DISAGREE`] errors and [`MATERIAL`] of the value, or
/// beyond [`DISAGREE_LARGE`] errors and [`LARGE`] of it, or beyond [`DISAGREE_VAST`] errors
/// and [`VAST`] of it.
pub fn apart(values: [f64; 2], errors: [f64; 2]) -> Option<(f64, f64)> {
    let [a, b] = values;
    let z = (a - b).abs() / errors[0].hypot(errors[1]).max(1e-300);
    let rel = (a - b).abs() / a.abs().max(b.abs()).max(1e-300);
    if !z.is_finite() || !errors.iter().all(|e| e.is_finite()) {
        None
    } else if z > DISAGREE && rel > MATERIAL {
        Some((z, DISAGREE))
    } else if z > DISAGREE_LARGE && rel >= LARGE {
        Some((z, DISAGREE_LARGE))
    } else if z > DISAGREE_VAST && rel >= VAST {
        Some((z, DISAGREE_VAST))
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::apart;

    #[test]
    fn halves_far_apart_disagree_at_fewer_errors_than_halves_close_together() {
        // The box under a dark spring read by the small MLP: γ1 on the earlier and the later
        // half (4.4 errors, 72 % apart).
        let (z, limit) = apart([0.0243, 0.0867], [0.0013, 0.014]).expect("disagree");
        assert!((z - 4.4).abs() < 0.1 && limit == super::DISAGREE_LARGE);
        // As many errors apart but 4 % of the value: a right answer's spread.
        assert_eq!(apart([1.00, 1.04], [0.006, 0.006]), None);
        // 29 % apart at 2.3 errors (a right pendulum damping at level 2).
        assert_eq!(apart([0.071, 0.1], [0.009, 0.009]), None);
        // One half a damping, the other next to none, at 2.6 errors (the shaken rod and bob
        // read by the small MLP, γ1 +56 %); opposite signs 135 % apart at 1.3 errors (a right
        // answer under a moving light) stay.
        let (z, limit) = apart([0.1683, 0.0166], [0.0174, 0.0566]).expect("disagree");
        assert!(
            (z - 2.56).abs() < 0.02 && limit == super::DISAGREE_VAST,
            "{z}"
        );
        assert_eq!(apart([0.0834, -0.0292], [0.0701, 0.0490]), None);
        // Many errors apart and material: the first rule, as before.
        assert_eq!(
            apart([1.0, 1.1], [0.01, 0.01]).map(|a| a.1),
            Some(super::DISAGREE)
        );
        // No errors to weigh them by.
        assert_eq!(apart([1.0, 2.0], [f64::NAN, 0.1]), None);
    }
}
