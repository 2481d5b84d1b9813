//! The ranking of fitted candidates: which law the evidence favours, and whether the call is
//! close. Pure arithmetic on each candidate's verdict, law fit and parameter count, so the rule
//! is tested here without training anything.

use crate::verdict::grade::Grade;
use serde::Serialize;

/// Within this factor of the best unexplained share, a candidate explains the motion as well as
/// the best (the rest is training noise: the same law fitted twice differs by this much).
pub const TIE_FACTOR: f64 = 3.0;

/// Below this share of the motion within clips left unexplained, every candidate explains the
/// frames equally well (their residuals are the pictures' own noise and the encoder's).
pub const TIE_FLOOR: f64 = 1e-3;

/// (richer, nested): laws that hold another as a limit (the pendulum is the oscillator at
/// small swings). The richer one has more freedom, yet it is chosen when the nested one is
/// graded worse: the nested law's doubt (its frequency differs between small and large
/// swings) is what the richer law explains. Where the nested law is chosen and the richer one
/// explains the motion too, the choice says how their answers relate (the third member).
pub const NESTED: &[(&str, &str, &str)] = &[(
    "pendulum",
    "damped-oscillator",
    "the oscillator is the pendulum at small swings, gamma0 = g/L, gamma1 its damping",
)];

/// How `nested`'s answer relates to `richer`'s, where one holds the other as a limit.
fn limit(richer: &str, nested: &str) -> Option<&'static str> {
    NESTED
        .iter()
        .find(|(r, n, _)| *r == richer && *n == nested)
        .map(|(_, _, how)| *how)
}

/// One candidate as the ranking sees it.
#[derive(Debug, Clone, Serialize)]
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
    /// Whether it explains the motion as well as the best (within [`TIE_FACTOR`] or below
    /// [`TIE_FLOOR`]) without being unreliable: the set the choice is made in.
    pub explains: bool,
}

