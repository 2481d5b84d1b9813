//! The verdict on real recordings nobody here made: each shared recording (`--recordings`,
//! `../shared/real-videos/` by default; its README gives the readings and the known values)
//! estimated as a new user would, with only the readings the physics needs for SI and no
//! model, stride, crop or trim. Every candidate the model choice tried is an answer: right
//! where its law is the system's and its value is within the bar of the known one, wrong
//! otherwise (another law, or a value outside the bar; on the negative control every answer is
//! wrong). The detection rate is the share of wrong answers not graded ok, the false-alarm rate
//! the share of right answers not graded ok, over the chosen answers and over every candidate.
//! Then a few read as a lab would (`AS_A_LAB`: a stick in the picture, the floor at an impact),
//! rated apart.

use crate::options::{shown, Opt};
use crate::recordings::{Recording, AS_A_LAB, RECORDINGS};
use crate::runner::Runner;
use crate::table::{self, Cell, Table};
use estimator::digits::sig;
use estimator::verdict::Grade;

/// One candidate's answer on a recording, judged.
struct Answer {
    recording: String,
    model: String,
    chosen: bool,
    answer: String,
    /// The known value's relative error, where the law is the system's.
    error: Option<f64>,
    right: bool,
    grade: Grade,
    checks: String,
}

/// `name = value unit, …` (a candidate's answer line) → (name, value).
fn values(answer: &str) -> Vec<(String, f64)> {
    answer
        .split(", ")
        .filter_map(|part| {
            let (name, rest) = part.split_once(" = ")?;
            let value = rest.split_whitespace().next()?.parse::<f64>().ok()?;
            Some((name.trim().to_string(), value))
        })
        .collect()
}

pub fn make(r: &Runner) -> anyhow::Result<Table> {
    let dir = r.recordings.clone();
    let present = |set: &'static [Recording]| -> Vec<&'static Recording> {
        set.iter()
            .take(if r.quick() { 2 } else { set.len() })
            .filter(|rec| dir.join(rec.file).exists())
            .collect()
    };
    let chosen = present(&RECORDINGS);
    let lab = if r.quick() {
        Vec::new()
    } else {
        present(&AS_A_LAB)
    };
    r.begin("real", chosen.len() + lab.len());
    let mut answers = Vec::new();
    for rec in &chosen {
        answers.extend(answers_of(r, &dir, rec, rec.file.to_string(), false)?.0);
    }
    let mut as_lab = Vec::new();
    let mut frames = Vec::new();
    for rec in &lab {
        let label = format!("{} {}", rec.file, shown(rec.readings));
        let (answers, frame) = answers_of(r, &dir, rec, label, true)?;
        as_lab.extend(answers);
        frames.extend(frame.map(|jpeg| (rec, jpeg)));
    }
    let mut t = Table::new(
        "real",
        "The verdict on real recordings: every candidate's answer, right or wrong, and its grade",
        &[
            ("recording", "recording"),
            ("candidate", "model"),
            ("chosen", "chosen"),
            ("answer", "answer"),
            ("error against the known value", "error"),
            ("right", "right"),
            ("grade", "grade"),
            ("checks with reasons", "checks"),
        ],
    );
    for a in answers.iter().chain(&as_lab) {
        t.push(vec![
            Cell::text(&a.recording),
            Cell::text(&a.model),
            Cell::text(if a.chosen { "yes" } else { "" }),
            Cell::text(&a.answer),
            Cell::rel(a.error),
            Cell::text(if a.right { "yes" } else { "no" }),
            Cell::text(a.grade.name()),
            Cell::text(&a.checks),
        ]);
    }
    for (what, set) in [
        (
            "chosen answers",
            answers.iter().filter(|a| a.chosen).collect::<Vec<_>>(),
        ),
        ("answers of every candidate", answers.iter().collect()),
    ] {
        t.note(rates(what, &set));
    }
    if !as_lab.is_empty() {
        t.note(rates(
            "answers read as a lab would (the last rows: a stick, the floor at the impact)",
            &as_lab.iter().collect::<Vec<_>>(),
        ));
    }
    let looked_for = if r.quick() { 2 } else { RECORDINGS.len() };
    if chosen.len() < looked_for {
        t.note(format!(
            "{} of the {} recordings were not found in {} (--recordings).",
            looked_for - chosen.len(),
            looked_for,
            dir.display()
        ));
    }
    t.note(
        "Runs: `estimate FILE READINGS --seed 0`, the readings as the recordings' README offers \
         them (the incline's tilt and distances, the ball's and the jar's times and heights), no \
         --model, --crop, --start/--end or --stride. Right: the candidate's law is the \
         system's (for the pendulum and the springs both the oscillator and the pendulum: at \
         small swings one is the other) and its value within \
         2 % of the known one (falls and inclines 3 %). Candidates that gave no estimate are \
         left out.",
    );
    for rec in &chosen {
        t.note(format!("{}: {}.", rec.file, rec.source));
    }
    for rec in &lab {
        t.note(format!(
            "{} {}: {} (no --reference where a stick is given; the bars are issue 64's).",
            rec.file,
            shown(rec.readings),
            rec.source
        ));
    }
    for (rec, jpeg) in frames {
        let stem = rec.file.rsplit_once('.').map_or(rec.file, |s| s.0);
        let stick = rec.readings.iter().any(|o| matches!(o, Opt::Stick(_)));
        let caption = format!(
            "{} {}: its frame.jpg, the track in white (blue where its law holds){}",
            rec.file,
            shown(rec.readings),
            if stick { ", the stick in orange" } else { "" }
        );
        t.picture(format!("real-{stem}.jpg"), jpeg, &caption);
    }
    Ok(t)
}

