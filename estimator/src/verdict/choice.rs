//! The model's choice (`--model auto`): a call only the unexplained share decided, between
//! candidates graded alike with as many parameters, is a close one.

use super::{Check, Grade, Reason};
use crate::report::Report;

pub struct Choice;

impl Check for Choice {
    fn name(&self) -> &'static str {
        "choice"
    }
    fn judge(&self, r: &Report) -> Vec<Reason> {
        let Some(c) = &r.model_choice else {
            return Vec::new();
        };
        let Some(other) = &c.close else {
            return Vec::new();
        };
        let share = |name: &str| {
            c.candidates
                .iter()
                .find(|x| x.model == name)
                .and_then(|x| x.unexplained)
                .map_or("?".into(), |u| format!("{:.2} %", 100.0 * u))
        };
        vec![Reason::new(
            self.name(),
            Grade::Doubtful,
            format!(
                "a close call: {} and {other} explain the motion about as well ({} and {} of \
                 it left unexplained), with as many parameters and the same verdict; if you know \
                 the system, pass --model",
                c.chosen,
                share(&c.chosen),
                share(other)
            ),
        )]
    }
}
