//! How the verdict grades answers: default runs on every `gen` scene (whose errors against the
//! truth are known) and the constructed failures of issue 17 (a harmonic, frames out of order,
//! a scene that does not move, one law's data read with another, clips too short for the
//! damping). The false-alarm rate is the share of runs within their accuracy bars that are
//! not graded `ok`; a constructed failure must never be graded `ok`.

use crate::options::{shown, Opt};
use crate::runner::{DataSpec, Runner};
use crate::table::{self, Cell, Table};
use crate::worker::Run;
use physvid_testkit::failures::Failure;
use std::path::{Path, PathBuf};

/// The accuracy bar of a reported value (relative error), where it has ground truth.
fn bar(name: &str) -> f64 {
    match name {
        "gamma1" => 0.10,
        "damping" => 0.05,
        _ => 0.01,
    }
}

/// One row: what was run and how it was graded.
struct Row {
    case: String,
    constructed: bool,
    command: String,
    report: Run,
}

impl Row {
    /// Every value with truth within its bar (`None` without truth).
    fn within(&self) -> Option<bool> {
        let judged: Vec<bool> = self
            .report
            .parameters
            .iter()
            .filter_map(|p| p.relative_error.map(|e| e.abs() <= bar(&p.name)))
            .collect();
        (!judged.is_empty()).then(|| judged.iter().all(|b| *b))
    }

    fn cells(&self) -> Vec<Cell> {
        let values: Vec<String> = self
            .report
            .parameters
            .iter()
            .filter(|p| p.units == "SI")
            .map(|p| {
                let mut s = format!("{} {:.5}", p.name, p.estimate);
                if let Some(se) = p.standard_error {
                    s += &format!(" ± {se:.2e}");
                }
                if let Some(e) = p.relative_error {
                    s += &format!(" ({:+.2} %)", e * 100.0);
                }
                s
            })
            .collect();
        let v = &self.report.verdict;
        vec![
            Cell::text(&self.case),
            Cell::text(if self.constructed { "failure" } else { "right" }),
            Cell::text(format!("`{}`", self.command)),
            Cell::text(values.join("; ")),
            Cell::text(match self.within() {
                Some(true) => "yes",
                Some(false) => "no",
                None => "–",
            }),
            Cell::text(v.grade.name()),
            table::checks(v),
        ]
    }
}

pub fn make(r: &Runner) -> anyhow::Result<Table> {
    let quick = r.quick();
    let disc_seeds: u64 = if quick { 1 } else { 5 };
    let delfys_seeds: u64 = if quick { 1 } else { 2 };
    let settings: &[u8] = if quick { &[2] } else { &[1, 2, 3] };
    let failures = 7;
    let runs = 4 * disc_seeds as usize + 5 * settings.len() * delfys_seeds as usize + failures;
    r.begin("verdict", runs);
    let mut rows = Vec::new();
    for scene in ["intensity", "position", "scale", "rod"] {
        for seed in 0..disc_seeds {
            let mut spec = DataSpec::new(scene, quick);
            spec.seed = seed;
            rows.push(right(r, &spec, &[Opt::Seed(seed)])?);
        }
    }
    for scene in [
        "pendulum",
        "torricelli",
        "sliding-block",
        "led",
        "free-fall",
    ] {
        for &setting in settings {
            for seed in 0..delfys_seeds {
                let mut spec = DataSpec::new(scene, quick);
                (spec.setting, spec.seed) = (setting, seed);
                rows.push(right(r, &spec, &[Opt::Seed(seed)])?);
            }
        }
    }
    rows.extend(constructed(r)?);
    let mut t = Table::new(
        "verdict",
        "The verdict on right answers and on constructed failures",
        &[
            ("case", "case"),
            ("kind", "kind"),
            ("command", "command"),
            ("SI values ± std. error (error)", "values"),
            ("within bar", "within_bar"),
            ("grade", "grade"),
            ("checks with reasons", "checks"),
        ],
    );
    for row in &rows {
        t.push(row.cells());
    }
    let right_rows: Vec<&Row> = rows.iter().filter(|r| !r.constructed).collect();
    let within: Vec<&&Row> = right_rows
        .iter()
        .filter(|r| r.within() == Some(true))
        .collect();
    let ok = |rows: &[&&Row]| {
        rows.iter()
            .filter(|r| r.report.verdict.grade == estimator::verdict::Grade::Ok)
            .count()
    };
    let outside: Vec<&&Row> = right_rows
        .iter()
        .filter(|r| r.within() == Some(false))
        .collect();
    let failed: Vec<&Row> = rows.iter().filter(|r| r.constructed).collect();
    let failed_ok = failed
        .iter()
        .filter(|r| r.report.verdict.grade == estimator::verdict::Grade::Ok)
        .count();
    t.note(format!(
        "Right answers: {} of {} default runs on `gen`'s scenes within their bars, {} of those \
         graded ok ({:.1} %; false alarms {}); of the {} outside their bars, {} graded ok.",
        within.len(),
        right_rows.len(),
        ok(&within),
        100.0 * ok(&within) as f64 / within.len().max(1) as f64,
        within.len() - ok(&within),
        outside.len(),
        ok(&outside)
    ));
    t.note(format!(
        "Constructed failures: {} of {} graded ok (must be none).",
        failed_ok,
        failed.len()
    ));
    t.note(
        "Bars: relative error within 1 % (γ0, every SI value of the Delfys75 systems), 10 % (γ1), \
         5 % (the pendulum's damping). Data: `gen --scenario SCENE` with the command's flags \
         (500 clips of 50×50; the rod at 50×50 too). Runs: `estimate DATA --seed S`; the \
         constructed failures' flags are in their rows.",
    );
    Ok(t)
}

