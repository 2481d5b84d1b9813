//! A release read from crowded frames: a fall or slide from rest takes its clips' start times
//! from the release, the vertex of the parabola its first positions trace (`data::descent`).
//! Where something else moves or differs beside the object as it starts (the hand that held
//! it opening, or pulled back), those positions are pulled with it and the release moves by
//! frames; g goes as 1/(t − release)², so on a short fall each frame is a few per cent.

use super::{Check, Grade, Reason};
use crate::analysis::Run;
use physvid_shared::cli::approx;

pub struct Release;

/// The share of the descent's early frames that are crowded (`Descent::crowded`) from which
/// the answer is doubtful. Measured: falls drawn with nothing beside the ball (`descent_cli`'s
/// six, a 120-fps render) 0; a hand opening beside the ball 0.06 and 0.15 (release 0.4 and
/// 0.7 frames late, g −0.4 % and +1.4 %); a hand pulled back up as it lets go 0.30 (release
/// 8.5 frames early, g −16 %); the shared ball 0.45 in grey (release 2.7 frames late against
/// the one its colour shows at full resolution), 0 with its release read by its colour (`data::tinted`).
pub const DOUBTFUL_FROM: f64 = 0.2;

impl Check for Release {
    fn name(&self) -> &'static str {
        "release"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let Some(d) = r.recording.as_ref().and_then(|rec| rec.descent) else {
            return Vec::new();
        };
        if d.crowded < DOUBTFUL_FROM {
            return Vec::new();
        }
        vec![Reason::new(
            self.name(),
            Grade::Doubtful,
            format!(
                "something beside the object moves or differs where it starts (a hand letting \
                 go?): on {} % of the frames where the release is read, more than the object \
                 is measured there, so the release (frame {}) may be frames off, and with it \
                 every rate read from the fall; a recording where the object starts alone \
                 (the hand above it, out of the picture, or still until the object is clear), \
                 or an object whose colour sets it apart from what is beside it",
                approx(100.0 * d.crowded),
                approx(d.release)
            ),
        )
        .measured(d.crowded, DOUBTFUL_FROM)]
    }
}
