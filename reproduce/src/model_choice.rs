//! The model chosen by the evidence (`estimate DATA --model auto`) on `gen`'s scenes: every
//! built-in system of one latent number at its three settings, clean and under the two lowest
//! levels of footage of others (a texture behind, sensor noise and a drifting light together),
//! over seeds; the share chosen right and the confusion matrix. meta.json still gives each set's
//! calibration (a sliding block's incline, a fall's start times), never its model.

use crate::options::Opt;
use crate::runner::{DataSpec, Job, Runner};
use crate::table::{Cell, Table};
use std::collections::BTreeMap;

/// The scenes and the model each one is of.
const SCENES: [(&str, &str); 8] = [
    ("intensity", "damped-oscillator"),
    ("position", "damped-oscillator"),
    ("scale", "damped-oscillator"),
    ("pendulum", "pendulum"),
    ("torricelli", "torricelli"),
    ("sliding-block", "sliding-block"),
    ("led", "led"),
    ("free-fall", "free-fall"),
];

/// The footage of others at `level` (0: clean).
fn perturbed(level: u8) -> Vec<String> {
    match level {
        0 => Vec::new(),
        l => vec![
            "--perturb".into(),
            format!("texture:{l},noise:{l},drift:{l}"),
        ],
    }
}

pub fn make(r: &Runner) -> anyhow::Result<Table> {
    let quick = r.quick();
    let seeds: u64 = if quick { 1 } else { 3 };
    let levels: &[u8] = if quick { &[0] } else { &[0, 1, 2] };
    let settings = |scene: &str| -> &[u8] {
        match (quick, matches!(scene, "intensity" | "position" | "scale")) {
            (_, true) => &[1],
            (true, false) => &[2],
            (false, false) => &[1, 2, 3],
        }
    };
    let runs: usize = SCENES.iter().map(|(s, _)| settings(s).len()).sum::<usize>()
        * seeds as usize
        * levels.len();
    r.begin("model-choice", runs);
    let mut t = Table::new(
        "model-choice",
        "The model chosen by the evidence (--model auto) on gen's scenes",
        &[
            ("data", "data"),
            ("true model", "truth"),
            ("chosen", "chosen"),
            ("right", "right"),
            ("grade", "grade"),
            ("candidates (verdict, unexplained share)", "candidates"),
            ("wall s", "wall_s"),
        ],
    );
    let mut cases: Vec<(&str, DataSpec)> = Vec::new();
    for (scene, truth) in SCENES {
        for &setting in settings(scene) {
            for seed in 0..seeds {
                for &level in levels {
                    let mut spec = DataSpec::new(scene, quick);
                    (spec.setting, spec.seed, spec.extra) = (setting, seed, perturbed(level));
                    cases.push((truth, spec));
                }
            }
        }
    }
    let jobs: Vec<Job> = cases
        .iter()
        .map(|(_, spec)| Job::new(spec.clone(), vec![Opt::Model("auto")]))
        .collect();
    let runs = r.estimate_all(&jobs)?;
    let mut confusion: BTreeMap<(&str, String), usize> = BTreeMap::new();
    let (mut right, mut total) = (0, 0);
    for ((truth, spec), rep) in cases.iter().zip(&runs) {
        let truth = *truth;
        let choice = rep.model_choice.as_ref().expect("--model auto chooses");
        let ok = choice.chosen == truth;
        (right, total) = (right + ok as usize, total + 1);
        *confusion.entry((truth, choice.chosen.clone())).or_default() += 1;
        let ranking: Vec<String> = choice
            .candidates
            .iter()
            .map(|c| {
                format!(
                    "{} ({}, {})",
                    c.model,
                    c.grade.map_or("no estimate", |g| g.name()),
                    c.unexplained_text()
                )
            })
            .collect();
        t.push(vec![
            Cell::text(spec.command().replace("gen ", "")),
            Cell::text(truth),
            Cell::text(&choice.chosen),
            Cell::text(if ok { "yes" } else { "no" }),
            Cell::text(rep.verdict.grade.name()),
            Cell::text(ranking.join("; ")),
            Cell::num(Some(choice.wall_time_s), 1),
        ]);
    }
    t.note(format!(
        "The true model chosen in {right} of {total} runs ({:.1} %).",
        100.0 * right as f64 / total.max(1) as f64
    ));
    let chosen: Vec<&str> = {
        let mut c: Vec<&str> = confusion.keys().map(|(_, c)| c.as_str()).collect();
        c.sort();
        c.dedup();
        c
    };
    let mut matrix = format!(
        "Confusion (rows: true model; columns: chosen):\n\n| true \\ chosen | {} |\n|---|{}\n",
        chosen.join(" | "),
        "---|".repeat(chosen.len())
    );
    let mut truths: Vec<&str> = SCENES.iter().map(|(_, m)| *m).collect();
    truths.dedup();
    for truth in truths {
        let counts: Vec<String> = chosen
            .iter()
            .map(|c| {
                confusion
                    .get(&(truth, c.to_string()))
                    .map_or("·".into(), |n| n.to_string())
            })
            .collect();
        matrix += &format!("| {truth} | {} |\n", counts.join(" | "));
    }
    t.note(matrix);
    t.note(
        "Data: `gen --scenario SCENE` with the row's flags (500 clips of 50×50; --quick: 120 of \
         32×32, setting 2, seed 0, clean). Run: `estimate DATA --model auto` (each candidate's \
         default fit). Candidates: the built-in models of one latent number; sliding-block and \
         free-fall are one law, told apart by the calibration (an incline angle in meta.json), \
         so only one of them is tried on each set.",
    );
    Ok(t)
}