/// Every answer on the recording `rec` (in `dir`), read with its readings and seed 0, labelled
/// `label`: every candidate where the model was chosen, else the one run's; and, `pictured`,
/// the run's frame.jpg where it ran here.
fn answers_of(
    r: &Runner,
    dir: &std::path::Path,
    rec: &Recording,
    label: String,
    pictured: bool,
) -> anyhow::Result<(Vec<Answer>, Option<Vec<u8>>)> {
    let mut answers = Vec::new();
    let mut opts = rec.readings.to_vec();
    opts.push(Opt::Seed(0));
    let (run, frame) = if pictured {
        r.estimate_pictured(&dir.join(rec.file), &opts)?
    } else {
        (r.estimate(&dir.join(rec.file), &opts)?, None)
    };
    // Every candidate where the model was chosen; where the object's track guided the run to
    // one law on its span, that answer alone.
    let tried: Vec<(String, Option<Grade>, String, String, bool)> = match &run.model_choice {
        Some(choice) => choice
            .candidates
            .iter()
            .map(|c| {
                let chosen = c.model == choice.chosen;
                let reasons = c.reasons.join(", ");
                (c.model.clone(), c.grade, c.answer.clone(), reasons, chosen)
            })
            .collect(),
        None => {
            // The track's values in metres (by a stick or on a plane) beside the latent's.
            let track = run.track.as_ref().map_or(&[][..], |t| t.si());
            let answer = run
                .parameters
                .iter()
                .filter(|p| p.units == "SI")
                .map(|p| format!("{} = {} {}", p.name, sig(p.estimate), p.unit))
                .chain(
                    track
                        .iter()
                        .map(|v| format!("track's {} = {} {}", v.name, sig(v.value), v.unit)),
                )
                .collect::<Vec<_>>()
                .join(", ");
            let grade = Some(run.verdict.grade);
            let reasons = table::checks_named(&run.verdict);
            vec![(run.model.clone(), grade, answer, reasons, true)]
        }
    };
    for (model, grade, answer, checks, chosen) in tried {
        let Some(grade) = grade else { continue };
        let error = rec.known.iter().filter(|k| k.model == model).find_map(|k| {
            values(&answer)
                .into_iter()
                .find(|(n, _)| n == k.parameter)
                .map(|(_, v)| (v / k.value - 1.0, k.bar))
        });
        answers.push(Answer {
            recording: label.clone(),
            model,
            chosen,
            answer,
            error: error.map(|e| e.0),
            right: error.is_some_and(|(e, bar)| e.abs() <= bar),
            grade,
            checks,
        });
    }
    Ok((answers, frame))
}

/// The detection and false-alarm rates over `answers`, in a sentence about `what`.
fn rates(what: &str, answers: &[&Answer]) -> String {
    let (right, wrong): (Vec<&&Answer>, Vec<&&Answer>) = answers.iter().partition(|a| a.right);
    let not_ok = |set: &[&&Answer]| set.iter().filter(|a| a.grade != Grade::Ok).count();
    table::rates(
        what,
        (right.len(), not_ok(&right)),
        (wrong.len(), not_ok(&wrong)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_candidates_answer_line_reads_as_its_values() {
        assert_eq!(
            values("length = 1.12710 m, damping = 2.77877e-6 1/s, g_over_l = 8.70378 1/s^2"),
            vec![
                ("length".to_string(), 1.1271),
                ("damping".to_string(), 2.77877e-6),
                ("g_over_l".to_string(), 8.70378)
            ]
        );
        assert_eq!(
            values("g = 10.0183 m/s^2"),
            vec![("g".to_string(), 10.0183)]
        );
        assert!(values("no estimate: the training diverged").is_empty());
    }
}
