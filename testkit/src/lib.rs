//! Test support shared by the end-to-end tests of `gen`, `estimate` and `reproduce`:
//! `TestCommand`, a small builder for running a real binary and asserting on its outcome (as
//! ripgrep's tests/util.rs does). Each crate's tests find their binary with
//! `env!("CARGO_BIN_EXE_…")` and add their own helpers. `failures` holds the verdict's
//! constructed failures, which `reproduce verdict` draws too; `slurm` a one-node Slurm cluster
//! for the job-array tests.

pub mod failures;
pub mod slurm;

use std::ffi::{OsStr, OsString};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};

/// An invocation of a binary being built.
#[derive(Debug, Clone)]
pub struct TestCommand {
    bin: PathBuf,
    args: Vec<OsString>,
    env: Vec<(OsString, OsString)>,
    dir: Option<PathBuf>,
    stdout: Option<PathBuf>,
}

impl TestCommand {
    /// `bin` with no arguments yet.
    pub fn new(bin: impl Into<PathBuf>) -> TestCommand {
        TestCommand {
            bin: bin.into(),
            args: Vec::new(),
            env: Vec::new(),
            dir: None,
            stdout: None,
        }
    }

    pub fn arg(mut self, a: impl AsRef<OsStr>) -> TestCommand {
        self.args.push(a.as_ref().to_owned());
        self
    }

    pub fn args<S: AsRef<OsStr>>(mut self, a: impl IntoIterator<Item = S>) -> TestCommand {
        self.args
            .extend(a.into_iter().map(|s| s.as_ref().to_owned()));
        self
    }

    /// `--out DIR`.
    pub fn out(self, dir: &Path) -> TestCommand {
        self.arg("--out").arg(dir)
    }

    /// `--quiet`.
    pub fn quiet(self) -> TestCommand {
        self.arg("--quiet")
    }

    /// Sets an environment variable for the run.
    pub fn env(mut self, k: impl AsRef<OsStr>, v: impl AsRef<OsStr>) -> TestCommand {
        self.env
            .push((k.as_ref().to_owned(), v.as_ref().to_owned()));
        self
    }

    /// Runs in `dir` instead of the test's working directory.
    pub fn current_dir(mut self, dir: &Path) -> TestCommand {
        self.dir = Some(dir.to_path_buf());
        self
    }

    /// Sends standard output to the file `path` (`/dev/full`: a full disk) instead of
    /// capturing it.
    pub fn stdout_to(mut self, path: &Path) -> TestCommand {
        self.stdout = Some(path.to_path_buf());
        self
    }

    fn command(&self) -> Command {
        let mut c = Command::new(&self.bin);
        c.args(&self.args)
            .envs(self.env.iter().map(|(k, v)| (k, v)));
        if let Some(dir) = &self.dir {
            c.current_dir(dir);
        }
        if let Some(path) = &self.stdout {
            let file = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            c.stdout(file);
        }
        c
    }

    /// Runs the command and returns its output.
    pub fn output(&self) -> Output {
        self.command()
            .output()
            .unwrap_or_else(|e| panic!("{} does not run: {e}", self.bin.display()))
    }

    /// Starts the command without waiting for it (its output captured), for a test that stops
    /// it midway.
    pub fn spawn(&self) -> Child {
        self.command()
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("{} does not run: {e}", self.bin.display()))
    }

    /// Runs and asserts success.
    pub fn ok(&self) -> Output {
        let o = self.output();
        assert!(o.status.success(), "{:?}: {}", self.args, stderr(&o));
        o
    }

    /// Runs `estimate` and asserts it gave an estimate and wrote its files: exit code 0, or 4
    /// when the verdict graded the answer unreliable (runs of a few epochs that test the
    /// plumbing, not the answer, are often that).
    pub fn estimated(&self) -> Output {
        let o = self.output();
        assert!(
            matches!(o.status.code(), Some(0 | 4)),
            "{:?}: {}",
            self.args,
            stderr(&o)
        );
        o
    }

    /// Runs and asserts the bad-input contract: exit code 2 and one line on stderr that
    /// contains `needle`.
    pub fn bad_input(&self, needle: &str) {
        let o = self.output();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{:?}: {err}", self.args);
        assert_eq!(
            err.trim().lines().count(),
            1,
            "{:?}: not one line: {err}",
            self.args
        );
        assert!(err.contains(needle), "{:?}: {err}", self.args);
    }
}

/// Whether a tool a test needs is `available`. When it is not: under `CI=true` (where
/// `scripts/setup.sh` has installed ffmpeg and chromium) the test fails, naming it; elsewhere
/// the test is skipped visibly, with `why` on stderr, and this returns false.
pub fn require(what: &str, available: bool, why: &str) -> bool {
    if available {
        return true;
    }
    if std::env::var("CI").is_ok_and(|v| v == "true" || v == "1") {
        panic!(
            "{what} is missing under CI=true: scripts/setup.sh should have installed it ({why})"
        );
    }
    eprintln!("SKIPPED: {what} is missing ({why})");
    false
}

/// Stderr as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Stdout as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}
