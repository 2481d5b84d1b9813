//! The verdict's types: a `Grade`, the `Reason`s the checks give, and the `Verdict` (the
//! worst grade and the reasons). Kept apart from the checks, which read the report, so that
//! the report can hold a verdict without depending on them.

use serde::Serialize;

/// How far an answer can be trusted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
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
#[derive(Debug, Clone, Serialize)]
pub struct Reason {
    /// The check's name.
    pub check: &'static str,
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
}

/// The verdict: the worst grade among the reasons (`ok` without any).
#[derive(Debug, Clone, Serialize)]
pub struct Verdict {
    pub grade: Grade,
    pub reasons: Vec<Reason>,
}

impl Verdict {
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
