//! Harmonics: a latent that is an even function of the motion (a bob's height, |x|) swings at
//! twice the motion's frequency, and the law fits it there as well as the motion at its own.
//! Such a latent folds a coordinate of the picture (see `evidence::fold`): one side of the
//! swing and the other give the same latent, so the picture's coordinate is not a function of
//! the latent while the latent is one of it. Where the object's track corroborates the rate
//! (`routes::corroborates`), the rates are not the fold's four times the motion's: a fold at the
//! doubtful tier is then a note. Where the track guides and its values are the answer, the
//! track's law is held against the same frames (`Evidence::track_fold`, as for `motion`) and
//! the lesser of the two folds is judged where that law follows the scene's main motion (the
//! `motion` check's limit): a folded latent beside a track's law that folds less is no second
//! opinion on the answer (a note), not a doubt of it.

use super::{motion, routes, Check, Grade, Reason};
use crate::analysis::Run;
use physvid_shared::cli::approx;

pub struct Harmonic;

use crate::evidence::fold::{FOLDED, MAYBE_FOLDED};

impl Check for Harmonic {
    fn name(&self) -> &'static str {
        "harmonic"
    }
    fn judge(&self, r: &Run) -> Vec<Reason> {
        let Some(latent) = r.evidence.fold.as_ref().map(|f| f.folded_share) else {
            return Vec::new();
        };
        let oscillates = r.config.model.rate(&r.final_values).is_some();
        // The track's law is a reference only where it follows the scene's main motion (the
        // `motion` check's limit): a tree's branches' law explains a fifth of its frames.
        let track = r
            .evidence
            .track_fold
            .as_ref()
            .filter(|f| f.explained_share >= motion::DOUBTFUL_BELOW)
            .map(|f| f.folded_share);
        let (share, whose) = match track.filter(|t| *t < latent) {
            Some(t) => (t, Whose::Track { latent }),
            None => (latent, Whose::Latent),
        };
        let Some(grade) = graded(share) else {
            return match whose {
                Whose::Track { latent } if graded(latent).is_some() => {
                    vec![no_second_opinion(self.name(), latent, share)]
                }
                _ => Vec::new(),
            };
        };
        let reason = folds(self.name(), grade, share, whose, oscillates);
        match grade {
            Grade::Doubtful => vec![reason.unless(routes::corroborated(r))],
            _ => vec![reason],
        }
    }
}

/// Whose fold is judged: the latent's, or the track's law's where it folds less than the
/// latent's (`latent`) and the answer is the track's.
#[derive(Clone, Copy)]
enum Whose {
    Latent,
    Track { latent: f64 },
}

/// The grade of a folded share (`None`: not folded).
fn graded(share: f64) -> Option<Grade> {
    if share >= FOLDED {
        Some(Grade::Unreliable)
    } else if share >= MAYBE_FOLDED {
        Some(Grade::Doubtful)
    } else {
        None
    }
}

/// The reason of a fold `share` graded `grade`.
fn folds(name: &'static str, grade: Grade, share: f64, whose: Whose, oscillates: bool) -> Reason {
    let consequence = if oscillates {
        "it follows an even function of the motion (a height, a distance from the middle), \
         which swings at twice the motion's frequency, so the rates come out about four \
         times too large (γ0, g/L); the fundamental is near a quarter of them: crop to the \
         object's path (--crop) or start there (--init ... --single-start)"
    } else {
        "it does not follow the motion one to one (an even function of it?): crop to the \
         object's path (--crop) and check the model"
    };
    let who = match whose {
        Whose::Latent => "the latent folds the picture".to_string(),
        Whose::Track { latent } => format!(
            "the object's track's law, whose values are the answer, folds the picture as the \
             latent does ({} %)",
            approx(100.0 * latent)
        ),
    };
    Reason::new(
        name,
        grade,
        format!(
            "{who}: frames on either side of the motion give the same value ({} % \
             of the frames' leading components differ between them by an amount it fixes); \
             {consequence}",
            approx(100.0 * share),
        ),
    )
    .measured(share, FOLDED)
}

/// The note of a `latent` folded where the track's law, whose values are the answer, folds
/// `track`, too little to grade.
fn no_second_opinion(name: &'static str, latent: f64, track: f64) -> Reason {
    Reason::new(
        name,
        Grade::Ok,
        format!(
            "the latent folds the picture ({} % of the frames' leading components differ \
             between the motion's sides by an amount it fixes) where the object's track's law, \
             whose values are the answer, folds {} %: the latent is no second opinion on them, \
             whatever its values",
            approx(100.0 * latent),
            approx(100.0 * track)
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lesser_fold_is_graded_and_a_folded_latent_beside_an_unfolded_track_noted() {
        // A 90° swing at 15 fps: the latent folds 18 %, the track's law 8.6 % (doubtful).
        let r = folds(
            "harmonic",
            Grade::Doubtful,
            0.086,
            Whose::Track { latent: 0.178 },
            true,
        );
        assert!(
            r.detail.contains("the object's track's law"),
            "{}",
            r.detail
        );
        assert!(r.detail.contains("(17.8 %)"), "{}", r.detail);
        assert_eq!(graded(0.086), Some(Grade::Doubtful));
        assert_eq!(graded(FOLDED), Some(Grade::Unreliable));
        assert_eq!(graded(0.049), None);
        // A tree's branches: the latent folds 10.8 %, the track's law nothing.
        let note = no_second_opinion("harmonic", 0.108, 0.0);
        assert_eq!(note.grade, Grade::Ok);
        assert!(note.detail.contains("no second opinion"), "{}", note.detail);
    }
}
