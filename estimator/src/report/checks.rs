//! Checks of an answer against the data it came from, reported as warnings: a motion faster
//! than the frames can sample or too slow to show within a clip (dt wrong, or the wrong
//! model), and parameters that training never moved from their start.

use crate::physics::ModelRef;
use physvid_shared::cli::approx;

/// The least phase (rad) or decay a clip must span of the answer's motion to have shown it.
pub const MIN_SPAN: f64 = 0.05;

/// Warnings about `params` (the answer) for clips of `frames` frames `dt` apart, trained from
/// `start`.
pub fn answer_warnings(
    model: ModelRef,
    params: &[f64],
    start: &[f64],
    frames: usize,
    dt: f64,
) -> Vec<String> {
    let mut warnings = Vec::new();
    if let Some(rate) = model.rate(params).filter(|r| r.is_finite()) {
        let span = frames.saturating_sub(1) as f64 * dt;
        if rate * dt > std::f64::consts::PI {
            warnings.push(format!(
                "the answer's motion (rate {} /s) is faster than frames {dt} s apart can sample \
                 (rate·dt = {} > π): it cannot have been seen; check dt (--dt, or --stride and \
                 --fps) and the model",
                approx(rate),
                approx(rate * dt)
            ));
        } else if rate * span < MIN_SPAN {
            warnings.push(format!(
                "the answer's motion (rate {} /s) spans only {} rad over a clip of {} s: the \
                 clips barely show it; check dt (--dt, or --stride and --fps) and the model",
                approx(rate),
                approx(rate * span),
                approx(span)
            ));
        }
    }
    let unmoved = params
        .iter()
        .zip(start)
        .all(|(p, s)| (p - s).abs() <= 1e-9 * s.abs().max(1e-12));
    if unmoved && !params.is_empty() {
        warnings.push(
            "training left every parameter at its start: nothing in the frames moved them, so \
             the values are the start, not a measurement"
                .to_string(),
        );
    }
    warnings
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn answers_the_frames_cannot_show_are_flagged() {
        let osc = ModelRef::by_name("damped-oscillator").unwrap();
        let start = [1.0, 0.1];
        // γ0 = 4 (ω = 2 rad/s), 20 frames of 0.2 s: seen.
        assert!(answer_warnings(osc, &[4.0, 0.08], &start, 20, 0.2).is_empty());
        let fast = answer_warnings(osc, &[4.0, 0.08], &start, 20, 2.0);
        assert!(fast[0].contains("faster than frames 2 s apart"), "{fast:?}");
        let slow = answer_warnings(osc, &[4.0, 0.08], &start, 20, 1e-4);
        assert!(slow[0].contains("barely show it"), "{slow:?}");
        let unmoved = answer_warnings(osc, &start, &start, 20, 0.2);
        assert!(unmoved[0].contains("left every parameter at its start"));
        // A draining tank has no rate to judge; it moved.
        let tank = ModelRef::by_name("torricelli").unwrap();
        assert!(answer_warnings(tank, &[0.2, -3.0], &[0.1, -3.0], 20, 1e-4).is_empty());
    }
}
