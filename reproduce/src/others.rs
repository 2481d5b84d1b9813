//! The verdict on footage rendered by others: `scripts/others_suite.py` draws a black rod and
//! bob the way another group's robustness suite does (numpy, no code shared with `gen`; 64×64
//! grey, 20 fps, 157 frames, θ'' + 0.08 θ' + 4.0016 θ = 0 from 60°) clean and under texture,
//! moving clutter, camera shake, brightness drift, a circling light with a shadow, an occluder
//! and noise at levels 1–5, as MP4 files. Each is estimated as a new user would (no model, no
//! flags): right where the chosen law is the pendulum's or the oscillator's with γ0 (g/L)
//! within 2 % and γ1 (the damping) within 10 %; the detection rate is the share of wrong answers
//! not graded ok, the false-alarm rate the share of right answers not graded ok. Not used to
//! tune any check (a held-out measure).

use crate::options::Opt;
use crate::runner::Runner;
use crate::table::{self, Cell, Table};
use crate::worker::Run;
use estimator::verdict::Grade;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The suite's truth (the script's constants).
const GAMMA0: f64 = 4.0016;
const GAMMA1: f64 = 0.08;
/// The bars: γ0 (g/L) 2 %, γ1 (damping) 10 %.
const BAR0: f64 = 0.02;
const BAR1: f64 = 0.10;

/// The conditions and levels drawn (the quick set: the clean control and two harsh ones).
const CONDITIONS: &str = "clean,texture,clutter,shake,drift,light,occlusion,noise";
const QUICK_CONDITIONS: &str = "clean,clutter";
const LEVELS: &str = "1,2,3,4,5";
const QUICK_LEVELS: &str = "3";

/// The renderer, beside the workspace.
fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scripts/others_suite.py")
}

/// The Python that has numpy: the project's environment (`scripts/setup.sh`), else `python3`.
fn python() -> PathBuf {
    let venv = Path::new(env!("CARGO_MANIFEST_DIR")).join("../.venv/bin/python");
    if venv.exists() {
        venv
    } else {
        PathBuf::from("python3")
    }
}

/// One render's answer, judged.
struct Answer {
    render: String,
    model: String,
    /// γ0's and γ1's relative errors (g/L and the damping for the pendulum).
    errors: Option<(f64, f64)>,
    /// γ1's standard error over its value.
    spread: Option<f64>,
    right: bool,
    grade: Grade,
    checks: Cell,
    /// The track's chosen law and its γ0's and γ1's relative errors, judged by the same bars.
    track: Option<(String, Option<(f64, f64)>)>,
}

impl Answer {
    fn track_right(&self) -> bool {
        self.track
            .as_ref()
            .and_then(|t| t.1)
            .is_some_and(|(e0, e1)| e0.abs() <= BAR0 && e1.abs() <= BAR1)
    }
}

/// The names of the rate and the damping in `law`'s values (the oscillator's, or the
/// pendulum's and the swing's).
fn rate_and_damping(law: &str) -> (&'static str, &'static str) {
    match law {
        "damped-oscillator" | "oscillation" | "angular-oscillation" => ("gamma0", "gamma1"),
        _ => ("g_over_l", "damping"),
    }
}

fn judged(render: String, run: &Run) -> Answer {
    let model = run.model.clone();
    let (rate, damping) = rate_and_damping(&model);
    let pair = run.value(rate).zip(run.value(damping));
    let errors = pair.map(|(a, b)| (a.estimate / GAMMA0 - 1.0, b.estimate / GAMMA1 - 1.0));
    let spread = pair.and_then(|(_, b)| b.standard_error.map(|s| s / b.estimate.abs()));
    let track = run.track.as_ref().and_then(|k| {
        let law = k.chosen.clone()?;
        let (rate, damping) = rate_and_damping(&law);
        let errors = k
            .value(rate)
            .zip(k.value(damping))
            .map(|(a, b)| (a / GAMMA0 - 1.0, b / GAMMA1 - 1.0));
        Some((law, errors))
    });
    Answer {
        track,
        render,
        right: errors.is_some_and(|(e0, e1)| e0.abs() <= BAR0 && e1.abs() <= BAR1),
        model,
        errors,
        spread,
        grade: run.verdict.grade,
        checks: table::checks(&run.verdict),
    }
}

