//! Consistency: the answer refitted on halves of the training clips must agree within the
//! halves' own errors: the earlier and the later clips (a recording's parts), the clips low and
//! high in the latent's range, and those with small and large motions. A wrong law fits each
//! part of the range with other parameters (an exponential decay fitted to a draining tank
//! decays faster where the level is low); halves that disagree in order say the motion changes
//! over the recording. Only values in SI units are compared: a latent-unit value moves with
//! the latent's arbitrary map (a tank's k_latent along with its base, while k stays put).

use super::{Check, Grade, Reason};
use crate::report::Report;
use physvid_shared::cli::approx;

pub struct Halves;

/// Halves further apart than this many standard errors of their difference, and by more than
/// [`MATERIAL`] of the value, are doubtful: the errors leave the encoder's own small bias
/// across the range out (correct answers on `gen`'s scenes differ by up to 1.2 % between
/// halves, at up to 26 standard errors), and the verdict is about differences that matter.
pub const DISAGREE: f64 = 5.0;
pub const MATERIAL: f64 = 0.02;

impl Check for Halves {
    fn name(&self) -> &'static str {
        "consistency"
    }
    fn judge(&self, r: &Report) -> Vec<Reason> {
        let mut out = Vec::new();
        // Values in latent units move along with the latent's arbitrary map (a tank's k_latent
        // with its base); only what the physics fixes is compared.
        for p in r.parameters.iter().filter(|p| p.units == "SI") {
            let worst = p
                .splits
                .iter()
                .filter_map(|s| {
                    let [Some(ea), Some(eb)] = s.errors else {
                        return None;
                    };
                    let [a, b] = s.values;
                    let z = (a - b).abs() / ea.hypot(eb).max(1e-300);
                    let rel = (a - b).abs() / a.abs().max(b.abs()).max(1e-300);
                    (z.is_finite() && rel > MATERIAL).then_some((z, s))
                })
                .max_by(|x, y| x.0.total_cmp(&y.0));
            let Some((z, s)) = worst.filter(|(z, _)| *z > DISAGREE) else {
                continue;
            };
            let [first, second] = s.by.halves();
            out.push(
                Reason::new(
                    self.name(),
                    Grade::Doubtful,
                    format!(
                        "{} refitted on {first} and on {second} disagree ({} and {}, {} standard \
                         errors apart): the law does not hold alike over the data (another \
                         model?), or the motion changes over the recording",
                        p.name,
                        approx(s.values[0]),
                        approx(s.values[1]),
                        approx(z)
                    ),
                )
                .measured(z, DISAGREE),
            );
        }
        out
    }
}
