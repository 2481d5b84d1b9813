//! The verdict's types: a `Grade`, the `Reason`s the checks give, and the `Verdict` (the
//! worst grade and the reasons). Kept apart from the checks, which read the pipeline's `Run`,
//! so that the model choice can grade its candidates without depending on them.

use serde::{Deserialize, Deserializer, Serialize};

/// How far an answer can be trusted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Grade {
    /// Nothing the checks can see speaks against it.
    Ok,
    /// Something speaks against it: read the reasons before using it.
    Doubtful,
    /// It is most likely wrong (or not determined by the data): do not use it as it stands.
    Unreliable,
}

impl Grade {
    pub fn name(self) -> &'static str {
        match self {
            Grade::Ok => "ok",
            Grade::Doubtful => "doubtful",
            Grade::Unreliable => "unreliable",
        }
    }

    /// The grade of a measure that must reach `doubtful_below` (unreliable under
    /// `unreliable_below`); `None` where it does.
    pub fn below(value: f64, unreliable_below: f64, doubtful_below: f64) -> Option<Grade> {
        if value < unreliable_below {
            Some(Grade::Unreliable)
        } else if value < doubtful_below {
            Some(Grade::Doubtful)
        } else {
            None
        }
    }
}

/// One finding of one check.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Reason {
    /// The check's name (read back as the name in [`super::CHECKS`]).
    #[serde(deserialize_with = "check_name")]
    pub check: CheckName,
    pub grade: Grade,
    /// What was found and what to do about it.
    pub detail: String,
    /// The figure the check measured, and the limit it was held against, where there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub value: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit: Option<f64>,
}

impl Reason {
    pub fn new(check: &'static str, grade: Grade, detail: impl Into<String>) -> Reason {
        Reason {
            check,
            grade,
            detail: detail.into(),
            value: None,
            limit: None,
        }
    }

    /// The figure measured and the limit it crossed.
    pub fn measured(mut self, value: f64, limit: f64) -> Reason {
        self.value = Some(value);
        self.limit = Some(limit);
        self
    }

    /// This reason as a note (`Grade::Ok`) where `answered` says why what it found is not held
    /// against the answer (the words appended to its detail); as it is otherwise.
    pub fn unless(mut self, answered: Option<String>) -> Reason {
        if let Some(why) = answered {
            self.grade = Grade::Ok;
            self.detail = format!("{}; {why}", self.detail);
        }
        self
    }
}

/// A check's name. Named so that serde's derive reads it with `check_name` instead of
/// borrowing a `&str` from the input, which a `'static` one cannot.
pub type CheckName = &'static str;

/// A check's name read back from report.json: the `&'static str` of the check in
/// [`super::CHECKS`] that has it.
fn check_name<'de, D: Deserializer<'de>>(d: D) -> Result<&'static str, D::Error> {
    let name = String::deserialize(d)?;
    super::CHECKS
        .iter()
        .map(|c| c.name())
        .chain([super::CHOICE])
        .find(|n| *n == name)
        .ok_or_else(|| serde::de::Error::custom(format!("no check is named {name:?}")))
}

/// The verdict: the worst grade among the reasons (`ok` without any).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Verdict {
    pub grade: Grade,
    pub reasons: Vec<Reason>,
}

impl Verdict {
    /// The verdict of `reasons`: the worst grade, the reasons worst first (in their order at
    /// equal grade).
    pub fn of(mut reasons: Vec<Reason>) -> Verdict {
        reasons.sort_by_key(|r| std::cmp::Reverse(r.grade));
        Verdict {
            grade: reasons.iter().map(|r| r.grade).max().unwrap_or(Grade::Ok),
            reasons,
        }
    }

    /// This verdict with `more` reasons weighed in.
    pub fn with(self, more: impl IntoIterator<Item = Reason>) -> Verdict {
        Verdict::of(self.reasons.into_iter().chain(more).collect())
    }

    /// The verdict as lines for the terminal.
    pub fn text(&self) -> String {
        let mut s = format!("verdict: {}", self.grade.name());
        if self.reasons.is_empty() {
            s += " (no check found anything against this answer)";
        }
        for r in &self.reasons {
            s += &format!("\n  - {} [{}]: {}", r.check, r.grade.name(), r.detail);
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_verdict_reads_back_from_its_json_with_every_check_by_name() {
        let reasons: Vec<Reason> = super::super::CHECKS
            .iter()
            .map(|c| Reason::new(c.name(), Grade::Doubtful, "x").measured(0.5, 0.2))
            .collect();
        let v = Verdict {
            grade: Grade::Doubtful,
            reasons,
        };
        let back: Verdict = serde_json::from_str(&serde_json::to_string(&v).unwrap()).unwrap();
        assert_eq!(back.grade, Grade::Doubtful);
        let names = |v: &Verdict| v.reasons.iter().map(|r| r.check).collect::<Vec<_>>();
        assert_eq!(names(&back), names(&v));
        assert_eq!(back.reasons[0].value, Some(0.5));
        let unknown = r#"{"grade":"ok","reasons":[{"check":"nonesuch","grade":"ok","detail":""}]}"#;
        let e = serde_json::from_str::<Verdict>(unknown).unwrap_err();
        assert!(e.to_string().contains("nonesuch"), "{e}");
    }

    #[test]
    fn a_reason_answered_is_a_note_that_says_why() {
        let doubt = || Reason::new("law", Grade::Doubtful, "10 % unexplained").measured(0.1, 0.05);
        let kept = doubt().unless(None);
        assert_eq!(
            (kept.grade, kept.detail.as_str()),
            (Grade::Doubtful, "10 % unexplained")
        );
        let note = doubt().unless(Some("the track measures the same rate".into()));
        assert_eq!(note.grade, Grade::Ok);
        assert_eq!(
            note.detail,
            "10 % unexplained; the track measures the same rate"
        );
        assert_eq!((note.value, note.limit), (Some(0.1), Some(0.05)));
        assert_eq!(Verdict::of(vec![note]).grade, Grade::Ok);
    }
}
