//! The model choice's own reason in the chosen answer's verdict: a call only the unexplained
//! share decided, between candidates graded alike with as many parameters, is a close one.

use super::rank::ModelChoice;
use crate::verdict::{Grade, Reason, CHOICE};

/// What the choice `c` adds to its chosen answer's verdict: doubt where the call was close.
pub fn close_call(c: &ModelChoice) -> Option<Reason> {
    let other = c.close.as_ref()?;
    let share = |name: &str| {
        c.candidates
            .iter()
            .find(|x| x.model == name)
            .and_then(|x| x.unexplained)
            .map_or("?".into(), |u| format!("{:.2} %", 100.0 * u))
    };
    Some(Reason::new(
        CHOICE,
        Grade::Doubtful,
        format!(
            "a close call: {} and {other} explain the motion about as well ({} and {} of \
             it left unexplained), with as many parameters and the same verdict; if you know \
             the system, pass --model",
            c.chosen,
            share(&c.chosen),
            share(other)
        ),
    ))
}
