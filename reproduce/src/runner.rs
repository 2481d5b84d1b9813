//! `DataSpec` (a dataset as `gen` would make it, from the same arguments) and `Runner`, which
//! renders datasets into a scratch directory and runs estimations as `estimate` would, with one
//! progress bar over a table's runs.

use crate::options::{request, shown, Opt};
use crate::shard::{Call, Sharded, Sharding, State};
use crate::worker::{estimate_apart, Run};
use estimator::cli::DeviceChoice;
use estimator::report::Report;
use estimator::Request;
use generator::{generate_to_disk, GenArgs, SceneRef};
use indicatif::ProgressBar;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;

/// A dataset as `gen` would make it.
#[derive(Debug, Clone, PartialEq)]
pub struct DataSpec {
    pub scenario: &'static str,
    pub samples: usize,
    pub size: usize,
    /// Frames per clip and dt (the scene's default when `None`).
    pub frames: Option<usize>,
    pub dt: Option<f64>,
    pub setting: u8,
    pub seed: u64,
    pub noise: f64,
    /// Further `gen` arguments (`--set NAME=VALUE`, `--color`, `--perturb NAME:LEVEL`).
    pub extra: Vec<String>,
}

impl DataSpec {
    /// The paper's set (500 clips of 50×50), or a small one for `--quick`.
    pub fn new(scenario: &'static str, quick: bool) -> DataSpec {
        DataSpec {
            scenario,
            samples: if quick { 120 } else { 500 },
            size: if quick { 32 } else { 50 },
            frames: None,
            dt: None,
            setting: 1,
            seed: 0,
            noise: 0.0,
            extra: Vec::new(),
        }
    }

    /// The `gen` arguments that write this dataset (without `--out`).
    pub fn args(&self) -> Vec<String> {
        let mut a = vec![
            "--scenario".to_string(),
            self.scenario.into(),
            "--samples".into(),
            self.samples.to_string(),
            "--size".into(),
            self.size.to_string(),
        ];
        let mut add = |flag: &str, value: String| a.extend([flag.to_string(), value]);
        if SceneRef::by_name(self.scenario).is_some_and(|s| s.has_settings()) {
            add("--setting", self.setting.to_string());
        }
        if let Some(f) = self.frames {
            add("--frames", f.to_string());
        }
        if let Some(dt) = self.dt {
            add("--dt", dt.to_string());
        }
        if self.noise > 0.0 {
            add("--noise", self.noise.to_string());
        }
        add("--seed", self.seed.to_string());
        a.extend(self.extra.iter().map(|e| e.to_string()));
        a
    }

    /// The `gen` command that writes this dataset.
    pub fn command(&self) -> String {
        format!("gen {}", self.args().join(" "))
    }
}

/// Renders datasets and runs estimations for the tables, with one progress bar over the runs.
pub struct Runner {
    pub(crate) quick: bool,
    pub(crate) device: DeviceChoice,
    /// CPU threads of an estimation in this process (`--threads`; all cores without it).
    pub(crate) threads: Option<usize>,
    /// Estimations side by side, each in a process of its own (1: one at a time, here).
    pub(crate) jobs: usize,
    /// CPU threads of each of those (`--threads`, or the cores shared out by `--jobs`).
    pub(crate) job_threads: usize,
    pub(crate) scratch: PathBuf,
    /// Where the shared real recordings are (`--recordings`).
    pub(crate) recordings: PathBuf,
    pub(crate) bar: ProgressBar,
    /// stderr is not a terminal (a log file, CI): one line per finished run instead of the bar.
    pub(crate) lines: bool,
    /// `--scratch` was given: keep every dataset there.
    pub(crate) keep: bool,
    /// `--shard I/N` or `--merge DIR...`.
    pub(crate) sharding: Option<State>,
}

impl Runner {
    pub fn quick(&self) -> bool {
        self.quick
    }

    /// Starts a table of `runs` estimations.
    pub fn begin(&self, table: &str, runs: usize) {
        self.bar.set_length(runs as u64);
        self.bar.set_position(0);
        self.bar.set_prefix(table.to_string());
        self.bar.reset_elapsed();
        if let Some(s) = &self.sharding {
            s.begin(table);
        }
    }

    /// Where `spec` is rendered.
    fn dataset_dir(&self, spec: &DataSpec) -> PathBuf {
        self.scratch.join(
            spec.command()
                .replace("gen ", "")
                .replace("--", "")
                .replace([' ', '='], "_"),
        )
    }