pub fn make(r: &Runner) -> anyhow::Result<Table> {
    let dir = r.scratch.join("others");
    std::fs::create_dir_all(&dir)?;
    let (conditions, levels) = if r.quick() {
        (QUICK_CONDITIONS, QUICK_LEVELS)
    } else {
        (CONDITIONS, LEVELS)
    };
    let out = Command::new(python())
        .arg(script())
        .arg(&dir)
        .args(["--mp4", "--conditions", conditions, "--levels", levels])
        .output()
        .map_err(|e| anyhow::anyhow!("{}: {e}", python().display()))?;
    anyhow::ensure!(
        out.status.success(),
        "{} failed (it needs numpy and ffmpeg: scripts/setup.sh): {}",
        script().display(),
        String::from_utf8_lossy(&out.stderr).trim()
    );
    let mut renders: Vec<PathBuf> = std::fs::read_dir(&dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "mp4"))
        .collect();
    renders.sort();
    r.begin("others", renders.len());
    let mut answers = Vec::new();
    for path in &renders {
        let run = r.estimate(path, &[Opt::Seed(0)])?;
        let name = path
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
        answers.push(judged(name, &run));
    }
    r.discard(&dir);
    let mut t = Table::new(
        "others",
        "Footage rendered by others: a rod and bob under clutter, shake, light, occlusion, noise",
        &[
            ("render", "render"),
            ("model chosen", "model"),
            ("γ0 (g/L) error", "gamma0_error"),
            ("γ1 (damping) error", "gamma1_error"),
            ("γ1's error / γ1", "gamma1_spread"),
            ("right", "right"),
            ("grade", "grade"),
            ("checks with reasons", "checks"),
            ("track's law", "track_law"),
            ("track's γ0 error", "track_gamma0_error"),
            ("track's γ1 error", "track_gamma1_error"),
            ("track right", "track_right"),
        ],
    );
    for a in &answers {
        t.push(vec![
            Cell::text(&a.render),
            Cell::text(&a.model),
            Cell::rel(a.errors.map(|e| e.0)),
            Cell::rel(a.errors.map(|e| e.1)),
            Cell::num(a.spread, 2),
            Cell::text(if a.right { "yes" } else { "no" }),
            Cell::text(a.grade.name()),
            a.checks.clone(),
            Cell::text(a.track.as_ref().map_or("–", |t| t.0.as_str())),
            Cell::rel(a.track.as_ref().and_then(|t| t.1).map(|e| e.0)),
            Cell::rel(a.track.as_ref().and_then(|t| t.1).map(|e| e.1)),
            Cell::text(if a.track_right() { "yes" } else { "no" }),
        ]);
    }
    t.note(rates(&answers));
    t.note(format!(
        "The track alone (its chosen law's values, whether or not it guides the run; where it \
         guides, the answer is the track's, the latent's its second opinion): right on {} of {} \
         renders.",
        answers.iter().filter(|a| a.track_right()).count(),
        answers.len()
    ));
    t.note(format!(
        "Renders: `scripts/others_suite.py DIR --mp4 --conditions {conditions} --levels \
         {levels}` (seed 7 + 100·level); runs: `estimate RENDER.mp4 --seed 0`, no model. Right: \
         the oscillator's or the pendulum's law with γ0 (g/L) within {:.0} % of {GAMMA0} s⁻² and \
         γ1 (the damping) within {:.0} % of {GAMMA1} s⁻¹. Over a clip of 7.85 s the swing decays \
         by 27 %, so γ1 is the hard half: the column of its standard error over its value says \
         how well each run claims to know it.",
        100.0 * BAR0,
        100.0 * BAR1
    ));
    Ok(t)
}

/// The detection and false-alarm rates over `answers`, in a sentence.
fn rates(answers: &[Answer]) -> String {
    let (right, wrong): (Vec<&Answer>, Vec<&Answer>) = answers.iter().partition(|a| a.right);
    let not_ok = |set: &[&Answer]| set.iter().filter(|a| a.grade != Grade::Ok).count();
    table::rates(
        &format!("{} renders", answers.len()),
        (right.len(), not_ok(&right)),
        (wrong.len(), not_ok(&wrong)),
    )
}