/// What the choice found, in report.json's `model_choice`.
#[derive(Debug, Clone, Serialize)]
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

    /// One line: the model, its grade and unexplained share, its answer.
    pub fn line(&self) -> String {
        match self.grade {
            Some(g) => format!(
                "{:<18} {:<10} {:>9}  {}",
                self.model,
                g.name(),
                self.unexplained_text(),
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
            "model chosen: {} ({})\n{:<18} {:<10} {:>9}  answer\n",
            self.chosen, self.why, "candidate", "verdict", "unexpl."
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

/// Ranks `candidates` (in the order tried) and returns the choice, or `None` when none gave an
/// estimate.
pub fn rank(mut candidates: Vec<Candidate>) -> Option<ModelChoice> {
    let fitted = |c: &Candidate| c.grade.is_some();
    let usable = |c: &Candidate| fitted(c) && c.grade != Some(Grade::Unreliable);
    // Unreliable candidates compete only when every candidate is.
    let desperate = !candidates.iter().any(usable);
    let pool: Vec<usize> = if !desperate {
        (0..candidates.len())
            .filter(|&i| usable(&candidates[i]))
            .collect()
    } else {
        (0..candidates.len())
            .filter(|&i| fitted(&candidates[i]))
            .collect()
    };
    let u = |c: &Candidate| {
        c.unexplained
            .filter(|u| u.is_finite())
            .unwrap_or(f64::INFINITY)
    };
    let best = pool
        .iter()
        .map(|&i| u(&candidates[i]))
        .fold(f64::INFINITY, f64::min);
    let bar = (TIE_FACTOR * best).max(TIE_FLOOR);
    for &i in &pool {
        candidates[i].explains = u(&candidates[i]) <= bar;
    }
    // The choice: among those that explain the motion as well as the best, the one with the
    // least freedom (parameters and per-clip states the data do not need), then the better
    // grade, then the smaller share left.
    let key = |c: &Candidate| {
        (
            !c.explains,
            c.freedom(),
            c.grade.unwrap_or(Grade::Unreliable),
            u(c).to_bits(),
        )
    };
    candidates.sort_by(|a, b| match (fitted(a), fitted(b)) {
        (true, true) => key(a).cmp(&key(b)),
        (a, b) => b.cmp(&a),
    });
    // A nested law graded worse than its richer law, which explains the motion as well, gives
    // way to it.
    let richer = candidates.first().and_then(|first| {
        candidates.iter().position(|c| {
            c.explains && c.grade < first.grade && limit(&c.model, &first.model).is_some()
        })
    });
    if let Some(i) = richer {
        let c = candidates.remove(i);
        candidates.insert(0, c);
    }
    let first = candidates.first().filter(|c| fitted(c))?.clone();
    let close = candidates
        .get(1)
        .filter(|c| c.explains && c.grade == first.grade && c.freedom() == first.freedom());
    let mut why = match (desperate, candidates.iter().filter(|c| c.explains).count()) {
        _ if richer.is_some() => format!(
            "{} explains the motion as well as the simpler law it holds as a limit, {}, which the verdict doubts",
            first.model, candidates[1].model
        ),
        (true, _) => "every candidate's fit is unreliable; the least unexplained motion kept".into(),
        (false, 1) => format!(
            "the only candidate whose law explains the motion (the others leave more than {TIE_FACTOR}× its unexplained share, or are unreliable)"
        ),
        (false, n) => format!(
            "{n} candidates explain the motion about as well; the one with the least freedom (parameters and per-clip states), then the better verdict, then the least unexplained motion kept"
        ),
    };
    // The nested law kept where its richer law explains as well: the two answers are one.
    let kept_limit = candidates
        .iter()
        .filter(|c| c.explains && richer.is_none())
        .find_map(|c| Some((c.model.as_str(), limit(&c.model, &first.model)?)));
    if let Some((wider, how)) = kept_limit {
        why.push_str(&format!(
            "; the data do not show {wider}'s further freedom: {how} ({wider}'s answer is in its row)"
        ));
    }
    Some(ModelChoice {
        chosen: first.model.clone(),
        close: close.map(|c| c.model.clone()),
        candidates,
        why,
        cut: None,
        wall_time_s: 0.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(model: &str, grade: Option<Grade>, u: f64, parameters: usize) -> Candidate {
        Candidate {
            model: model.into(),
            grade,
            unexplained: Some(u),
            parameters,
            clip_states: 0,
            answer: String::new(),
            reasons: Vec::new(),
            explains: false,
        }
    }

    #[test]
    fn the_simpler_law_wins_when_both_explain_the_motion() {
        // The pendulum nests the oscillator: on small swings it fits as well, with more
        // parameters.
        let r = rank(vec![
            c("damped-oscillator", Some(Grade::Ok), 1.6e-4, 2),
            c("pendulum", Some(Grade::Ok), 7e-6, 4),
            c("led", Some(Grade::Unreliable), 0.9, 1),
        ])
        .unwrap();
        assert_eq!(r.chosen, "damped-oscillator");
        assert_eq!(r.close, None);
        assert_eq!(r.candidates[2].model, "led");
        // Said to be the pendulum's limit, whose answer is the same.
        assert!(r.why.contains("gamma0 = g/L"), "{}", r.why);
        // Not where the pendulum does not explain the motion.
        let r = rank(vec![
            c("damped-oscillator", Some(Grade::Ok), 1.6e-3, 2),
            c("pendulum", Some(Grade::Ok), 9e-2, 4),
        ])
        .unwrap();
        assert!(!r.why.contains("g/L"), "{}", r.why);
    }

    #[test]
    fn less_freedom_beats_a_better_grade_and_a_clear_misfit_loses() {
        // Large swings: the oscillator leaves six times the pendulum's share.
        let r = rank(vec![
            c("damped-oscillator", Some(Grade::Doubtful), 2.8e-3, 2),
            c("pendulum", Some(Grade::Ok), 4.7e-4, 4),
        ])
        .unwrap();
        assert_eq!(r.chosen, "pendulum");
        // Smaller swings: within the tie, yet the oscillator's doubt is the pendulum's law.
        let r = rank(vec![
            c("damped-oscillator", Some(Grade::Doubtful), 1.1e-3, 2),
            c("pendulum", Some(Grade::Ok), 5.9e-4, 4),
        ])
        .unwrap();
        assert_eq!(r.chosen, "pendulum");
        // A fall with known start times fits no velocity per clip: the tank's law, with one
        // more parameter, is not needed even where the verdict doubts the fall.
        let mut fall = c("free-fall", Some(Grade::Doubtful), 8.0e-3, 1);
        fall.clip_states = 1;
        let mut tank = c("torricelli", Some(Grade::Ok), 4.4e-3, 2);
        tank.clip_states = 1;
        assert_eq!(rank(vec![tank, fall]).unwrap().chosen, "free-fall");
        let r = rank(vec![
            c("torricelli", Some(Grade::Ok), 7.7e-4, 2),
            c("free-fall", Some(Grade::Ok), 5.1e-3, 2),
        ])
        .unwrap();
        assert_eq!(r.chosen, "torricelli");
        assert!(!r.candidates[1].explains && r.close.is_none());
    }

    #[test]
    fn alike_candidates_are_a_close_call_and_no_estimate_ranks_last() {
        let mut none = c("spring", None, f64::NAN, 5);
        none.unexplained = None;
        let r = rank(vec![
            none,
            c("torricelli", Some(Grade::Ok), 2.0e-3, 2),
            c("led", Some(Grade::Ok), 1.5e-3, 2),
        ])
        .unwrap();
        assert_eq!(r.chosen, "led");
        assert_eq!(r.close.as_deref(), Some("torricelli"));
        assert_eq!(r.candidates[2].model, "spring");
        assert!(rank(vec![c("x", None, 0.1, 1)]).is_none());
        // All unreliable: the least unexplained is kept, and said to be so.
        let r = rank(vec![
            c("a", Some(Grade::Unreliable), 0.5, 1),
            c("b", Some(Grade::Unreliable), 0.05, 1),
        ])
        .unwrap();
        assert_eq!(r.chosen, "b");
        assert!(r.why.starts_with("every candidate"), "{}", r.why);
    }
}