    /// Renders `spec` into the scratch directory (once; later calls reuse it).
    pub fn dataset(&self, spec: &DataSpec) -> anyhow::Result<PathBuf> {
        let dir = self.dataset_dir(spec);
        if !dir.join("meta.json").exists() {
            self.bar.set_message(spec.command());
            let mut args = spec.args();
            args.extend(["--out".into(), dir.display().to_string(), "--force".into()]);
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            generate_to_disk(&GenArgs::config_from(&args)?)?;
        }
        Ok(dir)
    }

    /// Deletes a dataset no later run needs (the coverage table renders twenty), unless the
    /// user asked to keep them with `--scratch`.
    pub fn discard(&self, dir: &Path) {
        if !self.keep {
            let _ = std::fs::remove_dir_all(dir);
        }
    }

    /// Trains on `data` as `estimate DATA OPTIONS...` would, in this process (quietly, outputs
    /// discarded; every candidate with `--model auto`). Sharded, shard 1 runs and records it,
    /// the others stop the table ([`Sharded`]), a merge reads it from the records.
    pub fn estimate(&self, data: &Path, opts: &[Opt]) -> anyhow::Result<Run> {
        let Some(s) = &self.sharding else {
            return Ok(self.estimate_here(data, opts)?.0);
        };
        let what = format!("estimate {} {}", named(data), shown(opts));
        let (call, mine) = s.next_one();
        match &s.mode {
            Sharding::Shard(_) if mine => {
                let run = self.estimate_here(data, opts)?.0;
                s.record(call, what, &run);
                Ok(run)
            }
            Sharding::Shard(_) => Err(Sharded.into()),
            Sharding::Merge(_) => s.recorded(call, &what),
        }
    }

    /// [`Runner::estimate`] with the run's frame.jpg (`estimator::output::frame_picture`: a
    /// frame of a recording with the track and the stick drawn) where it ran here (none from
    /// another shard's records).
    pub fn estimate_pictured(
        &self,
        data: &Path,
        opts: &[Opt],
    ) -> anyhow::Result<(Run, Option<Vec<u8>>)> {
        if self.sharding.is_some() {
            return Ok((self.estimate(data, opts)?, None));
        }
        let (run, report) = self.estimate_here(data, opts)?;
        Ok((run, estimator::output::frame_picture(&report)))
    }

    /// [`Runner::estimate`] here and now, with the whole report.
    fn estimate_here(&self, data: &Path, opts: &[Opt]) -> anyhow::Result<(Run, Report)> {
        self.bar
            .set_message(format!("estimate {} {}", named(data), shown(opts)));
        let req = self.request(data, opts, &self.scratch.join("run"), self.threads)?;
        let report = estimator::estimation(&req)?.report;
        let run = Run::of(&report)?;
        self.finished(data, opts, &run);
        Ok((run, report))
    }

    /// The typed run of `opts` on `data`, quiet, into `out`, on this runner's device and
    /// `threads` CPU threads (all cores: `None`).
    fn request(
        &self,
        data: &Path,
        opts: &[Opt],
        out: &Path,
        threads: Option<usize>,
    ) -> anyhow::Result<Request> {
        let base = |r: &mut Request| {
            (r.quiet, r.out, r.training.device) = (true, out.to_path_buf(), self.device);
            if let Some(t) = threads {
                r.training.threads = t;
            }
        };
        request(data, base, opts)
    }

    /// Counts a finished run on `data` (a line of its own where stderr is not a terminal).
    fn finished(&self, data: &Path, opts: &[Opt], run: &Run) {
        self.bar.inc(1);
        if self.lines {
            eprintln!(
                "{} {}/{}: estimate {} {} ({:.1} s)",
                self.bar.prefix(),
                self.bar.position(),
                self.bar.length().unwrap_or(0),
                named(data),
                shown(opts),
                run.wall_time_s
            );
        }
    }

