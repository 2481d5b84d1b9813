//! Footage we did not make, in miniature: every `gen --perturb` condition at every level on
//! the oscillator's scenes and the pendulum, default `estimate`, the error against the truth
//! and whether the verdict flagged the cells outside tolerance (γ0 2 %, γ1 10 %; the
//! pendulum's L 2 %).

use crate::runner::{DataSpec, Job, Runner};
use crate::table::{self, Cell, Table};
use estimator::verdict::Grade;
use generator::perturb::{MAX_LEVEL, PERTURBATIONS};

/// (scene, the values judged with their tolerances).
const SCENES: [(&str, &[(&str, f64)]); 4] = [
    ("intensity", &[("gamma0", 0.02), ("gamma1", 0.10)]),
    ("position", &[("gamma0", 0.02), ("gamma1", 0.10)]),
    ("scale", &[("gamma0", 0.02), ("gamma1", 0.10)]),
    ("pendulum", &[("length", 0.02)]),
];

pub fn make(r: &Runner) -> anyhow::Result<Table> {
    let levels: Vec<u8> = if r.quick() {
        vec![3]
    } else {
        (1..=MAX_LEVEL).collect()
    };
    let scenes: &[(&str, &[(&str, f64)])] = if r.quick() { &SCENES[1..2] } else { &SCENES };
    r.begin(
        "robustness",
        PERTURBATIONS.len() * levels.len() * scenes.len(),
    );
    let mut t = Table::new(
        "robustness",
        "Robustness: perturbed scenes, error and verdict",
        &[
            ("condition", "condition"),
            ("level", "level"),
            ("scene", "scene"),
            ("values (rel. error)", "values"),
            ("within tolerance", "within"),
            ("grade", "grade"),
            ("checks with reasons", "checks"),
            ("wall s", "wall_s"),
        ],
    );
    let mut cases = Vec::new();
    for (k, p) in PERTURBATIONS.iter().enumerate() {
        for &level in &levels {
            for &(scene, judged) in scenes {
                let mut spec = DataSpec::new(scene, r.quick());
                spec.extra = vec!["--perturb".into(), format!("{}:{level}", p.name())];
                cases.push((k, level, scene, judged, spec));
            }
        }
    }
    let jobs: Vec<Job> = cases
        .iter()
        .map(|c| Job::new(c.4.clone(), Vec::new()))
        .collect();
    let runs = r.estimate_all(&jobs)?;
    let (mut cells, mut within, mut outside_flagged, mut outside) = (0, 0, 0, 0);
    let mut per_condition: Vec<(usize, usize)> = vec![(0, 0); PERTURBATIONS.len()];
    for ((k, level, scene, judged, _), rep) in cases.iter().zip(&runs) {
        let p = PERTURBATIONS[*k];
        let errors: Vec<(String, Option<f64>, f64)> = judged
            .iter()
            .map(|(name, tol)| {
                let e = rep.value(name).and_then(|v| v.relative_error);
                (name.to_string(), e, *tol)
            })
            .collect();
        let ok = errors
            .iter()
            .all(|(_, e, tol)| e.is_some_and(|e| e.abs() <= *tol));
        let grade = rep.verdict.grade;
        cells += 1;
        per_condition[*k].1 += 1;
        if ok {
            within += 1;
            per_condition[*k].0 += 1;
        } else {
            outside += 1;
            outside_flagged += (grade != Grade::Ok) as usize;
        }
        let values: Vec<String> = errors
            .iter()
            .map(|(name, e, _)| {
                let v = rep.value(name).map_or(f64::NAN, |v| v.estimate);
                match e {
                    Some(e) => format!("{name} {v:.4} ({:+.2} %)", e * 100.0),
                    None => format!("{name} {v:.4}"),
                }
            })
            .collect();
        t.push(vec![
            Cell::text(p.name()),
            Cell::num(Some(*level as f64), 0),
            Cell::text(*scene),
            Cell::text(values.join("; ")),
            Cell::text(if ok { "yes" } else { "no" }),
            Cell::text(grade.name()),
            table::checks(&rep.verdict),
            Cell::num(Some(rep.wall_time_s), 1),
        ]);
    }
    t.note(format!(
        "Within tolerance: {within} of {cells} cells ({:.0} %); outside: {outside}, of which \
         {outside_flagged} graded doubtful or unreliable by the verdict (every one must be).",
        100.0 * within as f64 / cells.max(1) as f64
    ));
    let each: Vec<String> = PERTURBATIONS
        .iter()
        .zip(&per_condition)
        .map(|(p, (w, c))| format!("{} {w}/{c}", p.name()))
        .collect();
    t.note(format!("Per condition: {}.", each.join(", ")));
    let levels_text: Vec<String> = PERTURBATIONS
        .iter()
        .map(|p| format!("{}: {}", p.name(), p.help()))
        .collect();
    t.note(format!(
        "Data: `gen --scenario SCENE --perturb CONDITION:LEVEL` ({} clips of {}×{}, seed 0; the \
         pendulum at setting 1). Levels: {}.",
        DataSpec::new("position", r.quick()).samples,
        DataSpec::new("position", r.quick()).size,
        DataSpec::new("position", r.quick()).size,
        levels_text.join("; ")
    ));
    t.note(
        "Runs: `estimate DATA` (defaults). Tolerance: γ0 within 2 %, γ1 within 10 % (the \
         oscillator's scenes), L within 2 % (the pendulum).",
    );
    Ok(t)
}
