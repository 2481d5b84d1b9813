//! Consistency: the answer refitted on halves of the training clips must agree within the
//! halves' own errors: the earlier and the later clips (a recording's parts), the clips low and
//! high in the latent's range, and those with small and large motions. A wrong law fits each
//! part of the range with other parameters (an exponential decay fitted to a draining tank
//! decays faster where the level is low); halves that disagree in order say the motion changes
//! over the recording. Only values in SI units are compared: a latent-unit value moves with
//! the latent's arbitrary map (a tank's k_latent along with its base, while k stays put).
//! Each half's standard error is taken at least as large as the whole answer's: a half cannot
//! pin the value better than all the data, and a half of a short recording has few blocks of
//! time to estimate its own error from (a roll of 44 frames: halves at ±0.066 and ±0.0068
//! m/s², the whole ±0.11).
//! Where the object's track guides the run and corroborates the rate (its own halves agree by
//! this same rule and its whole rate is the latent's: `corroborates`), the latent's
//! halves that disagree are its encoder's gain over the motion's range, not the law's, and are
//! not held against the answer. So are its halves of a value the track measures beside that
//! rate (the oscillator's γ1, the pendulum's damping): the answer is then the track's
//! (`guide::combine`), with an error at least half the difference of the track's own halves, so
//! that a damping that changes over the span (dry friction: a larger γ1 as the swing dies
//! down) is in the answer's error bar, and what the latent's halves add is its encoder's gain.

use super::routes::{answered_by_track, corroborates};
use super::{Check, Grade, Reason};
use crate::agreement::apart;
use crate::analysis::Run;
use physvid_shared::cli::approx;

pub struct Halves;

impl Check for Halves {
    fn name(&self) -> &'static str {
        "consistency"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let mut out = Vec::new();
        // Values in latent units move along with the latent's arbitrary map (a tank's k_latent
        // with its base); only what the physics fixes is compared.
        for p in r.parameters.iter().filter(|p| p.units == "SI") {
            // A half determines the value no better than all the data do.
            let floor = p.standard_error.filter(|e| e.is_finite()).unwrap_or(0.0);
            let worst = p
                .splits
                .iter()
                .filter_map(|s| {
                    let [Some(ea), Some(eb)] = s.errors else {
                        return None;
                    };
                    apart(s.values, [ea.max(floor), eb.max(floor)]).map(|(z, limit)| (z, limit, s))
                })
                .max_by(|x, y| x.0.total_cmp(&y.0));
            let Some((z, limit, s)) = worst else {
                continue;
            };
            // The track's halves agree and its rate is the latent's: the law holds alike; a value
            // the track measures beside it is reported as the track's, its halves in its error.
            if corroborates(r, p) || answered_by_track(r, &p.name) {
                continue;
            }
            let [first, second] = s.by.halves();
            out.push(
                Reason::new(
                    self.name(),
                    Grade::Doubtful,
                    format!(
                        "{} refitted on {first} and on {second} disagree ({} and {}, {} standard \
                         errors apart): the law does not hold alike over the data (another \
                         model?), the motion changes over the recording, or the encoder reads \
                         large and small motions with different gains",
                        p.name,
                        approx(s.values[0]),
                        approx(s.values[1]),
                        approx(z)
                    ),
                )
                .measured(z, limit),
            );
        }
        out
    }
}
