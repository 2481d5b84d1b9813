//! Is `--ensemble`'s spread honest? Twenty intensity sets (gen seeds 0–19), each estimated by an
//! ensemble of five trainings with the exact block: how often the truth lies within mean ± 2 std.

use crate::options::Opt;
use crate::runner::{DataSpec, Job, Runner};
use crate::table::{Cell, Table};

pub fn make(r: &Runner) -> anyhow::Result<Table> {
    let (sets, k) = if r.quick() { (3u64, 3usize) } else { (20, 5) };
    let mut t = Table::new(
        "coverage",
        "Ensemble coverage: truth within mean ± 2 std",
        &[
            ("data seed", "data_seed"),
            ("γ0 mean", "gamma0_mean"),
            ("γ0 std", "gamma0_std"),
            ("γ0 covered", "gamma0_covered"),
            ("γ1 mean", "gamma1_mean"),
            ("γ1 std", "gamma1_std"),
            ("γ1 covered", "gamma1_covered"),
            ("wall s", "wall_s"),
        ],
    );
    r.begin("coverage", sets as usize);
    let (mut hits0, mut hits1) = (0, 0);
    let mut truth = (f64::NAN, f64::NAN);
    let jobs: Vec<Job> = (0..sets)
        .map(|seed| {
            let mut spec = DataSpec::new("intensity", r.quick());
            spec.seed = seed;
            Job::new(spec, vec![Opt::Ensemble(k)])
        })
        .collect();
    let runs = r.estimate_all(&jobs)?;
    for (seed, rep) in (0..sets).zip(&runs) {
        let e = rep
            .ensemble
            .as_ref()
            .ok_or_else(|| anyhow::anyhow!("--ensemble {k} gave no ensemble"))?;
        let get = |name: &str| e.values.iter().find(|v| v.name == name);
        let (g0, g1) = (get("gamma0"), get("gamma1"));
        let covered = |v: Option<&estimator::analysis::ensemble::EnsembleValue>| {
            v.and_then(|v| v.truth_within_2std).unwrap_or(false)
        };
        hits0 += covered(g0) as usize;
        hits1 += covered(g1) as usize;
        truth = (
            g0.and_then(|v| v.truth).unwrap_or(f64::NAN),
            g1.and_then(|v| v.truth).unwrap_or(f64::NAN),
        );
        let yes_no = |b: bool| Cell::text(if b { "yes" } else { "no" });
        t.push(vec![
            Cell::num(Some(seed as f64), 0),
            Cell::num(g0.map(|v| v.mean), 5),
            Cell::num(g0.map(|v| v.std), 5),
            yes_no(covered(g0)),
            Cell::num(g1.map(|v| v.mean), 5),
            Cell::num(g1.map(|v| v.std), 5),
            yes_no(covered(g1)),
            Cell::num(Some(rep.wall_time_s), 1),
        ]);
    }
    t.push(vec![
        Cell::text("covered"),
        Cell::Empty,
        Cell::Empty,
        Cell::text(format!("{hits0}/{sets}")),
        Cell::Empty,
        Cell::Empty,
        Cell::text(format!("{hits1}/{sets}")),
        Cell::Empty,
    ]);
    let spec = DataSpec::new("intensity", r.quick());
    t.note(format!(
        "Data: `{}` with --seed 0–{} (truth γ0 = {:.4}, γ1 = {:.2}).",
        spec.command().replace(" --seed 0", ""),
        sets - 1,
        truth.0,
        truth.1
    ));
    t.note(format!(
        "Runs: `estimate DATA --ensemble {k}` (exact block; training seeds 0–{}). Covered: |mean − \
         truth| ≤ 2·std, std the members' sample standard deviation. The spread is that of the \
         training seed only (weights, batch order); the dataset's own noise is not in it.",
        k - 1
    ));
    Ok(t)
}
