//! The answer against the frames it came from: a motion faster than frames dt apart can sample,
//! or too slow to show within a clip (a wrong dt, or the wrong model).

use super::{Check, Grade, Reason};
use crate::analysis::Run;
use physvid_shared::cli::approx;

pub struct Sampling;

/// The least phase (rad) or decay a clip must span of the answer's motion to have shown it.
pub const MIN_SPAN: f64 = 0.05;
/// The phase (rad) an oscillation's clips must span, half a period, for its frequency to rest
/// on more than their curvature (which any steady acceleration or decay gives too: a fall read
/// as a slow swing spans 0.19 rad per clip, a draining tank read as a 1.5-km pendulum 1.55
/// rad; the oscillating scenes and recordings the tool has seen span 4.8 rad or more).
pub const MIN_OSCILLATION_SPAN: f64 = std::f64::consts::PI;

impl Check for Sampling {
    fn name(&self) -> &'static str {
        "sampling"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let model = r.config.model;
        let Some(rate) = model.rate(&r.final_values).filter(|v| v.is_finite()) else {
            return Vec::new();
        };
        let (frames, dt) = (r.shape[1], r.dt);
        let span = frames.saturating_sub(1) as f64 * dt;
        if rate * dt > std::f64::consts::PI {
            return vec![Reason::new(
                self.name(),
                Grade::Unreliable,
                format!(
                    "the answer's motion (rate {} /s) is faster than frames {} s apart can \
                     sample (rate·dt = {} > π): it cannot have been seen; check dt (--dt, or \
                     --stride and --fps) and the model",
                    approx(rate),
                    approx(dt),
                    approx(rate * dt)
                ),
            )
            .measured(rate * dt, std::f64::consts::PI)];
        }
        if rate * span < MIN_SPAN {
            return vec![Reason::new(
                self.name(),
                Grade::Unreliable,
                format!(
                    "the answer's motion (rate {} /s) spans only {} rad over a clip of {} s: the \
                     clips barely show it; check dt (--dt, or --stride and --fps) and the model",
                    approx(rate),
                    approx(rate * span),
                    approx(span)
                ),
            )
            .measured(rate * span, MIN_SPAN)];
        }
        if model.oscillates(&r.final_values) && rate * span < MIN_OSCILLATION_SPAN {
            return vec![Reason::new(
                self.name(),
                Grade::Doubtful,
                format!(
                    "each clip spans only {} rad of the answer's oscillation (less than half a \
                     period: no clip shows it swing back): its frequency rests on the clips' \
                     curvature alone, which a steady acceleration or decay gives too; longer \
                     clips (--frames-per-clip, --stride) or another model",
                    approx(rate * span)
                ),
            )
            .measured(rate * span, MIN_OSCILLATION_SPAN)];
        }
        Vec::new()
    }
}