    /// Every job's run, in the jobs' order. Sharded, this shard's jobs run and are recorded and
    /// the table stops ([`Sharded`]); a merge reads every job's run from the records.
    pub fn estimate_all(&self, jobs: &[Job]) -> anyhow::Result<Vec<Run>> {
        let Some(s) = &self.sharding else {
            return self.run_all(jobs);
        };
        let what = |j: &Job| {
            let file = j.file.map_or(String::new(), |f| format!("/{f}"));
            format!("{}{file} · estimate {}", j.data.command(), shown(&j.opts))
        };
        if !s.records() {
            return (0..jobs.len())
                .map(|i| s.recorded(Call::Job(i), &what(&jobs[i])))
                .collect();
        }
        let mine: Vec<usize> = (0..jobs.len()).filter(|&i| s.holds_job(i)).collect();
        let subset: Vec<Job> = mine.iter().map(|&i| jobs[i].clone()).collect();
        let runs = self.run_all(&subset)?;
        for (i, run) in mine.into_iter().zip(&runs) {
            s.record(Call::Job(i), what(&jobs[i]), run);
        }
        Err(Sharded.into())
    }

    /// Every job's run, in the jobs' order: `--jobs` of them side by side, each in a process
    /// of its own (one at a time in this process with `--jobs 1`). Each dataset is rendered
    /// before its first job and deleted after its last.
    fn run_all(&self, jobs: &[Job]) -> anyhow::Result<Vec<Run>> {
        let dirs: Vec<PathBuf> = jobs.iter().map(|j| self.dataset_dir(&j.data)).collect();
        let uses = Mutex::new(dirs.iter().fold(HashMap::new(), |mut m, d| {
            *m.entry(d.clone()).or_insert(0usize) += 1;
            m
        }));
        let render = Mutex::new(());
        let one = |i: usize, out: &Path| -> anyhow::Result<Run> {
            let dir = {
                let _turn = render.lock().expect("no render panicked");
                self.dataset(&jobs[i].data)?
            };
            let data = jobs[i].file.map_or(dir.clone(), |f| dir.join(f));
            let run = if self.jobs > 1 {
                let what = format!("estimate {} {}", named(&data), shown(&jobs[i].opts));
                self.bar.set_message(what.clone());
                let req = self.request(&data, &jobs[i].opts, out, Some(self.job_threads))?;
                let run = estimate_apart(&req, &out.with_extension("cbor"), &what)?;
                self.finished(&data, &jobs[i].opts, &run);
                run
            } else {
                self.estimate_here(&data, &jobs[i].opts)?.0
            };
            let mut uses = uses.lock().expect("no job panicked");
            let left = uses.get_mut(&dirs[i]).expect("every job's dataset counted");
            *left -= 1;
            if *left == 0 {
                self.discard(&dir);
            }
            Ok(run)
        };
        if self.jobs <= 1 {
            return (0..jobs.len())
                .map(|i| one(i, &self.scratch.join("run")))
                .collect();
        }
        let next = AtomicUsize::new(0);
        let failed = AtomicBool::new(false);
        let runs: Mutex<Vec<Option<anyhow::Result<Run>>>> =
            Mutex::new((0..jobs.len()).map(|_| None).collect());
        std::thread::scope(|s| {
            for w in 0..self.jobs.min(jobs.len()) {
                let (next, failed, runs, one) = (&next, &failed, &runs, &one);
                let out = self.scratch.join(format!("run-{w}"));
                s.spawn(move || loop {
                    let i = next.fetch_add(1, Ordering::SeqCst);
                    if i >= jobs.len() || failed.load(Ordering::SeqCst) {
                        break;
                    }
                    let run = one(i, &out);
                    failed.fetch_or(run.is_err(), Ordering::SeqCst);
                    runs.lock().expect("no job panicked")[i] = Some(run);
                });
            }
        });
        runs.into_inner()
            .expect("no job panicked")
            .into_iter()
            .flatten()
            .collect()
    }
}

/// One estimation of a table: `estimate DATA OPTIONS...` on the dataset `data` renders (or on
/// one of its files, `file`).
#[derive(Debug, Clone)]
pub struct Job {
    pub data: DataSpec,
    pub opts: Vec<Opt>,
    /// A file of the dataset's to read instead of its directory (`frames.npy`: a bare array).
    pub file: Option<&'static str>,
}

impl Job {
    pub fn new(data: DataSpec, opts: Vec<Opt>) -> Job {
        Job {
            data,
            opts,
            file: None,
        }
    }
}

/// `data` as a progress line names it: its file or folder name (a data set's folder says its
/// scene and flags, a recording its file).
fn named(data: &Path) -> String {
    data.file_name().map_or_else(
        || data.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}