/// A default run on `spec`.
fn right(r: &Runner, spec: &DataSpec, opts: &[Opt]) -> anyhow::Result<Row> {
    let data = r.dataset(spec)?;
    let report = r.estimate(&data, opts)?;
    Ok(Row {
        case: format!(
            "{} setting {} seed {}",
            spec.scenario, spec.setting, spec.seed
        ),
        constructed: false,
        command: format!("{} · estimate DATA {}", spec.command(), shown(opts)),
        report,
    })
}

/// A data set's frames with `failure`, as a bare `.npy` named `name` in the scratch directory.
fn altered(r: &Runner, data: &Path, name: &str, failure: Failure) -> anyhow::Result<PathBuf> {
    let path = r.scratch.join(format!("{name}.npy"));
    failure.write(data, &path)?;
    Ok(path)
}

/// The constructed failures.
fn constructed(r: &Runner) -> anyhow::Result<Vec<Row>> {
    let quick = r.quick();
    let mut rows = Vec::new();
    let mut run = |case: &str, data: &Path, command: String, opts: &[Opt]| -> anyhow::Result<()> {
        let report = r.estimate(data, opts)?;
        rows.push(Row {
            case: case.to_string(),
            constructed: true,
            command: format!("{command} · estimate DATA {}", shown(opts)),
            report,
        });
        Ok(())
    };
    let osc = [Opt::Dt(0.2), Opt::Model("damped-oscillator")];
    let rod = DataSpec::new("rod", quick);
    let data = r.dataset(&rod)?;
    run(
        "the oscillator forced onto its 2ω harmonic",
        &data,
        rod.command(),
        &[
            Opt::SingleStart,
            Opt::Init(vec![("gamma0".into(), 16.0), ("gamma1".into(), 0.16)]),
        ],
    )?;
    let intensity = DataSpec::new("intensity", quick);
    let data = r.dataset(&intensity)?;
    let shuffled = altered(r, &data, "shuffled", Failure::Shuffled)?;
    run(
        "frames shuffled within each clip",
        &shuffled,
        format!("{} (frames shuffled)", intensity.command()),
        &osc,
    )?;
    let position = DataSpec::new("position", quick);
    let data = r.dataset(&position)?;
    let still = altered(r, &data, "still-noise", Failure::StillWithNoise)?;
    run(
        "a still scene with sensor noise (σ 0.05)",
        &still,
        format!("{} (first frame held, noise)", position.command()),
        &osc,
    )?;
    let flicker = altered(r, &data, "still-flicker", Failure::StillUnderFlicker)?;
    run(
        "a still scene under a flickering light (±20 %)",
        &flicker,
        format!("{} (first frame held, gain)", position.command()),
        &osc,
    )?;
    let tank = DataSpec::new("torricelli", quick);
    let data = r.dataset(&tank)?;
    run(
        "Torricelli's tank read as an LED",
        &data.join("frames.npy"),
        format!("{} (frames.npy)", tank.command()),
        &[Opt::Dt(1.0), Opt::Model("led")],
    )?;
    let fall = DataSpec::new("free-fall", quick);
    let data = r.dataset(&fall)?;
    run(
        "a free fall read as an oscillator",
        &data.join("frames.npy"),
        format!("{} (frames.npy)", fall.command()),
        &[Opt::Dt(0.0333333), Opt::Model("damped-oscillator")],
    )?;
    let mut short = DataSpec::new("intensity", quick);
    (short.samples, short.frames, short.dt) = (20, Some(6), Some(0.05));
    let data = r.dataset(&short)?;
    run(
        "clips too short for the damping (20 clips of 0.25 s)",
        &data,
        short.command(),
        &[],
    )?;
    Ok(rows)
}
