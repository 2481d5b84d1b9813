//! One candidate's fit as the ranking sees it (its verdict, its law's and its latent's
//! evidence, its freedom) and the choice the ranking makes of them, as printed and reported.

use crate::verdict::grade::Grade;
use serde::{Deserialize, Serialize};

/// One candidate as the ranking sees it.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Candidate {
    pub model: String,
    /// Its verdict (`None`: it gave no estimate).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grade: Option<Grade>,
    /// The share of the latent's motion within validation clips its rollout leaves
    /// unexplained (`evidence.law.unexplained_within`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unexplained: Option<f64>,
    /// The block's learned parameters (the law's, its map's, its offsets).
    pub parameters: usize,
    /// The states fitted to each clip besides them (the frames its rollout starts from).
    pub clip_states: usize,
    /// Its answer in a line (`name = value unit`, …), or why it gave none.
    pub answer: String,
    /// The checks that spoke against it.
    pub reasons: Vec<String>,
    /// The share of the picture (the frames' leading principal components) its latent explains
    /// as a function of it (`evidence.fold.explained_share`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub picture: Option<f64>,
    /// Whether it explains the motion as well as the best (within the ranking's tie factor or
    /// below its floor) without being unreliable or losing the picture: the set the choice is
    /// made in.
    pub explains: bool,
}

/// What the choice found, in report.json's `model_choice`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ModelChoice {
    pub chosen: String,
    /// Every candidate tried, the chosen first.
    pub candidates: Vec<Candidate>,
    /// A candidate that explains the motion as well, graded alike, with as much freedom: only
    /// the unexplained share separates them (a close call).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub close: Option<String>,
    /// How the choice was made, in words.
    pub why: String,
    /// How a recording was cut into clips for every candidate, and why.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cut: Option<String>,
    /// Seconds for every candidate's fit (and the chosen one's ensemble).
    pub wall_time_s: f64,
}

impl Candidate {
    /// What the candidate may adjust to fit: its parameters and each clip's starting states.
    pub fn freedom(&self) -> usize {
        self.parameters + self.clip_states
    }

    /// Its unexplained share as a percentage ("–" without one).
    pub fn unexplained_text(&self) -> String {
        self.unexplained
            .map_or("–".into(), |u| format!("{:.3} %", 100.0 * u))
    }

    /// The share of the picture its latent explains as a percentage ("–" without one).
    pub fn picture_text(&self) -> String {
        self.picture
            .map_or("–".into(), |e| format!("{:.1} %", 100.0 * e))
    }

    /// One line: the model, its grade, unexplained share and picture share, its answer.
    pub fn line(&self) -> String {
        match self.grade {
            Some(g) => format!(
                "{:<18} {:<10} {:>9} {:>8}  {}",
                self.model,
                g.name(),
                self.unexplained_text(),
                self.picture_text(),
                self.answer
            ),
            None => format!("{:<18} no estimate: {}", self.model, self.answer),
        }
    }
}

impl ModelChoice {
    /// The ranking as a table, the chosen first.
    pub fn text(&self) -> String {
        let mut out = format!(
            "model chosen: {} ({})\n{:<18} {:<10} {:>9} {:>8}  answer\n",
            self.chosen, self.why, "candidate", "verdict", "unexpl.", "picture"
        );
        if let Some(cut) = &self.cut {
            out.insert_str(
                out.find('\n').map_or(0, |i| i + 1),
                &format!("clips: {cut}\n"),
            );
        }
        for c in &self.candidates {
            out.push_str(&c.line());
            out.push('\n');
        }
        out
    }
}
